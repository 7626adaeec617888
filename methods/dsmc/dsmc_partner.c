/* The stand-in for a recent partner. Two particles that collided are
 * correlated until each has met others: in an inelastic gas they would
 * meet again with a reduced relative speed, where hard disks would have
 * separated, so a cell that keeps them together cools too slowly. Yet
 * forbidding the pair loses collisions the rate needs (the cell counts
 * them as each other's partners: 25 % of the rate with cells of lambda/8,
 * docs/methods/dsmc.md). So when a candidate pair has collided within the
 * last two collisions of either, one of them, drawn at random, meets
 * another particle of the cell instead, or, when the pair is alone in its
 * cell, of the smallest square of cells around it that holds one. Calls
 * no other file of the backend. */
#include <math.h>

#include "dsmc_int.h"
#include "dsmc_rng.h"

/* Cells lo..hi along an axis of n cells, R around c; 1 when that is the
 * whole axis. */
static int axis(int c, int R, int n, int wraps, int *lo, int *hi)
{
    if (wraps && 2 * R + 1 >= n)
        *lo = 0, *hi = n - 1;
    else if (wraps)
        *lo = c - R, *hi = c + R;
    else
        *lo = c - R < 0 ? 0 : c - R, *hi = c + R >= n ? n - 1 : c + R;
    return *lo == 0 && *hi == n - 1;
}

static inline size_t pool_cell(const gr_dsmc *d, int x, int y)
{
    return (size_t)((y + d->gy) % d->gy) * (size_t)d->gx + (size_t)((x + d->gx) % d->gx);
}

static inline size_t count(const gr_dsmc *d, size_t e) { return d->start[e + 1] - d->start[e]; }

static size_t pool_count(const gr_dsmc *d, const gr_dsmc_pool *p)
{
    size_t tot = 0;
    for (int y = p->lo[1]; y <= p->hi[1]; y++)
        for (int x = p->lo[0]; x <= p->hi[0]; x++)
            tot += count(d, pool_cell(d, x, y));
    return tot;
}

gr_dsmc_pool gr_dsmc_pool_of(const gr_dsmc *d, size_t c, int R0)
{
    int cx = (int)(c % (size_t)d->gx), cy = (int)(c / (size_t)d->gx);
    gr_dsmc_pool p;
    for (int R = R0;; R++) {
        int all = axis(cx, R, d->gx, d->gx == d->nx, &p.lo[0], &p.hi[0]);
        all &= axis(cy, R, d->gy, d->gy == d->ny, &p.lo[1], &p.hi[1]);
        if (all || pool_count(d, &p) > 2)
            return p;
    }
}

/* |v_k - vbar| + max_l |v_l - vbar| with vbar the pair's mean. */
double gr_dsmc_pool_bound(const gr_dsmc *d, const gr_dsmc_pool *p, size_t i, size_t j)
{
    double mx = 0.5 * (d->vx[i] + d->vx[j]), my = 0.5 * (d->vy[i] + d->vy[j]), v2 = 0;
    for (int y = p->lo[1]; y <= p->hi[1]; y++)
        for (int x = p->lo[0]; x <= p->hi[0]; x++) {
            size_t e = pool_cell(d, x, y);
            for (size_t q = d->start[e]; q < d->start[e + 1]; q++) {
                size_t l = d->order[q];
                double ux = d->vx[l] - mx, uy = d->vy[l] - my, u2 = ux * ux + uy * uy;
                v2 = u2 > v2 ? u2 : v2;
            }
        }
    double hx = 0.5 * (d->vx[i] - d->vx[j]), hy = 0.5 * (d->vy[i] - d->vy[j]);
    return sqrt(hx * hx + hy * hy) + sqrt(v2);
}

/* Uniform over the others: the draw u picks the w-th particle that is not
 * the pair among the m - 2 of the cell or the tot - 2 of the pool, in
 * cell order, so that one draw suffices. */
size_t gr_dsmc_stand_in(const gr_dsmc *d, double u, size_t a, size_t m, const gr_dsmc_pool *p, size_t i, size_t j)
{
    if (m > 2) {
        size_t w = gr_dsmc_below(u, m - 2);
        for (size_t q = a; q < a + m; q++) {
            size_t l = d->order[q];
            if (l != i && l != j && !w--)
                return l;
        }
        return (size_t)-1;
    }
    size_t tot = pool_count(d, p);
    if (tot < 3)
        return (size_t)-1;
    size_t w = gr_dsmc_below(u, tot - 2);
    for (int y = p->lo[1]; y <= p->hi[1]; y++)
        for (int x = p->lo[0]; x <= p->hi[0]; x++) {
            size_t e = pool_cell(d, x, y);
            for (size_t q = d->start[e]; q < d->start[e + 1]; q++) {
                size_t l = d->order[q];
                if (l != i && l != j && !w--)
                    return l;
            }
        }
    return (size_t)-1;
}
