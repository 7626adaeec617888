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
    c->smax[a->s] = a->smax;
    c->sel[a->s] = a->sel;
    c->sarg_i[a->s] = a->si;
    c->sarg_j[a->s] = a->sj;
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
        int fresh;
        size_t own = c->tag[i] < c->tag[j] ? i : j;
        key = c->tag[own == i ? j : i];
        slot = dem_hist_slot(&c->d->hist, own, key, c->E, &fresh);
        if (slot < 0) {
            c->hist_full = 1;
            c->full_i = (long)own;
        } else if (!fresh) {
            zeta = c->d->hist.z[slot];
        }
        /* v_t and F_t are symmetric in i and j, so zeta needs no sign per owner */
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
    if (TL == GR_TANG_SPRING) {
        int fresh;
        slot = dem_hist_slot(&c->d->hist, i, key, c->E, &fresh);
        if (slot < 0) {
            c->hist_full = 1;
            c->full_i = (long)i;
        } else if (!fresh) {
            zeta = c->d->hist.z[slot];
        }
    }
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

#include "dem_batch.h"

/* The batched strip in a function of its own per law: inlined beside the
 * one-pair loop it made that loop slower too (register pressure). */
#define DEM_SB(NL, TL)                                                                 \
    static __attribute__((noinline)) void sb_##NL##_##TL(dem_ctx *c, int s)            \
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
        c->strial[2 * s + ph] = omp_get_wtime() - t0;
        if (ph == 1)
            c->sway[s] = c->strial[2 * s] <= c->strial[2 * s + 1];
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
 * push them, all done by then. */
static inline void kick_after(dem_ctx *c, int s)
{
    gr_dem *d = c->d;
    int ns = d->strips.n;
    for (int r = s; r <= s + 1 && r < ns; r++)
        if (c->kicker[r] == s)
            c->kin[r] = gr_dem_kick(d, c->kick_p, 1 - c->kick_p, (size_t)d->strips.i0[r],
                                    (size_t)d->strips.i0[r + 1], c->svmax + r);
}

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
            c->stime[s] = c->stime[s] > 0 ? 0.75 * c->stime[s] + 0.25 * dt : dt;
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


void gr_dem_eval_free(struct gr_dem_eval *ev)
{
    if (!ev)
        return;
    free(ev->smax), free(ev->sel), free(ev->sseg), free(ev->soff), free(ev->svy);
    free(ev->si), free(ev->sj), free(ev->son);
    free(ev->stime), free(ev->strial), free(ev->sway), free(ev->split), free(ev->kin), free(ev->kicker);
    free(ev->smove), free(ev->svmax), free(ev->tdrift);
    free((void *)ev->dflag), free((void *)ev->cflag);
    free(ev);
}

static int eval_scratch(gr_dem *d, int ns, int nseg, size_t nsf, int nth, gr_err *err)
{
    struct gr_dem_eval *ev = d->ev;
    if (!ev && !(ev = d->ev = calloc(1, sizeof *ev)))
        return gr_fail(err, GR_ERUN, "out of memory in the force evaluation");
    if ((size_t)ns > ev->cap_ns) {
        free(ev->smax), free(ev->sel), free(ev->si), free(ev->sj), free(ev->stime);
        free(ev->strial), free(ev->sway);
        free(ev->kin), free(ev->kicker), free(ev->smove);
        free(ev->svmax), free(ev->tdrift), free((void *)ev->dflag), free((void *)ev->cflag);
        ev->svmax = malloc((size_t)ns * sizeof *ev->svmax);
        ev->tdrift = calloc((size_t)ns, sizeof *ev->tdrift);
        ev->dflag = malloc((size_t)ns * sizeof *ev->dflag);
        ev->cflag = malloc((size_t)ns * sizeof *ev->cflag);
        for (int k = 0; ev->dflag && ev->cflag && k < ns; k++) {
            atomic_init(&ev->dflag[k], ev->epoch);
            atomic_init(&ev->cflag[k], ev->epoch);
        }
        ev->kin = malloc((size_t)ns * sizeof *ev->kin);
        ev->kicker = malloc((size_t)ns * sizeof *ev->kicker);
        ev->smove = malloc((size_t)ns * 2 * sizeof *ev->smove);
        ev->smax = malloc((size_t)ns * sizeof *ev->smax);
        ev->sel = malloc((size_t)ns * sizeof *ev->sel);
        ev->si = malloc((size_t)ns * sizeof *ev->si);
        ev->sj = malloc((size_t)ns * sizeof *ev->sj);
        ev->stime = calloc((size_t)ns, sizeof *ev->stime);
        ev->strial = calloc(2 * (size_t)ns, sizeof *ev->strial);
        ev->sway = calloc((size_t)ns, 1);
        ev->cap_ns = (size_t)ns;
    } else if (ns != ev->ns) {
        memset(ev->stime, 0, (size_t)ns * sizeof *ev->stime);
    }
    size_t nsp = (size_t)4 * ((size_t)nth + 1); /* three colours, then the one cut */
    if (nsp > ev->cap_split) {
        free(ev->split);
        ev->split = malloc(nsp * sizeof *ev->split);
        ev->cap_split = nsp;
    }
    if ((size_t)nseg + 1 > ev->cap_seg) {
        free(ev->soff), free(ev->svy), free(ev->son);
        ev->soff = malloc(((size_t)nseg + 1) * sizeof *ev->soff);
        ev->svy = malloc(((size_t)nseg + 1) * sizeof *ev->svy);
        ev->son = malloc((size_t)nseg + 1);
        ev->cap_seg = (size_t)nseg + 1;
    }
    if (nsf > ev->cap_sseg) {
        free(ev->sseg);
        ev->sseg = aligned_alloc(64, nsf * sizeof *ev->sseg);
        ev->cap_sseg = nsf;
    }
    if (!ev->smax || !ev->sel || !ev->si || !ev->sj || !ev->soff || !ev->svy || !ev->son || !ev->sseg ||
        !ev->stime || !ev->strial || !ev->sway || !ev->split || !ev->kin || !ev->kicker || !ev->smove || !ev->svmax ||
        !ev->tdrift || !ev->dflag || !ev->cflag) {
        gr_dem_eval_free(ev);
        d->ev = NULL;
        return gr_fail(err, GR_ERUN, "out of memory in the force evaluation");
    }
    return GR_OK;
}

int gr_dem_eval_begin(gr_dem *d, int q, double t_eval, uint64_t E, double integ, int mode, gr_err *err)
{
    if (mode == GR_DEM_NB_CELLS) {
        if (gr_dem_bin(d, d->f[F_X][q], d->f[F_Y][q], err))
            return err->code;
    }
    int ns = mode == GR_DEM_NB_BRUTE ? 1 : d->strips.n;
    int nseg = d->nseg;
    /* whole cache lines per strip: strips of a colour run at once */
    size_t sstride = ((size_t)(nseg > 0 ? nseg : 1) * 3 + 7) & ~(size_t)7;
    size_t nsf = (size_t)ns * sstride;
    int nth = (int)(d->par.threads > 0 ? d->par.threads : 1);
    if (eval_scratch(d, ns, nseg, nsf, nth, err))
        return err->code;
    struct gr_dem_eval *ev = d->ev;
    memset(ev->sseg, 0, nsf * sizeof *ev->sseg);
    for (int s = 0; s < ns; s++) {
        ev->smax[s] = -INFINITY;
        ev->sel[s] = 0.0;
        ev->si[s] = ev->sj[s] = -1;
    }
    for (int k = 0; k < nseg; k++) {
        ev->son[k] = t_eval < d->seg[k].open_time;
        ev->soff[k] = ev->svy[k] = 0.0;
        if (d->seg[k].vibrating) {
            ev->soff[k] = gr_floor_offset(&d->sc.floor, t_eval);
            ev->svy[k] = gr_floor_velocity(&d->sc.floor, t_eval);
        }
    }
    size_t n = d->n;
    if (!d->f_zeroed) {
        memset(d->f[F_FX][q], 0, n * sizeof(double));
        memset(d->f[F_FY][q], 0, n * sizeof(double));
        if (d->rot)
            memset(d->f[F_TQ][q], 0, n * sizeof(double));
    }
    d->f_zeroed = 0;
    ev->mode = mode;
    ev->ns = ns;
    ev->nseg = nseg;
    ev->t_eval = t_eval;
    ev->E = E;
    ev->c = (dem_ctx){
        .d = d,
        .x = d->f[F_X][q], .y = d->f[F_Y][q],
        .fx = d->f[F_FX][q], .fy = d->f[F_FY][q], .tq = d->f[F_TQ][q],
        .ux = d->f[F_VX][q], .uy = d->f[F_VY][q], .uw = d->f[F_W][q], .rad = d->rad,
        .tag = d->tag, .flags = d->flags,
        .law = {d->kn, d->gn, d->kt, d->gt, d->mu, d->par.dt, d->clip},
        .law_w = {d->kn, d->gw, d->kt, d->gt, d->mu, d->par.dt, d->clip},
        .E = E, .integ = integ, .Lx = d->Lx, .Ly = d->Ly,
        .seg_off = ev->soff, .seg_vy = ev->svy, .seg_on = ev->son,
        .smax = ev->smax, .sel = ev->sel, .sarg_i = ev->si, .sarg_j = ev->sj, .sseg = ev->sseg,
        .sstride = sstride, .ncol = ns > 1 ? gr_dem_colours(d) : 1,
        .stime = ev->stime, .strial = ev->strial, .sway = ev->sway, .split = ev->split, .nth = nth,
    };
    gr_dem_split_strips(d, ev, nth);
    return GR_OK;
}

int gr_dem_eval_ncolours(const gr_dem *d) { return d->ev ? d->ev->c.ncol : 1; }

void gr_dem_eval_colour(gr_dem *d, int col) { dispatch(&d->ev->c, d->ev->mode, col); }

/* The evaluation's error, if any: a grain out of history slots, or the
 * largest overlap past the bound (pair bi, bj; bj = -1 - s a segment). */
static int eval_error(const gr_dem *d, const dem_ctx *c, double best, long bi, long bj, gr_err *err)
{
    const struct gr_dem_eval *ev = d->ev;
    if (c->hist_full)
        return gr_fail(err, GR_ERUN, "t = %.9g: grain id %lld has more than %d contacts at once; the packing is unphysically compressed",
                       ev->t_eval, (long long)d->tag_id[d->tag[c->full_i]], d->hist.cap);
    if (!(best > d->par.max_overlap))
        return GR_OK;
    char other[96];
    if (bj >= 0)
        snprintf(other, sizeof other, "grain id %lld", (long long)d->tag_id[d->tag[bj]]);
    else
        snprintf(other, sizeof other, "wall segment %ld", -1 - bj);
    if (ev->E == 0)
        return gr_fail(err, GR_EINPUT,
                       "initial state: grain id %lld overlaps %s by %.4g of its diameter (bound max_overlap = %g); place the grains apart",
                       (long long)d->tag_id[d->tag[bi]], other, best, d->par.max_overlap);
    return gr_fail(err, GR_ERUN,
                   "unstable at t = %.9g: grain id %lld overlaps %s by %.4g of its diameter (bound max_overlap = %g); lower dt or check the scene",
                   ev->t_eval, (long long)d->tag_id[d->tag[bi]], other, best, d->par.max_overlap);
}

/* Per segment, the strips' forces summed in strip order. */
static void segment_sums(const struct gr_dem_eval *ev, double *seg_out)
{
    for (int k = 0; k < ev->nseg; k++) {
        double a = 0, b = 0, cfn = 0;
        for (int s = 0; s < ev->ns; s++) {
            const double *sf = ev->sseg + (size_t)s * ev->c.sstride + (size_t)k * 3;
            a += sf[0];
            b += sf[1];
            cfn += sf[2];
        }
        seg_out[3 * k] = a;
        seg_out[3 * k + 1] = b;
        seg_out[3 * k + 2] = cfn;
    }
}

int gr_dem_eval_end(gr_dem *d, double *seg_out, gr_err *err)
{
    struct gr_dem_eval *ev = d->ev;
    dem_ctx *c = &ev->c;
    size_t n = d->n;
    if (d->ext_fx) {
        for (size_t i = 0; i < n; i++) {
            c->fx[i] += d->ext_fx[i];
            c->fy[i] += d->ext_fy[i];
        }
    }
    double best = 0.0, eel = 0.0;
    long bi = -1, bj = -1;
    for (int s = 0; s < ev->ns; s++) {
        eel += ev->sel[s];
        if (ev->smax[s] > best) {
            best = ev->smax[s];
            bi = ev->si[s];
            bj = ev->sj[s];
        }
    }
    if (seg_out)
        segment_sums(ev, seg_out);
    d->max_ovl = best;
    d->eel_eval = eel;
    return eval_error(d, c, best, bi, bj, err);
}

void gr_dem_eval_run(gr_dem *d)
{
    int nth = (int)(d->par.threads > 0 ? d->par.threads : 1), ncol = gr_dem_eval_ncolours(d);
    if (nth > 1 && d->ev->ns > 1 && !omp_in_parallel()) {
#pragma omp parallel num_threads(nth)
        for (int col = 0; col < ncol; col++)
            gr_dem_eval_colour(d, col);
    } else {
        for (int col = 0; col < ncol; col++)
            gr_dem_eval_colour(d, col);
    }
}

int gr_dem_eval_at(gr_dem *d, int q, double t_eval, uint64_t E, double integ, int mode,
                   double *seg_out, gr_err *err)
{
    if (gr_dem_eval_begin(d, q, t_eval, E, integ, mode, err))
        return err->code;
    gr_dem_eval_run(d);
    return gr_dem_eval_end(d, seg_out, err);
}
