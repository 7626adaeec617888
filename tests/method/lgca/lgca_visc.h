/* Shared by the lgca viscosity tests: the decay of a shear wave and
 * Frisch et al.'s FHP-III Boltzmann viscosity (Complex Systems 1, 649
 * (1987)), nu(d) = 1/(28 d (1-d) (1 - 8 d (1-d)/7)) - 1/8 in a^2/dt, d the
 * mean occupation per channel (mass / 7 per node). */
#ifndef GR_LGCA_VISC_H
#define GR_LGCA_VISC_H

#include "lgca_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static inline double lgca_frisch_nu(double d) { return 1 / (28 * d * (1 - d) * (1 - 8 * d * (1 - d) / 7)) - 0.125; }

typedef struct {
    double d, eps, k;
} lgca_shear;

/* u_x = (6/7) eps sin(k y) on a uniform occupation d (rest channel too). */
static inline double lgca_shear_fill(int c, double x, double y, void *ctx)
{
    (void)x;
    const lgca_shear *w = ctx;
    if (c == LGCA_REST)
        return w->d;
    return w->d * (1 + 2 * LGCA_SX[c] * w->eps * sin(w->k * y));
}

/* Projection of the x momentum on sin(k y) (lattice units): the sums per
 * row and lane parity first, one pass over the moving bits. */
static inline double lgca_mode_shear(const lgca *L, double k, long *acc)
{
    memset(acc, 0, 2 * (size_t)L->ni * sizeof *acc);
    size_t nw = (size_t)L->nw;
    for (int j = 0; j < L->nj; j++) {
        const uint64_t *p = L->lane[j];
        long *a = acc + (size_t)(j & 1) * (size_t)L->ni;
        for (size_t w = 0; w < nw; w++) {
            uint64_t r1 = p[nw + w], r2 = p[2 * nw + w], l1 = p[4 * nw + w], l2 = p[5 * nw + w];
            for (uint64_t any = r1 | r2 | l1 | l2; any; any &= any - 1) {
                int b = __builtin_ctzll(any);
                a[w * 64 + (size_t)b] += (long)(r1 >> b & 1) + (long)(r2 >> b & 1) - (long)(l1 >> b & 1) -
                                         (long)(l2 >> b & 1);
            }
        }
    }
    double r = 0;
    for (int par = 0; par < 2; par++)
        for (int i = 0; i < L->ni; i++)
            r += (double)acc[(size_t)par * (size_t)L->ni + (size_t)i] * sin(k * (i + 0.25 + 0.5 * par) * L->a);
    return r * LGCA_SX[1];
}

/* A periodic FHP-III scene whose collision bits are seeded by seed, so
 * that runs of different seeds are independent realisations (the initial
 * fill and the chiralities both differ). */
static inline void lgca_seeded_text(char *buf, size_t n, int nx, int ny, uint64_t seed)
{
    char base[1024];
    lgca_periodic_text(base, sizeof base, nx, ny, "rules = fhp3\n");
    const char *rest = strstr(base, "[domain]");
    snprintf(buf, n, "[scene]\nseed = %llu\n%s", (unsigned long long)seed, rest ? rest : "");
}

/* FHP-III shear viscosity from the decay of a shear wave of wavelength ny a
 * on nx lanes: the least-squares slope of the mode's logarithm over steps
 * [t0, t1] (every 5), divided by -k^2. eps is scaled by (1-d)/d above half
 * filling, so that the holes' flow is as weak as the particles' below it
 * (the model's particle-hole symmetry maps d to 1 - d). */
static inline double lgca_shear_viscosity(double d, int nx, int ny, double eps, int t0, int t1, uint64_t seed)
{
    char text[1024];
    lgca_seeded_text(text, sizeof text, nx, ny, seed);
    gr_scene *sc;
    gr_sim *s = lgca_make(text, &sc);
    lgca *L = gr_sim_state(s);
    lgca_shear w = {d, d > 0.5 ? eps * (1 - d) / d : eps, 2 * M_PI / ny};
    lgca_fill(L, lgca_shear_fill, &w, seed);
    long *acc = malloc(2 * (size_t)L->ni * sizeof *acc);
    assert_non_null(acc);
    gr_err e = {0};
    double st = 0, sl = 0, stt = 0, stl = 0, n = 0;
    for (int t = 1; t <= t1; t++) {
        assert_int_equal(gr_sim_step(s, &e), GR_OK);
        if (t < t0 || t % 5)
            continue;
        double a = lgca_mode_shear(L, w.k, acc);
        assert_true(a > 0);
        double l = log(a);
        st += t, sl += l, stt += (double)t * t, stl += t * l, n++;
    }
    free(acc);
    lgca_drop(s, sc);
    return -(n * stl - st * sl) / (n * stt - st * st) / (w.k * w.k);
}

#endif
