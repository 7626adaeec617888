/* The one-pair loop's pieces: per-strip tallies, a pair contact, a wall
 * contact, a grain's own sum, and a grain's list pairs and walls one pair
 * at a time. Included by dem_force.c only (and, through dem_batch.h,
 * shared with the batched loop). */
#ifndef GR_DEM_PAIR_H
#define GR_DEM_PAIR_H

#include <math.h>
#include <stdint.h>

#include "dem_contact.h"
#include "dem_eval.h"
#include "geom.h"

/* Per-strip tallies live on the strip's stack while it runs: strips of one
 * colour run at once, and shared per-strip slots touched at every contact
 * would put the threads' cache lines in a tug of war. */
typedef struct {
    double smax, sel;
    long si, sj;
    int s;
} dem_acc;

static inline dem_acc acc_start(int s) { return (dem_acc){-INFINITY, 0.0, -1, -1, s}; }

static inline void acc_store(dem_ctx *c, const dem_acc *a)
{
    dem_strip *r = c->st + a->s;
    r->smax = a->smax;
    r->sel = a->sel;
    r->si = a->si;
    r->sj = a->sj;
}

DEM_INLINE void track(dem_acc *a, double rel, long i, long j, double el)
{
    a->sel += el;
    if (rel > a->smax) {
        a->smax = rel;
        a->si = i;
        a->sj = j;
    }
}

/* The tangential spring of (own, key): its slot (-1 when the table is
 * full, which the step reports) and, unless the contact is new, its zeta. */
DEM_INLINE long hist_find(dem_ctx *c, size_t own, int32_t key, double *zeta)
{
    int fresh;
    long slot = dem_hist_slot(&c->d->hist, own, key, c->E, &fresh);
    if (slot < 0) {
        c->hist_full = 1;
        c->full_i = (long)own;
    } else if (!fresh) {
        *zeta = c->d->hist.z[slot];
    }
    return slot;
}

/* Pair contact i-j (j = i + separation dx, dy) if they overlap. */
DEM_INLINE void pair(dem_ctx *c, const int NL, const int TL, dem_acc *a, size_t i, size_t j,
                     double dx, double dy, double *fxi, double *fyi, double *tqi)
{
    double ri = c->rad[i], rj = c->rad[j], rs = ri + rj;
    double r2 = dx * dx + dy * dy;
    if (r2 >= rs * rs)
        return;
    double r = sqrt(r2);
    double xi = rs - r;
    double inv = r > 0 ? 1.0 / r : 0.0;
    double nx = dx * inv, ny = dy * inv;
    if (r == 0) nx = 1.0;
    double dvx = c->ux[j] - c->ux[i], dvy = c->uy[j] - c->uy[i];
    double wsum = 0.0;
    if (TL != GR_TANG_NONE)
        wsum = c->uw[i] * ri + c->uw[j] * rj;
    double Fx, Fy, Ft, zeta = 0.0;
    long slot = -1;
    int32_t key = 0;
    if (TL == GR_TANG_SPRING) {
        size_t own = c->tag[i] < c->tag[j] ? i : j;
        key = c->tag[own == i ? j : i];
        /* v_t and F_t are symmetric in i and j, so zeta needs no sign per owner */
        slot = hist_find(c, own, key, &zeta);
    }
    double el;
    dem_law_eval(&c->law, NL, TL, xi, nx, ny, dvx, dvy, wsum, &zeta, c->integ, &Fx, &Fy, &Ft, &el);
    if (TL == GR_TANG_SPRING && slot >= 0)
        dem_hist_write(&c->d->hist, slot, key, zeta, c->E);
    c->fx[j] += Fx;
    c->fy[j] += Fy;
    *fxi -= Fx;
    *fyi -= Fy;
    if (TL != GR_TANG_NONE) {
        c->tq[j] -= Ft * rj;
        *tqi -= Ft * ri;
    }
    /* compared without a divide, as in dem_batch.h, so that either loop
     * records the same pair */
    double dm = 2.0 * (ri < rj ? ri : rj);
    a->sel += el;
    if (xi > a->smax * dm) {
        a->smax = xi / dm;
        a->si = (long)i;
        a->sj = (long)j;
    }
}

/* Contacts of grain i with segment k. */
DEM_INLINE void wall(dem_ctx *c, const int NL, const int TL, dem_acc *a, size_t i, int k,
                     double *fxi, double *fyi, double *tqi)
{
    const gr_dem_seg *sg = &c->d->seg[k];
    double off = c->seg_off[k];
    double ax = sg->x0, ay = sg->y0 + off, bx = sg->x1, by = sg->y1 + off;
    double r = c->rad[i], xi, nx, ny;
    if (!dem_seg_contact(ax, ay, bx - ax, by - ay, c->x[i], c->y[i], r, &xi, &nx, &ny))
        return;
    double dvx = c->ux[i], dvy = c->uy[i] - c->seg_vy[k];
    double wsum = TL != GR_TANG_NONE ? c->uw[i] * r : 0.0;
    double Fx, Fy, Ft, zeta = 0.0;
    long slot = -1;
    int32_t key = (int32_t)(c->d->ntag + (size_t)k);
    if (TL == GR_TANG_SPRING)
        slot = hist_find(c, i, key, &zeta);
    double el;
    dem_law_eval(&c->law_w, NL, TL, xi, nx, ny, dvx, dvy, wsum, &zeta, c->integ, &Fx, &Fy, &Ft, &el);
    if (TL == GR_TANG_SPRING && slot >= 0)
        dem_hist_write(&c->d->hist, slot, key, zeta, c->E);
    *fxi += Fx;
    *fyi += Fy;
    if (TL != GR_TANG_NONE)
        *tqi -= Ft * r;
    double *sf = c->sseg + (size_t)a->s * c->sstride + (size_t)k * 3;
    sf[0] -= Fx;
    sf[1] -= Fy;
    sf[2] += Fx * nx + Fy * ny;
    track(a, xi / (2.0 * r), (long)i, -1 - k, el);
}

DEM_INLINE void add_i(dem_ctx *c, size_t i, double fxi, double fyi, double tqi, const int TL)
{
    c->fx[i] += fxi;
    c->fy[i] += fyi;
    if (TL != GR_TANG_NONE)
        c->tq[i] += tqi;
}

/* Grain i's list pairs and walls, one pair at a time. */
DEM_INLINE void grain_verlet(dem_ctx *c, const int NL, const int TL, dem_acc *acc, int32_t i)
{
    gr_dem *d = c->d;
    const int32_t *restrict nbs = d->nb_start, *restrict nbj = d->nb_j;
    const int32_t *restrict sgs = d->sg_start, *restrict sgj = d->sg_j;
    double fxi = 0, fyi = 0, tqi = 0;
    double xi = c->x[i], yi = c->y[i];
    for (int32_t k = nbs[i]; k < nbs[i + 1]; k++) {
        int32_t j = nbj[k];
        double dx = c->x[j] - xi, dy = c->y[j] - yi;
        if (c->Lx > 0) dx = gr_min_image(dx, c->Lx);
        if (c->Ly > 0) dy = gr_min_image(dy, c->Ly);
        pair(c, NL, TL, acc, (size_t)i, (size_t)j, dx, dy, &fxi, &fyi, &tqi);
    }
    for (int32_t k = sgs[i]; k < sgs[i + 1]; k++)
        if (c->seg_on[sgj[k]])
            wall(c, NL, TL, acc, (size_t)i, sgj[k], &fxi, &fyi, &tqi);
    add_i(c, (size_t)i, fxi, fyi, tqi, TL);
}

#endif
