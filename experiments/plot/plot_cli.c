/* grano plot RESULT.h5 [OUT]: one frame of a result as a figure. */
#include <stdlib.h>
#include <string.h>

#include "cmd.h"
#include "files.h"
#include "opts.h"
#include "view.h"

static void usage(FILE *f)
{
    fprintf(f,
        "usage: grano plot RESULT.h5 [OUT.png|OUT.svg|OUT.pdf] [options]\n\n"
        "Draw one frame of a grano result (any method; a checkpoint too): the grains as\n"
        "disks coloured by a quantity, fixed grains grey, or a field as a colour map (the\n"
        "lattice gas, which has no grains: its packing fraction). The gnuplot script that\n"
        "remakes the figure is saved beside it (OUT.gp). OUT defaults to RESULT's name\n"
        "and -frameK.png; its format follows its name (.png, .svg, .pdf).\n\n"
        "options:\n"
        "      --frame K        frame K (0 the first; negative from the end; default -1, the last)\n"
        "      --time T         the frame nearest time T\n"
        "      --format F       png, svg or pdf (for the default OUT)\n");
    vw_usage_common(f);
    fprintf(f,
        "  -h, --help           this help\n"
        "      --version        the version\n\n"
        "Prints OUT. Bad input (flags, a quantity or field the file does not hold, a file\n"
        "with nothing to draw) exits with code 2, nothing written.\n");
}

/* OUT's format (png, svg, pdf), checked against --format. */
static int out_format(const char *out, const char *want, const char **fmt, gr_err *err)
{
    const char *dot = strrchr(out, '.'), *slash = strrchr(out, '/');
    if (!dot || (slash && dot < slash) || (strcmp(dot, ".png") && strcmp(dot, ".svg") && strcmp(dot, ".pdf")))
        return gr_fail(err, GR_EINPUT, "OUT: '%s' does not end in .png, .svg or .pdf", out);
    *fmt = dot + 1;
    if (want && strcmp(want, *fmt))
        return gr_fail(err, GR_EINPUT, "--format %s, but OUT '%s' names a %s", want, out, *fmt);
    return GR_OK;
}

/* RESULT without .h5 (or .ckpt), then -frameK.FMT */
static void default_out(const char *in, size_t k, const char *fmt, char *buf, size_t n)
{
    size_t l = strlen(in);
    if (l > 3 && !strcmp(in + l - 3, ".h5"))
        l -= 3;
    else if (l > 5 && !strcmp(in + l - 5, ".ckpt"))
        l -= 5;
    snprintf(buf, n, "%.*s-frame%zu.%s", (int)l, in, k, fmt);
}

static int pick_frame(const vw_view *v, const vw_opts *o, size_t *k, gr_err *err)
{
    size_t n = vw_count(v);
    if (o->has_time) {
        *k = vw_nearest(v, o->time);
        return GR_OK;
    }
    long f = o->has_frame ? o->frame : -1;
    if (f < -(long)n || f >= (long)n)
        return gr_fail(err, GR_EINPUT, "--frame %ld: the file has %zu frames (0 .. %zu, or -%zu .. -1 from the end)",
                       f, n, n - 1, n);
    *k = f < 0 ? (size_t)((long)n + f) : (size_t)f;
    return GR_OK;
}

/* The colour scale (and the network's force scale) of the loaded frame. */
static int scales(const vw_view *v, const vw_opts *o, double range[2], double *fref, char *label, size_t n,
                  gr_err *err)
{
    const double *val, *fn;
    size_t nv, nf;
    vw_values(v, &val, &nv);
    vw_forces(v, &fn, &nf);
    double *pool = malloc((nv > nf ? nv : nf) * sizeof *pool + 1), fr[2];
    if (!pool)
        return gr_fail(err, GR_ERUN, "out of memory");
    static const double top[2] = {0, 98};
    if (nf)
        memcpy(pool, fn, nf * sizeof *pool);
    gr_plot_percentiles(pool, nf, top, fr);
    *fref = nf ? fr[1] : 0;
    if (o->has_range) {
        range[0] = o->range[0], range[1] = o->range[1];
        snprintf(label, n, "%s", vw_label(v));
    } else {
        if (nv)
            memcpy(pool, val, nv * sizeof *pool);
        gr_plot_percentiles(pool, nv, o->pct, range);
        gr_plot_scale_label(vw_label(v), o->pct, label, n);
    }
    free(pool);
    return GR_OK;
}

static int draw(vw_view *v, const vw_opts *o, const char *out, gr_err *err)
{
    double range[2] = {0, 1}, fref = 0;
    char label[400];
    int w, h;
    if (scales(v, o, range, &fref, label, sizeof label, err))
        return err->code;
    vw_size(v, &w, &h);
    FILE *gp = gr_plot_open(out, w, h, err);
    if (!gp)
        return err->code;
    vw_body(v, gp, range[0], range[1], fref, label);
    return gr_plot_close(gp, out, err);
}

int cmd_plot(int argc, char **argv)
{
    vw_opts o;
    vw_opts_init(&o);
    int first, rc = exp_getopt_main("plot", argc, argv, vw_options(0), vw_option, &o, usage, 2, &first);
    if (rc >= 0)
        return rc;
    gr_err e = {0};
    const char *fmt = o.format ? o.format : "png";
    if (first >= argc)
        gr_fail(&e, GR_EINPUT, "missing RESULT.h5");
    else if (!vw_opts_check(&o, 0, &e) && first + 1 < argc)
        out_format(argv[first + 1], o.format, &fmt, &e);
    if (e.code) {
        fprintf(stderr, "grano plot: %s (see grano plot --help)\n", e.msg);
        return 2;
    }
    vw_view *v = vw_open(argv[first], &o, &e);
    size_t k = 0;
    char out[1200];
    if (v && !pick_frame(v, &o, &k, &e)) {
        if (first + 1 < argc)
            snprintf(out, sizeof out, "%s", argv[first + 1]);
        else
            default_out(argv[first], k, fmt, out, sizeof out);
        if (!exp_check_writable(out, "OUT", 1, &e) && !vw_load(v, k, &e))
            draw(v, &o, out, &e);
    }
    vw_free(v);
    if (e.code) {
        fprintf(stderr, "grano plot: %s\n", e.msg);
        return e.code;
    }
    printf("%s\n", out);
    return 0;
}
