/* grano silo-start: figures (gnuplot, data inline) and plain tables. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "parts.h"
#include "plot.h"
#include "silo_start.h"

const long ss_fig32_steps[6] = {300, 700, 1100, 1700, 6300, 10000};


static void datablock(FILE *gp, const char *name, const double *v, size_t rows, size_t cols,
                      int skip_nonpos_col)
{
    fprintf(gp, "$%s << EOD\n", name);
    for (size_t i = 0; i < rows; i++) {
        if (skip_nonpos_col >= 0 && !(v[i * cols + (size_t)skip_nonpos_col] > 0))
            continue;
        int finite = 1;
        for (size_t j = 0; j < cols; j++)
            finite &= isfinite(v[i * cols + j]);
        if (!finite)
            continue;
        for (size_t j = 0; j < cols; j++)
            fprintf(gp, "%.8g%c", v[i * cols + j], j + 1 < cols ? ' ' : '\n');
    }
    fprintf(gp, "EOD\n");
}

int ss_fig_velocity(const char *png, const ss_ctx *c, const ss_res *r, const long *steps,
                        size_t nsteps, gr_err *err)
{
    int nx = (int)r->grid[0], ny = (int)r->grid[1];
    FILE *gp = gr_plot_open(png, 200 * (int)nsteps + 190, 580, err);
    if (!gp)
        return err->code;
    double vmax = 1e-9;
    for (size_t k = 0; k < nsteps; k++) {
        size_t j = 0;
        while (j < c->ntimes && c->times[j] != steps[k])
            j++;
        fprintf(gp, "$f%zu << EOD\n", k);
        for (int iy = 0; iy < ny; iy++) {
            for (int ix = 0; ix < nx; ix++) {
                double v = j < c->ntimes ? -r->vy[j * (size_t)(nx * ny) + (size_t)(iy * nx + ix)] : NAN;
                if (isfinite(v) && v > vmax)
                    vmax = v;
                fprintf(gp, "%g %g %g\n", r->grid[2] + (ix + 0.5) * r->grid[4],
                        r->grid[3] + (iy + 0.5) * r->grid[5], isfinite(v) ? v : 0.0);
            }
            fprintf(gp, "\n");
        }
        fprintf(gp, "EOD\n");
    }
    fprintf(gp, "set multiplot title 'Mean downward velocity -v_y, D = %g d, %d discharges (thesis fig. 3.2)'\n",
            r->D, c->nreal);
    fprintf(gp, "set size ratio -1\nset cbrange [0:%g]\nunset key\nset tics font ',8'\n", vmax);
    fprintf(gp, "set xlabel 'x / d' font ',9'\nset cblabel '-v_y / (g d)^{1/2}'\n");
    fprintf(gp, "set palette defined (0 '#ffffff', 0.15 '#fdbb2d', 0.5 '#b21f1f', 1 '#1a2a6c')\n");
    for (size_t k = 0; k < nsteps; k++) {
        /* panels placed by hand up to 0.92 of the width: the colour bar
         * has the rest, clear of the last panel */
        double w = 0.86 / (double)nsteps, x0 = 0.03 + (double)k * w;
        fprintf(gp, "set lmargin at screen %g\nset rmargin at screen %g\nset tmargin at screen 0.86\n"
                    "set bmargin at screen 0.12\n", x0 + 0.022, x0 + w - 0.004);
        fprintf(gp, k ? "unset ylabel\n" : "set ylabel 'y / d' font ',9'\n");
        fprintf(gp, "set title '%ld steps'\n%s", steps[k], k + 1 < nsteps ? "unset colorbox\n"
                    : "set colorbox user origin screen 0.91, 0.2 size screen 0.012, 0.6\n");
        fprintf(gp, "plot $f%zu using 1:2:3 with image\n", k);
    }
    fprintf(gp, "unset multiplot\n");
    return gr_plot_close(gp, png, err);
}

static const char *const marks[] = {"pt 6 ps 1.1", "pt 4 ps 1.1", "pt 8", "pt 10", "pt 12", "pt 2"};

int ss_fig_pdf(const char *png, const ss_res *res, size_t nr, int w, int vert_first,
                   const char *title, gr_err *err)
{
    FILE *gp = gr_plot_open(png, 1100, 480, err);
    if (!gp)
        return err->code;
    for (size_t o = 0; o < nr; o++) {
        fprintf(gp, "$q%zu << EOD\n", o);
        for (int b = 0; b < NB; b++)
            fprintf(gp, "%g %g %g\n", res[o].pdf[w][b][0], res[o].pdf[w][b][1], res[o].pdf[w][b][3]);
        fprintf(gp, "EOD\n");
    }
    fprintf(gp, "set multiplot layout 1,2 title '%s'\nset logscale y\nset format y '10^{%%L}'\nset yrange [1e-5:2]\nset xrange [-%g:%g]\nset key bottom center font ',9' spacing 0.9\n",
            title, UMAX, UMAX);
    fprintf(gp, "P(u) = (2/pi)/(1+u*u)**2\nG(u) = exp(-u*u/2)/sqrt(2*pi)\n");
    for (int panel = 0; panel < 2; panel++) {
        int col = (panel == 0) == vert_first ? 3 : 2; /* 3: vertical, 2: horizontal */
        fprintf(gp, "set xlabel '%s / {/Symbol s}'\nset ylabel 'probability density P'\n",
                col == 3 ? "{/Symbol D}y" : "{/Symbol D}x");
        fprintf(gp, "set title '(%c) %s'\nplot ", 'a' + panel, col == 3 ? "vertical" : "horizontal");
        for (size_t o = 0; o < nr; o++)
            fprintf(gp, "$q%zu using 1:($%d>0?$%d:1/0) with points %s lc rgb 'black' title 'D = %g d (fall %.2g d)', ",
                    o, col, col, marks[o % 6], res[o].D, res[o].stats[w][1]);
        fprintf(gp, "P(x) lw 2 lc rgb 'red' title 'eq. 3.4', G(x) lw 2 lc rgb 'blue' title 'Gaussian'\n");
    }
    fprintf(gp, "unset multiplot\n");
    return gr_plot_close(gp, png, err);
}

int ss_fig_msd(const char *png, const ss_res *res, size_t nr, gr_err *err)
{
    FILE *gp = gr_plot_open(png, 560 * (int)nr, 480, err);
    if (!gp)
        return err->code;
    fprintf(gp, "set multiplot layout 1,%zu title 'Mean square displacement (thesis fig. 3.4)'\n", nr);
    fprintf(gp, "set logscale xy\nset format y '10^{%%L}'\nset xlabel 't / {/Symbol t}'\nset ylabel '<{/Symbol D}^2>/d^2'\nset key top left\n");
    for (size_t o = 0; o < nr; o++) {
        const ss_res *r = &res[o];
        double v[SS_MAX_SLOTS * 3];
        for (size_t s = 0; s < r->ns; s++)
            v[3 * s] = r->lag[s], v[3 * s + 1] = r->mx[s], v[3 * s + 2] = r->my[s];
        char nm[32];
        snprintf(nm, sizeof nm, "m%zu", o);
        datablock(gp, nm, v, r->ns, 3, 1);
        fprintf(gp, "set title 'D = %g d'\n", r->D);
        fprintf(gp, "plot $m%zu using 1:2 with points pt 1 lc rgb 'black' title 'x', $m%zu using 1:3 with points pt 2 lc rgb 'red' title 'y'", o, o);
        for (int comp = 0; comp < 2 && 1; comp++)
            if (r->fit_ok[comp])
                fprintf(gp, ", (x>=%g && x<=%g) ? %g*x**%g : 1/0 lw 2 lc rgb '%s' title '%s: slope %.2f'",
                        r->fit_range[0], r->fit_range[1], r->fit[comp].p[0], r->fit[comp].p[1],
                        comp ? "red" : "black", comp ? "y" : "x", r->fit[comp].p[1]);
        fprintf(gp, "\n");
    }
    fprintf(gp, "unset multiplot\n");
    return gr_plot_close(gp, png, err);
}

int ss_fig_kurtosis(const char *png, const ss_res *res, size_t nr, gr_err *err)
{
    FILE *gp = gr_plot_open(png, 560 * (int)nr, 480, err);
    if (!gp)
        return err->code;
    fprintf(gp, "set multiplot layout 1,%zu title 'Excess kurtosis <x^4>/(3<x^2>^2) - 1 against distance fallen (thesis fig. 3.6)'\n", nr);
    fprintf(gp, "set logscale x\nset format x '10^{%%L}'\nset xlabel 'mean distance fallen / d'\nset ylabel 'excess kurtosis {/Symbol k} (dimensionless)'\n"
                "set key below\n");
    for (size_t o = 0; o < nr; o++) {
        const ss_res *r = &res[o];
        double v[SS_MAX_SLOTS * 3];
        for (size_t s = 0; s < r->ns; s++)
            v[3 * s] = r->fall[s], v[3 * s + 1] = r->kx[s], v[3 * s + 2] = r->ky[s];
        char nm[32];
        snprintf(nm, sizeof nm, "k%zu", o);
        datablock(gp, nm, v, r->ns, 3, 0);
        fprintf(gp, "set title 'D = %g d'\n", r->D);
        fprintf(gp, "plot $k%zu using 1:2 with linespoints pt 6 lc rgb 'black' title 'horizontal', $k%zu using 1:3 with linespoints pt 4 lc rgb 'red' title 'vertical', 0 lc rgb 'gray' notitle\n", o, o);
    }
    fprintf(gp, "unset multiplot\n");
    return gr_plot_close(gp, png, err);
}

/* Field times of orifice o with a change measured (the discharge reached
 * the second field time). */
static size_t stationarity_points(const ss_ctx *c, const double *table, size_t o)
{
    size_t n = 0;
    for (size_t j = 0; j < c->ntimes; j++)
        n += isfinite(table[(o * c->ntimes + j) * 3 + 2]) != 0;
    return n;
}

int ss_fig_stationarity(const char *png, const ss_ctx *c, const ss_res *res, size_t nr,
                        const double *table, gr_err *err)
{
    size_t any = 0;
    for (size_t o = 0; o < nr; o++)
        any += stationarity_points(c, table, o);
    if (!any) { /* discharges shorter than two field times (--max-steps): no figure, not an empty one */
        remove(png);
        return GR_OK;
    }
    FILE *gp = gr_plot_open(png, 700, 480, err);
    if (!gp)
        return err->code;
    for (size_t o = 0; o < nr; o++) {
        fprintf(gp, "$s%zu << EOD\n", o);
        for (size_t j = 0; j < c->ntimes; j++) {
            const double *row = table + (o * c->ntimes + j) * 3;
            if (isfinite(row[2]))
                fprintf(gp, "%g %g\n", row[0], row[2]);
        }
        fprintf(gp, "EOD\n");
    }
    fprintf(gp, "set logscale x\nset xlabel 'steps after opening'\nset ylabel '|v_j - v_{j-1}| / |v_j|'\n");
    fprintf(gp, "set title 'Approach of the velocity field to the stationary profile'\nplot ");
    int first = 1;
    for (size_t o = 0; o < nr; o++)
        if (stationarity_points(c, table, o)) {
            fprintf(gp, "%s$s%zu using 1:2 with linespoints %s title 'D = %g d'", first ? "" : ", ", o,
                    marks[o % 6], res[o].D);
            first = 0;
        }
    fprintf(gp, "\n");
    return gr_plot_close(gp, png, err);
}

int ss_pictures(const ss_ctx *c, char *const *parts, size_t last_orif, gr_err *err)
{
    gr_particles *p = gr_particles_create(0, err);
    if (!p)
        return err->code;
    silo_cfg cfg = c->base;
    cfg.orifice = c->orifice[last_orif];
    gr_scene *sc = silo_scene(&cfg, 0, err);
    int rc = sc ? GR_OK : err->code;
    char png[1200], title[128];
    gr_ckpt *ck = rc ? NULL : gr_ckpt_open(parts[last_orif * (size_t)c->nreal], err);
    if (!rc && !ck)
        rc = err->code;
    if (!rc && !(rc = exp_get_particles(ck, "final", p, err))) {
        snprintf(png, sizeof png, "%s/silo_snapshot.png", c->dir);
        snprintf(title, sizeof title, "silo-start, D = %g d, end of the start of the discharge", cfg.orifice);
        rc = gr_plot_snapshot(png, p, sc->width, cfg.base + cfg.height + 2,
                              exp_get_scalar(ck, "steps") * cfg.dt, title, err);
    }
    size_t nf = 0;
    gr_err ig = {0};
    if (!rc && !gr_ckpt_len(ck, "filling", &nf, &ig) && !(rc = exp_get_particles(ck, "filling", p, err))) {
        snprintf(png, sizeof png, "%s/fig3_1_filling.png", c->dir);
        rc = gr_plot_snapshot(png, p, sc->width, sc->height, exp_get_scalar(ck, "t_filling"),
                              cfg.hopper ? "filling through the hopper (thesis fig. 3.1)"
                                         : "filling (quick mode: from a lattice in the silo, no hopper)", err);
    }
    if (ck) {
        gr_ckpt_close(ck, &ig);
    }
    gr_scene_free(sc);
    gr_particles_free(p);
    return rc;
}

