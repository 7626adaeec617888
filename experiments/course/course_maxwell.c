/* grano course maxwell: elastic disks started at one speed relax to
 * Maxwell's speed distribution within a few collisions per disk; the
 * distance to it after C/N = 0.5, 1, 2, 3 and --collisions (10) collisions
 * per disk. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "course.h"
#include "plot.h"
#include "stats.h"
#include "table.h"

#define NSTAGE 5
#define NBIN 24

typedef struct {
    long n, runs;
    double L, v0;
    double stage[NSTAGE];     /* collisions per disk at each histogram */
    double *speeds;           /* [stage][run * n + i] */
    gr_hist *hist[NSTAGE];
    gr_scene *sc0;            /* the first run's scene, for the result file */
    double ks[NSTAGE], tab[NSTAGE * 5], htab[NBIN * (NSTAGE + 2)];
} maxwell;

/* Maxwell's speed law in 2D for <v^2> = V0^2: F(v) = 1 - exp(-v^2/V0^2). */
static double maxwell_cdf(double v, void *u)
{
    double v0 = *(const double *)u;
    return v > 0 ? 1.0 - exp(-v * v / (v0 * v0)) : 0.0;
}

/* One realisation: the speeds at each stage into the histograms. */
static int one_run(const course_opts *o, maxwell *w, long r, gr_err *err)
{
    long n = w->n;
    char text[1024];
    snprintf(text, sizeof text,
             "[scene]\nname = course-maxwell\nseed = %lu\n[domain]\nwidth = %g\nheight = %g\n"
             "[material]\nrestitution = 1\n[species]\ndiameter = 1\ncount = %ld\n"
             "[init]\nkind = lattice\nspacing = %g\nvelocity = speed\nv0 = %g\n",
             o->seed + (unsigned long)r, w->L, w->L, n, course_spacing(n, w->L), w->v0);
    gr_scene *sc;
    gr_sim *s;
    if (course_sim(text, o, NULL, &sc, &s, err))
        return err->code;
    uint64_t pairs;
    gr_particles *p = gr_particles_create((size_t)n, err);
    int rc = !p ? err->code : course_pairs(s, "grano course maxwell", &pairs, err);
    for (int k = 0; k < NSTAGE && !rc; k++) {
        if ((rc = course_advance_pairs(s, (uint64_t)(w->stage[k] * n), err)) || (rc = gr_sim_snapshot(s, p, err)))
            break;
        for (long i = 0; i < n; i++) {
            double v = hypot(p->vx[i], p->vy[i]);
            w->speeds[(size_t)k * (size_t)(n * w->runs) + (size_t)(r * n + i)] = v;
            gr_hist_add(w->hist[k], v);
        }
    }
    gr_particles_free(p);
    gr_sim_free(s);
    if (r == 0)
        w->sc0 = sc;
    else
        gr_scene_free(sc);
    return rc;
}

/* Distances to Maxwell (KS and chi^2) and the table rows of each stage. */
static int distances(maxwell *w, gr_err *err)
{
    size_t ns = (size_t)(w->n * w->runs);
    double dens[NSTAGE][NBIN], centre[NBIN], v0 = w->v0;
    for (int k = 0; k < NSTAGE; k++) {
        double chi2, pv;
        int dof;
        if (gr_ks_distance(w->speeds + (size_t)k * ns, ns, maxwell_cdf, &v0, &w->ks[k], err) ||
            gr_hist_chi2(w->hist[k], maxwell_cdf, &v0, 5, &chi2, &dof, &pv, err))
            return err->code ? err->code : GR_ERUN;
        gr_hist_density(w->hist[k], centre, dens[k], NULL);
        double row[5] = {w->stage[k], w->ks[k], chi2, dof, pv};
        memcpy(w->tab + 5 * k, row, sizeof row);
    }
    for (int b = 0; b < NBIN; b++) {
        double *h = w->htab + b * (NSTAGE + 2);
        h[0] = centre[b];
        for (int k = 0; k < NSTAGE; k++)
            h[1 + k] = dens[k][b];
        h[NSTAGE + 1] = 2 * centre[b] / (v0 * v0) * exp(-centre[b] * centre[b] / (v0 * v0));
    }
    return GR_OK;
}

static void print_rows(FILE *f, const double *v, int rows, int cols)
{
    for (int r = 0; r < rows; r++)
        for (int c = 0; c < cols; c++)
            fprintf(f, "%.8g%c", v[r * cols + c], c + 1 < cols ? ' ' : '\n');
}

/* maxwell.dat (the distances, then the histograms) and maxwell.h5. */
static int write_results(const course_opts *o, const maxwell *w, gr_err *err)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/maxwell.dat", o->out);
    FILE *f = exp_dat_open(path, err);
    if (!f)
        return err->code;
    fprintf(f, "# collisions/N KS chi2 dof p   (data set 0; data set 1, the histograms, follows)\n");
    print_rows(f, w->tab, NSTAGE, 5);
    /* Two blank lines end a data set for gnuplot's `index`. */
    fprintf(f, "\n\n# v f(v) at C/N = 0.5 1 2 3 %g, Maxwell 2v/V0^2 exp(-v^2/V0^2)   (data set 1)\n", w->stage[NSTAGE - 1]);
    print_rows(f, w->htab, NBIN, NSTAGE + 2);
    if (exp_dat_close(f, path, err))
        return err->code;
    char what[128];
    snprintf(what, sizeof what, "speed, density at C/N = 0.5 1 2 3 %g, Maxwell 2v/V0^2 exp(-v^2/V0^2)",
             w->stage[NSTAGE - 1]);
    gr_h5md *h = course_h5(o, "maxwell.h5", w->sc0, err);
    int rc = !h || exp_put_result(h, "maxwell/distance", NSTAGE, 5, "collisions_per_grain,ks,chi2,dof,pvalue",
                                  "distance to Maxwell after C/N collisions", w->tab, err) ||
             exp_put_result(h, "maxwell/histograms", NBIN, NSTAGE + 2, NULL,
                            what, w->htab, err);
    rc = course_h5_close(h, o, "maxwell.h5", rc ? (err->code ? err->code : GR_ERUN) : GR_OK, err);
    return rc ? (err->code ? err->code : GR_ERUN) : GR_OK;
}

static int plot(const course_opts *o, const maxwell *w, gr_err *err)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/maxwell.png", o->out);
    FILE *gp = gr_plot_open(path, 1200, 500, err);
    if (!gp)
        return err->code;
    fprintf(gp, "$h << EOD\n");
    for (int b = 0; b < NBIN; b++)
        for (int c = 0; c < NSTAGE + 2; c++)
            fprintf(gp, "%.6g%c", w->htab[b * (NSTAGE + 2) + c], c + 1 < NSTAGE + 2 ? ' ' : '\n');
    fprintf(gp, "EOD\n$k << EOD\n");
    for (int k = 0; k < NSTAGE; k++)
        fprintf(gp, "%g %g\n", w->stage[k], w->ks[k]);
    fprintf(gp, "EOD\nset multiplot layout 1,2\n");
    fprintf(gp, "set title 'Speed histograms, %ld disks x %ld runs'\nset xlabel 'v / V_0'\n"
                "set ylabel 'f(v) / V_0^{-1}'\nset key top right\n", w->n, w->runs);
    fprintf(gp, "plot for [k=2:6] $h u 1:k w histeps lw 2 t sprintf('C/N = %%s', word('0.5 1 2 3 %g', k-1)), "
                "2*x*exp(-x*x) w l lw 3 dt 2 lc 'black' t 'Maxwell'\n", w->stage[NSTAGE - 1]);
    fprintf(gp, "set title 'Kolmogorov-Smirnov distance to Maxwell'\nset xlabel 'collisions per disk C/N'\n"
                "set ylabel 'KS distance D (dimensionless)'\nset logscale xy\nset key top right\n");
    fprintf(gp, "plot $k w lp pt 7 lw 2 t 'measured', %g w l dt 2 lc 'black' t 'noise of %ld exact Maxwell samples'\n"
                "unset multiplot\n",
            0.87 / sqrt((double)(w->n * w->runs)), w->n * w->runs);
    return gr_plot_close(gp, path, err);
}

static void report(const course_opts *o, const maxwell *w)
{
    gr_progress_finish(o->pg);
    printf("maxwell: %ld elastic disks in a %g x %g box, %ld runs, %s\n", w->n, w->L, w->L, w->runs,
           course_how(o));
    printf("  collisions/N   KS distance   chi2/dof   p-value\n");
    for (int k = 0; k < NSTAGE; k++) {
        const double *r = w->tab + 5 * k;
        printf("  %12.1f   %11.4f   %8.2f   %7.3g\n", r[0], r[1], r[2] / r[3], r[4]);
    }
    size_t ns = (size_t)(w->n * w->runs);
    printf("  (KS distance of %zu exact Maxwell samples: about %.4f)\n", ns, 0.87 / sqrt((double)ns));
}

int course_maxwell(const course_opts *o, gr_err *err)
{
    maxwell w = {.n = (o->given & COURSE_N) ? o->n : o->quick ? 100 : 400,
                 .runs = (o->given & COURSE_RUNS) ? o->runs : o->quick ? 4 : 25,
                 .v0 = 1.0,
                 .stage = {0.5, 1, 2, 3, (o->given & COURSE_COLLISIONS) ? o->collisions : 10}};
    /* the slides' box: packing fraction pi/16 (400 disks in 40 x 40) */
    if (course_box(o, w.n, M_PI / 16, &w.L, err))
        return err->code;
    if (!(w.stage[NSTAGE - 1] > w.stage[NSTAGE - 2]))
        return gr_fail(err, GR_EINPUT, "--collisions: maxwell's last histogram (%g collisions per disk) must come "
                                       "after its fourth, at 3",
                       w.stage[NSTAGE - 1]);
    size_t ns = (size_t)(w.n * w.runs);
    w.speeds = malloc(NSTAGE * ns * sizeof *w.speeds);
    int rc = w.speeds ? GR_OK : gr_fail(err, GR_ERUN, "out of memory");
    for (int k = 0; k < NSTAGE && !rc; k++)
        if (!(w.hist[k] = gr_hist_create(NBIN, 0.0, 3.0 * w.v0, err)))
            rc = err->code;
    for (long r = 0; r < w.runs && !rc; r++) {
        rc = one_run(o, &w, r, err);
        gr_progress_update(o->pg, (double)(r + 1) / (double)w.runs, "runs done", (double)(r + 1));
    }
    if (!rc && !(rc = distances(&w, err))) {
        report(o, &w);
        rc = write_results(o, &w, err);
    }
    if (!rc)
        rc = plot(o, &w, err);
    if (!rc)
        printf("  wrote %s/maxwell.{h5,dat,png}\n", o->out);
    for (int k = 0; k < NSTAGE; k++)
        gr_hist_free(w.hist[k]);
    free(w.speeds);
    gr_scene_free(w.sc0);
    /* the exercise's claim: the distance shrinks to the sampling noise */
    if (!rc && !(w.ks[NSTAGE - 1] < w.ks[0] && w.ks[NSTAGE - 1] < 3.0 * 0.87 / sqrt((double)ns)))
        rc = gr_fail(err, GR_ERUN, "maxwell: the speed distribution did not relax (KS %g -> %g)", w.ks[0],
                     w.ks[NSTAGE - 1]);
    return rc;
}
