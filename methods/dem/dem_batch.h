/* The Verlet-list pair loop in batches, for the laws without spring history.
 * Most list pairs are not in contact (a skin of 0.2 d lists about three
 * neighbours per grain against 1-2 contacts in a dense bed, fewer where it
 * flows), and a branch per pair on a coin-toss test mispredicts often. So a
 * strip is taken in chunks of grains, each in three passes:
 *   1. over the chunk's lists, squared distance against (ri + rj)^2, every
 *      pair written and the cursor moved by the test's 0 or 1: the
 *      contacting pairs packed, in list order, without a branch;
 *   2. the contact law for the packed pairs, one loop without branches
 *      that the compiler vectorises (square roots and the divide two to
 *      eight at a time);
 *   3. the forces added to the grains in the order of the scalar loop
 *      (list order, then walls, then the grain's own sum), so that every
 *      sum keeps its bits and the result stays independent of threads.
 * Included by dem_force.c only. */
#ifndef GR_DEM_BATCH_H
#define GR_DEM_BATCH_H

#include <math.h>
#include <stdint.h>
#ifdef __SSE2__
#include <emmintrin.h>
#endif

#include "dem_contact.h"
#include "dem_eval.h"

typedef struct {
    int32_t i[DEM_BATCH], j[DEM_BATCH];
    double dx[DEM_BATCH], dy[DEM_BATCH], r2[DEM_BATCH], rs[DEM_BATCH];
    double r[DEM_BATCH], sxi[DEM_BATCH]; /* distance, square root of the overlap */
    /* pass 2's results: force on j, torques on j and i, elastic energy, overlap */
    double fx[DEM_BATCH], fy[DEM_BATCH], tj[DEM_BATCH], ti[DEM_BATCH], el[DEM_BATCH], xi[DEM_BATCH];
} dem_batch;

/* out[k] = sqrt(in[k]) for k < m, two at a time where SSE2 is (every
 * x86-64): libm's sqrt may set errno, which keeps the compiler from
 * vectorising a loop that calls it; the instruction rounds the same. */
DEM_INLINE void batch_sqrt(const double *restrict in, double *restrict out, int m)
{
    int k = 0;
#ifdef __SSE2__
    for (; k + 2 <= m; k += 2)
        _mm_storeu_pd(out + k, _mm_sqrt_pd(_mm_loadu_pd(in + k)));
#endif
    for (; k < m; k++)
        out[k] = sqrt(in[k]);
}

/* Pass 2 over the m packed contacts. Written as the scalar pair() computes
 * (the same operations in the same order, no contraction under C11), so
 * the vectorised loops give the same bits. */
DEM_INLINE void batch_law(const dem_ctx *c, const int NL, const int TL, dem_batch *restrict b, int m)
{
    const double *restrict ux = c->ux, *restrict uy = c->uy, *restrict uw = c->uw, *restrict rad = c->rad;
    const double kn = c->law.kn, gn = c->law.gn, gt = c->law.gt, mu = c->law.mu;
    const int clip = c->law.clip;
    /* pass 1 stored the separation only: r^2, r_i + r_j again (the same
     * operations), and grains on one spot get n = (1, 0) */
    for (int k = 0; k < m; k++) {
        double dx = b->dx[k], dy = b->dy[k], r2 = dx * dx + dy * dy;
        b->r2[k] = r2;
        b->rs[k] = rad[b->i[k]] + rad[b->j[k]];
        b->dx[k] = r2 > 0 ? dx : 1.0;
        b->dy[k] = r2 > 0 ? dy : 0.0;
    }
    batch_sqrt(b->r2, b->r, m);
    for (int k = 0; k < m; k++)
        b->xi[k] = b->rs[k] - b->r[k];
    if (NL == GR_NORMAL_HERTZ)
        batch_sqrt(b->xi, b->sxi, m);
    for (int k = 0; k < m; k++) {
        int32_t i = b->i[k], j = b->j[k];
        double r = b->r[k], xi = b->xi[k];
        /* r = 0 (grains on one spot; dx = 1, dy = 0 above): n = (1, 0) */
        double inv = 1.0 / (r + (double)(r == 0.0));
        double nx = b->dx[k] * inv, ny = b->dy[k] * inv;
        double dvx = ux[j] - ux[i], dvy = uy[j] - uy[i];
        double vn = dvx * nx + dvy * ny;
        double el = NL == GR_NORMAL_HERTZ ? kn * xi * b->sxi[k] : kn * xi;
        double fn = el - gn * vn;
        fn = clip && fn < 0.0 ? 0.0 : fn;
        double ft = 0.0;
        if (TL != GR_TANG_NONE) {
            double ri = rad[i], rj = rad[j];
            double wsum = uw[i] * ri + uw[j] * rj;
            double vt = -dvx * ny + dvy * nx - wsum;
            double afn = fabs(fn);
            if (TL == GR_TANG_COULOMB) {
                ft = vt > 0 ? -mu * afn : vt < 0 ? mu * afn : 0.0;
            } else if (TL == GR_TANG_VISCOUS) {
                ft = -gt * vt;
            } else {
                double a = gt * fabs(vt), bb = mu * afn;
                double mm = a < bb ? a : bb;
                ft = vt > 0 ? -mm : vt < 0 ? mm : 0.0;
            }
            b->tj[k] = ft * rj;
            b->ti[k] = ft * ri;
        }
        b->fx[k] = fn * nx - ft * ny;
        b->fy[k] = fn * ny + ft * nx;
        b->el[k] = el * xi * (NL == GR_NORMAL_HERTZ ? 0.4 : 0.5);
    }
}

/* Pass 3, flat: grain i's list pairs all have j > i (dem_neigh.c), so
 * within a chunk no contact adds to a grain whose turn has come, and its
 * own sum may wait until a run of grains is done: fx[i] still gets its
 * terms in the scalar loop's order. The run ends at each grain with wall
 * segments, whose walls follow its pairs (the elastic energy and the
 * largest overlap are taken in the scalar loop's order too). One loop
 * over a run's contacts instead of one per grain: the predictor lost that
 * loop's end about once per grain. */
DEM_INLINE void batch_add(dem_ctx *c, const int NL, const int TL, dem_acc *a, const dem_batch *restrict b,
                          int32_t g0, int ng, int m)
{
    double *restrict fx = c->fx, *restrict fy = c->fy, *restrict tq = c->tq;
    const double *restrict rad = c->rad;
    const int32_t *restrict sgs = c->d->sg_start, *restrict sgj = c->d->sg_j;
    double ox[DEM_BATCH_GRAINS], oy[DEM_BATCH_GRAINS], ot[DEM_BATCH_GRAINS];
    int32_t wg[DEM_BATCH_GRAINS + 1];
    int nw = 0;
    for (int g = 0; g < ng; g++) {
        ox[g] = oy[g] = ot[g] = 0.0;
        wg[nw] = g;
        nw += sgs[g0 + g] < sgs[g0 + g + 1];
    }
    wg[nw++] = ng - 1; /* the chunk's last run */
    int k = 0, g = 0;
    for (int w = 0; w < nw && g < ng; w++) {
        int ge = wg[w];
        int32_t ie = g0 + ge;
        /* contacts are packed in list order: grain ie's end where i passes it */
        for (; k < m && b->i[k] <= ie; k++) {
            int32_t i = b->i[k], j = b->j[k], gi = i - g0;
            fx[j] += b->fx[k];
            fy[j] += b->fy[k];
            ox[gi] -= b->fx[k];
            oy[gi] -= b->fy[k];
            if (TL != GR_TANG_NONE) {
                tq[j] -= b->tj[k];
                ot[gi] -= b->ti[k];
            }
            double ri = rad[i], rj = rad[j], dm = 2.0 * (ri < rj ? ri : rj);
            a->sel += b->el[k];
            if (b->xi[k] > a->smax * dm) {
                a->smax = b->xi[k] / dm;
                a->si = i;
                a->sj = j;
            }
        }
        for (int32_t q = sgs[ie]; q < sgs[ie + 1]; q++)
            if (c->seg_on[sgj[q]])
                wall(c, NL, TL, a, (size_t)ie, sgj[q], ox + ge, oy + ge, ot + ge);
        for (; g <= ge; g++)
            add_i(c, (size_t)(g0 + g), ox[g], oy[g], ot[g], TL);
    }
}

/* Pass 1 over list pairs k0 .. k1 - 1 (PER: periodic sides, a constant
 * so that the open silo's loop carries no wrap tests); returns the
 * number of contacts packed. */
DEM_INLINE int batch_test(const dem_ctx *c, const int PER, dem_batch *restrict b, int32_t k0, int32_t k1)
{
    const int32_t *restrict nbj = c->d->nb_j, *restrict nbi = c->d->nb_i;
    const double *restrict x = c->x, *restrict y = c->y, *restrict rad = c->rad;
    const double Lx = c->Lx, Ly = c->Ly;
    int m = 0;
    for (int32_t k = k0; k < k1; k++) {
        int32_t i = nbi[k], j = nbj[k];
        double dx = x[j] - x[i], dy = y[j] - y[i];
        if (PER && Lx > 0) dx = gr_min_image(dx, Lx);
        if (PER && Ly > 0) dy = gr_min_image(dy, Ly);
        double rs = rad[i] + rad[j], r2 = dx * dx + dy * dy;
        b->i[m] = i, b->j[m] = j, b->dx[m] = dx, b->dy[m] = dy;
        m += r2 < rs * rs;
    }
    return m;
}

/* Strip s in chunks: pass 1 (batch_test), then passes 2 and 3. Pass 1
 * runs over the chunk's list pairs in one flat loop (the grain of each
 * pair from nb_i): a loop per grain ended after its 0 to 6 pairs, a branch
 * the predictor loses about once per grain. */
DEM_INLINE void strip_batched(dem_ctx *c, const int NL, const int TL, int s)
{
    gr_dem *d = c->d;
    const int32_t *restrict nbs = d->nb_start;
    const int per = c->Lx > 0 || c->Ly > 0;
    int32_t i0 = d->strips.i0[s], i1 = d->strips.i0[s + 1];
    dem_acc acc = acc_start(s);
    dem_batch b;
    for (int32_t g0 = i0; g0 < i1;) {
        /* the most grains (up to DEM_BATCH_GRAINS) whose list pairs fit:
         * nbs is monotone, so a binary search whose steps depend only on
         * the count (a loop per grain lost its end to the predictor) */
        int32_t kb = nbs[g0];
        int ng = 0, n = (i1 - g0 < DEM_BATCH_GRAINS ? i1 - g0 : DEM_BATCH_GRAINS) + 1;
        while (n > 1) {
            int half = n / 2;
            ng = nbs[g0 + ng + half] - kb <= DEM_BATCH ? ng + half : ng;
            n -= half;
        }
        if (ng == 0) {
            /* a grain with more list pairs than a batch holds: one at a time */
            grain_verlet(c, NL, TL, &acc, g0++);
            continue;
        }
        int32_t k1 = nbs[g0 + ng];
        int m = per ? batch_test(c, 1, &b, kb, k1) : batch_test(c, 0, &b, kb, k1);
        batch_law(c, NL, TL, &b, m);
        batch_add(c, NL, TL, &acc, &b, g0, ng, m);
        g0 += ng;
    }
    acc_store(c, &acc);
}

#endif
