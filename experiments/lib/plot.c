#include "plot.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

const char *gr_plot_format_of(const char *path)
{
    size_t l = strlen(path);
    if (l > 4 && !strcmp(path + l - 4, ".svg"))
        return "svg";
    if (l > 4 && !strcmp(path + l - 4, ".pdf"))
        return "pdf";
    return "png";
}

/* "<path without .png/.svg/.pdf>.<ext>" */
static void sibling(const char *path, const char *ext, char *buf, size_t n)
{
    size_t l = strlen(path);
    if (l > 4 && (!strcmp(path + l - 4, ".png") || !strcmp(path + l - 4, ".svg") || !strcmp(path + l - 4, ".pdf")))
        l -= 4;
    snprintf(buf, n, "%.*s.%s", (int)l, path, ext);
}

void gr_plot_quote(const char *s, char *buf, size_t n)
{
    size_t k = 0;
    if (n < 3)
        return;
    buf[k++] = '\'';
    for (; *s; s++) {
        size_t need = *s == '\'' ? 2 : 1;
        if (k + need + 2 > n)
            break;
        if (*s == '\'')
            buf[k++] = '\'';
        buf[k++] = *s == '\n' ? ' ' : *s;
    }
    buf[k++] = '\'';
    buf[k] = '\0';
}

/* The terminal lines of a script: PNG, SVG or PDF of the same size. */
static void terminal(FILE *f, const char *fmt, const char *out, int w, int h)
{
    char q[1300];
    gr_plot_quote(out, q, sizeof q);
    if (!strcmp(fmt, "svg"))
        fprintf(f, "set terminal svg size %d,%d enhanced font 'DejaVu Sans,11'\n", w, h);
    else if (!strcmp(fmt, "pdf"))
        fprintf(f, "set terminal pdfcairo size %g,%g enhanced font 'DejaVu Sans,9'\n", w / 96.0, h / 96.0);
    else
        fprintf(f, "set terminal pngcairo size %d,%d enhanced font 'DejaVu Sans,11'\n", w, h);
    fprintf(f, "set output %s\n", q);
}

/* The script is written as <script>.part and renamed at close, so that a
 * script under its name is always whole. */
FILE *gr_plot_open(const char *path, int w, int h, gr_err *err)
{
    char gp_path[1200], part[1300];
    sibling(path, "gp", gp_path, sizeof gp_path);
    snprintf(part, sizeof part, "%s.part", gp_path);
    FILE *gp = fopen(part, "w");
    if (!gp) {
        gr_fail(err, GR_ERUN, "%s: cannot write the figure's script", gp_path);
        return NULL;
    }
    fprintf(gp, "# %s: gnuplot %s remakes it (data inline)\n# size %d %d\n", path, gp_path, w, h);
    terminal(gp, gr_plot_format_of(path), path, w, h);
    return gp;
}

int gr_plot_have_gnuplot(void)
{
    return gr_plot_on_path("gnuplot");
}

int gr_plot_on_path(const char *prog)
{
    const char *path = getenv("PATH");
    char dir[1100];
    while (path && *path) {
        size_t l = strcspn(path, ":");
        snprintf(dir, sizeof dir, "%.*s/%s", (int)(l < 900 ? l : 900), path, prog);
        if (l && access(dir, X_OK) == 0)
            return 1;
        path += l + (path[l] == ':');
    }
    return 0;
}

/* Run gnuplot on the saved script, its terminal lines replaced by those of
 * fmt writing <out>.part, which becomes out once gnuplot has succeeded. */
static int render(const char *gp_path, const char *fmt, const char *out, gr_err *err)
{
    FILE *in = fopen(gp_path, "r");
    if (!in)
        return gr_fail(err, GR_ERUN, "%s: cannot read the figure's script", gp_path);
    char line[4096], part[1300];
    snprintf(part, sizeof part, "%s.part", out);
    int w = 800, h = 600, skip = 0;
    /* gnuplot writes the picture to its standard output when it cannot
     * open the file: never onto grano's results. */
    FILE *gp = popen("gnuplot >/dev/null", "w");
    while (gp && fgets(line, sizeof line, in)) {
        if (!skip && sscanf(line, "# size %d %d", &w, &h) == 2) {
            fputs(line, gp);
            terminal(gp, fmt, part, w, h);
            skip = 2; /* the script's own terminal lines that follow */
        } else if (skip && !strncmp(line, "set ", 4) && skip--) {
            continue;
        } else {
            fputs(line, gp);
        }
    }
    fclose(in);
    if (!gp)
        return gr_fail(err, GR_ERUN, "%s: cannot start gnuplot", out);
    fprintf(gp, "unset output\n");
    int st = pclose(gp);
    if (st == -1 || !WIFEXITED(st) || WEXITSTATUS(st) != 0) {
        unlink(part);
        return gr_fail(err, GR_ERUN, "%s: gnuplot failed (status %d; the script is %s)", out, st, gp_path);
    }
    if (rename(part, out)) {
        unlink(part);
        return gr_fail(err, GR_ERUN, "%s: cannot rename %s to it", out, part);
    }
    return GR_OK;
}

int gr_plot_close(FILE *gp, const char *path, gr_err *err)
{
    char gp_path[1200], part[1300], other[1200];
    sibling(path, "gp", gp_path, sizeof gp_path);
    snprintf(part, sizeof part, "%s.part", gp_path);
    if (ferror(gp) | fclose(gp)) {
        unlink(part);
        return gr_fail(err, GR_ERUN, "%s: write failed", gp_path);
    }
    if (rename(part, gp_path)) {
        unlink(part);
        return gr_fail(err, GR_ERUN, "%s: cannot rename %s to it", gp_path, part);
    }
    if (!gr_plot_have_gnuplot())
        return gr_fail(err, GR_ERUN,
                       "gnuplot is not installed, so %s was not drawn (its script is saved as %s): install "
                       "it with 'apt-get install gnuplot-nox' (./grano.sh deps does)", path, gp_path);
    const char *fmt = gr_plot_format_of(path);
    int rc = render(gp_path, fmt, path, err);
    /* GRANO_FIGURES=svg,pdf: the same figure in those formats too */
    const char *more = getenv("GRANO_FIGURES");
    for (const char *f = "svg\0pdf\0"; !rc && more && *f; f += strlen(f) + 1)
        if (strstr(more, f) && strcmp(f, fmt)) {
            sibling(path, f, other, sizeof other);
            rc = render(gp_path, f, other, err);
        }
    return rc;
}

/* A log axis's tic label as people write it: plain from 0.01 to 9999,
 * otherwise a power of ten, 10^{-6} or 2×10^{-6} (enhanced text), never
 * gnuplot's 1x10-6 or 1e-06. */
static void tic_label(char *out, size_t n, double v)
{
    if (v >= 0.01 && v < 1e4) {
        snprintf(out, n, "%g", v);
        return;
    }
    int e = (int)floor(log10(v) + 1e-9);
    double m = v / pow(10, e);
    if (fabs(m - 1) < 1e-9)
        snprintf(out, n, "10^{%d}", e);
    else
        snprintf(out, n, "%g×10^{%d}", m, e);
}

/* Labelled tics on a log axis over [lo, hi]: the coarsest of three
 * mantissa sets that puts three or more in range. */
static void log_tics(FILE *gp, const char *axis, double lo, double hi)
{
    static const double sets[3][9] = {{1, 2, 5}, {1, 1.5, 2, 3, 4, 5, 6, 7, 8}, {1, 1.1, 1.2, 1.3, 1.5, 2, 3, 5, 7}};
    static const int len[3] = {3, 9, 9};
    for (int k = 0; k < 3; k++) {
        double v[64];
        int n = 0;
        for (double dec = pow(10, floor(log10(lo))); dec <= hi && n < 56; dec *= 10)
            for (int j = 0; j < len[k]; j++)
                if (sets[k][j] * dec >= lo && sets[k][j] * dec <= hi)
                    v[n++] = sets[k][j] * dec;
        /* many decades: gnuplot's own tics at the powers of ten */
        if (n > 12 && k == 0) {
            fprintf(gp, "set %stics auto\nset format %s \"10^{%%L}\"\n", axis, axis);
            return;
        }
        if (n >= 3 || k == 2) {
            fprintf(gp, "set %stics (", axis);
            for (int j = 0; j < n; j++) {
                char lab[48];
                tic_label(lab, sizeof lab, v[j]);
                fprintf(gp, "%s\"%s\" %.8g", j ? ", " : "", lab, v[j]);
            }
            fprintf(gp, ")\n");
            return;
        }
    }
}

void gr_plot_log_axis(FILE *gp, const char *axis, double lo, double hi)
{
    if (!(lo > 0) || !(hi >= lo) || !isfinite(hi))
        return;
    /* data within a thousandth of a decade (0.23 %) are one value: a band around it */
    double span = log10(hi / lo), pad = span > 1e-3 ? 0.1 * span : 0.05;
    double a = lo / pow(10, pad), b = hi * pow(10, pad);
    fprintf(gp, "set logscale %s\nset %srange [%.8g:%.8g]\n", axis, axis, a, b);
    log_tics(gp, axis, a, b);
}
