/* The event loops: the efficient scheme (cells, per-particle lists, the
 * complete binary tree, collision counters) and the slides' algorithm v1.0
 * (predict everything, take the minimum, O(N^2) per event). Both count
 * state-changing events (pair, wall and floor collisions) as steps. */
#include <math.h>
#include <stdio.h>

#include "edmd_int.h"

/* Cell lists are singly linked: a grain's predecessor is found from the
 * head (a cell holds about one grain, and its head and grains are in cache
 * by then), where a back link would cost a random line per change. */
void edmd_cell_remove(gr_edmd *s, int32_t i)
{
    edmd_p *p = &s->p[i];
    int32_t *link = &s->chead[p->cell];
    while (*link != i)
        link = &s->p[*link].cnext;
    *link = p->cnext;
}

void edmd_cell_insert(gr_edmd *s, int32_t i, int c)
{
    edmd_p *p = &s->p[i];
    p->cell = c;
    p->cnext = s->chead[c];
    s->chead[c] = i;
}

int edmd_schedule_all(gr_edmd *s, gr_err *err)
{
    for (size_t i = 0; i < s->n; i++)
        edmd_list_clear(s, (int32_t)i);
    for (size_t i = 0; i < s->n; i++)
        if (!s->gone[i] && edmd_predict_all(s, (int32_t)i))
            return gr_fail(err, GR_ERUN, "edmd: out of memory for events");
    if (s->use_cal)
        return edmd_cal_build(s) ? gr_fail(err, GR_ERUN, "edmd: out of memory for the calendar") : GR_OK;
    edmd_tree_build(s);
    return GR_OK;
}

static void do_cross(gr_edmd *s, int32_t i, int dir)
{
    edmd_p *p = &s->p[i];
    if (s->cacc)
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
        if (j >= 0)
            return gr_fail(err, GR_ERUN,
                           "edmd: inelastic collapse at t = %.17g: %llu collisions without time "
                           "advancing (last between grains %lld and %lld); set [edmd] collapse = tc "
                           "or threshold",
                           t, (unsigned long long)s->stuck, (long long)s->id[i], (long long)s->id[j]);
        return gr_fail(err, GR_ERUN,
                       "edmd: inelastic collapse at t = %.17g: %llu collisions without time advancing "
                       "(last grain %lld against a wall); set [edmd] collapse = tc or threshold",
                       t, (unsigned long long)s->stuck, (long long)s->id[i]);
    }
    return GR_OK;
}

/* Grain i's earliest event may have changed: tell the queue. */
static inline int q_update(gr_edmd *s, int32_t i)
{
    if (s->use_cal)
        return edmd_cal_push(s, i);
    edmd_tree_update(s, i);
    return GR_OK;
}

#define OOM(s, err) gr_fail(err, GR_ERUN, "edmd: out of memory for the event lists (%d per grain)", (s)->ecap)

int edmd_advance_tree(gr_edmd *s, double t_end, uint64_t max_coll, gr_err *err)
{
    uint64_t done = 0;
    for (;;) {
        if (max_coll && done >= max_coll)
            return GR_OK;
        if (s->sort_period && s->steps - s->last_sort >= s->sort_period && edmd_sort(s, err))
            return err->code;
        int32_t i;
        double t;
        if (s->use_cal) {
            i = edmd_cal_top(s);
            if (i == -2)
                return gr_fail(err, GR_ERUN, "edmd: out of memory for the calendar");
            t = i >= 0 ? edmd_slab(s, i)->t : EDMD_INF;
        } else {
            i = s->node[1].i;
            t = s->node[1].t;
        }
        if (!(t <= t_end) || t == EDMD_INF)
            break;
        if (s->use_cal) {
            s->fr_head++; /* consumed: the grain's next entry is queued below */
            if (s->P >= EDMD_PREFETCH_P)
                edmd_lookahead(s);
        }
        /* the grain, its leaf and its slab are all needed: fetch them at once */
        __builtin_prefetch(&s->p[i], 1);
        __builtin_prefetch(s->ev + (size_t)i * (size_t)s->ecap, 1);
        if (s->P >= EDMD_PREFETCH_P && !s->use_cal)
            edmd_tree_prefetch(s, i);
        edmd_ev ev = *edmd_slab(s, i);
        if (ev.partner >= 0) {
            __builtin_prefetch(&s->p[ev.partner], 1);
            __builtin_prefetch(s->ev + (size_t)ev.partner * (size_t)s->ecap, 1);
        }
        const int32_t e = 0; /* the earliest event's slot */
        int kind = edmd_ev_kind(&ev);
        if (kind == EV_PAIR) {
            int32_t j = ev.partner;
            if (s->p[j].ncol != ev.pncol) {
                s->cnt.stale++;
                edmd_list_remove(s, i, e);
                if (q_update(s, i))
                    return OOM(s, err);
                continue;
            }
            if (check_collapse(s, i, j, t, err))
                return err->code;
            if (s->P >= EDMD_PREFETCH_P && !s->use_cal) { /* the calendar's look-ahead did it */
                edmd_tree_prefetch(s, j);
                edmd_prefetch_block(s, i);
                edmd_prefetch_block(s, j);
            }
            s->t = t;
            edmd_collide_pair(s, i, j, t);
            edmd_list_clear(s, i);
            edmd_list_clear(s, j);
            if (edmd_predict_all(s, i) || edmd_predict_all(s, j))
                return OOM(s, err);
            if (q_update(s, i) || q_update(s, j))
                return OOM(s, err);
            done++;
            s->steps++;
        } else if (kind == EV_WALL) {
            int w = edmd_ev_sub(&ev);
            if (w >= W_SEG && t >= s->seg[w - W_SEG].open_time) { /* the gate has opened */
                s->cnt.stale++;
                edmd_list_remove(s, i, e);
                if (q_update(s, i))
                    return OOM(s, err);
                continue;
            }
            if (w != W_EXIT && check_collapse(s, i, -1, t, err))
                return err->code;
            s->t = t;
            if (w == W_EXIT) {
                if (edmd_exit(s, i, t, err))
                    return err->code;
                edmd_list_clear(s, i);
                if (!s->gone[i] && edmd_predict_all(s, i))
                    return OOM(s, err);
                if (q_update(s, i))
                    return OOM(s, err);
                continue;
            }
            edmd_collide_wall(s, i, w, t);
            edmd_list_clear(s, i);
            if (edmd_predict_all(s, i))
                return OOM(s, err);
            if (q_update(s, i))
                return OOM(s, err);
            done++;
            s->steps++;
        } else {
            s->t = t;
            edmd_list_remove(s, i, e);
            do_cross(s, i, edmd_ev_sub(&ev));
            if (edmd_predict_cross(s, i, edmd_ev_sub(&ev)))
                return OOM(s, err);
            if (q_update(s, i))
                return OOM(s, err);
            s->cnt.crossing++;
        }
    }
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
