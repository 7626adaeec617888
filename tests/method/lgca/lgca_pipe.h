/* Shared by the lgca pipe tests: granular flow down a vertical pipe
 * (Peng and Herrmann, Phys. Rev. E 49, R1796 (1994)): nx lanes between
 * wall lanes, ny rows periodic along the pipe, gravity g set on the
 * lattice (the scene format has no gravity along a periodic side). */
#ifndef GR_LGCA_PIPE_H
#define GR_LGCA_PIPE_H

#include "lgca_test.h"
#include "lgca_waves.h"

#include <stdlib.h>
#include <string.h>

typedef struct {
    double d, g, p, b, stop; /* occupation per channel and the rule probabilities */
    int lanes, rows, transient, steps;
} lgca_pipe;

static inline double lgca_pipe_fill(int c, double x, double y, void *ctx)
{
    (void)c, (void)x, (void)y;
    return *(const double *)ctx;
}

/* Particles per row (all fluid lanes). */
static inline void lgca_pipe_rows(const lgca *L, double *r)
{
    memset(r, 0, sizeof *r * (size_t)L->ni);
    size_t nw = (size_t)L->nw;
    for (int j = 1; j < L->nj - 1; j++)
        for (int c = 0; c < LGCA_CH; c++)
            for (size_t w = 0; w < nw; w++)
                for (uint64_t x = L->lane[j][(size_t)c * nw + w]; x; x &= x - 1)
                    r[w * 64 + (size_t)__builtin_ctzll(x)] += 1;
}

/* Particles per bin of 4 rows from the particles per row r. */
static inline void lgca_pipe_bins(const double *r, int nb, float *bins)
{
    for (int b = 0; b < nb; b++)
        bins[b] = (float)(r[4 * b] + r[4 * b + 1] + r[4 * b + 2] + r[4 * b + 3]);
}

/* The pipe q after its transient: scene seed `seed`, filled with the
 * stream `fill`, gravity's order LGCA_GRAV_* `order`. */
static inline gr_sim *lgca_pipe_start(const lgca_pipe *q, int seed, int fill, int order, gr_scene **sc)
{
    static const char *const orders[] = {"rest", "movers", "alternate"};
    char text[1024];
    snprintf(text, sizeof text,
             "[scene]\nseed = %d\n[domain]\nwidth = %.17g\nheight = %.17g\nleft = wall\nright = wall\n"
             "bottom = periodic\ntop = periodic\n[init]\nkind = occupation\noccupation = 0\n[lgca]\ndt = 1\n"
             "rules = granular\np = %g\nb = %g\nstop = %g\ngravity_order = %s\n",
             seed, (q->lanes + 2) * sqrt(3.0) / 2 * (1 + 1e-12), q->rows * (1 + 1e-12), q->p, q->b, q->stop,
             orders[order]);
    gr_sim *s = lgca_make(text, sc);
    lgca *L = gr_sim_state(s);
    lgca_fill(L, lgca_pipe_fill, (void *)&q->d, (uint64_t)fill);
    for (int j = 0; j < L->nj; j += L->nj - 1) /* nothing inside the walls */
        for (int i = 0; i < L->ni; i++)
            for (int c = 0; c < LGCA_CH; c++)
                lgca_put(L, i, j, c, 0);
    L->thr_g = (uint32_t)lround(q->g * 65536);
    gr_err e = {0};
    assert_int_equal(gr_sim_advance(s, (uint64_t)q->transient, 0, &e), GR_OK);
    return s;
}

/* The contrast of long density waves: the structure factor of the density
 * on bins of 4 rows, its mean over the four longest wavelengths over its
 * mean at wavelengths near 16 rows (1 for uncorrelated noise), averaged
 * over the run every 16 steps. rows_out (steps x rows, or NULL) receives
 * the particles per row at every step. */
static inline double lgca_pipe_run(const lgca_pipe *q, float *rows_out)
{
    gr_scene *sc;
    gr_sim *s = lgca_pipe_start(q, 5, 7, LGCA_GRAV_REST, &sc);
    lgca *L = gr_sim_state(s);
    gr_err e = {0};
    int ni = L->ni, nb = ni / 4;
    double *r = malloc(sizeof *r * (size_t)ni), lo = 0, mid = 0;
    float *v = malloc(sizeof *v * (size_t)nb);
    assert_true(r && v);
    for (int t = 0; t < q->steps; t++) {
        assert_int_equal(gr_sim_step(s, &e), GR_OK);
        lgca_pipe_rows(L, r);
        if (rows_out)
            for (int i = 0; i < ni; i++)
                rows_out[(size_t)t * (size_t)ni + (size_t)i] = (float)r[i];
        if (t % 16)
            continue;
        lgca_pipe_bins(r, nb, v);
        lgca_waves_contrast_frame(v, nb, &lo, &mid);
    }
    free(v);
    free(r);
    lgca_drop(s, sc);
    return lo / mid;
}

#endif
