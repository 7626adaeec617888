/* The event loops: the efficient scheme (cells, per-particle lists, the
 * event queue, collision counters) and the slides' algorithm v1.0
 * (predict everything, take the minimum, O(N^2) per event). Both count
 * state-changing events (pair, wall and floor collisions) as steps. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "edmd_int.h"

int edmd_schedule_all(gr_edmd *s, gr_err *err)
{
    for (size_t i = 0; i < s->n; i++)
        edmd_list_clear(s, (int32_t)i);
    for (size_t i = 0; i < s->n; i++)
        if (!s->gone[i] && !s->p[i].asleep && edmd_predict_all(s, (int32_t)i))
            return gr_fail(err, GR_ERUN, "edmd: out of memory for events");
    if (s->q->build(s))
        return gr_fail(err, GR_ERUN, "edmd: out of memory for the event queue");
    s->t_gate = edmd_next_gate(s, s->t);
    return GR_OK;
}

static void do_cross(gr_edmd *s, int32_t i, int dir)
{
    edmd_p *p = &s->p[i];
    if (edmd_measuring_cells(s))
        edmd_field_flush(s, i, s->t);
    int ix = p->cell % s->nx, iy = p->cell / s->nx;
    edmd_cell_remove(s, i);
    switch (dir) {
    case DIR_RIGHT:
        if (++ix == s->nx) {
            ix = 0;
            p->x -= s->W;
        }
        break;
    case DIR_LEFT:
        if (--ix < 0) {
            ix = s->nx - 1;
            p->x += s->W;
        }
        break;
    case DIR_UP:
        if (++iy == s->ny) {
            iy = 0;
            p->y -= s->H - s->ybot;
        }
        break;
    default:
        if (--iy < 0) {
            iy = s->ny - 1;
            p->y += s->H - s->ybot;
        }
        break;
    }
    edmd_cell_insert(s, i, ix + s->nx * iy);
}

/* What to try after a collapse: the guard when it is off; when it is on,
 * a collapse it let through is a grain held at zero gap (at rest on a
 * wall under gravity, or wedged), which a larger guard only postpones. */
static const char *collapse_hint(const gr_edmd *s, char *buf, size_t n)
{
    if (s->prm.collapse == GR_EDMD_COLLAPSE_NONE)
        return "set [edmd] collapse = tc, threshold or sleep";
    if (s->prm.collapse == GR_EDMD_COLLAPSE_TC || s->prm.collapse == GR_EDMD_COLLAPSE_SLEEP)
        snprintf(buf, n, "the guard collapse = %s (tc = %g) is on and did not prevent it: a grain at rest "
                         "against a wall under gravity; try a larger [edmd] tc (10 times), or dem or cd, "
                         "which model resting packings",
                 s->prm.collapse == GR_EDMD_COLLAPSE_SLEEP ? "sleep" : "tc", s->prm.tc);
    else
        snprintf(buf, n, "the guard collapse = threshold (v_threshold = %g) is on and did not prevent it: a "
                         "grain at rest against a wall under gravity; a resting packing is dem's or cd's to "
                         "model", s->prm.v_threshold);
    return buf;
}

static int check_collapse(gr_edmd *s, int32_t i, int32_t j, double t, gr_err *err)
{
    if (!isfinite(t))
        return gr_fail(err, GR_ERUN, "edmd: event time %g for grain %lld at t = %.17g", t,
                       (long long)s->id[i], s->t);
    if (t - s->t_prev_coll <= 1e-13 * (1.0 + fabs(t)))
        s->stuck++;
    else
        s->stuck = 0;
    s->t_prev_coll = t;
    if (s->stuck > 100000 + 10 * (uint64_t)s->n) {
        char buf[300];
        const char *hint = collapse_hint(s, buf, sizeof buf);
        if (j >= 0)
            return gr_fail(err, GR_ERUN,
                           "edmd: inelastic collapse at t = %.17g: %llu collisions without time "
                           "advancing (last between grains %lld and %lld); %s",
                           t, (unsigned long long)s->stuck, (long long)s->id[i], (long long)s->id[j], hint);
        return gr_fail(err, GR_ERUN,
                       "edmd: inelastic collapse at t = %.17g: %llu collisions without time advancing "
                       "(last grain %lld against a wall); %s",
                       t, (unsigned long long)s->stuck, (long long)s->id[i], hint);
    }
    return GR_OK;
}

/* The event handlers return 1 for a state-changing event (a step), 0 for
 * another, -1 on failure (err set). Grain i's event is ev, at time t. */
static int oom(const gr_edmd *s, gr_err *err)
{
    gr_fail(err, GR_ERUN, "edmd: out of memory for the event lists (%d per grain)", s->ecap);
    return -1;
}

/* A stale event only drops itself. */
static int drop(gr_edmd *s, int32_t i, gr_err *err)
{
    s->cnt.stale++;
    edmd_list_remove(s, i, 0);
    return s->q->update(s, i) ? oom(s, err) : 0;
}

/* Grain i's events after a collision: its own, or, if it fell asleep,
 * its moving neighbours' contacts with it. */
static int after_collision(gr_edmd *s, int32_t i)
{
    if (!s->p[i].asleep)
        return edmd_predict_all(s, i) || s->q->update(s, i);
    return edmd_sleep_neighbours(s, i) || s->q->update(s, i);
}

/* Sleeping grain m wakes at time t with a new collision count, so that
 * its moving neighbours' contacts with it as a sleeper go stale, and its
 * own events. */
static int rouse(gr_edmd *s, int32_t m, double t)
{
    edmd_wake(s, m, t);
    s->p[m].ncol++;
    edmd_list_clear(s, m);
    return edmd_predict_all(s, m) || s->q->update(s, m);
}

/* Grain j no longer holds the sleepers beside or above it: they wake at
 * time t, and those beside or above them, and so on. A grain woken at
 * rest is about to move and holds nobody: a sleeper over it would pin it
 * at zero gap, where its bounces take no time. A moving grain j that left
 * a collision fast (`moving`) is no support either (rest.c counts only
 * sleepers and slow grains), but it frees only the sleepers nothing else
 * holds: a grain sliding under a bed it touches would otherwise wake the
 * whole bed at each of its bounces. */
static int wake_above(gr_edmd *s, int32_t j, double t, int moving)
{
    if (!s->wake_stack && !(s->wake_stack = malloc(s->n * sizeof *s->wake_stack)))
        return GR_ERUN;
    int32_t *st = s->wake_stack;
    size_t top = 0;
    st[top++] = j;
    while (top) {
        int32_t k = st[--top];
        size_t got = edmd_rests_on(s, k, st + top, s->n - top), kept = top;
        for (size_t q = top; q < top + got; q++) {
            if (moving && k == j && edmd_held(s, st[q]))
                continue;
            if (rouse(s, st[q], t))
                return GR_ERUN;
            st[kept++] = st[q];
        }
        top = kept;
    }
    return GR_OK;
}

/* A sleeper may rest on a slow moving grain (rest.c); once that grain
 * leaves a collision faster than v_sleep it is no support. */
static int release(gr_edmd *s, int32_t k, double t)
{
    if (!s->sleep_on || !edmd_any_asleep(s) || s->p[k].asleep || edmd_slow(s, k))
        return GR_OK;
    return wake_above(s, k, t, 1);
}

/* A gate opens at s->t_gate: the grains over it were no sleeper's
 * support, but a sleeper may lean on one that rested on the gate, so
 * every sleeper wakes there. */
static int gate_opens(gr_edmd *s, gr_err *err)
{
    double t = s->t_gate;
    edmd_measure_advance(s, t);
    s->t = t;
    for (size_t m = 0; m < s->n && edmd_any_asleep(s); m++)
        if (s->p[m].asleep && rouse(s, (int32_t)m, t))
            return oom(s, err);
    s->t_gate = edmd_next_gate(s, t);
    return 0;
}

/* Moving grain i meets sleeping grain j, which wakes or stays put. */
static int on_sleeper(gr_edmd *s, int32_t i, int32_t j, double t, gr_err *err)
{
    s->t = t;
    edmd_collide_sleeper(s, i, j, t);
    edmd_list_clear(s, i);
    if (!s->p[j].asleep && (edmd_predict_all(s, j) || s->q->update(s, j) || wake_above(s, j, t, 0)))
        return oom(s, err);
    return after_collision(s, i) || release(s, i, t) ? oom(s, err) : 1;
}

static inline int on_pair(gr_edmd *s, int32_t i, const edmd_ev *ev, double t, gr_err *err)
{
    int32_t j = ev->partner;
    if (s->p[j].ncol != ev->pncol)
        return drop(s, i, err);
    if (check_collapse(s, i, j, t, err))
        return -1;
    if (s->p[j].asleep)
        return on_sleeper(s, i, j, t, err);
    if (edmd_engine_prefetches(s)) {
        s->q->prefetch(s, j);
        edmd_prefetch_block(s, i);
        edmd_prefetch_block(s, j);
    }
    s->t = t;
    edmd_collide_pair(s, i, j, t);
    edmd_list_clear(s, i);
    edmd_list_clear(s, j);
    if (edmd_predict_all(s, i) || edmd_predict_all(s, j) || s->q->update(s, i) || s->q->update(s, j) ||
        release(s, i, t) || release(s, j, t))
        return oom(s, err);
    return 1;
}

static inline int on_wall(gr_edmd *s, int32_t i, const edmd_ev *ev, double t, gr_err *err)
{
    int w = edmd_ev_sub(ev);
    if (w >= W_SEG && t >= s->seg[w - W_SEG].open_time) /* the gate has opened */
        return drop(s, i, err);
    if (w != W_EXIT && check_collapse(s, i, -1, t, err))
        return -1;
    s->t = t;
    if (w == W_EXIT) {
        if (edmd_exit(s, i, t, err))
            return -1;
        edmd_list_clear(s, i);
        if ((!s->gone[i] && edmd_predict_all(s, i)) || s->q->update(s, i))
            return oom(s, err);
        return 0;
    }
    edmd_collide_wall(s, i, w, t);
    edmd_list_clear(s, i);
    return after_collision(s, i) || release(s, i, t) ? oom(s, err) : 1;
}

static inline int on_cross(gr_edmd *s, int32_t i, const edmd_ev *ev, double t, gr_err *err)
{
    s->t = t;
    edmd_list_remove(s, i, 0);
    do_cross(s, i, edmd_ev_sub(ev));
    if (edmd_predict_cross(s, i, edmd_ev_sub(ev)) || s->q->update(s, i))
        return oom(s, err);
    s->cnt.crossing++;
    return 0;
}

/* The next event, taken from the queue and handled; the earliest event of
 * a grain is its slab's slot 0. */
int edmd_advance_tree(gr_edmd *s, double t_end, uint64_t max_coll, gr_err *err)
{
    const edmd_queue *q = s->q;
    const int pf = edmd_engine_prefetches(s);
    uint64_t done = 0;
    for (;;) {
        if (max_coll && done >= max_coll)
            return GR_OK;
        if (s->sort_period && s->steps - s->last_sort >= s->sort_period && edmd_sort(s, err))
            return err->code;
        double t;
        int32_t i = q->top(s, &t);
        if (i == -2)
            return gr_fail(err, GR_ERUN, "edmd: out of memory for the event queue");
        if (s->t_gate <= t && s->t_gate <= t_end) {
            if (gate_opens(s, err))
                return err->code;
            continue;
        }
        if (!(t <= t_end) || t == EDMD_INF)
            break;
        q->pop(s);
        /* the grain, its leaf and its slab are all needed: fetch them at once */
        __builtin_prefetch(&s->p[i], 1);
        __builtin_prefetch(s->ev + (size_t)i * (size_t)s->ecap, 1);
        if (pf)
            q->prefetch(s, i);
        edmd_ev ev = *edmd_slab(s, i);
        if (ev.partner >= 0) {
            __builtin_prefetch(&s->p[ev.partner], 1);
            __builtin_prefetch(s->ev + (size_t)ev.partner * (size_t)s->ecap, 1);
        }
        int kind = edmd_ev_kind(&ev);
        int r = kind == EV_PAIR ? on_pair(s, i, &ev, t, err)
                : kind == EV_WALL ? on_wall(s, i, &ev, t, err)
                                  : on_cross(s, i, &ev, t, err);
        if (r < 0)
            return err->code;
        done += (uint64_t)r;
        s->steps += (uint64_t)r;
    }
    if (s->t_gate <= t_end && gate_opens(s, err))
        return err->code;
    if (t_end < EDMD_INF && t_end > s->t)
        s->t = t_end;
    return GR_OK;
}

/* Algorithm v1.0: every pair and every wall, every event. */
int edmd_advance_naive(gr_edmd *s, double t_end, uint64_t max_coll, gr_err *err)
{
    uint64_t done = 0;
    int32_t n = (int32_t)s->n;
    for (;;) {
        if (max_coll && done >= max_coll)
            return GR_OK;
        double best = EDMD_INF;
        int32_t bi = -1, bj = -1;
        for (int32_t i = 0; i < n; i++)
            for (int32_t j = i + 1; j < n; j++) {
                if (s->gone[i] || s->gone[j])
                    continue;
                double t = edmd_pair_time(s, &s->p[i], &s->p[j]);
                if (t < best) {
                    best = t;
                    bi = i;
                    bj = j;
                }
            }
        for (int32_t i = 0; i < n; i++)
            for (int w = 0; w < W_SEG + s->nseg; w++) {
                if (s->gone[i] || (w > W_EXIT && w < W_SEG))
                    continue;
                int rel = w == W_FLOOR  ? s->floor != GR_FLOOR_FIXED
                          : w == W_EXIT ? s->y_exit > -EDMD_INF || s->open[0] || s->open[1] || s->open[3]
                          : w >= W_SEG  ? 1
                                        : s->hard[w] && !(w == GR_BOTTOM && s->floor != GR_FLOOR_FIXED);
                if (!rel)
                    continue;
                double t = edmd_wall_time(s, i, w, s->t, EDMD_INF);
                if (t < best) {
                    best = t;
                    bi = i;
                    bj = -1 - w;
                }
            }
        if (best < s->t)
            best = s->t;
        if (!(best <= t_end) || best == EDMD_INF)
            break;
        if (check_collapse(s, bi, bj >= 0 ? bj : -1, best, err))
            return err->code;
        s->t = best;
        if (bj >= 0)
            edmd_collide_pair(s, bi, bj, best);
        else if (-1 - bj == W_EXIT) {
            if (edmd_exit(s, bi, best, err))
                return err->code;
            continue;
        } else
            edmd_collide_wall(s, bi, -1 - bj, best);
        done++;
        s->steps++;
    }
    if (t_end < EDMD_INF && t_end > s->t)
        s->t = t_end;
    return GR_OK;
}
