/* grano info FILE: what a result (or checkpoint) file holds. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmd.h"
#include "h5md.h"
#include "method.h"
#include "opts.h"
#include "scene.h"

static void usage(FILE *f)
{
    fprintf(f,
        "usage: grano info [--xdmf] [--verify] FILE\n\n"
        "Describe what a grano result or checkpoint file (H5MD, docs/output-format.md)\n"
        "holds: who wrote it, the scene, method and seed, the particles and frames with\n"
        "their time range, the observables (with the last sample), fields, result\n"
        "tables, and whether it holds a checkpoint.\n\n"
        "options:\n"
        "  --xdmf       also (re)write the ParaView sidecar FILE.xdmf from what the file\n"
        "               holds (a killed run's sidecar may miss its last frames)\n"
        "  --verify     first read every dataset back to its end, checking the checksums\n"
        "               of its chunks and of the file's metadata; a damaged file is named\n"
        "               with its first damaged dataset (exit 1)\n"
        "  -h, --help   this help\n"
        "  --version    grano's version\n\n"
        "Exit status: 0 on success, 1 if the file cannot be read to the end, 2 for a\n"
        "missing file, a file grano did not write, or bad usage.\n");
}

static size_t count_lines(const char *s)
{
    size_t n = 0;
    for (; *s; s++)
        n += *s == '\n';
    return n;
}

/* The sides as the scene states them (wall, periodic, open), with the
 * scene's wall segments; H5MD's per-axis boundary ("none" for anything
 * not periodic) alone would call a box with walls unbounded. */
static void describe_sides(const gr_h5md_info *in, char *buf, size_t n)
{
    static const char *const bc[] = {"wall", "periodic", "open"};
    const char *names[GR_MAX_METHODS + 1];
    gr_method_names(names, GR_MAX_METHODS + 1);
    gr_err e = {0};
    gr_scene *sc = in->scene_text ? gr_scene_parse(in->scene_text, in->path, names, &e) : NULL;
    /* a scene changed after parsing (a test's) is told by the file's axes */
    if (sc && ((sc->side[GR_LEFT] == GR_BC_PERIODIC) != !!in->periodic[0] ||
               (sc->side[GR_BOTTOM] == GR_BC_PERIODIC) != !!in->periodic[1])) {
        gr_scene_free(sc);
        sc = NULL;
    }
    if (!sc) {
        snprintf(buf, n, "boundaries x %s, y %s (H5MD)", in->periodic[0] ? "periodic" : "not periodic",
                 in->periodic[1] ? "periodic" : "not periodic");
        return;
    }
    const gr_bc *s = sc->side;
    if (s[GR_LEFT] == s[GR_RIGHT] && s[GR_BOTTOM] == s[GR_TOP])
        snprintf(buf, n, "sides x %s, y %s", bc[s[GR_LEFT]], bc[s[GR_BOTTOM]]);
    else
        snprintf(buf, n, "sides left %s, right %s, bottom %s, top %s", bc[s[GR_LEFT]], bc[s[GR_RIGHT]],
                 bc[s[GR_BOTTOM]], bc[s[GR_TOP]]);
    size_t k = strlen(buf);
    if (sc->nsegments > 0 && k < n)
        snprintf(buf + k, n - k, ", %d wall segment%s", sc->nsegments, sc->nsegments > 1 ? "s" : "");
    gr_scene_free(sc);
}

static int print_frames(gr_h5md_reader *r, const gr_h5md_info *in, gr_err *err)
{
    if (!in->nframes && !(isfinite(in->box[0]) && isfinite(in->box[1]))) {
        printf("trajectory   none: a file of result tables (below): grano course, grano compare\n");
        return GR_OK;
    }
    char sides[160];
    describe_sides(in, sides, sizeof sides);
    printf("box          %g x %g d; %s\n", in->box[0], in->box[1], sides);
    if (!in->nframes) {
        printf("particles    no trajectory frames\n");
        return GR_OK;
    }
    double *t = malloc(in->nframes * sizeof *t);
    uint64_t *s = malloc(in->nframes * sizeof *s);
    gr_particles *p = gr_particles_create(in->nparticles, err);
    int rc = !t || !s || !p ? gr_fail(err, GR_ERUN, "out of memory") : GR_OK;
    if (!rc)
        rc = gr_h5md_read_times(r, t, s, err);
    if (!rc)
        rc = gr_h5md_read_frame(r, in->nframes - 1, p, NULL, NULL, err);
    if (!rc) {
        size_t fixed = 0, gone = 0;
        for (size_t i = 0; i < p->n; i++) {
            fixed += (p->flags[i] & GR_PF_FIXED) != 0;
            gone += !(p->flags[i] & GR_PF_FIXED) && (p->flags[i] & GR_PF_GONE);
        }
        printf("particles    %zu per frame; in the last frame %zu mobile, %zu fixed, %zu gone\n",
               in->nparticles, p->n - fixed - gone, fixed, gone);
        printf("frames       %zu, t = %g .. %g tau (steps %llu .. %llu)\n", in->nframes, t[0],
               t[in->nframes - 1], (unsigned long long)s[0],
               (unsigned long long)s[in->nframes - 1]);
    }
    free(t);
    free(s);
    gr_particles_free(p);
    return rc;
}

/* Each observable's last value, as the method declared it; a validity
 * limit broken during the run is said with the key that changes it. */
static int print_obs(gr_h5md_reader *r, const gr_h5md_info *in, gr_err *err)
{
    char **names;
    size_t n;
    int rc = gr_h5md_list(r, "observables", &names, &n, err);
    if (rc)
        return rc;
    if (!n || !in->nobs) {
        printf("observables  none\n");
        gr_h5md_names_free(names, n);
        return GR_OK;
    }
    double t0, t1;
    size_t ns;
    char p[300];
    snprintf(p, sizeof p, "observables/%s", names[0]);
    if ((rc = gr_h5md_series_info(r, p, &ns, &t0, &t1, err)))
        goto done;
    printf("observables  %zu samples, t = %g .. %g tau; the last:\n", in->nobs, t0, t1);
    int broken = 0;
    for (size_t i = 0; i < n && !rc; i++) {
        double v[2];
        int nc;
        char key[128];
        if ((rc = gr_h5md_obs_last(r, names[i], v, &nc, key, sizeof key, err)))
            break;
        if (nc == 2)
            printf("  %-18s (%.6g, %.6g)\n", names[i], v[0], v[1]);
        else
            printf("  %-18s %.6g%s\n", names[i], v[0], key[0] && v[0] > 0 ? "  <- validity limit broken" : "");
        broken += key[0] && v[0] > 0;
    }
    if (!rc && broken)
        printf("validity     %d limit(s) broken during the run: the counters marked above count the steps "
               "that broke them (grano methods NAME: the key that changes each)\n", broken);
done:
    gr_h5md_names_free(names, n);
    return rc;
}

static int print_fields(gr_h5md_reader *r, gr_err *err)
{
    char **names;
    size_t n;
    int rc = gr_h5md_list(r, "fields", &names, &n, err);
    if (rc)
        return rc;
    if (!n)
        printf("fields       none\n");
    for (size_t i = 0; i < n && !rc; i++) {
        gr_field_desc f;
        size_t samples;
        char path[300];
        double t0, t1;
        snprintf(path, sizeof path, "fields/%s", names[i]);
        if (!(rc = gr_h5md_field_info(r, names[i], &f, &samples, err)) &&
            !(rc = gr_h5md_series_info(r, path, &samples, &t0, &t1, err)))
            printf("%-12s %s: %d x %d cells of %g x %g d%s, %zu samples, t = %g .. %g\n",
                   i ? "" : "fields", names[i], f.nx, f.ny, f.dx, f.dy,
                   f.ncomp == 2 ? ", vector" : f.ncomp == 4 ? ", 2x2 tensor" : "", samples, t0, t1);
    }
    gr_h5md_names_free(names, n);
    return rc;
}

/* A result's description and columns, and its values when it is small
 * (a course exercise's table, a fit). */
static int print_table(gr_h5md_reader *r, const char *name, size_t rows, size_t cols, gr_err *err)
{
    char desc[512], names[512];
    double *v = NULL;
    int rc = gr_h5md_result_text(r, name, desc, sizeof desc, names, sizeof names, err);
    printf("%s%s\n", desc[0] ? ": " : "", desc);
    if (!rc && names[0])
        printf("%-12s   columns: %s\n", "", names);
    size_t nc = cols ? cols : 1;
    if (rc || rows * nc > 120 || nc > 10)
        return rc;
    if ((rc = gr_h5md_read_result(r, name, &rows, &cols, &v, err)))
        return rc;
    for (size_t i = 0; i < rows; i++) {
        printf("%-12s  ", "");
        for (size_t j = 0; j < nc; j++)
            printf(" %11.5g", v[i * nc + j]);
        printf("\n");
    }
    free(v);
    return GR_OK;
}

/* results/ may hold subgroups: walk them. */
static int print_results(gr_h5md_reader *r, const char *group, int *shown, gr_err *err)
{
    char **names;
    size_t n;
    int rc = gr_h5md_list(r, group, &names, &n, err);
    for (size_t i = 0; i < n && !rc; i++) {
        char path[600];
        snprintf(path, sizeof path, "%s/%s", group, names[i]);
        size_t rows, cols;
        gr_err e2 = {0};
        if (gr_h5md_read_result(r, path + strlen("results/"), &rows, &cols, NULL, &e2)) {
            rc = print_results(r, path, shown, err); /* a subgroup */
            continue;
        }
        if (cols)
            printf("%-12s %s [%zu x %zu]", *shown ? "" : "results", path + 8, rows, cols);
        else
            printf("%-12s %s [%zu]", *shown ? "" : "results", path + 8, rows);
        (*shown)++;
        rc = print_table(r, path + 8, rows, cols, err);
    }
    gr_h5md_names_free(names, n);
    return rc;
}

typedef struct {
    int xdmf, verify;
} info_flags;

static int info_option(void *ctx, int id, const char *arg, gr_err *err)
{
    (void)arg;
    info_flags *f = ctx;
    if (id == 'x')
        f->xdmf = 1;
    else if (id == 'V')
        f->verify = 1;
    else
        return gr_fail(err, GR_EINPUT, "unknown option");
    return 0;
}

int cmd_info(int argc, char **argv)
{
    static const struct option opts[] = {
        {"xdmf", no_argument, NULL, 'x'}, {"verify", no_argument, NULL, 'V'}, {NULL, 0, NULL, 0}};
    info_flags fl = {0, 0};
    int first = 0;
    int prc = exp_getopt_main("info", argc, argv, opts, info_option, &fl, usage, 1, &first);
    if (prc >= 0)
        return prc;
    if (first != argc - 1) {
        fprintf(stderr, "grano info: expected one FILE\n");
        usage(stderr);
        return 2;
    }
    const char *file = argv[first];
    gr_err err = {0};
    size_t nd = 0;
    unsigned long long nb = 0;
    /* a damaged file is named before anything of it is described */
    if (fl.verify && gr_h5_verify(file, &nd, &nb, &err)) {
        fprintf(stderr, "grano info: %s\n", err.msg);
        return 1;
    }
    gr_h5md_reader *r = gr_h5md_open(file, &err);
    if (!r && fl.verify) {
        /* a table file (compare.h5, silo-*.h5) is checked all the same */
        printf("file         %s\nverified     %zu datasets read back to their ends, %.3g MB, no checksum failed (%s)\n", file, nd,
               (double)nb / 1e6, err.msg);
        return 0;
    }
    if (!r) {
        fprintf(stderr, "grano info: %s\n", err.msg);
        return err.code ? err.code : 1;
    }
    const gr_h5md_info *in = gr_h5md_info_of(r);
    printf("file         %s\n", in->path);
    if (in->writing)
        printf("writing      a run is writing it, or its run was killed (the frames so far, "
               "read as HDF5's SWMR reader; h5py: h5py.File(path, 'r', swmr=True))\n");
    printf("creator      %s %s (H5MD %d.%d), author %s\n", in->creator, in->creator_version,
           in->h5md_version[0], in->h5md_version[1], in->author);
    printf("scene        %s (from %s, %zu lines stored)\n", in->scene_name[0] ? in->scene_name : "?",
           in->scene_path[0] ? in->scene_path : "?", count_lines(in->scene_text));
    printf("method       %s, seed %llu\n", in->method[0] ? in->method : "?",
           (unsigned long long)in->seed);
    if (in->derived[0])
        printf("derived      %s\n", in->derived);
    int rc = print_frames(r, in, &err);
    /* a table file (no trajectory, no series) has no observables or fields to list */
    int series = in->nframes || in->nobs;
    if (!rc && series)
        rc = print_obs(r, in, &err);
    if (!rc && series)
        rc = print_fields(r, &err);
    int shown = 0;
    if (!rc)
        rc = print_results(r, "results", &shown, &err);
    if (!rc && !shown)
        printf("results      none\n");
    if (!rc) {
        char **names;
        size_t n;
        if (in->has_checkpoint && !(rc = gr_h5md_list(r, "checkpoint", &names, &n, &err))) {
            printf("checkpoint   yes: %zu entries (restart with grano run --restart %s)\n", n, in->path);
            gr_h5md_names_free(names, n);
        } else if (!rc) {
            printf("checkpoint   no\n");
        }
    }
    if (!rc && fl.xdmf && !(rc = gr_h5md_write_xdmf(r, &err)))
        printf("wrote        %s.xdmf\n", in->path);
    if (!rc && fl.verify)
        printf("verified     %zu datasets read back to their ends, %.3g MB, no checksum failed\n", nd, (double)nb / 1e6);
    gr_h5md_reader_free(r);
    if (rc) {
        fprintf(stderr, "grano info: %s\n", err.msg);
        return rc;
    }
    return 0;
}
