/* grano course cooling: homogeneous cooling of inelastic disks, the
 * temperature against collisions per disk (exp(-(1 - alpha^2) C/N)) and
 * against time (Haff's law with Enskog's time), after an elastic warm-up
 * that builds the equilibrium pair correlations. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "course.h"
#include "refs.h"
#include "plot.h"
#include "table.h"

#define NSAMP 25
static const double eta = 0.05;

typedef struct {
    long n;
    double L, alpha, chi;
    gr_scene *sc;                 /* the inelastic scene, for the result file */
    double tab[(NSAMP + 1) * 6];  /* C/N t T/T0 exp_law haff tau */
} cooling;

static void scene_text(const course_opts *o, const cooling *w, double alpha, char *text, size_t n)
{
    snprintf(text, n,
             "[scene]\nname = course-cooling\nseed = %lu\n[domain]\nwidth = %.17g\nheight = %.17g\n"
             "left = periodic\nright = periodic\nbottom = periodic\ntop = periodic\n"
             "[material]\nrestitution = %g\n[species]\ndiameter = 1\ncount = %ld\n"
             "[init]\nkind = lattice\nspacing = %.17g\nvelocity = gaussian\nv0 = 1\n",
             o->seed, w->L, w->L, alpha, w->n, 0.99 * w->L / ceil(sqrt((double)w->n)));
}

/* The elastic warm-up (3 collisions per disk): its grains in *p. */
static int warm_up(const course_opts *o, const cooling *w, gr_particles *p, gr_err *err)
{
    char text[1024];
    scene_text(o, w, 1.0, text, sizeof text);
    gr_scene *sc;
    gr_sim *s;
    if (course_sim(text, o, NULL, &sc, &s, err))
        return err->code;
    int rc = course_advance_pairs(s, (uint64_t)(3 * w->n), err) || gr_sim_snapshot(s, p, err);
    gr_sim_free(s);
    gr_scene_free(sc);
    return rc ? (err->code ? err->code : GR_ERUN) : GR_OK;
}

/* Quench the warmed-up grains to restitution alpha and sample the
 * temperature NSAMP times up to cmax collisions per disk. */
static int quench(const course_opts *o, cooling *w, gr_particles *p, gr_err *err)
{
    char text[1024];
    scene_text(o, w, w->alpha, text, sizeof text);
    gr_sim *s;
    if (course_sim(text, o, p, &w->sc, &s, err))
        return err->code;
    double a2 = w->alpha * w->alpha, cmax = o->quick ? 4.0 : 6.0, T0 = 0, t0 = gr_sim_time(s);
    long n = w->n;
    uint64_t c0 = 0, c;
    int rc = course_pairs(s, "grano course cooling", &c0, err);
    for (int k = 0; k <= NSAMP && !rc; k++) {
        if (k && (rc = course_advance_pairs(s, c0 + (uint64_t)(cmax * n * k / NSAMP), err)))
            break;
        gr_obs ob;
        if ((rc = gr_sim_snapshot(s, p, err)) || (rc = course_pairs(s, "", &c, err)))
            break;
        gr_obs_from_particles(p, 0, &ob);
        if (k == 0)
            T0 = ob.temperature;
        double tau = 2.0 / ((1 - a2) * (n / (w->L * w->L)) * w->chi * sqrt(M_PI * T0));
        double C = (double)(c - c0) / n, t = gr_sim_time(s) - t0;
        double row[6] = {C, t, ob.temperature / T0, exp(-(1 - a2) * C), 1 / ((1 + t / tau) * (1 + t / tau)), tau};
        memcpy(w->tab + 6 * k, row, sizeof row);
        gr_progress_update(o->pg, (double)k / NSAMP, "T / T0", ob.temperature / T0);
    }
    gr_sim_free(s);
    return rc;
}

/* The table on stdout and in cooling.dat, and the largest deviations. */
static int report(const course_opts *o, const cooling *w, double *worst_c, double *worst_t, gr_err *err)
{
    gr_progress_finish(o->pg);
    printf("cooling: %ld disks, packing fraction %g, alpha = %g, Enskog chi = %.4f, Haff time tau = %.4g\n", w->n,
           eta, w->alpha, w->chi, w->tab[5]);
    printf("  C/N     t          T/T0       exp(-(1-a^2)C/N)  Haff 1/(1+t/tau)^2\n");
    *worst_c = *worst_t = 0;
    for (int k = 0; k <= NSAMP; k++) {
        const double *r = w->tab + 6 * k;
        *worst_c = fmax(*worst_c, fabs(r[2] / r[3] - 1));
        *worst_t = fmax(*worst_t, fabs(r[2] / r[4] - 1));
        if (k % 5 == 0)
            printf("  %-6.2f  %-9.4g  %-9.5f  %-16.5f  %.5f\n", r[0], r[1], r[2], r[3], r[4]);
    }
    printf("  largest deviation: %.2f %% from the law in C/N, %.2f %% from Haff's law with Enskog's tau\n",
           100 * *worst_c, 100 * *worst_t);
    char path[1200];
    snprintf(path, sizeof path, "%s/cooling.dat", o->out);
    if (exp_write_dat(path, "C/N t T/T0 exp_law haff tau", w->tab, NSAMP + 1, 6, err))
        return err->code;
    gr_h5md *h = course_h5(o, "cooling.h5", w->sc, err);
    int rc = !h || exp_put_result(h, "cooling/temperature", NSAMP + 1, 6,
                                  "collisions_per_grain,t,T_over_T0,exp_law,haff,tau",
                                  "homogeneous cooling against Haff", w->tab, err);
    if (h)
        rc = gr_h5md_close(h, err) || rc;
    return rc ? (err->code ? err->code : GR_ERUN) : GR_OK;
}

static int plot(const course_opts *o, const cooling *w, gr_err *err)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/cooling.png", o->out);
    FILE *gp = gr_plot_open(path, 1200, 500, err);
    if (!gp)
        return err->code;
    const double *tab = w->tab;
    fprintf(gp, "$d << EOD\n");
    for (int k = 0; k <= NSAMP; k++)
        fprintf(gp, "%.6g %.6g %.6g %.6g %.6g\n", tab[6 * k], tab[6 * k + 1], tab[6 * k + 2], tab[6 * k + 3],
                tab[6 * k + 4]);
    fprintf(gp, "EOD\nset multiplot layout 1,2\nset logscale y\nset key top right\n");
    fprintf(gp, "set title 'Cooling, {/Symbol a} = %g: T against collisions'\nset xlabel 'collisions per disk C/N'\n"
                "set ylabel 'T / T_0 (T_0: temperature at the quench)'\nplot $d u 1:3 w p pt 7 t 'measured', $d u 1:4 w l lw 2 "
                "t 'exp(-(1-{/Symbol a}^2) C/N)'\n", w->alpha);
    fprintf(gp, "set title 'Haff law, Enskog {/Symbol t} = %.3g'\nset xlabel '1 + t/{/Symbol t} (t in units of d/V_0)'\nset logscale x\n"
                "plot $d u (1+$2/%.8g):3 w p pt 7 t 'measured', $d u (1+$2/%.8g):5 w l lw 2 "
                "t '(1+t/{/Symbol t})^{-2}'\nunset multiplot\n", tab[5], tab[5], tab[5]);
    return gr_plot_close(gp, path, err);
}

int course_cooling(const course_opts *o, gr_err *err)
{
    cooling w = {.n = o->quick ? 2000 : 20000, .alpha = o->alpha, .chi = exp_chi_luding(eta)};
    w.L = sqrt(w.n * M_PI / 4 / eta);
    gr_particles *p = gr_particles_create((size_t)w.n, err);
    int rc = !p || warm_up(o, &w, p, err) || quench(o, &w, p, err);
    gr_particles_free(p);
    double worst_c = 0, worst_t = 0;
    rc = rc || report(o, &w, &worst_c, &worst_t, err) || plot(o, &w, err);
    gr_scene_free(w.sc);
    if (rc)
        return err->code ? err->code : GR_ERUN;
    printf("  wrote %s/cooling.{h5,dat,png}\n", o->out);
    if (worst_c > 0.03 || worst_t > 0.06)
        return gr_fail(err, GR_ERUN, "cooling: the temperature left Haff's law (%.2g, %.2g)", worst_c, worst_t);
    return GR_OK;
}
