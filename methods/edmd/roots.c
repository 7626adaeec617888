/* Contact times that are no quadratic: the sinusoidal floor (a
 * transcendental equation) and a segment end under gravity (a quartic),
 * both by bounded subdivision, so that no touching is missed. Used by the
 * prediction (predict.c) and the segments (segment.c). */
#include <math.h>

#include "edmd_int.h"

/* The sinusoidal floor: h(t) = y(t) - r - A cos(omega t). */
typedef struct {
    const edmd_p *p;
    double g, A, om, M;
    int nev;
    int point;       /* 1: h = |r(t) - E|^2 - R^2 for a segment end E */
    double ex, ey;
} floor_ctx;

static double fh(floor_ctx *c, double t)
{
    c->nev++;
    if (c->point) {
        double qx = edmd_x_at(c->p, t) - c->ex, qy = edmd_y_at(c->p, t, c->g) - c->ey;
        return qx * qx + qy * qy - c->p->r * c->p->r;
    }
    return edmd_y_at(c->p, t, c->g) - c->p->r - c->A * cos(c->om * t);
}
static double fdh(const floor_ctx *c, double t)
{
    if (c->point) {
        double qx = edmd_x_at(c->p, t) - c->ex, qy = edmd_y_at(c->p, t, c->g) - c->ey;
        return 2.0 * (qx * c->p->vx + qy * edmd_vy_at(c->p, t, c->g));
    }
    return edmd_vy_at(c->p, t, c->g) + c->A * c->om * sin(c->om * t);
}

/* First t in (a, b] with h(t) <= 0, given h(a) > 0; |h''| <= M bounds how
 * deep h can dip between two samples, so a root is never skipped. */
static double first_root(floor_ctx *c, double a, double ha, double b, double hb, int depth)
{
    double L = b - a;
    double tol = 4e-16 * (fabs(a) + 1.0);
    if (hb <= 0.0 && L <= tol)
        return b;
    if (hb > 0.0) {
        double lb = (ha < hb ? ha : hb) - c->M * L * L / 8.0;
        if (lb > 0.0 || L <= tol || depth > 200 || c->nev > 20000)
            return EDMD_INF;
        /* concave lower bound from the slope at a: positive at both ends */
        if (ha + fdh(c, a) * L - 0.5 * c->M * L * L > 0.0)
            return EDMD_INF;
    }
    double m = a + 0.5 * L;
    if (m <= a || m >= b)
        return hb <= 0.0 ? b : EDMD_INF;
    double hm = fh(c, m);
    if (hm <= 0.0)
        return first_root(c, a, ha, m, hm, depth + 1);
    double r = first_root(c, a, ha, m, hm, depth + 1);
    if (r < EDMD_INF)
        return r;
    return first_root(c, m, hm, b, hb, depth + 1);
}

/* The first root of h in [a, b], starting from a point that may be in
 * contact: a grain in contact and approaching collides at once; one just
 * leaving has h >= ha + dha s - M s^2 / 2 > ha up to s = 2 dha / M, and
 * gets past the contact at s = dha / M unless ha, a round-off depth, is
 * larger than dha^2 / 2M. That happens when a grain chatters on a floor
 * pressing it (a collapse onto the floor, unguarded), or rolls over a
 * segment's end (the silo's orifice edge) in elastic bounces of the TC
 * guard that round-off has worn down below the resolution of h. Answering
 * "no contact" there let the floor escape the grain's list, which then
 * fell through the floor (vibrated.ini with collapse = none, seed 5,
 * t = 459.6). Answering a + dha / M (the next contact, with no impulse
 * while the grain still leaves) is a Zeno sequence: each move is
 * proportional to the speed left, which gravity takes away in proportion
 * to the move, so the moves shrink geometrically to the turning point and
 * time stops (compare silo.ini, tc = 1e-5: grain 338 on the orifice edge
 * at t = 7.697, 1e5 events without time advancing). So a grain near the
 * surface moves on by at least the slack time, by which it has turned
 * back into the wall by at most M s^2 / 2 = hs (EDMD_SLACK in depth):
 * there it collides at an approach speed the guard's elastic bounces
 * resolve (their depth stays within hs), or it still leaves (no impulse,
 * time has advanced), or it got clear and the search goes on. The move
 * stops at b: the floor's b is a certain contact (the grain below the
 * floor's lowest point), which must not be lost; beyond a segment end's b
 * (the next cell crossing) the search starts again anyway. A grain deeper
 * than 2 hs has sunk through inelastic bounces at the slack time (each
 * takes less speed back than the wall's pull gives it): it goes on by
 * dha / M, a collapse the engine reports rather than a grain sinking. */
static double slack_depth(const floor_ctx *c)
{
    return c->point ? 2.0 * c->p->r * EDMD_SLACK : EDMD_SLACK; /* h of a point is |q|^2 - R^2 */
}

static double root_from(floor_ctx *c, double a, double b)
{
    double ha = fh(c, a), dha = fdh(c, a);
    if (ha <= 0.0) {
        if (dha <= 0.0)
            return a;
        double a1 = a + dha / c->M, hs = slack_depth(c);
        double h1 = a1 < b ? fh(c, a1) : 0.0;
        if (h1 <= 0.0 && ha >= -2.0 * hs)
            a1 = fmin(a + fmax(dha / c->M, sqrt(2.0 * hs / c->M)), b);
        else if (a1 >= b)
            return EDMD_INF;
        a = a1;
        ha = h1 > 0.0 ? h1 : fh(c, a);
        if (ha <= 0.0)
            return a;
    }
    return first_root(c, a, ha, b, fh(c, b), 0);
}

/* First contact in [a, b] of a grain with a segment end (ex, ey) under
 * gravity (a quartic): bounded subdivision as for the floor, with the
 * curvature bound of |r - E|^2 over the interval. */
double edmd_point_time(const gr_edmd *s, const edmd_p *p, double ex, double ey, double a, double b)
{
    double g = s->g;
    if (!(b > a))
        return EDMD_INF;
    double L = b - a, vya = edmd_vy_at(p, a, g), vyb = edmd_vy_at(p, b, g);
    double vmax2 = p->vx * p->vx + fmax(vya * vya, vyb * vyb);
    double qy = fabs(edmd_y_at(p, a, g) - ey) + fabs(vya) * L + 0.5 * g * L * L;
    floor_ctx c = {p, g, 0, 0, 2.0 * (vmax2 + g * qy) + 1e-300, 0, 1, ex, ey};
    return root_from(&c, a, b);
}

int edmd_floor_band(const edmd_p *p, double g, double A, double period, double horizon, double *a,
                    double *b)
{
    /* enter the band y - r <= A where the floor can be met */
    if (edmd_y_at(p, *a, g) - p->r > A) {
        double te = p->t + edmd_fall_time(p->y - p->r - A, p->vy, g);
        if (!(te < horizon))
            return 0;
        *a = te > *a ? te : *a;
    }
    /* certain contact by the time it falls to the floor's lowest point */
    *b = p->t + edmd_fall_time(p->y - p->r + A, p->vy, g);
    if (!(*b < EDMD_INF))
        *b = *a + period;
    if (*b > horizon)
        *b = horizon;
    return *b > *a;
}

double edmd_floor_sine_time(const gr_edmd *s, const edmd_p *p, double a, double horizon)
{
    double g = s->g, A = s->fA, om = s->fomega;
    double b;
    if (!edmd_floor_band(p, g, A, 2.0 * M_PI / om, horizon, &a, &b))
        return EDMD_INF;
    floor_ctx c = {p, g, A, om, g + A * om * om, 0, 0, 0, 0};
    return root_from(&c, a, b);
}

