#include "plot.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

/* "<png without .png>.<ext>" */
static void sibling(const char *png, const char *ext, char *buf, size_t n)
{
    size_t l = strlen(png);
    if (l > 4 && !strcmp(png + l - 4, ".png"))
        l -= 4;
    snprintf(buf, n, "%.*s.%s", (int)l, png, ext);
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

/* The terminal lines of a script: PNG (what the saved script makes), or
 * SVG / PDF of the same size. */
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

FILE *gr_plot_open(const char *png, int w, int h, gr_err *err)
{
    char gp_path[1200];
    sibling(png, "gp", gp_path, sizeof gp_path);
    FILE *gp = fopen(gp_path, "w");
    if (!gp) {
        gr_fail(err, GR_ERUN, "%s: cannot write the figure's script", gp_path);
        return NULL;
    }
    fprintf(gp, "# %s: gnuplot %s remakes it (data inline)\n# size %d %d\n", png, gp_path, w, h);
    terminal(gp, "png", png, w, h);
    return gp;
}

int gr_plot_have_gnuplot(void)
{
    const char *path = getenv("PATH");
    char dir[1100];
    while (path && *path) {
        size_t l = strcspn(path, ":");
        snprintf(dir, sizeof dir, "%.*s/gnuplot", (int)(l < 1000 ? l : 1000), path);
        if (l && access(dir, X_OK) == 0)
            return 1;
        path += l + (path[l] == ':');
    }
    return 0;
}

/* Run gnuplot on the saved script, its terminal lines replaced for fmt. */
static int render(const char *gp_path, const char *fmt, const char *out, gr_err *err)
{
    FILE *in = fopen(gp_path, "r");
    if (!in)
        return gr_fail(err, GR_ERUN, "%s: cannot read the figure's script", gp_path);
    char line[4096];
    int w = 800, h = 600, skip = 0;
    /* gnuplot writes the picture to its standard output when it cannot
     * open the file: never onto grano's results. */
    FILE *gp = popen("gnuplot >/dev/null", "w");
    while (gp && fgets(line, sizeof line, in)) {
        if (sscanf(line, "# size %d %d", &w, &h) == 2 && strcmp(fmt, "png")) {
            terminal(gp, fmt, out, w, h);
            skip = 2; /* the PNG terminal lines that follow */
        } else if (skip && !strncmp(line, "set ", 4)) {
            skip--;
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
        unlink(out);
        return gr_fail(err, GR_ERUN, "%s: gnuplot failed (status %d; the script is %s)", out, st, gp_path);
    }
    return GR_OK;
}

int gr_plot_close(FILE *gp, const char *png, gr_err *err)
{
    char gp_path[1200], other[1200];
    sibling(png, "gp", gp_path, sizeof gp_path);
    if (fclose(gp))
        return gr_fail(err, GR_ERUN, "%s: write failed", gp_path);
    if (!gr_plot_have_gnuplot())
        return gr_fail(err, GR_ERUN,
                       "gnuplot is not installed, so %s was not drawn (its script is saved as %s): install "
                       "it with 'apt-get install gnuplot-nox' (./grano.sh deps does)", png, gp_path);
    int rc = render(gp_path, "png", png, err);
    /* GRANO_FIGURES=svg,pdf: the same figure in those formats too */
    const char *more = getenv("GRANO_FIGURES");
    for (const char *f = "svg\0pdf\0"; !rc && more && *f; f += strlen(f) + 1)
        if (strstr(more, f)) {
            sibling(png, f, other, sizeof other);
            rc = render(gp_path, f, other, err);
        }
    return rc;
}

int gr_plot_snapshot(const char *png, const gr_particles *p, double width, double height,
                     double t, const char *title, gr_err *err)
{
    /* Pixels follow the box's aspect ratio, about 800 on the long side. */
    double s = 800.0 / (width > height ? width : height);
    int w = (int)(width * s) + 230, h = (int)(height * s) + 60; /* room for the colour bar label */
    FILE *gp = gr_plot_open(png, w, h, err);
    if (!gp)
        return err->code;
    double vmax = 0;
    fprintf(gp, "$mobile << EOD\n");
    for (size_t i = 0; i < p->n; i++) {
        if (p->flags[i] & (GR_PF_FIXED | GR_PF_GONE))
            continue;
        double v = hypot(p->vx[i], p->vy[i]);
        vmax = v > vmax ? v : vmax;
        fprintf(gp, "%.6g %.6g %.6g %.6g\n", p->x[i], p->y[i], p->radius[i], v);
    }
    fprintf(gp, "EOD\n$fixed << EOD\n");
    int nfixed = 0;
    for (size_t i = 0; i < p->n; i++)
        if ((p->flags[i] & GR_PF_FIXED) && !(p->flags[i] & GR_PF_GONE)) {
            fprintf(gp, "%.6g %.6g %.6g\n", p->x[i], p->y[i], p->radius[i]);
            nfixed++;
        }
    fprintf(gp, "EOD\n");
    char full[300], q[620];
    int len = snprintf(full, sizeof full, "%s, t = %.4g {/Symbol t}", title, t) - 10;
    gr_plot_quote(full, q, sizeof q);
    /* a long title in a narrow figure: a smaller font, not a clipped line */
    double fs = 11.0, fit = 1.7 * (double)w / (double)(len > 1 ? len : 1);
    fprintf(gp, "set title %s font ',%.3g'\n", q, fit < fs ? (fit > 6 ? fit : 6) : fs);
    fprintf(gp, "set size ratio -1\nset xrange [0:%g]\nset yrange [0:%g]\n", width, height);
    fprintf(gp, "set xlabel 'x / d'\nset ylabel 'y / d'\n");
    fprintf(gp, "set cblabel '|v| / (g d)^{1/2}'\nset cbrange [0:%g]\n", vmax > 0 ? vmax : 1);
    fprintf(gp, "set palette defined (0 '#1a2a6c', 0.5 '#b21f1f', 1 '#fdbb2d')\n");
    fprintf(gp, "set style fill solid 1.0 noborder\n");
    fprintf(gp, "plot $mobile using 1:2:3:4 with circles lc palette notitle");
    if (nfixed)
        fprintf(gp, ", $fixed using 1:2:3 with circles lc rgb '#808080' notitle");
    fprintf(gp, "\n");
    return gr_plot_close(gp, png, err);
}

int gr_plot_field(const char *png, const gr_plot_grid *g, double width, double height, double t,
                  const char *title, gr_err *err)
{
    /* true proportions unless the domain is a long thin strip (a pipe) */
    int square = width < 5 * height && height < 5 * width;
    double s = 800.0 / (width > height ? width : height);
    int w = square ? (int)(width * s) + 200 : width < height ? 400 : 1000;
    int h = square ? (int)(height * s) + 60 : width < height ? 1000 : 400;
    FILE *gp = gr_plot_open(png, w, h, err);
    if (!gp)
        return err->code;
    double vmax = 0;
    fprintf(gp, "$field << EOD\n");
    for (int iy = 0; iy < g->ny; iy++) {
        for (int ix = 0; ix < g->nx; ix++) {
            double v = g->v[(size_t)iy * (size_t)g->nx + (size_t)ix];
            vmax = v > vmax ? v : vmax;
            fprintf(gp, "%.6g %.6g %.6g\n", g->x0 + (ix + 0.5) * g->cx, g->y0 + (iy + 0.5) * g->cy, v);
        }
        fprintf(gp, "\n");
    }
    fprintf(gp, "EOD\n");
    fprintf(gp, "set title '%s, t = %.4g {/Symbol t}'\n", title, t);
    fprintf(gp, "%sset xrange [0:%g]\nset yrange [0:%g]\n", square ? "set size ratio -1\n" : "", width, height);
    fprintf(gp, "set xlabel 'x / d'\nset ylabel 'y / d'\nset cblabel '%s'\n", g->label);
    fprintf(gp, "set cbrange [0:%g]\n", vmax > 0 ? vmax : 1);
    fprintf(gp, "set palette defined (0 '#ffffff', 0.3 '#fdbb2d', 0.7 '#b21f1f', 1 '#1a2a6c')\n");
    fprintf(gp, "plot $field using 1:2:3 with image notitle\n");
    return gr_plot_close(gp, png, err);
}
