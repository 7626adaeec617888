/* The calendar's look-ahead: its front holds the next events in order, so
 * the lines each will read are requested several events before it runs.
 * Read-only and only hints: no result depends on this file. */
#include "edmd_int.h"

/* The lines are requested in stages along the chain of dependent loads:
 * first the grain, its leaf and slab; when those have arrived, its partner
 * and the cell heads around it; then the first grains of those cells and
 * the partner's heads; last the partner's first grains. A superseded entry
 * costs a few useless requests. */
static inline void pf_heads(const gr_edmd *s, int c)
{
    int nc = s->nx * s->ny;
    for (int dy = -1; dy <= 1; dy++) {
        int r = c + dy * s->nx;
        int a = r - 1, b = r + 1;
        a = a < 0 ? 0 : a >= nc ? nc - 1 : a;
        b = b < 0 ? 0 : b >= nc ? nc - 1 : b;
        edmd_pf(&s->chead[a]);
        edmd_pf(&s->chead[b]);
    }
}

/* The first grains of the cells around c, but for those also around
 * `but` (-1: none), whose lines are requested already (the partner's
 * block overlaps the grain's). Their successors are not requested:
 * finding one reads the first grain's line, requested only two events
 * before, and the look-ahead then waited on that line more often than a
 * second grain (rare below eta 0.5) saved a miss. */
static inline void pf_grains(const gr_edmd *s, int c, int but)
{
    int nc = s->nx * s->ny, bx = 0, by = 0;
    if (but >= 0) {
        bx = but % s->nx;
        by = but / s->nx;
    }
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++) {
            int cc = c + dy * s->nx + dx;
            cc = cc < 0 ? cc + nc : cc >= nc ? cc - nc : cc;
            cc = cc < 0 ? 0 : cc >= nc ? nc - 1 : cc; /* boxes one or two cells high */
            if (but >= 0) {
                int ex = cc % s->nx - bx, ey = cc / s->nx - by;
                if (ex >= -1 && ex <= 1 && ey >= -1 && ey <= 1)
                    continue;
            }
            int32_t j = s->chead[cc];
            if (j >= 0)
                edmd_pf(&s->p[j]);
        }
}

/* The slab's first line (the second, if in use, once the grain is in). */
static inline void pf_slab(const gr_edmd *s, int32_t i)
{
    edmd_pf(s->ev + (size_t)i * (size_t)s->ecap);
}

/* What a collision reads beside the grain's line: its mass, and its spin
 * and collision clock when rough or guarded. */
static inline void pf_grain_side(const gr_edmd *s, int32_t i)
{
    if (s->m_one == 0.0)
        edmd_pf(&s->m[i]);
    if (s->rough) {
        edmd_pf(&s->w[i]);
        edmd_pf(&s->inertia[i]);
    }
    if (s->prm.collapse != GR_EDMD_COLLAPSE_NONE)
        edmd_pf(&s->tlast[i]);
}

/* The cell around which the event at front position k will look for
 * partners (for a crossing, the cell it enters), and its partner (-1 if
 * none); -1, -1 when the entry is superseded, or, once the partner's line
 * has been requested (stale_known), when its pair event is stale: a stale
 * event only drops itself, and a partner's collision counter never goes
 * back, so prefetching its cells would be wasted. */
static inline int la_cell(const gr_edmd *s, int32_t k, int32_t *partner, int stale_known)
{
    const edmd_qe *f = &s->fr[s->fr_head + k];
    const edmd_ev *e = edmd_slab(s, f->i);
    *partner = -1;
    if (e->t != f->t)
        return -1;
    int c = s->p[f->i].cell;
    if (e->partner >= 0) {
        if (stale_known && s->p[e->partner].ncol != e->pncol)
            return -1;
        *partner = e->partner;
        return c;
    }
    if (edmd_ev_kind(e) == EV_CROSS) {
        int nc = s->nx * s->ny;
        switch (edmd_ev_sub(e)) {
        case DIR_RIGHT: c += 1; break;
        case DIR_LEFT: c -= 1; break;
        case DIR_UP: c += s->nx; break;
        default: c -= s->nx; break;
        }
        c = c < 0 ? c + nc : c >= nc ? c - nc : c;
    }
    return c;
}

/* Stage q of the look-ahead for the entry at front position k. */
static void la_stage(const gr_edmd *s, int32_t k, int q)
{
    int32_t j;
    int c;
    if (q == 1) {
        int32_t i = s->fr[s->fr_head + k].i;
        edmd_pf(&s->p[i]);
        pf_slab(s, i);
        pf_grain_side(s, i);
    } else if ((c = la_cell(s, k, &j, q >= 3)) < 0) {
        return;

    } else if (q == 2) {
        int32_t i = s->fr[s->fr_head + k].i;
        if (s->p[i].nev > 4) /* a rescan reads them all */
            edmd_pf(s->ev + (size_t)i * (size_t)s->ecap + 4);
        pf_heads(s, c);
        if (j >= 0) {
            edmd_pf(&s->p[j]);
            pf_slab(s, j);
            pf_grain_side(s, j);
        }
    } else if (q == 3) {
        pf_grains(s, c, -1);
        if (j >= 0)
            pf_heads(s, s->p[j].cell);
    } else if (j >= 0) {
        pf_grains(s, s->p[j].cell, c);
    }
}

/* Each entry goes through the stages in order as it nears the head; the
 * stage reached is kept in the entry, since superseded entries dropped at
 * the head and new ones inserted make entries skip positions. */
void edmd_lookahead(gr_edmd *s)
{
    int32_t ahead = s->fr_n - s->fr_head;
    int32_t k = ahead - 1 < EDMD_LA_1 ? ahead - 1 : EDMD_LA_1;
    for (; k >= 0; k--) {
        edmd_qe *f = &s->fr[s->fr_head + k];
        int need = k <= EDMD_LA_4 ? 4 : k <= EDMD_LA_3 ? 3 : k <= EDMD_LA_2 ? 2 : 1;
        while (f->pad < need)
            la_stage(s, k, ++f->pad);
    }
}
