/* Which contacts hold a grain of the sleep model (collapse = sleep) up
 * against gravity, and which sleepers lose a support when a grain moves.
 *
 * A frictionless disk at rest is in equilibrium when its weight lies in
 * the cone of its contact normals: one normal straight up (the fixed
 * floor, a horizontal segment), or two on either side of the vertical
 * less than half a turn apart (two grains below; a grain below and a side
 * wall; a grain below and a neighbour pressing it sideways). A grain
 * resting on one slanted sleeper would roll off it and may not sleep.
 * Friction widens the cone; leaving it out only keeps more grains awake.
 * The contacts that count are static ones (the floor, side walls,
 * segments that never open, sleepers) and slow moving grains (below
 * v_sleep): a row of grains each resting on one grain below and pressed
 * against its neighbours holds as a whole, and its grains chatter at the
 * guard's scale for ever if none may sleep before another does. A sleeper
 * resting on a moving grain wakes when that grain leaves a collision fast
 * (engine.c), and every sleeper wakes when a gate opens. Contacts count
 * within HOLD_GAP of the pair's diameter: the grain has just collided with
 * one of them, the others it leans on at a round-off or a guard bounce's
 * distance, or a settling row's slack. */
#include <math.h>

#include "edmd_int.h"

#define HOLD_GAP 1e-2
/* a normal this close to the vertical holds alone */
#define FLAT 1e-6

/* The normals (from the contact to the grain) of a grain's supports. */
#define MAX_NORMALS 32
typedef struct {
    double x[MAX_NORMALS], y[MAX_NORMALS];
    int n, flat;
} lean;

static void add_normal(lean *l, double nx, double ny)
{
    if (fabs(nx) <= FLAT && ny > 0.0)
        l->flat = 1;
    else if (l->n < MAX_NORMALS) {
        l->x[l->n] = nx;
        l->y[l->n] = ny;
        l->n++;
    }
}

/* The vertical within the cone of two normals, one right of it and one
 * left, less than half a turn apart counterclockwise. */
static int holds(const lean *l)
{
    if (l->flat)
        return 1;
    for (int a = 0; a < l->n; a++)
        for (int b = 0; b < l->n; b++)
            if (l->x[a] > 0.0 && l->x[b] < 0.0 && l->x[a] * l->y[b] - l->y[a] * l->x[b] > 0.0)
                return 1;
    return 0;
}

/* Grain i's place and velocity now (a moving grain's stored ones are
 * those of its last event; a sleeper feels no gravity). */
typedef struct {
    double x, y, vx, vy, r;
} place;

static place now_of(const gr_edmd *s, int32_t i)
{
    const edmd_p *p = &s->p[i];
    double g = edmd_g_of(p, s->g);
    place q = {edmd_x_at(p, s->t), edmd_y_at(p, s->t, g), p->vx, edmd_vy_at(p, s->t, g), p->r};
    return q;
}

static void sides_and_segments(const gr_edmd *s, int32_t i, const place *a, lean *l)
{
    double gap = HOLD_GAP * 2.0 * a->r;
    if (s->hard[GR_BOTTOM] && s->floor == GR_FLOOR_FIXED && a->y - a->r - s->ybot < gap)
        add_normal(l, 0.0, 1.0);
    if (s->hard[GR_LEFT] && a->x - a->r < gap)
        add_normal(l, 1.0, 0.0);
    if (s->hard[GR_RIGHT] && s->W - a->x - a->r < gap)
        add_normal(l, -1.0, 0.0);
    if (!s->nseg)
        return;
    int c = s->p[i].cell;
    for (int32_t q = s->cseg_start[c]; q < s->cseg_start[c + 1]; q++) {
        int k = s->cseg[q];
        if (s->seg[k].open_time < EDMD_INF) /* a gate opens */
            continue;
        double nx, ny, d = edmd_segment_normal(s, k, a->x, a->y, &nx, &ny);
        if (d - a->r < gap)
            add_normal(l, nx, ny);
    }
}

/* (dx, dy) from b to a when they touch within the gap, else 0. */
static int touching(const gr_edmd *s, const place *a, const place *b, double *dx, double *dy)
{
    *dx = edmd_min_image(a->x - b->x, s->periodic_x ? s->W : 0.0);
    *dy = edmd_min_image(a->y - b->y, s->periodic_y ? s->H - s->ybot : 0.0);
    double sum = a->r + b->r, dist = sqrt(*dx * *dx + *dy * *dy);
    return dist - sum < HOLD_GAP * sum;
}

static int slow(const gr_edmd *s, int32_t i, const place *q)
{
    double v = sqrt(q->vx * q->vx + q->vy * q->vy) + (s->rough ? fabs(s->w[i]) * q->r : 0.0);
    return v < s->prm.v_sleep;
}

int edmd_slow(const gr_edmd *s, int32_t i)
{
    place q = now_of(s, i);
    return slow(s, i, &q);
}

int edmd_held(const gr_edmd *s, int32_t i)
{
    place a = now_of(s, i);
    lean l = {.n = 0, .flat = 0};
    sides_and_segments(s, i, &a, &l);
    int cells[9], ns = edmd_block_cells(s, i, cells);
    for (int k = 0; k < ns && !l.flat; k++)
        for (int32_t j = s->chead[cells[k]]; j >= 0; j = s->p[j].cnext) {
            if (j == i || s->gone[j])
                continue;
            place b = now_of(s, j);
            double dx, dy;
            if (!touching(s, &a, &b, &dx, &dy) || (!s->p[j].asleep && !slow(s, j, &b)))
                continue;
            double d = sqrt(dx * dx + dy * dy);
            add_normal(&l, dx / d, dy / d);
        }
    return holds(&l);
}

size_t edmd_rests_on(const gr_edmd *s, int32_t j, int32_t *out, size_t cap)
{
    place b = now_of(s, j);
    size_t n = 0;
    int cells[9], ns = edmd_block_cells(s, j, cells);
    for (int k = 0; k < ns; k++)
        for (int32_t i = s->chead[cells[k]]; i >= 0; i = s->p[i].cnext) {
            if (i == j || !s->p[i].asleep)
                continue;
            place a = now_of(s, i);
            double dx, dy;
            /* beside or above: it may lean on j */
            if (touching(s, &a, &b, &dx, &dy) && dy > -0.5 * (a.r + b.r) && n < cap)
                out[n++] = i;
        }
    return n;
}

double edmd_next_gate(const gr_edmd *s, double t)
{
    double next = EDMD_INF;
    for (int k = 0; s->sleep_on && k < s->nseg; k++)
        if (s->seg[k].open_time > t && s->seg[k].open_time < next)
            next = s->seg[k].open_time;
    return next;
}
