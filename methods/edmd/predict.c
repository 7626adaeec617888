/* Event prediction: pair collisions (a quadratic, since gravity cancels in
 * relative motion), hard walls and virtual-wall crossings (parabolas), the
 * vibrating floor (a transcendental equation, roots.c) and segments
 * (segment.c). Every time is a function of the particles' reference
 * states only, never of the moment of prediction, so the naive and the
 * tree algorithms compute the same bits. */
#include <math.h>

#include "edmd_int.h"

double edmd_pair_time(const gr_edmd *s, const edmd_p *a, const edmd_p *b)
{
    double t0 = a->t > b->t ? a->t : b->t;
    double sa = t0 - a->t, sb = t0 - b->t;
    double g = s->g;
    double dx = (b->x + b->vx * sb) - (a->x + a->vx * sa);
    double dy = (b->y + sb * (b->vy - 0.5 * g * sb)) - (a->y + sa * (a->vy - 0.5 * g * sa));
    double dvx = b->vx - a->vx;
    double dvy = (b->vy - g * sb) - (a->vy - g * sa);
    if (s->periodic_x)
        dx = edmd_min_image(dx, s->W);
    if (s->periodic_y)
        dy = edmd_min_image(dy, s->H - s->ybot);
    double bb = dx * dvx + dy * dvy;
    if (bb >= 0.0)
        return EDMD_INF;
    double sig = a->r + b->r;
    double c = dx * dx + dy * dy - sig * sig;
    if (c <= 0.0)
        return t0; /* touching or overlapping by rounding, and approaching */
    double vv = dvx * dvx + dvy * dvy;
    double disc = bb * bb - vv * c;
    if (disc <= 0.0)
        return EDMD_INF;
    return t0 + c / (sqrt(disc) - bb);
}

double edmd_cross_time(const gr_edmd *s, int32_t i, int *dir)
{
    const edmd_p *p = &s->p[i];
    int ix = p->cell % s->nx, iy = p->cell / s->nx;
    double best = EDMD_INF;
    *dir = -1;
    if (p->vx > 0.0 && (ix < s->nx - 1 || s->periodic_x)) {
        double d = (ix + 1) * s->cw - p->x;
        best = d > 0.0 ? d / p->vx : 0.0;
        *dir = DIR_RIGHT;
    } else if (p->vx < 0.0 && (ix > 0 || s->periodic_x)) {
        double d = p->x - ix * s->cw;
        best = d > 0.0 ? d / -p->vx : 0.0;
        *dir = DIR_LEFT;
    }
    double yb = s->ybot + iy * s->ch;
    /* Under gravity the rise to the top of the cell is solved from the
     * present state: from the reference state its first root may be a
     * passage through that level on the way up to an earlier cell. */
    double t0 = p->t, y = p->y, vy = p->vy;
    if (s->g != 0.0 && s->t > p->t) {
        best += p->t - s->t;
        t0 = s->t;
        y = edmd_y_at(p, t0, s->g);
        vy = edmd_vy_at(p, t0, s->g);
    }
    if (iy < s->ny - 1 || s->periodic_y) {
        double tu = edmd_rise_time(yb + s->ch - y, vy, s->g);
        if (tu < best) {
            best = tu;
            *dir = DIR_UP;
        }
    }
    if (iy > 0 || s->periodic_y) {
        double td = edmd_fall_time(y - yb, vy, s->g);
        if (td < best) {
            best = td;
            *dir = DIR_DOWN;
        }
    }
    return t0 + best;
}

/* Can a grain whose centre is in `cell` touch `wall`? */
int edmd_wall_relevant(const gr_edmd *s, int cell, int wall)
{
    int ix = cell % s->nx, iy = cell / s->nx;
    switch (wall) {
    case GR_LEFT:
        return s->hard[GR_LEFT] && ix == 0;
    case GR_RIGHT:
        return s->hard[GR_RIGHT] && ix == s->nx - 1;
    case GR_TOP:
        return s->hard[GR_TOP] && iy == s->ny - 1;
    case GR_BOTTOM:
        return s->hard[GR_BOTTOM] && s->floor == GR_FLOOR_FIXED && iy == 0;
    case W_FLOOR:
        return s->floor != GR_FLOOR_FIXED && (s->ybot + iy * s->ch < s->fA + s->rmax || iy == 0);
    case W_EXIT:
        return (s->y_exit > -EDMD_INF && s->ybot + iy * s->ch <= s->y_exit) || (s->open[GR_LEFT] && ix == 0) ||
               (s->open[GR_RIGHT] && ix == s->nx - 1) || (s->open[GR_TOP] && iy == s->ny - 1);
    default:
        return 0;
    }
}

/* The sawtooth floor rises at V = A omega / pi from -A to A and drops back:
 * on each rise h is a parabola, as for a fixed floor seen from the floor. */
static double floor_saw_time(const gr_edmd *s, const edmd_p *p, double a, double horizon)
{
    double g = s->g, A = s->fA, om = s->fomega;
    double V = A * om / M_PI, T = 2.0 * M_PI / om;
    double b;
    if (!edmd_floor_band(p, g, A, T, horizon, &a, &b))
        return EDMD_INF;
    double k = floor(a / T);
    for (int guard = 0; guard < 100000; guard++, k += 1.0) {
        double t0 = k * T, t1 = (k + 1.0) * T;
        double u = a > t0 ? a : t0;
        if (u > b)
            break;
        double h0 = edmd_y_at(p, u, g) - p->r - (-A + V * (u - t0));
        double h1 = edmd_vy_at(p, u, g) - V;
        double tc = u + edmd_fall_time(h0, h1, g);
        if (tc <= t1)
            return tc;
    }
    return EDMD_INF;
}

/* Time of the next collision with a wall, searched from t_from; walls with
 * an open-ended search (the moving floor) stop at the horizon. */
double edmd_wall_time(gr_edmd *s, int32_t i, int wall, double t_from, double horizon)
{
    const edmd_p *p = &s->p[i];
    double dt;
    switch (wall) {
    case GR_LEFT:
        if (p->vx >= 0.0)
            return EDMD_INF;
        dt = p->x - p->r;
        return p->t + (dt > 0.0 ? dt / -p->vx : 0.0);
    case GR_RIGHT:
        if (p->vx <= 0.0)
            return EDMD_INF;
        dt = s->W - p->r - p->x;
        return p->t + (dt > 0.0 ? dt / p->vx : 0.0);
    case GR_TOP:
        return p->t + edmd_rise_time(s->H - p->r - p->y, p->vy, s->g);
    case GR_BOTTOM:
        return p->t + edmd_fall_time(p->y - p->r, p->vy, s->g);
    case W_EXIT: {
        double te = EDMD_INF;
        if (s->y_exit > -EDMD_INF)
            te = fmin(te, edmd_fall_time(p->y - s->y_exit, p->vy, s->g));
        if (s->open[GR_LEFT] && p->vx < 0.0)
            te = fmin(te, p->x > 0.0 ? p->x / -p->vx : 0.0);
        if (s->open[GR_RIGHT] && p->vx > 0.0)
            te = fmin(te, p->x < s->W ? (s->W - p->x) / p->vx : 0.0);
        if (s->open[GR_TOP])
            te = fmin(te, edmd_rise_time(s->H - p->y, p->vy, s->g));
        return p->t + te;
    }
    case W_FLOOR: {
        double a = t_from > p->t ? t_from : p->t;
        switch (s->floor) {
        case GR_FLOOR_SINE:
            return edmd_floor_sine_time(s, p, a, horizon);
        case GR_FLOOR_SAWTOOTH:
            return floor_saw_time(s, p, a, horizon);
        default: /* high-frequency limits: the floor stays at y = 0 */
            return p->t + edmd_fall_time(p->y - p->r, p->vy, s->g);
        }
    }
    default:
        if (wall >= W_SEG)
            return edmd_segment_time(s, i, wall - W_SEG, t_from, horizon);
        return EDMD_INF;
    }
}

/* How far ahead moving grain i's contacts with sleepers are searched: to
 * its next crossing or hard-wall collision, events that cannot go stale
 * and after which its contacts are predicted again (predict_cross looks
 * at the sleepers of the whole new block). Gates and exits are left out:
 * a gate's event is dropped once it opens. */
static double mover_horizon(gr_edmd *s, int32_t i)
{
    int dir;
    double h = edmd_cross_time(s, i, &dir);
    if (dir < 0)
        h = EDMD_INF;
    unsigned mask = s->any_wall ? s->wmask[s->p[i].cell] & 0x1fu : 0u; /* the sides and the floor */
    for (int w = 0; mask; w++, mask >>= 1)
        if (mask & 1u)
            h = fmin(h, edmd_wall_time(s, i, w, s->t, h));
    if (!(h < EDMD_INF)) { /* it has crossed cells by the time it falls out of the domain */
        const edmd_p *p = &s->p[i];
        h = p->t + edmd_fall_time(p->y - s->ybot + 1.0, p->vy, s->g);
    }
    return h;
}

/* Moving grain i against sleeping grain j, which stays put: under gravity
 * their gap is no quadratic but the quartic of a segment's end (roots.c),
 * a circle of radius r_i + r_j about j's centre, searched up to i's
 * horizon. */
static double sleeper_time(gr_edmd *s, int32_t i, int32_t j)
{
    edmd_p q = s->p[i];
    const edmd_p *b = &s->p[j];
    q.r += b->r;
    double a = s->t > q.t ? s->t : q.t;
    return edmd_point_time(s, &q, b->x, b->y, a, mover_horizon(s, i));
}

static int push_pairs_in_cell(gr_edmd *s, int32_t i, int c)
{
    const edmd_p *pi = &s->p[i];
    double now = s->t;
    for (int32_t j = s->chead[c]; j >= 0; j = s->p[j].cnext) {
        if (j == i)
            continue;
        double t = s->p[j].asleep ? sleeper_time(s, i, j) : edmd_pair_time(s, pi, &s->p[j]);
        if (t < EDMD_INF && edmd_ev_push(s, i, t > now ? t : now, EV_PAIR, j, s->p[j].ncol))
            return GR_ERUN;
    }
    return GR_OK;
}

static int push_sleepers_in_cell(gr_edmd *s, int32_t i, int c)
{
    double now = s->t;
    for (int32_t j = s->chead[c]; j >= 0; j = s->p[j].cnext) {
        if (j == i || !s->p[j].asleep)
            continue;
        double t = sleeper_time(s, i, j);
        if (t < EDMD_INF && edmd_ev_push(s, i, t > now ? t : now, EV_PAIR, j, s->p[j].ncol))
            return GR_ERUN;
    }
    return GR_OK;
}

static int push_cross_and_walls(gr_edmd *s, int32_t i)
{
    int dir;
    double now = s->t;
    double tc = edmd_cross_time(s, i, &dir);
    if (dir >= 0 && tc < EDMD_INF && edmd_ev_push(s, i, tc > now ? tc : now, EV_CROSS, dir, 0))
        return GR_ERUN;
    unsigned mask = s->any_wall ? s->wmask[s->p[i].cell] : 0u; /* a random line when N is large */
    for (int w = 0; mask; w++, mask >>= 1) {
        if (!(mask & 1u))
            continue;
        double tw = edmd_wall_time(s, i, w, now, tc);
        if (tw <= tc && tw < EDMD_INF && edmd_ev_push(s, i, tw > now ? tw : now, EV_WALL, w, 0))
            return GR_ERUN;
    }
    if (s->nseg) {
        int c = s->p[i].cell;
        for (int32_t q = s->cseg_start[c]; q < s->cseg_start[c + 1]; q++) {
            double tw = edmd_segment_time(s, i, s->cseg[q], now, tc);
            if (tw <= tc && tw < EDMD_INF && edmd_ev_push(s, i, tw > now ? tw : now, EV_WALL, W_SEG + s->cseg[q], 0))
                return GR_ERUN;
        }
    }
    return GR_OK;
}

/* At large N an event's grains are anywhere in memory and the pair loops
 * then wait on one cache miss after another: a cell head, its first grain,
 * that grain's successor... Walking the nine cell lists side by side, one
 * step of each in turn, puts their misses in flight together; the pair
 * loops that follow then read cached lines. Read-only, so it changes no
 * result. A few steps cover the lists of cells about a diameter wide. */
static void walk_side_by_side(const gr_edmd *s, const int *cells, int ns)
{
    int32_t cur[9];
    for (int k = 0; k < ns; k++)
        cur[k] = s->chead[cells[k]];
    for (int step = 0; step < 4; step++) {
        int live = 0;
        for (int k = 0; k < ns; k++)
            if (cur[k] >= 0) {
                cur[k] = s->p[cur[k]].cnext;
                live = 1;
            }
        if (!live)
            break;
    }
    /* the loads feed nothing: keep the compiler from dropping them */
    for (int k = 0; k < ns; k++)
        __asm__ volatile("" : : "r"(cur[k]));
}

void edmd_prefetch_block(const gr_edmd *s, int32_t i)
{
    int cells[9];
    walk_side_by_side(s, cells, edmd_block_cells(s, i, cells));
}

/* All events of particle i (its list is empty): crossing, walls, pairs in
 * the 3x3 block of cells around it. */
int edmd_predict_all(gr_edmd *s, int32_t i)
{
    if (push_cross_and_walls(s, i))
        return GR_ERUN;
    int cells[9];
    int ns = edmd_block_cells(s, i, cells);
    for (int k = 0; k < ns; k++)
        if (push_pairs_in_cell(s, i, cells[k]))
            return GR_ERUN;
    return GR_OK;
}

/* After a crossing, the contacts with the sleepers of the block's other
 * cells, whose search stopped at the crossing (mover_horizon). */
static int sleepers_again(gr_edmd *s, int32_t i, const int *seen, int nseen)
{
    int cells[9];
    int ns = edmd_block_cells(s, i, cells);
    for (int k = 0; k < ns; k++) {
        int fresh = 0;
        for (int q = 0; q < nseen; q++)
            fresh |= seen[q] == cells[k];
        if (!fresh && push_sleepers_in_cell(s, i, cells[k]))
            return GR_ERUN;
    }
    return GR_OK;
}

/* After crossing in direction dir: the next crossing, the walls of the new
 * cell, and pairs with the row or column of cells that just became
 * neighbours (events with the others are already in some list). */
int edmd_predict_cross(gr_edmd *s, int32_t i, int dir)
{
    int c = s->p[i].cell, ix = c % s->nx, iy = c / s->nx;
    int seen[3], ns = 0;
    for (int k = -1; k <= 1; k++) {
        int cc;
        switch (dir) {
        case DIR_RIGHT: cc = edmd_wrap_cell(s, ix + 1, iy + k); break;
        case DIR_LEFT: cc = edmd_wrap_cell(s, ix - 1, iy + k); break;
        case DIR_UP: cc = edmd_wrap_cell(s, ix + k, iy + 1); break;
        default: cc = edmd_wrap_cell(s, ix + k, iy - 1); break;
        }
        if (cc < 0)
            continue;
        int dup = 0;
        for (int q = 0; q < ns; q++)
            dup |= seen[q] == cc;
        if (dup)
            continue;
        seen[ns++] = cc;
    }
    if (edmd_engine_prefetches(s))
        walk_side_by_side(s, seen, ns); /* overlaps the crossing and wall times */
    if (push_cross_and_walls(s, i))
        return GR_ERUN;
    for (int k = 0; k < ns; k++)
        if (push_pairs_in_cell(s, i, seen[k]))
            return GR_ERUN;
    return edmd_any_asleep(s) ? sleepers_again(s, i, seen, ns) : GR_OK;
}

/* Grain i fell asleep: every moving grain of its block predicts its
 * contact with it (their events with i as it moved went stale). */
int edmd_sleep_neighbours(gr_edmd *s, int32_t i)
{
    int cells[9];
    int ns = edmd_block_cells(s, i, cells);
    double now = s->t;
    for (int k = 0; k < ns; k++)
        for (int32_t j = s->chead[cells[k]]; j >= 0; j = s->p[j].cnext) {
            if (j == i || s->p[j].asleep)
                continue;
            double t = sleeper_time(s, j, i);
            if (t < EDMD_INF && (edmd_ev_push(s, j, t > now ? t : now, EV_PAIR, i, s->p[i].ncol) ||
                                 s->q->update(s, j)))
                return GR_ERUN;
        }
    return GR_OK;
}
