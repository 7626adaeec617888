/* grano movie RESULT.h5 OUT.mp4|OUT.gif: the frames of a result drawn by
 * one gnuplot process on one colour scale, encoded by ffmpeg (MP4) or by
 * gnuplot itself (GIF). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cmd.h"
#include "files.h"
#include "movie_enc.h"
#include "opts.h"
#include "view.h"

static void usage(FILE *f)
{
    fprintf(f,
        "usage: grano movie RESULT.h5 OUT.mp4|OUT.gif [options]\n\n"
        "The frames of a grano result as a movie, drawn as grano plot draws one, on one\n"
        "colour scale for the whole movie. MP4 (H.264) needs ffmpeg (apt-get install\n"
        "ffmpeg; ./grano.sh deps --optional); a GIF needs only gnuplot.\n\n"
        "options:\n"
        "      --every K        every K-th frame (default 1: all)\n"
        "      --from T         frames from time T on\n"
        "      --to T           frames up to time T\n"
        "      --fps N          frames per second, 1 to 60 (default 10)\n");
    vw_usage_common(f);
    fprintf(f,
        "                       (over all the frames drawn)\n"
        "  -h, --help           this help\n"
        "      --version        the version\n\n"
        "Prints OUT and its frames. Bad input exits with code 2, nothing written; the\n"
        "frames are drawn in a folder beside OUT, removed at the end.\n");
}

/* The frames drawn: those in [from, to], then every K-th of them. */
static size_t *select_frames(const vw_view *v, const vw_opts *o, size_t *m, gr_err *err)
{
    size_t n = vw_count(v), *sel = malloc((n + 1) * sizeof *sel), kept = 0;
    const double *t = vw_times(v);
    if (!sel) {
        gr_fail(err, GR_ERUN, "out of memory");
        return NULL;
    }
    *m = 0;
    for (size_t k = 0; k < n; k++) {
        double eps = 1e-9 * fmax(1.0, fabs(t[k]));
        if (t[k] >= o->from - eps && t[k] <= o->to + eps && kept++ % (size_t)o->every == 0)
            sel[(*m)++] = k;
    }
    if (!*m) {
        gr_fail(err, GR_EINPUT, "--from/--to: no frame in [%g, %g] (the file's %zu frames span t = %g .. %g)",
                o->from, o->to, n, t[0], t[n - 1]);
        free(sel);
        return NULL;
    }
    return sel;
}

/* Values of every frame drawn, a stride of them beyond this many. */
#define POOL_MAX ((size_t)1 << 24)

typedef struct {
    double *v;
    size_t n, cap, stride, seen;
} pool;

static int pool_add(pool *p, const double *v, size_t n, gr_err *err)
{
    for (size_t i = 0; i < n; i++, p->seen++) {
        if (p->seen % p->stride)
            continue;
        if (p->n == p->cap) {
            size_t cap = p->cap ? 2 * p->cap : 4096;
            double *x = cap <= POOL_MAX ? realloc(p->v, cap * sizeof *x) : NULL;
            if (!x && cap <= POOL_MAX)
                return gr_fail(err, GR_ERUN, "out of memory");
            if (!x) { /* full: keep every other value, and from now on half as many */
                for (size_t k = 0; k < p->n / 2; k++)
                    p->v[k] = p->v[2 * k];
                p->n /= 2, p->stride *= 2;
                continue;
            }
            p->v = x, p->cap = cap;
        }
        p->v[p->n++] = v[i];
    }
    return GR_OK;
}

/* The colour scale and the network's force scale over all frames drawn. */
static int scales(vw_view *v, const vw_opts *o, const size_t *sel, size_t m, double range[2], double *fref,
                  char *label, size_t n, gr_err *err)
{
    pool val = {.stride = 1}, fn = {.stride = 1};
    int rc = GR_OK;
    int need = !o->has_range || o->contacts;
    for (size_t s = 0; need && s < m && !rc; s++) {
        const double *x, *f;
        size_t nx, nf;
        if (mv_caught())
            rc = gr_fail(err, GR_ERUN, "interrupted");
        else if (!(rc = vw_load(v, sel[s], err))) {
            vw_values(v, &x, &nx);
            vw_forces(v, &f, &nf);
            rc = (o->has_range ? 0 : pool_add(&val, x, nx, err)) || pool_add(&fn, f, nf, err) ? err->code : 0;
        }
    }
    static const double top[2] = {0, 98};
    double fr[2];
    gr_plot_percentiles(fn.v, fn.n, top, fr);
    *fref = fn.n ? fr[1] : 0;
    if (o->has_range) {
        range[0] = o->range[0], range[1] = o->range[1];
        snprintf(label, n, "%s", vw_label(v));
    } else {
        gr_plot_percentiles(val.v, val.n, o->pct, range);
        char l[300];
        gr_plot_scale_label(vw_label(v), o->pct, l, sizeof l);
        snprintf(label, n, "%s of the %zu frames", l, m);
    }
    free(val.v);
    free(fn.v);
    return rc;
}

/* The script: one gnuplot terminal for all frames; a GIF's frames go into
 * part one after another, an MP4's into dir/f000000.png ... */
static int write_script(vw_view *v, const vw_opts *o, const size_t *sel, size_t m, int gif, const char *dir,
                        const char *part, const char *gp_path, gr_err *err)
{
    double range[2] = {0, 1}, fref = 0;
    char label[500], q[1400], f[1400];
    int w, h;
    if (scales(v, o, sel, m, range, &fref, label, sizeof label, err))
        return err->code;
    vw_size(v, &w, &h);
    FILE *gp = fopen(gp_path, "w");
    if (!gp)
        return gr_fail(err, GR_ERUN, "%s: cannot write the movie's script", gp_path);
    if (gif) {
        gr_plot_quote(part, q, sizeof q);
        fprintf(gp, "set terminal gif animate delay %ld loop 0 size %d,%d enhanced font 'DejaVu Sans,11'\n"
                    "set output %s\n", (100 + o->fps / 2) / o->fps, w, h, q);
    } else {
        fprintf(gp, "set terminal pngcairo size %d,%d enhanced font 'DejaVu Sans,11'\n", w, h);
    }
    int rc = GR_OK;
    for (size_t s = 0; s < m && !rc; s++) {
        if (mv_caught())
            rc = gr_fail(err, GR_ERUN, "interrupted");
        if (rc || (rc = vw_load(v, sel[s], err)))
            break;
        if (!gif) {
            snprintf(f, sizeof f, "%s/f%06zu.png", dir, s);
            gr_plot_quote(f, q, sizeof q);
            fprintf(gp, "set output %s\n", q);
        }
        vw_body(v, gp, range[0], range[1], fref, label);
    }
    fprintf(gp, "unset output\n");
    if ((ferror(gp) | fclose(gp)) && !rc)
        rc = gr_fail(err, GR_ERUN, "%s: write failed", gp_path);
    return rc;
}

static int make_movie(vw_view *v, const vw_opts *o, const char *out, int gif, size_t *m, gr_err *err)
{
    char dir[1300] = "", part[1300], gp[1400], log[1400];
    snprintf(part, sizeof part, "%s.part", out);
    size_t *sel = select_frames(v, o, m, err);
    int rc = sel ? mv_tmpdir(out, dir, sizeof dir, err) : err->code;
    snprintf(gp, sizeof gp, "%s/movie.gp", dir);
    snprintf(log, sizeof log, "%s/gnuplot.log", dir);
    char *argv[] = {"gnuplot", gp, NULL};
    if (!rc && !(rc = write_script(v, o, sel, *m, gif, dir, part, gp, err)) && !(rc = mv_run(argv, log, err)) &&
        !gif)
        rc = mv_encode_mp4(dir, o->fps, part, err);
    if (!rc && rename(part, out))
        rc = gr_fail(err, GR_ERUN, "cannot rename %s to %s", part, out);
    if (rc)
        remove(part);
    mv_rmdir(dir);
    free(sel);
    return rc;
}

/* OUT's kind, and the programs it needs: refused up front, saying how to
 * install them, so that no work is lost. */
static int check_out(const char *out, int *gif, gr_err *err)
{
    size_t l = strlen(out);
    *gif = l > 4 && !strcmp(out + l - 4, ".gif");
    if (!*gif && !(l > 4 && !strcmp(out + l - 4, ".mp4")))
        return gr_fail(err, GR_EINPUT, "OUT: '%s' does not end in .mp4 or .gif", out);
    if (!gr_plot_have_gnuplot())
        return gr_fail(err, GR_EINPUT, "%s needs gnuplot, which is not installed: 'apt-get install gnuplot-nox' "
                       "(./grano.sh deps does)", out);
    if (!*gif && !gr_plot_on_path("ffmpeg"))
        return gr_fail(err, GR_EINPUT, "%s needs ffmpeg, which is not installed: 'apt-get install ffmpeg' "
                       "(./grano.sh deps --optional does), or ask for a .gif, which gnuplot makes alone", out);
    return exp_check_writable(out, "OUT", 1, err);
}

int cmd_movie(int argc, char **argv)
{
    vw_opts o;
    vw_opts_init(&o);
    int first, gif = 0, rc = exp_getopt_main("movie", argc, argv, vw_options(1), vw_option, &o, usage, 2, &first);
    if (rc >= 0)
        return rc;
    gr_err e = {0};
    if (argc - first < 2)
        gr_fail(&e, GR_EINPUT, "%s", first < argc ? "missing OUT.mp4 or OUT.gif" : "missing RESULT.h5 and OUT");
    else
        vw_opts_check(&o, 1, &e);
    if (e.code) {
        fprintf(stderr, "grano movie: %s (see grano movie --help)\n", e.msg);
        return 2;
    }
    const char *out = argv[first + 1];
    size_t m = 0;
    vw_view *v = check_out(out, &gif, &e) ? NULL : vw_open(argv[first], &o, &e);
    mv_catch();
    if (v)
        make_movie(v, &o, out, gif, &m, &e);
    vw_free(v);
    mv_release();
    if (e.code) {
        fprintf(stderr, "grano movie: %s\n", e.msg);
        return e.code;
    }
    printf("%s: %zu frames\n", out, m);
    return 0;
}
