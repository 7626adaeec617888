/* grano export RESULT.h5: the trajectory in formats other tools read. */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cmd.h"
#include "export_fmt.h"
#include "h5md.h"
#include "method.h"
#include "opts.h"

static void usage(FILE *f)
{
    fprintf(f,
        "usage: grano export RESULT.h5 --format F [--frames RANGE] [--out FILE] [--force]\n\n"
        "Write the trajectory of a grano result file (or the state of a checkpoint) in a\n"
        "format other tools read; the 2-D system lies at z = 0 (docs/output-format.md).\n\n"
        "options:\n"
        "  -F, --format F      lammps-dump (LAMMPS, OVITO, VMD, ASE), extxyz (ASE, OVITO),\n"
        "                      csv (one row per grain and frame), lammps-data (one frame\n"
        "                      as a LAMMPS data file, atom style sphere; [init] kind = file\n"
        "                      reads it back, and extxyz too)\n"
        "  -n, --frames RANGE  I, I:J or I:J:K (Python slices: J excluded, negative counts\n"
        "                      from the end); default all frames, the last for lammps-data\n"
        "  -o, --out FILE      default: standard output\n"
        "  -f, --force         replace an existing FILE\n"
        "  -h, --help          this help\n"
        "      --version       the version\n");
}

/* Python slice semantics on n frames: first, end (excluded), stride. */
static int parse_range(const char *s, size_t n, long *a, long *b, long *k)
{
    long v[3] = {0, (long)n, 1};
    int given[3] = {0, 0, 0}, i = 0;
    const char *p = s;
    while (i < 3) {
        char *end;
        long x = strtol(p, &end, 10);
        if (end != p)
            v[i] = x, given[i] = 1;
        p = end;
        if (*p == ':' && i < 2)
            p++, i++;
        else
            break;
    }
    if (*p || !*s || (given[2] && v[2] <= 0))
        return -1;
    if (i == 0) {
        if (!given[0])
            return -1;
        v[1] = v[0] < 0 ? v[0] + (long)n + 1 : v[0] + 1;
        if (v[1] == 0)
            return -1;
    }
    for (int j = 0; j < 2; j++) {
        if (v[j] < 0)
            v[j] += (long)n;
        v[j] = v[j] < 0 ? 0 : v[j] > (long)n ? (long)n : v[j];
    }
    *a = v[0], *b = v[1], *k = v[2];
    return *a < *b ? 0 : -1;
}

typedef struct {
    const char *in, *out, *frames;
    int fmt, force;
} xp_args;

static int export_option(void *ctx, int id, const char *arg, gr_err *err)
{
    xp_args *a = ctx;
    switch (id) {
    case 'F':
        if ((a->fmt = xp_format_of(arg)) < 0)
            return gr_fail(err, GR_EINPUT, "--format: '%s' is not one of %s", arg, xp_format_names());
        return 0;
    case 'n': a->frames = arg; return 0;
    case 'o': a->out = arg; return 0;
    case 'f': a->force = 1; return 0;
    default: return gr_fail(err, GR_EINPUT, "unknown option");
    }
}

/* 0: go on; else the exit code (--help and --version: 0). */
static int parse_args(int argc, char **argv, xp_args *a, int *done)
{
    static const struct option opts[] = {
        {"format", required_argument, NULL, 'F'}, {"frames", required_argument, NULL, 'n'},
        {"out", required_argument, NULL, 'o'},    {"force", no_argument, NULL, 'f'},
        {NULL, 0, NULL, 0}};
    *a = (xp_args){.fmt = -1};
    int first, rc = exp_getopt_main("export", argc, argv, opts, export_option, a, usage, 1, &first);
    *done = rc >= 0;
    if (rc >= 0)
        return rc;
    if (first != argc - 1 || a->fmt < 0) {
        fprintf(stderr, "grano export: %s\n", first != argc - 1 ? "one RESULT.h5 expected" : "--format is required");
        usage(stderr);
        return 2;
    }
    a->in = argv[first];
    if (a->out && !a->force && access(a->out, F_OK) == 0) {
        fprintf(stderr, "grano export: --out: '%s' already exists; use --force to replace it\n", a->out);
        return 2;
    }
    return 0;
}

static int export_frames(gr_h5md_reader *r, const xp_args *a, long i0, long i1, long di, FILE *f, gr_err *err)
{
    const gr_h5md_info *in = gr_h5md_info_of(r);
    gr_particles *p = gr_particles_create(in->nparticles, err);
    if (!p)
        return err->code;
    xp_frame fr = {.box = {in->box[0], in->box[1]}, .periodic = {in->periodic[0], in->periodic[1]}, .p = p};
    int rc = GR_OK;
    for (long i = i0; i < i1 && !rc; i += di) {
        fr.index = (size_t)i;
        if (!(rc = gr_h5md_read_frame(r, (size_t)i, p, &fr.step, &fr.time, err)))
            rc = xp_write_frame(f, (xp_format)a->fmt, &fr, i == i0, err);
    }
    gr_particles_free(p);
    return rc;
}

/* Why a file has no frame to export: a lattice method writes fields, not
 * particles; a particle run may have ended before its first frame. */
static void no_trajectory(const char *path, const gr_h5md_info *in)
{
    const gr_method_type *m = in->method ? gr_method_find(in->method) : NULL;
    if (m && m->repr == GR_REPR_LATTICE)
        fprintf(stderr,
                "grano export: %s holds no trajectory (method %s writes fields and observables, not particles)\n",
                path, m->name);
    else
        fprintf(stderr, "grano export: %s holds no trajectory (no frame was written%s%s)\n", path,
                in->method ? " by method " : "", in->method ? in->method : "");
}

int cmd_export(int argc, char **argv)
{
    xp_args a;
    int done, rc = parse_args(argc, argv, &a, &done);
    if (rc || done)
        return rc;
    gr_err e = {0};
    gr_h5md_reader *r = gr_h5md_open(a.in, &e);
    if (!r) {
        fprintf(stderr, "grano export: %s\n", e.msg);
        return e.code;
    }
    size_t n = gr_h5md_info_of(r)->nframes;
    if (!n) {
        no_trajectory(a.in, gr_h5md_info_of(r));
        gr_h5md_reader_free(r);
        return 2;
    }
    long i0, i1, di;
    const char *range = a.frames ? a.frames : a.fmt == XP_LAMMPS_DATA ? "-1" : ":";
    if (parse_range(range, n, &i0, &i1, &di) ||
        (a.fmt == XP_LAMMPS_DATA && (i1 - i0 + di - 1) / di != 1)) {
        fprintf(stderr, "grano export: --frames: '%s' selects no%s frame of the %zu in %s\n", range,
                a.fmt == XP_LAMMPS_DATA ? " single" : "", n, a.in);
        gr_h5md_reader_free(r);
        return 2;
    }
    char part[1200];
    snprintf(part, sizeof part, "%s.part", a.out ? a.out : "");
    FILE *f = a.out ? fopen(part, "w") : stdout;
    if (!f) {
        fprintf(stderr, "grano export: --out: cannot write '%s'\n", part);
        gr_h5md_reader_free(r);
        return 2;
    }
    rc = export_frames(r, &a, i0, i1, di, f, &e);
    gr_h5md_reader_free(r);
    if (a.out) {
        /* written whole or not at all */
        if (fclose(f) && !rc)
            rc = gr_fail(&e, GR_ERUN, "%s: write failed", part);
        if (!rc && rename(part, a.out))
            rc = gr_fail(&e, GR_ERUN, "cannot rename %s to %s", part, a.out);
        if (rc)
            remove(part);
    } else if (fflush(stdout) && !rc) {
        rc = gr_fail(&e, GR_ERUN, "standard output: write failed");
    }
    if (rc)
        fprintf(stderr, "grano export: %s\n", e.msg);
    return rc;
}
