/* grano course pressure: the wall pressure of elastic disks in a box
 * against the density n = N/L^2 (ideal gas at low density, Luding's
 * hard-disk equation of state above) and against the speed V0 (p ~ V0^2). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <gsl/gsl_fit.h>

#include "course.h"
#include "refs.h"
#include "plot.h"
#include "table.h"

/* The densities of the sweep, as disks in the default 20 x 20 box (--box
 * scales them with the area). */
static const long ns_full[] = {4, 8, 16, 32, 64, 100, 144, 196, 256, 324}, ns_quick[] = {4, 16, 64, 196};
static const double v0s[] = {0.5, 1, 1.5, 2, 3};

typedef struct {
    double L, t_meas; /* box side; measurement window in L / V0 */
    long nfix;        /* disks of the sweep against V0 */
    long ns[10];      /* disks of the sweep against n */
    int nn, nv;
    double A[10 * 6]; /* N n p nT ideal_box eos_box */
    double B[5 * 3];  /* V0 p p/V0^2 */
    double c;         /* fit p = c V0^2 */
} pressure;

/* Mean wall pressure p of n elastic disks of speed v0 in an L x L box, the
 * kinetic energy per disk T, and the disk-disk collisions per disk of the
 * measurement. */
static int wall_pressure(const course_opts *o, const pressure *w, unsigned long seed, long n, double v0, double *p,
                         double *T, double *cpn, gr_err *err)
{
    char text[1024];
    snprintf(text, sizeof text,
             "[scene]\nname = course-pressure\nseed = %lu\n[domain]\nwidth = %g\nheight = %g\n"
             "[material]\nrestitution = 1\n[species]\ndiameter = 1\ncount = %ld\n"
             "[init]\nkind = lattice\nspacing = %g\nvelocity = speed\nv0 = %g\n",
             seed, w->L, w->L, n, fmin(10.0, course_spacing(n, w->L)), v0);
    gr_scene *sc;
    gr_sim *s;
    if (course_sim(text, o, NULL, &sc, &s, err))
        return err->code;
    /* relax (the speeds reach Maxwell's law in a few collisions per disk),
     * then average over a time with many wall hits per disk */
    double t_relax = 20 * w->L / v0, t_meas = w->t_meas * w->L / v0;
    uint64_t c0 = 0, c1 = 0;
    int rc = course_pairs(s, "grano course pressure", &c0, err);
    if (!rc)
        rc = gr_sim_advance(s, t_relax, 0, err) || course_pairs(s, "", &c0, err);
    if (!rc) {
        gr_sim_reset_window(s);
        rc = gr_sim_advance(s, t_relax + t_meas, 0, err) || course_pairs(s, "", &c1, err);
    }
    gr_obs ob;
    if (!rc && !(rc = gr_sim_observe(s, &ob, err))) {
        *p = ob.wall_pressure;
        /* elastic disks without gravity keep their kinetic energy: the
         * value at the end is its time average */
        *T = ob.ekin_trans / n;
        *cpn = (double)(c1 - c0) / n;
    }
    gr_sim_free(s);
    gr_scene_free(sc);
    return rc ? (err->code ? err->code : GR_ERUN) : GR_OK;
}

static int against_density(const course_opts *o, pressure *w, gr_err *err)
{
    const long *ns = w->ns;
    double L = w->L;
    printf("  N      n=N/L^2   p          n T        p/(nT)   hard-disk EOS p/(nT)   collisions/N\n");
    for (int k = 0; k < w->nn; k++) {
        double p = NAN, T = NAN, cpn = NAN;
        if (wall_pressure(o, w, o->seed, ns[k], 1.0, &p, &T, &cpn, err))
            return err->code;
        double nd = ns[k] / (L * L), eta = nd * M_PI / 4;
        /* centres stay sigma/2 from the walls: the ideal gas of the box
         * presses n T L / (L - sigma) on them; Z(eta) adds the collisions */
        double ideal = nd * T * L / (L - 1), eos = ideal * (1 + 2 * eta * exp_chi_luding(eta));
        double row[6] = {(double)ns[k], nd, p, nd * T, ideal, eos};
        memcpy(w->A + 6 * k, row, sizeof row);
        gr_progress_finish(o->pg);
        printf("  %-5ld  %-8.4f  %-9.5g  %-9.5g  %-7.4f  %-19.4f  %.4g\n", ns[k], nd, p, nd * T, p / (nd * T),
               eos / (nd * T), cpn);
        fflush(stdout);
        gr_progress_update(o->pg, (k + 1.0) / (w->nn + w->nv), "boxes done", k + 1.0);
    }
    return GR_OK;
}

static int against_v0(const course_opts *o, pressure *w, gr_err *err)
{
    gr_progress_finish(o->pg);
    printf("  N = %ld, against V0:\n  V0     p          p / V0^2\n", w->nfix);
    for (int k = 0; k < w->nv; k++) {
        double p = NAN, T = NAN, cpn = NAN;
        /* a different start for each V0: the law holds on average, not by scaling */
        if (wall_pressure(o, w, o->seed + 1 + (unsigned long)k, w->nfix, v0s[k], &p, &T, &cpn, err))
            return err->code;
        double row[3] = {v0s[k], p, p / (v0s[k] * v0s[k])};
        memcpy(w->B + 3 * k, row, sizeof row);
        gr_progress_finish(o->pg);
        printf("  %-5g  %-9.5g  %.5g\n", v0s[k], p, p / (v0s[k] * v0s[k]));
        fflush(stdout);
        gr_progress_update(o->pg, (w->nn + k + 1.0) / (w->nn + w->nv), "boxes done", w->nn + k + 1.0);
    }
    double cov = 0, ss = 0, xx[5], yy[5];
    for (int k = 0; k < w->nv; k++)
        xx[k] = w->B[3 * k] * w->B[3 * k], yy[k] = w->B[3 * k + 1];
    gsl_fit_mul(xx, 1, yy, 1, (size_t)w->nv, &w->c, &cov, &ss);
    printf("  fit p = c V0^2: c = %.5g +- %.2g (relative spread of p/V0^2: %.2g %%)\n", w->c, sqrt(cov),
           100 * sqrt(ss / w->nv) / (w->c * xx[w->nv - 1]));
    return GR_OK;
}

/* pressure_{density,v0}.dat and pressure.h5. */
static int write_results(const course_opts *o, const pressure *w, gr_err *err)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/pressure_density.dat", o->out);
    if (exp_write_dat(path, "N n p nT ideal_box eos_box", w->A, (size_t)w->nn, 6, err))
        return err->code;
    snprintf(path, sizeof path, "%s/pressure_v0.dat", o->out);
    if (exp_write_dat(path, "V0 p p/V0^2", w->B, (size_t)w->nv, 3, err))
        return err->code;
    /* the scenes differ by N; the file records the box */
    char text[128], vdesc[64];
    snprintf(text, sizeof text, "[domain]\nwidth = %.17g\nheight = %.17g\n[species]\ncount = 1\n", w->L, w->L);
    snprintf(vdesc, sizeof vdesc, "wall pressure against V0, N = %ld", w->nfix);
    gr_scene *sc = gr_scene_parse(text, "(course pressure)", NULL, err);
    gr_h5md *h = sc ? course_h5(o, "pressure.h5", sc, err) : NULL;
    int rc = !h || exp_put_result(h, "pressure/density", (size_t)w->nn, 6, "N,n,p,nT,ideal_box,eos_box",
                                  "wall pressure against n = N/L^2, V0 = 1", w->A, err) ||
             exp_put_result(h, "pressure/v0", (size_t)w->nv, 3, "V0,p,p_over_V0sq",
                            vdesc, w->B, err);
    rc = course_h5_close(h, o, "pressure.h5", rc ? (err->code ? err->code : GR_ERUN) : GR_OK, err);
    gr_scene_free(sc);
    return rc ? (err->code ? err->code : GR_ERUN) : GR_OK;
}

/* pressure_density.png (f = 0) or pressure_v0.png (f = 1). */
static int plot(const course_opts *o, const pressure *w, int f, gr_err *err)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/pressure_%s.png", o->out, f ? "v0" : "density");
    FILE *gp = gr_plot_open(path, 800, 560, err);
    if (!gp)
        return err->code;
    int rows = f ? w->nv : w->nn, cols = f ? 3 : 6;
    fprintf(gp, "$d << EOD\n");
    for (int k = 0; k < rows; k++)
        for (int q = 0; q < cols; q++)
            fprintf(gp, "%.6g%c", f ? w->B[3 * k + q] : w->A[6 * k + q], q + 1 < cols ? ' ' : '\n');
    fprintf(gp, "EOD\nset key top left\n");
    if (!f)
        fprintf(gp, "set title 'Wall pressure, V_0 = 1, L = %g d'\nset xlabel 'number density n = N/L^2 / d^{-2}'\n"
                    "set ylabel 'wall pressure p / (m V_0^2 d^{-2})'\n"
                    "plot $d u 2:3 w p pt 7 ps 1.5 t 'measured', $d u 2:4 w l lw 2 t 'ideal gas n T', "
                    "$d u 2:5 w l dt 2 lw 2 t 'ideal gas, walls', $d u 2:6 w l lw 2 t 'hard disks (Luding), walls'\n",
                w->L);
    else
        fprintf(gp, "set title 'Wall pressure against V_0, N = %ld, L = %g d'\nset xlabel 'V_0 / u (u: the speed unit, V_0 of the density sweep)'\n"
                    "set ylabel 'wall pressure p / (m u^2 d^{-2})'\n"
                    "plot $d u 1:2 w p pt 7 ps 1.5 t 'measured', %.8g*x*x w l lw 2 t 'p = %.4g V_0^2'\n",
                w->nfix, w->L, w->c, w->c);
    return gr_plot_close(gp, path, err);
}

/* The sweep's disks, scaled from the 20 x 20 box to L x L, each on its
 * starting lattice (spacing at most 10 d, above 1 d). */
static int sweep_counts(const course_opts *o, pressure *w, gr_err *err)
{
    const long *base = o->quick ? ns_quick : ns_full;
    for (int k = 0; k < w->nn; k++) {
        long n = lround((double)base[k] * w->L * w->L / 400.0);
        w->ns[k] = n < 1 ? 1 : n;
        if (!(course_spacing(w->ns[k], w->L) > 1.0))
            return gr_fail(err, GR_EINPUT, "--box: %ld disks do not fit on the starting lattice of a %g d box",
                           w->ns[k], w->L);
    }
    if (!(course_spacing(w->nfix, w->L) > 1.0))
        return gr_fail(err, GR_EINPUT, "--n: %ld disks do not fit on the starting lattice of a %g d box", w->nfix,
                       w->L);
    return GR_OK;
}

int course_pressure(const course_opts *o, gr_err *err)
{
    pressure w = {.nn = o->quick ? 4 : 10,
                  .nv = o->quick ? 3 : 5,
                  .L = (o->given & COURSE_BOX) ? o->box : 20.0,
                  .nfix = (o->given & COURSE_N) ? o->n : 100,
                  .t_meas = (o->given & COURSE_TIME) ? o->time : o->quick ? 200 : 500};
    if (sweep_counts(o, &w, err))
        return err->code;
    printf("pressure: elastic disks in a %g x %g box with walls, %s\n", w.L, w.L, course_how(o));
    int rc = against_density(o, &w, err) || against_v0(o, &w, err) || write_results(o, &w, err) ||
             plot(o, &w, 0, err) || plot(o, &w, 1, err);
    if (rc)
        return err->code ? err->code : GR_ERUN;
    printf("  wrote %s/pressure.h5, pressure_{density,v0}.{dat,png}\n", o->out);
    /* the exercise's claims: p ~ n at low density, p ~ V0^2 */
    const double *A = w.A, *B = w.B;
    if (fabs(A[2] / A[4] - 1) > 0.1)
        return gr_fail(err, GR_ERUN, "pressure: the dilute box is not an ideal gas (p / p_ideal = %g)", A[2] / A[4]);
    if (fabs(B[2] / B[3 * (w.nv - 1) + 2] - 1) > 0.05)
        return gr_fail(err, GR_ERUN, "pressure: p / V0^2 differs between V0 = %g and %g", B[0], B[3 * (w.nv - 1)]);
    return GR_OK;
}
