/* Helpers shared by the DSMC validation tests: an instance from INI text
 * (dsmc, or edmd as the reference on the same scene), advancing, the
 * temperature, a2, counters; the reference laws from experiments/lib/refs.h;
 * the scaled homogeneous cooling state and the Boltzmann a2 it is held to. */
#ifndef GR_DSMC_TEST_H
#define GR_DSMC_TEST_H

#include "sim_test.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dsmc/dsmc_int.h"
#include "init.h"
#include "method.h"
#include "refs.h"

/* An instance of method `m` ("dsmc" or "edmd") on the scene; *scp gets the
 * scene, for gr_scene_free after gr_sim_free. */
static inline gr_sim *ds_make_method(const char *m, const char *text, gr_scene **scp)
{
    static const char *const ext[] = {"dsmc", "edmd", NULL};
    *scp = st_scene(text, "dsmc-test.ini", ext);
    return st_sim(gr_method_find(m), *scp, NULL);
}

static inline gr_sim *ds_make(const char *text, gr_scene **scp) { return ds_make_method("dsmc", text, scp); }

static inline void ds_run_to(gr_sim *s, double t)
{
    gr_err e = {0};
    if (gr_sim_advance(s, t, 0, &e))
        print_error("advance: %s\n", e.msg);
    assert_int_equal(e.code, GR_OK);
}

static inline uint64_t ds_counter(gr_sim *s, const char *name)
{
    uint64_t v = 0;
    if (!gr_sim_counter(s, name, &v))
        fail_msg("no counter %s", name);
    return v;
}

static inline gr_obs ds_observe(gr_sim *s)
{
    gr_obs o;
    gr_err e = {0};
    assert_int_equal(gr_sim_observe(s, &o, &e), GR_OK);
    return o;
}

static inline double ds_temp(gr_sim *s) { return ds_observe(s).temperature; }

/* a2 = <v^4> / (2 <v^2>^2) - 1 of the peculiar velocities (2-D). */
static inline double ds_a2(const gr_dsmc *d)
{
    double mx = 0, my = 0, s2 = 0, s4 = 0, n = (double)d->n;
    for (size_t i = 0; i < d->n; i++)
        mx += d->vx[i] / n, my += d->vy[i] / n;
    for (size_t i = 0; i < d->n; i++) {
        double ux = d->vx[i] - mx, uy = d->vy[i] - my, u2 = ux * ux + uy * uy;
        s2 += u2 / n, s4 += u2 * u2 / n;
    }
    return s4 / (2 * s2 * s2) - 1;
}

/* `method` on a periodic box of n disks at packing eta, restitution alpha;
 * dsmc's step dtf mean free times (at T = 1), its cells `cell` diameters
 * (0: the default), its enskog `enskog`. */
#define DS_HCS_GAS                                                                                                     \
    "[scene]\nseed = %d\n[domain]\nwidth = %.17g\nheight = %.17g\nleft = periodic\nright = periodic\n"                 \
    "bottom = periodic\ntop = periodic\n[material]\nrestitution = %g\n[species]\ncount = %d\n"                         \
    "[init]\nkind = random\nvelocity = gaussian\nv0 = 1\n[dsmc]\ndt = %.17g\ncell = %g\nenskog = %s\n[edmd]\ncell = 10\n"

static inline gr_sim *ds_gas(const char *method, int seed, int n, double eta, double alpha, double dtf, double cell,
                             const char *enskog, gr_scene **sc)
{
    char text[1024];
    double L = sqrt(n * M_PI / 4 / eta), nd = n / (L * L);
    snprintf(text, sizeof text, DS_HCS_GAS, seed, L, L, alpha, n, dtf / (2 * sqrt(M_PI) * nd), cell, enskog);
    return ds_make_method(method, text, sc);
}

/* Mean and standard error of x[0..k) from blocks of b. */
static inline void ds_block_stats(const double *x, int k, int b, double *mean, double *err)
{
    int nb = k / b;
    double s = 0, s2 = 0;
    for (int j = 0; j < nb; j++) {
        double m = 0;
        for (int i = 0; i < b; i++)
            m += x[j * b + i] / b;
        s += m, s2 += m * m;
    }
    *mean = s / nb;
    *err = sqrt(fmax(0, s2 / nb - *mean * *mean) / (nb - 1));
}

/* The scaled HCS in one cell (no space: the Boltzmann HCS, so the
 * Boltzmann rate: chi would only change the time scale): every mean free
 * time (of the rescaled gas) the peculiar velocities go back to T = 1 (a2
 * is scale free); a2 sampled then, its error from blocks of 20; the cooling
 * per collision from the temperature each interval ends at and the
 * collisions in it. 10 intervals skipped. a2 is the sample's, without the
 * +1/N of docs/methods/dsmc.md. */
static inline void ds_scaled_hcs(double alpha, int n, double dtf, int K, double *a2, double *a2e, double *slope)
{
    gr_scene *sc;
    gr_sim *s = ds_gas("dsmc", 11, n, 0.3, alpha, dtf, 1e6, "no", &sc);
    gr_dsmc *d = gr_sim_state(s);
    double nd = n / (d->Lx * d->Ly), tau = 1.0 / (2 * sqrt(M_PI) * nd), lnT = 0, C = 0;
    double *x = malloc(sizeof *x * (size_t)K);
    assert_non_null(x);
    for (int k = -10; k < K; k++) {
        uint64_t p0 = ds_counter(s, "pair_collisions");
        ds_run_to(s, d->t + tau);
        double T = ds_temp(s), f = 1.0 / sqrt(T), mx = 0, my = 0;
        for (size_t i = 0; i < d->n; i++)
            mx += d->vx[i] / (double)d->n, my += d->vy[i] / (double)d->n;
        for (size_t i = 0; i < d->n; i++)
            d->vx[i] = (d->vx[i] - mx) * f, d->vy[i] = (d->vy[i] - my) * f;
        if (k >= 0) {
            x[k] = ds_a2(d);
            lnT += log(T), C += 2.0 * (double)(ds_counter(s, "pair_collisions") - p0) / (double)n;
        }
    }
    ds_block_stats(x, K, 20, a2, a2e);
    *slope = -lnT / C;
    free(x);
    gr_sim_free(s);
    gr_scene_free(sc);
}

/* The Boltzmann HCS a2 of hard disks beyond first Sonine, from
 * `/usr/bin/python3 tests/method/dsmc/sonine_hcs.py` (Sonine orders K = 2..8
 * by exact quadrature of the collisional moments, independent of dsmc):
 * `best` the middle of the range that K = 5..8 (linear and full closures)
 * span, `band` half that range. For alpha >= 0.7 the expansion converges
 * (band <= 3e-5); at 0.6 and 0.5 successive orders alternate about the value
 * and the band is what is known. */
static inline void ds_sonine_best(double alpha, double *best, double *band)
{
    static const struct {
        double alpha, best, band;
    } ref[] = {
        {0.5, 0.07627, 0.01121},  {0.6, 0.03322, 0.00060},   {0.7, -0.00204, 0.00002}, {0.8, -0.02626, 0.00003},
        {0.9, -0.03008, 0.00001}, {0.95, -0.02038, 0.00001}, {0.99, -0.00507, 0.00000},
    };
    for (size_t k = 0; k < sizeof ref / sizeof *ref; k++)
        if (fabs(ref[k].alpha - alpha) < 1e-9) {
            *best = ref[k].best, *band = ref[k].band;
            return;
        }
    fail_msg("no Sonine reference at alpha %g", alpha);
}

#endif
