/* What grains and fields look like: the datablocks and commands of one
 * frame, shared by the single figures and the movies. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "plot.h"

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

size_t gr_plot_percentiles(double *v, size_t n, const double pct[2], double range[2])
{
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if (isfinite(v[i]))
            v[m++] = v[i];
    if (!m) {
        range[0] = 0, range[1] = 1;
        return 0;
    }
    qsort(v, m, sizeof *v, cmp_double);
    for (int k = 0; k < 2; k++) {
        double pos = pct[k] / 100.0 * (double)(m - 1);
        size_t i = (size_t)floor(pos);
        i = i > m - 1 ? m - 1 : i;
        double frac = pos - (double)i, next = i + 1 < m ? v[i + 1] : v[i];
        range[k] = v[i] + (next - v[i]) * frac;
    }
    if (!(range[1] > range[0])) {
        double half = fmax(0.5, 1e-6 * fabs(range[0]));
        range[0] -= half, range[1] += half;
    }
    return m;
}

/* 1st, 2nd, 3rd, 4th, 11th, 22nd; 2.5th */
static const char *ordinal(double p)
{
    if (p != floor(p))
        return "th";
    long k = (long)p % 100;
    if (k >= 11 && k <= 13)
        return "th";
    return k % 10 == 1 ? "st" : k % 10 == 2 ? "nd" : k % 10 == 3 ? "rd" : "th";
}

void gr_plot_scale_label(const char *label, const double pct[2], char *buf, size_t n)
{
    snprintf(buf, n, "%s; scale: %g%s to %g%s percentile", label, pct[0], ordinal(pct[0]), pct[1],
             ordinal(pct[1]));
}

/* A title that fits: a long one in a narrow figure gets a smaller font,
 * not a clipped line. */
static void title_line(FILE *f, const char *title, double t, int w)
{
    char esc[600], full[700], q[1420];
    /* a scene's name is text: enhanced mode's marks in it are escaped */
    size_t k = 0, extra = 0;
    for (const char *c = title; *c && k + 3 < sizeof esc; c++) {
        if (strchr("_^@&{}~", *c))
            esc[k++] = '\\', extra++;
        esc[k++] = *c;
    }
    esc[k] = '\0';
    int len = snprintf(full, sizeof full, "%s, t = %.4g τ", esc, t) - 1 - (int)extra;
    gr_plot_quote(full, q, sizeof q);
    /* τ and the like as UTF-8: the GIF terminal has no Symbol font */
    fprintf(f, "set encoding utf8\n");
    double fs = 11.0, fit = 1.7 * (double)w / (double)(len > 1 ? len : 1);
    fprintf(f, "set title %s font ',%.3g'\n", q, fit < fs ? (fit > 6 ? fit : 6) : fs);
}

/* Tics at 1, 2 or 5 times a power of ten, at least 45 pixels apart, so
 * that a narrow box does not crowd its numbers. */
static void tics(FILE *f, double width, double height, double px_per_d)
{
    const char *axis[2] = {"x", "y"};
    double len[2] = {width, height};
    for (int a = 0; a < 2; a++) {
        double want = 45.0 / px_per_d, step = pow(10, floor(log10(want)));
        step *= want <= step ? 1 : want <= 2 * step ? 2 : want <= 5 * step ? 5 : 10;
        if (len[a] > 0 && isfinite(step) && step > 0)
            fprintf(f, "set %stics %g\n", axis[a], step);
    }
}

void gr_plot_disks_size(double width, double height, int *w, int *h)
{
    double s = 800.0 / (width > height ? width : height);
    *w = (int)(width * s) + 230, *h = (int)(height * s) + 60;
}

/* One datablock per width class that has lines (gnuplot warns of an empty
 * one); the classes drawn into has. */
static void lines_body(FILE *f, const gr_plot_disks *d, int has[GR_PLOT_LINE_CLASSES + 1])
{
    for (int c = 0; c <= GR_PLOT_LINE_CLASSES; c++)
        has[c] = 0;
    for (size_t k = 0; k < d->nlines; k++)
        if (d->lines[k].cls >= 1 && d->lines[k].cls <= GR_PLOT_LINE_CLASSES)
            has[d->lines[k].cls] = 1;
    for (int c = 1; c <= GR_PLOT_LINE_CLASSES; c++) {
        if (!has[c])
            continue;
        fprintf(f, "$net%d << EOD\n", c);
        for (size_t k = 0; k < d->nlines; k++)
            if (d->lines[k].cls == c)
                fprintf(f, "%.6g %.6g %.6g %.6g\n", d->lines[k].x, d->lines[k].y, d->lines[k].dx,
                        d->lines[k].dy);
        fprintf(f, "EOD\n");
    }
}

void gr_plot_disks_body(FILE *f, const gr_plot_disks *d)
{
    const gr_particles *p = d->p;
    int w, h, nfixed = 0, nmobile = 0, has[GR_PLOT_LINE_CLASSES + 1] = {0};
    gr_plot_disks_size(d->width, d->height, &w, &h);
    fprintf(f, "$mobile << EOD\n");
    for (size_t i = 0; i < p->n; i++)
        if (!(p->flags[i] & (GR_PF_FIXED | GR_PF_GONE))) {
            fprintf(f, "%.6g %.6g %.6g %.9g\n", p->x[i], p->y[i], p->radius[i], d->value[i]);
            nmobile++;
        }
    fprintf(f, "EOD\n$fixed << EOD\n");
    for (size_t i = 0; i < p->n; i++)
        if ((p->flags[i] & GR_PF_FIXED) && !(p->flags[i] & GR_PF_GONE)) {
            fprintf(f, "%.6g %.6g %.6g\n", p->x[i], p->y[i], p->radius[i]);
            nfixed++;
        }
    fprintf(f, "EOD\n");
    if (d->lines)
        lines_body(f, d, has);
    char q[1100];
    title_line(f, d->title, d->t, w);
    gr_plot_quote(d->label, q, sizeof q);
    fprintf(f, "set size ratio -1\nset xrange [0:%g]\nset yrange [0:%g]\n", d->width, d->height);
    tics(f, d->width, d->height, 800.0 / fmax(d->width, d->height));
    fprintf(f, "set xlabel 'x / d'\nset ylabel 'y / d'\n");
    fprintf(f, "set cblabel %s\nset cbrange [%.17g:%.17g]\n", q, d->lo, d->hi);
    /* under a network the grains take the palette halfway to white, so that
     * the lines stand out (not transparency: the GIF terminal fills
     * transparent disks grey) */
    if (d->lines)
        fprintf(f, "set palette defined (0 '#8d95b6', 0.5 '#d98f8f', 1 '#fedd96')\n");
    else
        fprintf(f, "set palette defined (0 '#1a2a6c', 0.5 '#b21f1f', 1 '#fdbb2d')\n");
    fprintf(f, "set style fill solid 1.0 noborder\n");
    /* the mobile grains always, even none (a NaN point), so that the
     * colour bar and the plot command are there */
    if (!nmobile)
        fprintf(f, "$mobile << EOD\nNaN NaN NaN NaN\nEOD\n");
    fprintf(f, "plot $mobile using 1:2:3:4 with circles lc palette notitle");
    if (nfixed)
        fprintf(f, ", $fixed using 1:2:3 with circles lc rgb '#808080' notitle");
    for (int c = 1; c <= GR_PLOT_LINE_CLASSES; c++)
        if (has[c])
            fprintf(f, ", $net%d using 1:2:3:4 with vectors nohead lw %g lc rgb '#000000' notitle", c, 0.6 * c);
    fprintf(f, "\n");
}

int gr_plot_disks_draw(const char *path, const gr_plot_disks *d, gr_err *err)
{
    int w, h;
    gr_plot_disks_size(d->width, d->height, &w, &h);
    FILE *gp = gr_plot_open(path, w, h, err);
    if (!gp)
        return err->code;
    gr_plot_disks_body(gp, d);
    return gr_plot_close(gp, path, err);
}

static const double default_pct[2] = {2, 98};

int gr_plot_snapshot(const char *png, const gr_particles *p, double width, double height,
                     double t, const char *title, gr_err *err)
{
    double *v = malloc((p->n ? p->n : 1) * sizeof *v), *pool = malloc((p->n ? p->n : 1) * sizeof *pool);
    if (!v || !pool) {
        free(v);
        free(pool);
        return gr_fail(err, GR_ERUN, "out of memory");
    }
    size_t m = 0;
    for (size_t i = 0; i < p->n; i++) {
        v[i] = hypot(p->vx[i], p->vy[i]);
        if (!(p->flags[i] & (GR_PF_FIXED | GR_PF_GONE)))
            pool[m++] = v[i];
    }
    double range[2];
    char label[300];
    gr_plot_percentiles(pool, m, default_pct, range);
    gr_plot_scale_label("|v| / (d/τ)", default_pct, label, sizeof label);
    gr_plot_disks d = {.p = p, .value = v, .lo = range[0], .hi = range[1], .label = label,
                       .width = width, .height = height, .t = t, .title = title};
    int rc = gr_plot_disks_draw(png, &d, err);
    free(v);
    free(pool);
    return rc;
}

void gr_plot_field_size(double width, double height, int *w, int *h)
{
    /* true proportions unless the domain is a long thin strip (a pipe) */
    int square = width < 5 * height && height < 5 * width;
    double s = 800.0 / (width > height ? width : height);
    *w = square ? (int)(width * s) + 200 : width < height ? 400 : 1000;
    *h = square ? (int)(height * s) + 60 : width < height ? 1000 : 400;
}

void gr_plot_field_body(FILE *f, const gr_plot_grid *g, double width, double height, double t,
                        const char *title)
{
    int w, h;
    gr_plot_field_size(width, height, &w, &h);
    int square = width < 5 * height && height < 5 * width;
    fprintf(f, "$field << EOD\n");
    for (int iy = 0; iy < g->ny; iy++) {
        for (int ix = 0; ix < g->nx; ix++)
            fprintf(f, "%.6g %.6g %.9g\n", g->x0 + (ix + 0.5) * g->cx, g->y0 + (iy + 0.5) * g->cy,
                    g->v[(size_t)iy * (size_t)g->nx + (size_t)ix]);
        fprintf(f, "\n");
    }
    fprintf(f, "EOD\n");
    char q[1100];
    title_line(f, title, t, w);
    gr_plot_quote(g->label, q, sizeof q);
    fprintf(f, "%sset xrange [0:%g]\nset yrange [0:%g]\n", square ? "set size ratio -1\n" : "", width, height);
    if (square)
        tics(f, width, height, 800.0 / fmax(width, height));
    fprintf(f, "set xlabel 'x / d'\nset ylabel 'y / d'\nset cblabel %s\n", q);
    fprintf(f, "set cbrange [%.17g:%.17g]\n", g->lo, g->hi);
    fprintf(f, "set palette defined (0 '#ffffff', 0.3 '#fdbb2d', 0.7 '#b21f1f', 1 '#1a2a6c')\n");
    fprintf(f, "plot $field using 1:2:3 with image notitle\n");
}

int gr_plot_field(const char *png, const gr_plot_grid *g, double width, double height, double t,
                  const char *title, gr_err *err)
{
    gr_plot_grid s = *g;
    char label[300];
    if (!(g->lo < g->hi)) {
        size_t nc = (size_t)g->nx * (size_t)g->ny;
        double *pool = malloc((nc ? nc : 1) * sizeof *pool), range[2];
        if (!pool)
            return gr_fail(err, GR_ERUN, "out of memory");
        memcpy(pool, g->v, nc * sizeof *pool);
        gr_plot_percentiles(pool, nc, default_pct, range);
        free(pool);
        s.lo = range[0], s.hi = range[1];
        gr_plot_scale_label(g->label, default_pct, label, sizeof label);
        s.label = label;
    }
    int w, h;
    gr_plot_field_size(width, height, &w, &h);
    FILE *gp = gr_plot_open(png, w, h, err);
    if (!gp)
        return err->code;
    gr_plot_field_body(gp, &s, width, height, t, title);
    return gr_plot_close(gp, png, err);
}
