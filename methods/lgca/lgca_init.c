/* The initial state. Grains (kind lattice, random or file) are put on
 * nodes: each on the node nearest its centre, in the channel nearest its
 * velocity (the rest channel below half the lattice speed), or if that is
 * taken the nearest free channel, or else a free channel of the nearest
 * node with one; the count is kept exactly. Occupations (kind =
 * occupation) fill each channel of each fluid node of the region with
 * probability `occupation` (`rest_occupation` for the rest channel). */
#include <math.h>
#include <stdlib.h>

#include "lgca_int.h"

int lgca_neighbour(const lgca *L, int i, int j, int k, int *pi, int *pj)
{
    static const int dj[6] = {0, 1, 1, 0, -1, -1};
    int odd = j & 1, di;
    switch (k) {
    case 0: di = 1; break;
    case 3: di = -1; break;
    case 1: case 5: di = odd; break;
    default: di = odd - 1; break;
    }
    int ti = i + di, tj = j + dj[k];
    if (ti < 0 || ti >= L->ni) {
        if (!L->per_i)
            return 0;
        ti = (ti + L->ni) % L->ni;
    }
    if (tj < 0 || tj >= L->nj) {
        if (!L->per_j)
            return 0;
        tj = (tj + L->nj) % L->nj;
    }
    *pi = ti, *pj = tj;
    return 1;
}

/* Channels in order of preference for a velocity (vx, vy). */
static void preference(const lgca *L, double vx, double vy, int order[LGCA_CH])
{
    double speed = hypot(vx, vy), c = L->a / L->par.dt;
    int n = 0;
    if (speed < 0.5 * c)
        order[n++] = LGCA_REST;
    int k = speed > 0 ? (int)lround(atan2(vx, vy) / (M_PI / 3)) : 0;
    k = (k % 6 + 6) % 6;
    static const int off[6] = {0, 1, -1, 2, -2, 3};
    for (int q = 0; q < 6; q++)
        order[n++] = ((k + off[q]) % 6 + 6) % 6;
    if (n < LGCA_CH)
        order[n++] = LGCA_REST;
}

static int try_node(lgca *L, int i, int j, const int order[LGCA_CH])
{
    if (i < 0 || i >= L->ni || j < 0 || j >= L->nj || lgca_is_solid(L, i, j))
        return 0;
    for (int q = 0; q < LGCA_CH; q++)
        if (!lgca_get(L, i, j, order[q])) {
            lgca_put(L, i, j, order[q], 1);
            return 1;
        }
    return 0;
}

static int place_grain(lgca *L, double x, double y, double vx, double vy)
{
    int order[LGCA_CH];
    preference(L, vx, vy, order);
    int j = (int)lround(x / L->h - 0.5);
    int i = (int)lround(y / L->a - 0.25 - 0.5 * (j & 1));
    /* rings of growing radius in (i, j) */
    for (int r = 0; r <= 6; r++)
        for (int dj = -r; dj <= r; dj++)
            for (int di = -r; di <= r; di++)
                if ((abs(di) == r || abs(dj) == r) && try_node(L, i + di, j + dj, order))
                    return 1;
    return 0;
}

static int from_grains(lgca *L, const gr_particles *p, gr_err *err)
{
    for (size_t k = 0; k < p->n; k++) {
        if (p->flags[k] & (GR_PF_FIXED | GR_PF_GONE))
            continue;
        if (!place_grain(L, p->x[k], p->y[k], p->vx[k], p->vy[k])) {
            char where[1200];
            gr_scene_where(L->sc, "init", "kind", where, sizeof where);
            return gr_fail(err, GR_EINPUT, "%s: grain %zu at (%g, %g) finds no free lattice channel near it; too dense for the lattice",
                           where, k, p->x[k], p->y[k]);
        }
    }
    return GR_OK;
}

static void from_occupation(lgca *L, gr_rng *rng)
{
    const gr_init *in = &L->sc->init;
    for (int j = 0; j < L->nj; j++)
        for (int i = 0; i < L->ni; i++) {
            double x, y;
            lgca_node_xy(L, i, j, &x, &y);
            if (x < in->x0 || x >= in->x1 || y < in->y0 || y >= in->y1 || lgca_is_solid(L, i, j))
                continue;
            for (int c = 0; c < LGCA_CH; c++)
                lgca_put(L, i, j, c, gr_rng_uniform(rng) < (c == LGCA_REST ? in->rest_occupation : in->occupation));
        }
}

int lgca_init_state(lgca *L, const gr_particles *init, gr_rng *rng, gr_err *err)
{
    if (L->sc->init.kind == GR_INIT_OCCUPATION) {
        from_occupation(L, rng);
        return GR_OK;
    }
    return from_grains(L, init, err);
}
