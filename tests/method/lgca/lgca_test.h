/* Shared by the lgca tests: a backend instance from scene text. */
#ifndef GR_LGCA_TEST_H
#define GR_LGCA_TEST_H

#include "sim_test.h"

#include "init.h"
#include "lgca/lgca_int.h"
#include "method.h"

extern const gr_method_type gr_lgca_method;

static inline gr_sim *lgca_make(const char *text, gr_scene **scp)
{
    static const char *const ext[] = {"lgca", NULL};
    *scp = st_scene(text, "lgca-test.ini", ext);
    return st_sim(&gr_lgca_method, *scp, NULL);
}

static inline void lgca_drop(gr_sim *s, gr_scene *sc)
{
    gr_sim_free(s);
    gr_scene_free(sc);
}

/* Integer momentum (lgca_state_momentum units) and mass of the lattice. */
static inline void lgca_totals(const lgca *L, int64_t *mass, int64_t *qx, int64_t *qy)
{
    *mass = *qx = *qy = 0;
    for (int j = 0; j < L->nj; j++)
        for (int i = 0; i < L->ni; i++) {
            unsigned s = 0;
            for (int c = 0; c < LGCA_CH; c++)
                s |= (unsigned)lgca_get(L, i, j, c) << c;
            int x, y;
            lgca_state_momentum(s, &x, &y);
            *mass += __builtin_popcount(s), *qx += x, *qy += y;
        }
}


/* A periodic scene of nx lanes and ny rows (lattice spacing 1). */
static inline void lgca_periodic_text(char *buf, size_t n, int nx, int ny, const char *extra)
{
    snprintf(buf, n,
             "[scene]\nseed = 5\n[domain]\nwidth = %.17g\nheight = %.17g\nleft = periodic\nright = periodic\n"
             "bottom = periodic\ntop = periodic\n[init]\nkind = occupation\noccupation = 0\n[lgca]\ndt = 1\n%s",
             nx * sqrt(3.0) / 2 * (1 + 1e-12), ny * (1 + 1e-12), extra);
}

/* Fill every channel at random with occupation f(k, x, y). */
static inline void lgca_fill(lgca *L, double (*f)(int k, double x, double y, void *ctx), void *ctx,
                             uint64_t seed)
{
    gr_err e = {0};
    gr_rng *r = gr_rng_create(seed, 77, &e);
    assert_non_null(r);
    for (int j = 0; j < L->nj; j++)
        for (int i = 0; i < L->ni; i++) {
            double x, y;
            lgca_node_xy(L, i, j, &x, &y);
            for (int k = 0; k < LGCA_CH; k++)
                lgca_put(L, i, j, k, gr_rng_uniform(r) < f(k, x, y, ctx));
        }
    gr_rng_free(r);
}

static const double LGCA_SX[6] = {0, 0.86602540378443865, 0.86602540378443865, 0, -0.86602540378443865,
                                  -0.86602540378443865};
static const double LGCA_SY[6] = {1, 0.5, -0.5, -1, -0.5, 0.5};

#endif
