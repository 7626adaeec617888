/* grano course: the three exercises of the lecture slides on event-driven
 * hard disks (docs/course.md): relaxation to the Maxwell distribution, wall
 * pressure against density and against V0, homogeneous cooling. Each
 * writes an HDF5 file (results/), a plain table and PNG figures. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_fit.h>

#include "cmd.h"
#include "edmd/edmd.h"
#include "h5md.h"
#include "init.h"
#include "plot.h"
#include "scene.h"
#include "stats.h"

typedef struct {
    const char *out;
    int quick;
    int naive;     /* algorithm v1.0 of the slides instead of the tree */
    double alpha;  /* cooling */
    unsigned long seed;
} course_opts;

/* A scene from text (the same keys as a scene file) and its edmd state. */
static int build(const char *text, const course_opts *o, gr_scene **psc, gr_edmd **ps, gr_err *err)
{
    const char *extra[] = {"edmd", NULL};
    char full[4096];
    snprintf(full, sizeof full, "%s[edmd]\nalgorithm = %s\n", text, o->naive ? "naive" : "tree");
    gr_scene *sc = gr_scene_parse(full, "(grano course)", extra, err);
    if (!sc)
        return err->code;
    gr_particles *p = gr_particles_create(0, err);
    gr_edmd_params prm;
    int rc = !p || gr_init_particles(sc, p, err) || gr_edmd_params_read(sc, &prm, err) ||
             gr_edmd_create(sc, p, &prm, ps, err);
    gr_particles_free(p);
    if (rc) {
        gr_scene_free(sc);
        return err->code ? err->code : GR_ERUN;
    }
    *psc = sc;
    return GR_OK;
}

/* Run until `target` disk-disk collisions have happened. */
static int advance_pairs(gr_edmd *s, uint64_t target, gr_err *err)
{
    gr_edmd_counters c;
    for (gr_edmd_get_counters(s, &c); c.pair < target; gr_edmd_get_counters(s, &c))
        if (gr_edmd_advance(s, INFINITY, target - c.pair, err))
            return err->code;
    return GR_OK;
}

static int put(gr_h5md *h, const char *name, size_t rows, size_t cols, const char *const *names,
               const char *desc, const double *v, gr_err *err)
{
    gr_result_desc d = {.name = name, .rows = rows, .cols = cols, .columns = names, .description = desc};
    return gr_h5md_write_result(h, &d, v, err);
}

static int table(const char *path, const char *head, const double *v, size_t rows, size_t cols, gr_err *err)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return gr_fail(err, GR_EINPUT, "%s: %s", path, strerror(errno));
    fprintf(f, "%s\n", head);
    for (size_t r = 0; r < rows; r++)
        for (size_t c = 0; c < cols; c++)
            fprintf(f, "%.8g%c", v[r * cols + c], c + 1 < cols ? ' ' : '\n');
    return fclose(f) ? gr_fail(err, GR_ERUN, "%s: write failed", path) : GR_OK;
}

/* Maxwell's speed law in 2D for <v^2> = V0^2: F(v) = 1 - exp(-v^2/V0^2). */
static double maxwell_cdf(double v, void *u)
{
    double v0 = *(const double *)u;
    return v > 0 ? 1.0 - exp(-v * v / (v0 * v0)) : 0.0;
}

/* ---- exercise 1: relaxation to the Maxwell distribution ---- */
#define NSTAGE 5
#define NBIN 24
static int ex_maxwell(const course_opts *o, gr_err *err)
{
    long n = o->quick ? 100 : 400, runs = o->quick ? 4 : 25;
    double L = o->quick ? 20 : 40, v0 = 1.0;
    const double stage[NSTAGE] = {0.5, 1, 2, 3, 10};
    gr_hist *hist[NSTAGE] = {0};
    double *speeds = malloc(NSTAGE * (size_t)(n * runs) * sizeof *speeds);
    int rc = speeds ? GR_OK : gr_fail(err, GR_ERUN, "out of memory");
    for (int k = 0; k < NSTAGE && !rc; k++)
        if (!(hist[k] = gr_hist_create(NBIN, 0.0, 3.0 * v0, err)))
            rc = err->code;
    gr_scene *sc0 = NULL;
    for (long r = 0; r < runs && !rc; r++) {
        char text[1024];
        snprintf(text, sizeof text,
                 "[scene]\nname = course-maxwell\nseed = %lu\n[domain]\nwidth = %g\nheight = %g\n"
                 "[material]\nrestitution = 1\n[species]\ndiameter = 1\ncount = %ld\n"
                 "[init]\nkind = lattice\nspacing = %g\nvelocity = speed\nv0 = %g\n",
                 o->seed + (unsigned long)r, L, L, n, 0.99 * L / ceil(sqrt((double)n)), v0);
        gr_scene *sc;
        gr_edmd *s;
        if ((rc = build(text, o, &sc, &s, err)))
            break;
        gr_particles *p = gr_particles_create((size_t)n, err);
        for (int k = 0; k < NSTAGE && !rc && p; k++) {
            if ((rc = advance_pairs(s, (uint64_t)(stage[k] * n), err)) || (rc = gr_edmd_snapshot(s, p, err)))
                break;
            for (long i = 0; i < n; i++) {
                double v = hypot(p->vx[i], p->vy[i]);
                speeds[(size_t)k * (size_t)(n * runs) + (size_t)(r * n + i)] = v;
                gr_hist_add(hist[k], v);
            }
        }
        if (!p && !rc)
            rc = err->code;
        gr_particles_free(p);
        gr_edmd_free(s);
        if (r == 0)
            sc0 = sc;
        else
            gr_scene_free(sc);
    }
    double ks[NSTAGE], chi2[NSTAGE], pv[NSTAGE], dens[NSTAGE][NBIN], centre[NBIN];
    int dof[NSTAGE];
    size_t ns = (size_t)(n * runs);
    for (int k = 0; k < NSTAGE && !rc; k++) {
        rc = gr_ks_distance(speeds + (size_t)k * ns, ns, maxwell_cdf, &v0, &ks[k], err) ||
             gr_hist_chi2(hist[k], maxwell_cdf, &v0, 5, &chi2[k], &dof[k], &pv[k], err);
        gr_hist_density(hist[k], centre, dens[k], NULL);
    }
    char path[1200];
    double tab[NSTAGE * 5], htab[NBIN * (NSTAGE + 2)];
    if (!rc) {
        printf("maxwell: %ld elastic disks in a %g x %g box, %ld runs, algorithm %s\n", n, L, L, runs,
               o->naive ? "naive (v1.0)" : "tree");
        printf("  collisions/N   KS distance   chi2/dof   p-value\n");
        for (int k = 0; k < NSTAGE; k++) {
            printf("  %12.1f   %11.4f   %8.2f   %7.3g\n", stage[k], ks[k], chi2[k] / dof[k], pv[k]);
            double row[5] = {stage[k], ks[k], chi2[k], dof[k], pv[k]};
            memcpy(tab + 5 * k, row, sizeof row);
        }
        printf("  (KS distance of %zu exact Maxwell samples: about %.4f)\n", ns, 0.87 / sqrt((double)ns));
        for (int b = 0; b < NBIN; b++) {
            htab[b * (NSTAGE + 2)] = centre[b];
            for (int k = 0; k < NSTAGE; k++)
                htab[b * (NSTAGE + 2) + 1 + k] = dens[k][b];
            htab[b * (NSTAGE + 2) + NSTAGE + 1] = 2 * centre[b] / (v0 * v0) * exp(-centre[b] * centre[b] / (v0 * v0));
        }
        snprintf(path, sizeof path, "%s/maxwell.dat", o->out);
        rc = table(path, "# collisions/N KS chi2 dof p ; then: v f(v) at each stage, Maxwell", tab, NSTAGE, 5, err);
        FILE *f = rc ? NULL : fopen(path, "a");
        for (int b = 0; f && b < NBIN; b++)
            for (int c = 0; c < NSTAGE + 2; c++)
                fprintf(f, "%.8g%c", htab[b * (NSTAGE + 2) + c], c + 1 < NSTAGE + 2 ? ' ' : '\n');
        if (f)
            fclose(f);
    }
    if (!rc) {
        snprintf(path, sizeof path, "%s/maxwell.h5", o->out);
        gr_h5md_opts ho = {.method = "edmd", .seed = o->seed, .force = 1, .no_xdmf = 1};
        gr_h5md *h = gr_h5md_create(path, sc0, &ho, err);
        const char *cn[5] = {"collisions_per_grain", "ks", "chi2", "dof", "pvalue"};
        rc = !h || put(h, "maxwell/distance", NSTAGE, 5, cn, "distance to Maxwell after C/N collisions", tab, err) ||
             put(h, "maxwell/histograms", NBIN, NSTAGE + 2, NULL,
                 "speed, density at C/N = 0.5 1 2 3 10, Maxwell 2v/V0^2 exp(-v^2/V0^2)", htab, err);
        if (h)
            rc = gr_h5md_close(h, err) || rc;
        rc = rc ? (err->code ? err->code : GR_ERUN) : GR_OK;
    }
    if (!rc) {
        snprintf(path, sizeof path, "%s/maxwell.png", o->out);
        FILE *gp = gr_plot_open(path, 1200, 500, err);
        if (!gp)
            rc = err->code;
        else {
            fprintf(gp, "$h << EOD\n");
            for (int b = 0; b < NBIN; b++)
                for (int c = 0; c < NSTAGE + 2; c++)
                    fprintf(gp, "%.6g%c", htab[b * (NSTAGE + 2) + c], c + 1 < NSTAGE + 2 ? ' ' : '\n');
            fprintf(gp, "EOD\n$k << EOD\n");
            for (int k = 0; k < NSTAGE; k++)
                fprintf(gp, "%g %g\n", stage[k], ks[k]);
            fprintf(gp, "EOD\nset multiplot layout 1,2\n");
            fprintf(gp, "set title 'Speed histograms, %ld disks x %ld runs'\nset xlabel 'v / V_0'\n"
                        "set ylabel 'f(v)'\nset key top right\n", n, runs);
            fprintf(gp, "plot for [k=2:6] $h u 1:k w histeps lw 2 t sprintf('C/N = %%s', word('0.5 1 2 3 10', k-1)), "
                        "2*x*exp(-x*x) w l lw 3 dt 2 lc 'black' t 'Maxwell'\n");
            fprintf(gp, "set title 'Kolmogorov-Smirnov distance to Maxwell'\nset xlabel 'collisions per disk C/N'\n"
                        "set ylabel 'D'\nset logscale xy\nunset key\n");
            fprintf(gp, "plot $k w lp pt 7 lw 2, %g w l dt 2 lc 'black'\nunset multiplot\n",
                    0.87 / sqrt((double)ns));
            rc = gr_plot_close(gp, path, err);
        }
    }
    if (!rc)
        printf("  wrote %s/maxwell.{h5,dat,png}\n", o->out);
    for (int k = 0; k < NSTAGE; k++)
        gr_hist_free(hist[k]);
    free(speeds);
    gr_scene_free(sc0);
    /* the exercise's claim: the distance shrinks to the sampling noise */
    if (!rc && !(ks[NSTAGE - 1] < ks[0] && ks[NSTAGE - 1] < 3.0 * 0.87 / sqrt((double)ns)))
        rc = gr_fail(err, GR_ERUN, "maxwell: the speed distribution did not relax (KS %g -> %g)", ks[0],
                     ks[NSTAGE - 1]);
    return rc;
}

/* Luding's hard-disk equation of state (Phys. Rev. E 63, 042201, 2001). */
static double z_luding(double eta)
{
    double u = 1 - eta;
    return 1 + 2 * eta * ((1 - 7 * eta / 16) / (u * u) - eta * eta * eta / (128 * u * u * u * u));
}

/* Mean wall pressure of n elastic disks of speed v0 in an L x L box. */
static int wall_pressure(const course_opts *o, unsigned long seed, long n, double L, double v0, double *p,
                         double *T, gr_err *err)
{
    char text[1024];
    snprintf(text, sizeof text,
             "[scene]\nname = course-pressure\nseed = %lu\n[domain]\nwidth = %g\nheight = %g\n"
             "[material]\nrestitution = 1\n[species]\ndiameter = 1\ncount = %ld\n"
             "[init]\nkind = lattice\nspacing = %g\nvelocity = speed\nv0 = %g\n",
             seed, L, L, n, fmin(10.0, 0.99 * L / ceil(sqrt((double)n))), v0);
    gr_scene *sc;
    gr_edmd *s;
    if (build(text, o, &sc, &s, err))
        return err->code;
    /* relax (the speeds reach Maxwell's law in a few collisions per disk),
     * then average over a time with many wall hits per disk */
    double t_relax = 20 * L / v0, t_meas = (o->quick ? 200 : 500) * L / v0;
    int rc = gr_edmd_advance(s, t_relax, 0, err);
    if (!rc) {
        gr_edmd_reset_averages(s);
        rc = gr_edmd_advance(s, t_relax + t_meas, 0, err);
    }
    if (!rc) {
        gr_edmd_averages a;
        gr_edmd_get_averages(s, &a);
        *p = a.pressure_walls;
        *T = a.ekin / n;
    }
    gr_edmd_free(s);
    gr_scene_free(sc);
    return rc;
}

/* ---- exercise 2: wall pressure against density and against V0 ---- */
static int ex_pressure(const course_opts *o, gr_err *err)
{
    const double L = 20;
    const long ns_full[] = {4, 8, 16, 32, 64, 100, 144, 196, 256, 324}, ns_quick[] = {4, 16, 64, 196};
    const long *ns = o->quick ? ns_quick : ns_full;
    int nn = o->quick ? 4 : 10;
    const double v0s[] = {0.5, 1, 1.5, 2, 3};
    int nv = o->quick ? 3 : 5;
    long nfix = 100;
    double A[10 * 6], B[5 * 3];
    int rc = GR_OK;
    printf("pressure: elastic disks in a %g x %g box with walls, algorithm %s\n", L, L, o->naive ? "naive" : "tree");
    printf("  N      n=N/L^2   p          n T        p/(nT)   hard-disk EOS p/(nT)\n");
    for (int k = 0; k < nn && !rc; k++) {
        double p = NAN, T = NAN;
        if ((rc = wall_pressure(o, o->seed, ns[k], L, 1.0, &p, &T, err)))
            break;
        double nd = ns[k] / (L * L);
        /* centres stay sigma/2 from the walls: the ideal gas of the box
         * presses n T L / (L - sigma) on them; Z(eta) adds the collisions */
        double ideal = nd * T * L / (L - 1), eos = ideal * z_luding(nd * M_PI / 4);
        double row[6] = {(double)ns[k], nd, p, nd * T, ideal, eos};
        memcpy(A + 6 * k, row, sizeof row);
        printf("  %-5ld  %-8.4f  %-9.5g  %-9.5g  %-7.4f  %.4f\n", ns[k], nd, p, nd * T, p / (nd * T),
               eos / (nd * T));
    }
    printf("  N = %ld, against V0:\n  V0     p          p / V0^2\n", nfix);
    for (int k = 0; k < nv && !rc; k++) {
        double p = NAN, T = NAN;
        /* a different start for each V0: the law holds on average, not by scaling */
        if ((rc = wall_pressure(o, o->seed + 1 + (unsigned long)k, nfix, L, v0s[k], &p, &T, err)))
            break;
        B[3 * k] = v0s[k];
        B[3 * k + 1] = p;
        B[3 * k + 2] = p / (v0s[k] * v0s[k]);
        printf("  %-5g  %-9.5g  %.5g\n", v0s[k], p, p / (v0s[k] * v0s[k]));
    }
    double c = 0, cov = 0, ss = 0, xx[5], yy[5];
    for (int k = 0; k < nv; k++)
        xx[k] = B[3 * k] * B[3 * k], yy[k] = B[3 * k + 1];
    if (!rc) {
        gsl_fit_mul(xx, 1, yy, 1, (size_t)nv, &c, &cov, &ss);
        printf("  fit p = c V0^2: c = %.5g +- %.2g (relative spread of p/V0^2: %.2g %%)\n", c, sqrt(cov),
               100 * sqrt(ss / nv) / (c * xx[nv - 1]));
    }
    char path[1200];
    gr_scene *sc = NULL;
    if (!rc) {
        snprintf(path, sizeof path, "%s/pressure_density.dat", o->out);
        rc = table(path, "# N n p nT ideal_box eos_box", A, (size_t)nn, 6, err);
    }
    if (!rc) {
        snprintf(path, sizeof path, "%s/pressure_v0.dat", o->out);
        rc = table(path, "# V0 p p/V0^2", B, (size_t)nv, 3, err);
    }
    if (!rc) {
        sc = gr_scene_parse("[domain]\nwidth = 20\nheight = 20\n[species]\ncount = 1\n", "(course pressure)", NULL, err);
        snprintf(path, sizeof path, "%s/pressure.h5", o->out);
        gr_h5md_opts ho = {.method = "edmd", .seed = o->seed, .force = 1, .no_xdmf = 1};
        gr_h5md *h = sc ? gr_h5md_create(path, sc, &ho, err) : NULL;
        const char *ca[6] = {"N", "n", "p", "nT", "ideal_box", "eos_box"}, *cb[3] = {"V0", "p", "p_over_V0sq"};
        rc = !h || put(h, "pressure/density", (size_t)nn, 6, ca, "wall pressure against n = N/L^2, V0 = 1", A, err) ||
             put(h, "pressure/v0", (size_t)nv, 3, cb, "wall pressure against V0, N = 100", B, err);
        if (h)
            rc = gr_h5md_close(h, err) || rc;
        rc = rc ? (err->code ? err->code : GR_ERUN) : GR_OK;
    }
    gr_scene_free(sc);
    for (int f = 0; f < 2 && !rc; f++) {
        snprintf(path, sizeof path, "%s/pressure_%s.png", o->out, f ? "v0" : "density");
        FILE *gp = gr_plot_open(path, 800, 560, err);
        if (!gp) {
            rc = err->code;
            break;
        }
        fprintf(gp, "$d << EOD\n");
        for (int k = 0; k < (f ? nv : nn); k++)
            for (int q = 0; q < (f ? 3 : 6); q++)
                fprintf(gp, "%.6g%c", f ? B[3 * k + q] : A[6 * k + q], q + 1 < (f ? 3 : 6) ? ' ' : '\n');
        fprintf(gp, "EOD\nset key top left\n");
        if (!f)
            fprintf(gp, "set title 'Wall pressure, V_0 = 1, L = %g'\nset xlabel 'n = N/L^2'\nset ylabel 'p'\n"
                        "plot $d u 2:3 w p pt 7 ps 1.5 t 'measured', $d u 2:4 w l lw 2 t 'ideal gas n T', "
                        "$d u 2:5 w l dt 2 lw 2 t 'ideal gas, walls', $d u 2:6 w l lw 2 t 'hard disks (Luding), walls'\n", L);
        else
            fprintf(gp, "set title 'Wall pressure against V_0, N = %ld, L = %g'\nset xlabel 'V_0'\nset ylabel 'p'\n"
                        "plot $d u 1:2 w p pt 7 ps 1.5 t 'measured', %.8g*x*x w l lw 2 t 'p = %.4g V_0^2'\n",
                    nfix, L, c, c);
        rc = gr_plot_close(gp, path, err);
    }
    if (!rc)
        printf("  wrote %s/pressure.h5, pressure_{density,v0}.{dat,png}\n", o->out);
    /* the exercise's claims: p ~ n at low density, p ~ V0^2 */
    if (!rc && fabs(A[2] / A[4] - 1) > 0.1)
        rc = gr_fail(err, GR_ERUN, "pressure: the dilute box is not an ideal gas (p / p_ideal = %g)", A[2] / A[4]);
    if (!rc && fabs(B[2] / B[3 * (nv - 1) + 2] - 1) > 0.05)
        rc = gr_fail(err, GR_ERUN, "pressure: p / V0^2 differs between V0 = %g and %g", B[0], B[3 * (nv - 1)]);
    return rc;
}

/* ---- exercise 3: homogeneous cooling (Haff's law) ---- */
static int ex_cooling(const course_opts *o, gr_err *err)
{
    long n = o->quick ? 2000 : 20000;
    double eta = 0.05, L = sqrt(n * M_PI / 4 / eta), alpha = o->alpha;
    char text[1024];
    snprintf(text, sizeof text,
             "[scene]\nname = course-cooling\nseed = %lu\n[domain]\nwidth = %.17g\nheight = %.17g\n"
             "left = periodic\nright = periodic\nbottom = periodic\ntop = periodic\n"
             "[material]\nrestitution = %g\n[species]\ndiameter = 1\ncount = %ld\n"
             "[init]\nkind = lattice\nspacing = %.17g\nvelocity = gaussian\nv0 = 1\n",
             o->seed, L, L, alpha, n, 0.99 * L / ceil(sqrt((double)n)));
    gr_scene *sc;
    gr_edmd *s;
    if (build(text, o, &sc, &s, err))
        return err->code;
    /* an elastic warm-up builds the equilibrium pair correlations */
    gr_edmd_set_restitution(s, 1.0, NAN);
    int rc = advance_pairs(s, (uint64_t)(3 * n), err);
    gr_edmd_set_restitution(s, alpha, NAN);
    gr_particles *p = gr_particles_create((size_t)n, err);
    gr_obs ob;
    gr_edmd_counters c0, c;
    gr_edmd_get_counters(s, &c0);
    double t0 = gr_edmd_time(s), T0 = 0;
    double u = 1 - eta, chi = (1 - 7 * eta / 16) / (u * u) - eta * eta * eta / (128 * u * u * u * u);
    const int nsamp = 25;
    double tab[26 * 6];
    double cmax = o->quick ? 4.0 : 6.0;
    for (int k = 0; k <= nsamp && !rc && p; k++) {
        if (k && (rc = advance_pairs(s, c0.pair + (uint64_t)(cmax * n * k / nsamp), err)))
            break;
        if ((rc = gr_edmd_snapshot(s, p, err)))
            break;
        gr_obs_from_particles(p, 0, &ob);
        gr_edmd_get_counters(s, &c);
        if (k == 0)
            T0 = ob.temperature;
        double tau = 2.0 / ((1 - alpha * alpha) * (n / (L * L)) * chi * sqrt(M_PI * T0));
        double C = (double)(c.pair - c0.pair) / n, t = gr_edmd_time(s) - t0;
        double row[6] = {C, t, ob.temperature / T0, exp(-(1 - alpha * alpha) * C), 1 / ((1 + t / tau) * (1 + t / tau)), tau};
        memcpy(tab + 6 * k, row, sizeof row);
    }
    if (!p && !rc)
        rc = err->code;
    gr_particles_free(p);
    gr_edmd_free(s);
    char path[1200];
    double worst_c = 0, worst_t = 0;
    if (!rc) {
        printf("cooling: %ld disks, packing fraction %g, alpha = %g, Enskog chi = %.4f, Haff time tau = %.4g\n", n,
               eta, alpha, chi, tab[5]);
        printf("  C/N     t          T/T0       exp(-(1-a^2)C/N)  Haff 1/(1+t/tau)^2\n");
        for (int k = 0; k <= nsamp; k++) {
            const double *r = tab + 6 * k;
            worst_c = fmax(worst_c, fabs(r[2] / r[3] - 1));
            worst_t = fmax(worst_t, fabs(r[2] / r[4] - 1));
            if (k % 5 == 0)
                printf("  %-6.2f  %-9.4g  %-9.5f  %-16.5f  %.5f\n", r[0], r[1], r[2], r[3], r[4]);
        }
        printf("  largest deviation: %.2f %% from the law in C/N, %.2f %% from Haff's law with Enskog's tau\n",
               100 * worst_c, 100 * worst_t);
        snprintf(path, sizeof path, "%s/cooling.dat", o->out);
        rc = table(path, "# C/N t T/T0 exp_law haff tau", tab, nsamp + 1, 6, err);
    }
    if (!rc) {
        snprintf(path, sizeof path, "%s/cooling.h5", o->out);
        gr_h5md_opts ho = {.method = "edmd", .seed = o->seed, .force = 1, .no_xdmf = 1};
        gr_h5md *h = gr_h5md_create(path, sc, &ho, err);
        const char *cn[6] = {"collisions_per_grain", "t", "T_over_T0", "exp_law", "haff", "tau"};
        rc = !h || put(h, "cooling/temperature", (size_t)nsamp + 1, 6, cn, "homogeneous cooling against Haff", tab, err);
        if (h)
            rc = gr_h5md_close(h, err) || rc;
        rc = rc ? (err->code ? err->code : GR_ERUN) : GR_OK;
    }
    gr_scene_free(sc);
    if (!rc) {
        snprintf(path, sizeof path, "%s/cooling.png", o->out);
        FILE *gp = gr_plot_open(path, 1200, 500, err);
        if (!gp)
            rc = err->code;
        else {
            fprintf(gp, "$d << EOD\n");
            for (int k = 0; k <= nsamp; k++)
                fprintf(gp, "%.6g %.6g %.6g %.6g %.6g\n", tab[6 * k], tab[6 * k + 1], tab[6 * k + 2],
                        tab[6 * k + 3], tab[6 * k + 4]);
            fprintf(gp, "EOD\nset multiplot layout 1,2\nset logscale y\nset key top right\n");
            fprintf(gp, "set title 'Cooling, {/Symbol a} = %g: T against collisions'\nset xlabel 'C/N'\n"
                        "set ylabel 'T/T_0'\nplot $d u 1:3 w p pt 7 t 'measured', $d u 1:4 w l lw 2 "
                        "t 'exp(-(1-{/Symbol a}^2) C/N)'\n", alpha);
            fprintf(gp, "set title 'Haff law, Enskog {/Symbol t} = %.3g'\nset xlabel '1 + t/{/Symbol t}'\nset logscale x\n"
                        "plot $d u (1+$2/%.8g):3 w p pt 7 t 'measured', $d u (1+$2/%.8g):5 w l lw 2 "
                        "t '(1+t/{/Symbol t})^{-2}'\nunset multiplot\n", tab[5], tab[5], tab[5]);
            rc = gr_plot_close(gp, path, err);
        }
    }
    if (!rc)
        printf("  wrote %s/cooling.{h5,dat,png}\n", o->out);
    if (!rc && (worst_c > 0.03 || worst_t > 0.06))
        rc = gr_fail(err, GR_ERUN, "cooling: the temperature left Haff's law (%.2g, %.2g)", worst_c, worst_t);
    return rc;
}

static void usage(FILE *f)
{
    fprintf(f, "usage: grano course EXERCISE [--quick] [--out DIR] [--naive] [--alpha A] [--seed S]\n\n"
               "The exercises of the lecture slides on event-driven hard disks (docs/course.md):\n"
               "  maxwell    speed histograms after N/2, N, 2N, 3N, 10N collisions against Maxwell's law\n"
               "  pressure   wall pressure against the density n = N/L^2 and against V0\n"
               "  cooling    homogeneous cooling of inelastic disks against Haff's law (--alpha, default 0.9)\n"
               "  all        the three in turn\n"
               "--out DIR: where the .h5, .dat and .png files go (default course-out); --quick: small\n"
               "runs for tests; --naive: the slides' algorithm v1.0 (default for maxwell) instead of\n"
               "the event tree; --tree forces the tree.\n");
}

int cmd_course(int argc, char **argv)
{
    if (argc < 2 || !strcmp(argv[1], "--help") || !strcmp(argv[1], "-h")) {
        usage(argc < 2 ? stderr : stdout);
        return argc < 2 ? 2 : 0;
    }
    const char *ex = argv[1];
    course_opts o = {.out = "course-out", .quick = 0, .naive = -1, .alpha = 0.9, .seed = 1};
    for (int a = 2; a < argc; a++) {
        if (!strcmp(argv[a], "--quick"))
            o.quick = 1;
        else if (!strcmp(argv[a], "--naive"))
            o.naive = 1;
        else if (!strcmp(argv[a], "--tree"))
            o.naive = 0;
        else if (a + 1 < argc && !strcmp(argv[a], "--out"))
            o.out = argv[++a];
        else if (a + 1 < argc && !strcmp(argv[a], "--alpha"))
            o.alpha = atof(argv[++a]);
        else if (a + 1 < argc && !strcmp(argv[a], "--seed"))
            o.seed = strtoul(argv[++a], NULL, 10);
        else {
            fprintf(stderr, "grano course: unknown or incomplete option '%s'\n", argv[a]);
            usage(stderr);
            return 2;
        }
    }
    if (!(o.alpha > 0 && o.alpha < 1)) {
        fprintf(stderr, "grano course: --alpha must be in (0, 1), got %g\n", o.alpha);
        return 2;
    }
    int all = !strcmp(ex, "all");
    if (!all && strcmp(ex, "maxwell") && strcmp(ex, "pressure") && strcmp(ex, "cooling")) {
        fprintf(stderr, "grano course: unknown exercise '%s'\n", ex);
        usage(stderr);
        return 2;
    }
    if (mkdir(o.out, 0777) && errno != EEXIST) {
        fprintf(stderr, "grano course: cannot create %s: %s\n", o.out, strerror(errno));
        return 2;
    }
    gsl_set_error_handler_off();
    gr_err err = {0};
    int rc = 0;
    int naive = o.naive;
    if (!rc && (all || !strcmp(ex, "maxwell"))) {
        o.naive = naive < 0 ? 1 : naive; /* the first exercise is the slides' v1.0 */
        rc = ex_maxwell(&o, &err);
    }
    o.naive = naive < 0 ? 0 : naive;
    if (!rc && (all || !strcmp(ex, "pressure")))
        rc = ex_pressure(&o, &err);
    if (!rc && (all || !strcmp(ex, "cooling")))
        rc = ex_cooling(&o, &err);
    if (rc) {
        fprintf(stderr, "grano course %s: %s\n", ex, err.msg);
        return rc;
    }
    return 0;
}
