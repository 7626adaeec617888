/* Force evaluation: pair and wall contacts over Verlet lists, linked cells
 * or all pairs. Threads take strips of cell rows in colours (two, three
 * when periodic in y), so no two threads write the same grain and the sums
 * do not depend on the thread count (bit-identical runs for any
 * --threads). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dem.h"
#include "dem_contact.h"
#include "dem_eval.h"
#include "geom.h"

#ifdef _OPENMP
#include <omp.h>
#endif

#include "dem_pair.h"
#include "dem_batch.h"

/* The batched strip in a function of its own per law: inlined beside the
 * one-pair loop it made that loop slower too (register pressure). */
#define DEM_SB(NL, TL)                                                                 \
    static __attribute__((noinline)) DEM_CLONES DEM_NODIST void sb_##NL##_##TL(dem_ctx *c, int s) \
    {                                                                                  \
        strip_batched(c, NL, TL, s);                                                   \
    }
DEM_SB(GR_NORMAL_HERTZ, GR_TANG_NONE) DEM_SB(GR_NORMAL_HERTZ, GR_TANG_COULOMB)
DEM_SB(GR_NORMAL_HERTZ, GR_TANG_VISCOUS) DEM_SB(GR_NORMAL_HERTZ, GR_TANG_REGULARISED)
DEM_SB(GR_NORMAL_LINEAR, GR_TANG_NONE) DEM_SB(GR_NORMAL_LINEAR, GR_TANG_COULOMB)
DEM_SB(GR_NORMAL_LINEAR, GR_TANG_VISCOUS) DEM_SB(GR_NORMAL_LINEAR, GR_TANG_REGULARISED)
#undef DEM_SB

DEM_INLINE void batched(dem_ctx *c, const int NL, const int TL, int s)
{
#define SB(TL_)                                                                        \
    case TL_: NL == GR_NORMAL_HERTZ ? sb_GR_NORMAL_HERTZ_##TL_(c, s) : sb_GR_NORMAL_LINEAR_##TL_(c, s); break;
    switch (TL) {
    SB(GR_TANG_NONE) SB(GR_TANG_COULOMB) SB(GR_TANG_VISCOUS) SB(GR_TANG_REGULARISED)
    default: break;
    }
#undef SB
}

/* Strip s with Verlet lists, in batches or one pair at a time. Which is
 * faster depends on the packing: where the contact test's outcome follows
 * a pattern (a lattice barely in touch, a gas) the branch is predicted and
 * the batches' extra stores cost more than they save; in a flowing silo it
 * is a coin toss. So every 64th evaluation the strip is timed one way, the
 * next the other, and the faster is kept: either way the same bits. */
DEM_INLINE void strip_verlet(dem_ctx *c, const int NL, const int TL, int s)
{
    gr_dem *d = c->d;
    unsigned ph = (unsigned)(c->E & 63);
    int batch = TL != GR_TANG_SPRING && (ph == 0 || (ph > 1 && c->sway[s]));
    double t0 = ph < 2 ? omp_get_wtime() : 0.0;
    if (batch) {
        batched(c, NL, TL, s);
    } else {
        int32_t i0 = d->strips.i0[s], i1 = d->strips.i0[s + 1];
        dem_acc acc = acc_start(s);
        for (int32_t i = i0; i < i1; i++)
            grain_verlet(c, NL, TL, &acc, i);
        acc_store(c, &acc);
    }
    if (ph < 2) {
        c->st[s].strial[ph] = omp_get_wtime() - t0;
        if (ph == 1)
            c->sway[s] = c->st[s].strial[0] <= c->st[s].strial[1];
    }
}

/* Forward neighbour cells of (cx, cy): east, and the three above. */
static int forward_cells(const gr_dem_cells *g, int cx, int cy, int32_t out[4])
{
    static const int off[4][2] = {{1, 0}, {-1, 1}, {0, 1}, {1, 1}};
    int m = 0;
    for (int k = 0; k < 4; k++) {
        int x = cx + off[k][0], y = cy + off[k][1];
        if (x < 0 || x >= g->nx) {
            if (!g->px)
                continue;
            x = (x + g->nx) % g->nx;
        }
        if (y >= g->ny) {
            if (!g->py)
                continue;
            y -= g->ny;
        }
        out[m++] = y * g->nx + x;
    }
    return m;
}

DEM_INLINE void strip_cells(dem_ctx *c, const int NL, const int TL, int s)
{
    gr_dem *d = c->d;
    const gr_dem_cells *g = &d->cells;
    dem_acc acc = acc_start(s);
    for (int row = d->strips.row0[s]; row < d->strips.row0[s + 1]; row++) {
        for (int cx = 0; cx < g->nx; cx++) {
            int32_t cell = row * g->nx + cx;
            int32_t nbc[4];
            int m = forward_cells(g, cx, row, nbc);
            for (int32_t a = g->start[cell]; a < g->start[cell + 1]; a++) {
                size_t i = (size_t)g->idx[a];
                double fxi = 0, fyi = 0, tqi = 0;
                int fi = (c->flags[i] & GR_PF_FIXED) != 0;
                for (int32_t b = a + 1; b < g->start[cell + 1]; b++) {
                    size_t j = (size_t)g->idx[b];
                    if (fi && (c->flags[j] & GR_PF_FIXED))
                        continue;
                    double dx = gr_min_image(c->x[j] - c->x[i], c->Lx);
                    double dy = gr_min_image(c->y[j] - c->y[i], c->Ly);
                    pair(c, NL, TL, &acc, i, j, dx, dy, &fxi, &fyi, &tqi);
                }
                for (int q = 0; q < m; q++) {
                    for (int32_t b = g->start[nbc[q]]; b < g->start[nbc[q] + 1]; b++) {
                        size_t j = (size_t)g->idx[b];
                        if (fi && (c->flags[j] & GR_PF_FIXED))
                            continue;
                        double dx = gr_min_image(c->x[j] - c->x[i], c->Lx);
                        double dy = gr_min_image(c->y[j] - c->y[i], c->Ly);
                        pair(c, NL, TL, &acc, i, j, dx, dy, &fxi, &fyi, &tqi);
                    }
                }
                if (!fi)
                    for (int32_t k = g->cell_seg_start[cell]; k < g->cell_seg_start[cell + 1]; k++)
                        if (c->seg_on[g->cell_seg[k]])
                            wall(c, NL, TL, &acc, i, g->cell_seg[k], &fxi, &fyi, &tqi);
                add_i(c, i, fxi, fyi, tqi, TL);
            }
        }
    }
    acc_store(c, &acc);
}

DEM_INLINE void all_brute(dem_ctx *c, const int NL, const int TL)
{
    gr_dem *d = c->d;
    dem_acc acc = acc_start(0);
    for (size_t i = 0; i < d->n; i++) {
        double fxi = 0, fyi = 0, tqi = 0;
        int fi = (c->flags[i] & GR_PF_FIXED) != 0;
        for (size_t j = i + 1; j < d->n; j++) {
            if (fi && (c->flags[j] & GR_PF_FIXED))
                continue;
            double dx = gr_min_image(c->x[j] - c->x[i], c->Lx);
            double dy = gr_min_image(c->y[j] - c->y[i], c->Ly);
            pair(c, NL, TL, &acc, i, j, dx, dy, &fxi, &fyi, &tqi);
        }
        if (!fi)
            for (int k = 0; k < d->nseg; k++)
                if (c->seg_on[k])
                    wall(c, NL, TL, &acc, i, k, &fxi, &fyi, &tqi);
        add_i(c, i, fxi, fyi, tqi, TL);
    }
    acc_store(c, &acc);
}

/* Strip s pushes the grains of s and s + 1 (and, periodic in y, strip 0
 * those of the last strip, but colour 0 is never the last to push): after
 * it, kick the strips whose last push it was, while their lines are in
 * this core's cache. Their velocities are read only by the strips that
 * push them, all done by then; and nothing of the strip changes before
 * the next step, so its drift can follow at once (into buffer 2). */
static inline void kick_one(dem_ctx *c, int r)
{
    gr_dem *d = c->d;
    size_t a = (size_t)d->strips.i0[r], b = (size_t)d->strips.i0[r + 1];
    if (c->pre)
        c->st[r].kin = gr_dem_kick_drift(d, c->kick_p, 1 - c->kick_p, 2, a, b, &c->st[r].svmax, c->st[r].spre,
                                      &d->exits_pre);
    else
        c->st[r].kin = gr_dem_kick(d, c->kick_p, 1 - c->kick_p, a, b, &c->st[r].svmax);
}

static inline void kick_after(dem_ctx *c, int s)
{
    int ns = c->d->strips.n;
    for (int r = s; r <= s + 1 && r < ns; r++)
        if (c->kicker[r] == s)
            kick_one(c, r);
}

void gr_dem_eval_kick_strip(gr_dem *d, int r) { kick_one(&d->ev->c, r); }

/* One colour's strips, shared among the threads of the enclosing parallel
 * region (run by one thread outside any region, in the same order). Each
 * thread takes the colour's strips in its run (dem_balance.c): the
 * contacts, not the grains, set a strip's cost, and in a bed under gravity
 * the deep strips have the most (a split by strip count left one thread idle a
 * third of the time). Which thread runs a strip changes no bit of the
 * result. */
DEM_INLINE void colour_loop(dem_ctx *c, const int NL, const int TL, int mode, int col)
{
    int ns = c->d->strips.n, ncol = c->ncol;
    int T = omp_get_num_threads(), t = omp_get_thread_num();
    int m = (ns - col + ncol - 1) / ncol, k0 = 0, k1 = m;
    if (T > 1 && T == c->nth)
        k0 = c->split[col * (T + 1) + t], k1 = c->split[col * (T + 1) + t + 1];
    else if (T > 1)
        k0 = (int)((long)m * t / T), k1 = (int)((long)m * (t + 1) / T);
    /* timing every 16th evaluation is enough to follow the load */
    int timed = T > 1 && (c->E & 15) == 0;
    for (int k = k0; k < k1; k++) {
        int s = col + k * ncol;
        double t0 = timed ? omp_get_wtime() : 0.0;
        if (mode == GR_DEM_NB_VERLET)
            strip_verlet(c, NL, TL, s);
        else
            strip_cells(c, NL, TL, s);
        if (c->kick)
            kick_after(c, s);
        if (timed) {
            double dt = omp_get_wtime() - t0;
            c->st[s].stime = c->st[s].stime > 0 ? 0.75 * c->st[s].stime + 0.25 * dt : dt;
        }
    }
#pragma omp barrier
}

DEM_INLINE void run_colour(dem_ctx *c, const int NL, const int TL, int mode, int col)
{
    if (mode == GR_DEM_NB_BRUTE) {
#pragma omp single
        all_brute(c, NL, TL);
        return;
    }
    colour_loop(c, NL, TL, mode, col);
}

/* CALL(NL, TL) with the contact law's constants, so that each law gets its
 * own compiled loop. */
#define DEM_DISPATCH(c, CALL)                                                          \
    do {                                                                               \
        if ((c)->d->normal == GR_NORMAL_HERTZ) {                                       \
            DEM_DISPATCH_T(c, CALL, GR_NORMAL_HERTZ)                                   \
        } else {                                                                       \
            DEM_DISPATCH_T(c, CALL, GR_NORMAL_LINEAR)                                  \
        }                                                                              \
    } while (0)
#define DEM_DISPATCH_T(c, CALL, NL)                                                    \
    switch ((c)->d->tang) {                                                            \
    case GR_TANG_NONE: CALL(NL, GR_TANG_NONE); break;                                  \
    case GR_TANG_COULOMB: CALL(NL, GR_TANG_COULOMB); break;                            \
    case GR_TANG_VISCOUS: CALL(NL, GR_TANG_VISCOUS); break;                            \
    case GR_TANG_REGULARISED: CALL(NL, GR_TANG_REGULARISED); break;                    \
    case GR_TANG_SPRING: CALL(NL, GR_TANG_SPRING); break;                              \
    }

static void dispatch(dem_ctx *c, int mode, int col)
{
#define RUN(NL, TL) run_colour(c, NL, TL, mode, col)
    DEM_DISPATCH(c, RUN);
#undef RUN
}

DEM_INLINE void one_strip(dem_ctx *c, const int NL, const int TL, int s)
{
    strip_verlet(c, NL, TL, s);
    if (c->kick)
        kick_after(c, s);
}

void gr_dem_eval_strip(gr_dem *d, int s)
{
    dem_ctx *c = &d->ev->c;
#define ONE(NL, TL) one_strip(c, NL, TL, s)
    DEM_DISPATCH(c, ONE);
#undef ONE
}

void gr_dem_eval_colour(gr_dem *d, int col) { dispatch(&d->ev->c, d->ev->mode, col); }
