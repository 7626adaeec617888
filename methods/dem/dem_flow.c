/* How the threads share a velocity Verlet step: the kick fused into the
 * colours of the force evaluation, and the one-barrier step
 * (gr_dem_eval_flow). Above the evaluation, below the step. */
#include <math.h>
#include <string.h>

#include "dem.h"
#include "dem_sync.h"
#include "dem_eval.h"

#ifdef _OPENMP
#include <omp.h>
#endif

int gr_dem_eval_fuse_kick(gr_dem *d, int p)
{
    struct gr_dem_eval *ev = d->ev;
    int ns = ev->ns, ncol = ev->c.ncol;
    const int32_t *i0 = d->strips.i0;
    ev->c.kick = 0;
    /* external forces join at the end of the evaluation, after any kick */
    if (ev->mode != GR_DEM_NB_VERLET || d->ext_fx || ns < 1 || i0[0] != 0 || (size_t)i0[ns] != d->n)
        return 0;
    /* a strip's pushes come from itself, the strip below, and (periodic in
     * y) strip 0 for the last one: the last of these colours kicks it */
    /* written only when it changes, and kin, svmax not cleared (every
     * strip is kicked once, which writes both): the worker threads keep
     * these lines in their caches from step to step */
    for (int r = 0; r < ns; r++) {
        int k = r;
        if (r >= 1 && (r - 1) % ncol > k % ncol)
            k = r - 1;
        if (ev->kicker[r] != k)
            ev->kicker[r] = k;
    }
    ev->c.kick = 1, ev->c.kick_p = p; /* the pointers: gr_dem_eval_begin */
    return 1;
}

int gr_dem_eval_pre(gr_dem *d, int on)
{
    struct gr_dem_eval *ev = d->ev;
    ev->c.pre = on && ev->c.kick;
    atomic_store_explicit(&d->exits_pre, 0, memory_order_relaxed);
    return ev->c.pre;
}

/* The two largest squared moves of strips [s0, s1) (pre: of the drift
 * done ahead), as gr_dem_top2 over their pairs in strip order. */
static void strips_top2(const dem_strip *st, int s0, int s1, int pre, double m[2])
{
    m[0] = m[1] = 0;
    for (int s = s0; s < s1; s++) {
        const double *v = pre ? st[s].spre : st[s].smove;
        gr_dem_top2_add(v[0], m);
        gr_dem_top2_add(v[1], m);
    }
}

static double strips_top2_sum(const struct gr_dem_eval *ev, int pre)
{
    double m[2];
    strips_top2(ev->st, 0, ev->ns, pre, m);
    return sqrt(m[0]) + sqrt(m[1]);
}

/* The two largest squared moves over the threads' own (pre: of the drift
 * done ahead): the same two as over every strip's. */
static double tred_top2(const struct gr_dem_eval *ev, int pre)
{
    double v[128];
    int T = ev->c.nth < 64 ? ev->c.nth : 64;
    for (int t = 0; t < T; t++) {
        const double *m = pre ? ev->tred[t].pre : ev->tred[t].move;
        v[2 * t] = m[0], v[2 * t + 1] = m[1];
    }
    return gr_dem_top2_sum(v, 2 * (size_t)T);
}

/* The first strip of thread 1's run in the one-barrier step: the serial
 * sums go on from there after thread 0's. */
static int tred_from(const struct gr_dem_eval *ev) { return ev->split[3 * (ev->c.nth + 1) + 1]; }

int gr_dem_pre_use(gr_dem *d, uint64_t E, double *moved)
{
    struct gr_dem_eval *ev = d->ev;
    int use = ev && d->pre_E == E && !d->need_build;
    d->pre_E = 0;
    if (ev)
        ev->drifted = use;
    if (!use)
        return 0;
    /* the drifted buffer becomes the new one; the state it replaces is
     * two steps old, and a refused step keeps the current one */
    int q = 1 - d->cur;
    for (int f = 0; f < F_NBASIC; f++) {
        double *t = d->f[f][q];
        d->f[f][q] = d->f[f][2];
        d->f[f][2] = t;
    }
    *moved = ev->tred_on ? tred_top2(ev, 1) : strips_top2_sum(ev, 1);
    atomic_store_explicit(&d->exits, atomic_load_explicit(&d->exits_pre, memory_order_relaxed),
                          memory_order_relaxed);
    d->exits_known = 1;
    return 1;
}

double gr_dem_eval_moved(const gr_dem *d)
{
    const struct gr_dem_eval *ev = d->ev;
    return ev->tred_on ? tred_top2(ev, 0) : strips_top2_sum(ev, 0);
}

double gr_dem_eval_kinetic(const gr_dem *d)
{
    const struct gr_dem_eval *ev = d->ev;
    double ek = 0.0;
    if (ev->tred_on) {
        ek = ev->tred[0].kin0;
        for (int s = tred_from(ev); s < ev->ns; s++)
            ek += ev->kin[s]; /* packed by the threads (reduce_run) */
        return ek;
    }
    for (int s = 0; s < ev->ns; s++)
        ek += ev->st[s].kin;
    return ek;
}

double gr_dem_eval_vmax2(const gr_dem *d)
{
    const struct gr_dem_eval *ev = d->ev;
    double m = 0.0;
    if (ev->tred_on) {
        for (int t = 0; t < ev->c.nth; t++)
            m = fmax(m, ev->tred[t].vmax2);
        return m;
    }
    for (int s = 0; s < ev->ns; s++)
        m = fmax(m, ev->st[s].svmax);
    return m;
}

/* ---- the step with one barrier ----------------------------------------
 * With two colours and the kick fused, a thread needs from the others only
 * the strips next to its own: a strip is pushed once its own grains and the
 * grains above it are drifted, and (colour 1) once its neighbours of colour
 * 0, which push the same grains, are done. So instead of a barrier after
 * the drift and after each colour, each strip carries two flags (the epoch
 * of its drift and of its pushes) and a thread waits only on the flags of
 * the strips beside its run. The order in which each grain receives its
 * pushes is that of the colours, as with barriers: the same bits. */

int gr_dem_eval_flow_begin(gr_dem *d)
{
    struct gr_dem_eval *ev = d->ev;
    int nth = ev->c.nth, ns = ev->ns;
    if (!ev->c.kick || ev->c.ncol != 2 || ns < 2 || nth < 2 || nth > 64)
        return 0;
    ev->epoch++;
    ev->tred_on = 1;
    ev->flow_E = ev->c.E, ev->flow_gen = d->list_gen;
    int cut[65], *S = ev->split + 3 * (nth + 1);
    if (!ev->cut_keep) {
        /* one cut for the whole step: a thread's run of strips is drifted,
         * pushed and kicked by it, so the time to balance is their sum */
        gr_dem_cut_runs(d, ev, 0, 1, ns, nth, cut);
        if (memcmp(cut, S, (size_t)(nth + 1) * sizeof *S)) /* as kicker above */
            memcpy(S, cut, (size_t)(nth + 1) * sizeof *S);
    }
    /* A run that starts at an even strip: the last push on that strip is
     * the previous run's (its strip below, colour 1), whose thread would
     * kick it and drift it ahead, so that the strip's lines moved to the
     * other core and back every step (thread 0 took 2-3 us longer than
     * thread 1 when the cut was even, under 1 us when odd). Its own thread
     * kicks it instead, after its run (kicker -1; gr_dem_eval_fuse_kick
     * restores the table at the next step). */
    for (int t = 1; t < nth; t++)
        if (S[t] > 0 && S[t] < ns && S[t] % 2 == 0)
            ev->kicker[S[t]] = -1;
    return 1;
}

int gr_dem_eval_flow_cut(const gr_dem *d, int T, int *cut)
{
    const struct gr_dem_eval *ev = d->ev;
    if (!ev || !ev->tred_on || ev->c.nth != T || ev->ns != d->strips.n)
        return 0;
    memcpy(cut, ev->split + 3 * (T + 1), (size_t)(T + 1) * sizeof *cut);
    return 1;
}

/* This thread's strips of colour col in [s0, s1), the two ends first (the
 * neighbours' runs wait on them), then the rest upwards. */
static int colour_order(int s0, int s1, int col, int *out)
{
    int first = s0 + ((col - s0) % 2 + 2) % 2, last = s1 - 1 - (((s1 - 1 - col) % 2 + 2) % 2), m = 0;
    if (first >= s1)
        return 0;
    out[m++] = first;
    if (last > first)
        out[m++] = last;
    for (int s = first + 2; s < last; s += 2)
        out[m++] = s;
    return m;
}

/* Thread t's results over its run [s0, s1): the overlap and the drift's
 * moves of the strips it pushed, the speeds and the moves ahead of those
 * it kicked (strip r is kicked after the pushes of kicker[r], r or r - 1,
 * or, kicker -1, by its own thread after its run). The other threads
 * pack their strips' sums, which the serial end adds in strip order, into
 * ev->sel and ev->kin: a line for eight strips, not a record each. */
static void reduce_run(struct gr_dem_eval *ev, int t, int s0, int s1)
{
    gr_dem_tred r = {.best = 0.0, .bi = -1, .bj = -1};
    const dem_strip *st = ev->st;
    for (int s = s0; s < s1; s++) {
        if (st[s].smax > r.best)
            r.best = st[s].smax, r.bi = st[s].si, r.bj = st[s].sj;
    }
    if (!ev->drifted)
        strips_top2(st, s0, s1, 0, r.move);
    int r0 = s0, r1 = s1 < ev->ns ? s1 + 1 : s1;
    if (r0 < r1 && ev->kicker[r0] >= 0 && ev->kicker[r0] < s0)
        r0++;
    if (r1 > s1 && (ev->kicker[s1] >= s1 || ev->kicker[s1] < 0))
        r1--;
    for (int s = r0; s < r1; s++)
        r.vmax2 = fmax(r.vmax2, st[s].svmax);
    if (ev->c.pre)
        strips_top2(st, r0, r1, 1, r.pre);
    if (t == 0) {
        /* strips [0, s1) are all pushed and kicked by this thread */
        for (int s = 0; s < s1; s++)
            r.eel0 += st[s].sel, r.kin0 += st[s].kin;
    } else {
        for (int s = s0; s < s1; s++)
            ev->sel[s] = st[s].sel;
        for (int s = r0; s < r1; s++)
            ev->kin[s] = st[s].kin;
    }
    ev->tred[t] = r;
}

/* The lines of strip s that its pushes and kick write (forces and
 * velocities of buffer q, and with the drift done ahead buffer 2), taken
 * for writing with prefetchw (GCC emits it for __builtin_prefetch only
 * with -mprfchw): run s - 1 of the thread below read them and pushed into
 * them this step, so each is in the other core's cache, and the stores of
 * the kick would fetch them one at a time, each for the full trip between
 * the cores (330 ns where they share no cache). A hint: nothing is
 * written, so the flags' order is all the safety needed. */
static void claim_strip(const gr_dem *d, int s, int q, int pre)
{
    static const int fq[] = {F_FX, F_FY, F_TQ, F_VX, F_VY, F_W}, f2[] = {F_X, F_Y, F_VX, F_VY, F_W, F_FX, F_FY, F_TQ};
    const double *a[14];
    int m = 0;
    for (int k = 0; k < 6; k++)
        if (d->f[fq[k]][q])
            a[m++] = d->f[fq[k]][q];
    for (int k = 0; pre && k < 8; k++)
        if (d->f[f2[k]][2])
            a[m++] = d->f[f2[k]][2];
    for (size_t i = (size_t)d->strips.i0[s] & ~(size_t)7; i < (size_t)d->strips.i0[s + 1]; i += 8)
        for (int k = 0; k < m; k++) {
#if defined(__x86_64__) || defined(__i386__)
            __asm__ volatile("prefetchw %0" ::"m"(a[k][i]));
#else
            __builtin_prefetch(a[k] + i, 1, 3);
#endif
        }
}

void gr_dem_eval_flow(gr_dem *d, int p, int q, int *scratch, size_t stride)
{
    struct gr_dem_eval *ev = d->ev;
    const int32_t *i0 = d->strips.i0;
    int ns = ev->ns, t = omp_get_thread_num(), T = ev->c.nth;
    scratch += (size_t)t * stride;
    const int *S = ev->split + 3 * (T + 1);
    int s0 = S[t], s1 = S[t + 1];
    uint64_t ep = ev->epoch;
    dem_strip *st = ev->st;
    int timed = (ev->c.E & 15) == 0;
    for (int s = s0; s < s1; s++) {
        double t0 = timed ? omp_get_wtime() : 0.0;
        if (!ev->drifted) /* else the last step's kicks did it */
            gr_dem_drift(d, p, q, 1, (size_t)i0[s], (size_t)i0[s + 1], st[s].smove, &d->exits);
        if (timed)
            st[s].tdrift = omp_get_wtime() - t0;
        atomic_store_explicit(&st[s].dflag, ep, memory_order_release);
    }
    for (int col = 0; col < 2; col++) {
        int m = colour_order(s0, s1, col, scratch);
        for (int k = 0; k < m; k++) {
            int s = scratch[k];
            if (s + 1 < ns)
                gr_dem_wait_epoch(&st[s + 1].dflag, ep);
            if (col == 1) {
                gr_dem_wait_epoch(&st[s - 1].cflag, ep); /* colour 1 strips are odd: s >= 1 */
                if (s == s0 && t > 0) /* the run below has pushed it (an odd cut) */
                    claim_strip(d, s, q, ev->c.pre);
                if (s + 1 < ns)
                    gr_dem_wait_epoch(&st[s + 1].cflag, ep);
            }
            double t0 = timed ? omp_get_wtime() : 0.0;
            gr_dem_eval_strip(d, s);
            if (timed) {
                double dt = omp_get_wtime() - t0 + st[s].tdrift;
                st[s].stime = st[s].stime > 0 ? 0.75 * st[s].stime + 0.25 * dt : dt;
            }
            atomic_store_explicit(&st[s].cflag, ep, memory_order_release);
        }
    }
    if (s0 < s1 && ev->kicker[s0] < 0) { /* see gr_dem_eval_flow_begin */
        gr_dem_wait_epoch(&st[s0 - 1].cflag, ep);
        double t0 = timed ? omp_get_wtime() : 0.0;
        gr_dem_eval_kick_strip(d, s0);
        if (timed) /* counted with the strip's own time of this step */
            st[s0].stime += 0.25 * (omp_get_wtime() - t0);
    }
    reduce_run(ev, t, s0, s1);
}
