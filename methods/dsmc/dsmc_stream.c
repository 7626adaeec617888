/* Free flight over a step: exact parabolas under gravity, and the walls and
 * floor met on the way treated as hard disks meet them (edmd's rules:
 * v'_n = (1 + e) V_p - e v_n with the floor's velocity V_p), so that DSMC
 * and edmd see the same boundaries. Calls no other file of the backend. */
#include <math.h>
#include <stdlib.h>

#include "dsmc_int.h"
#include "geom.h"

/* Bounces in one step after which the particle is taken to rest on the
 * wall: an inelastic bounce under gravity otherwise accumulates without end
 * (the inelastic collapse edmd guards against). */
#define MAX_BOUNCES 64

/* The first t > 0 at which f(t) = c0 + c1 t + c2 t^2 crosses zero going
 * down (f >= 0 is inside), or INFINITY. */
static double first_exit(double c0, double c1, double c2)
{
    if (c0 < 0 && c1 <= 0)
        return 0.0;
    if (c2 == 0.0)
        return c1 < 0 ? fmax(0.0, -c0 / c1) : INFINITY;
    double disc = c1 * c1 - 4 * c2 * c0;
    if (disc < 0)
        return INFINITY;
    double q = -0.5 * (c1 + copysign(sqrt(disc), c1));
    double r1 = q / c2, r2 = q != 0.0 ? c0 / q : r1;
    double lo = fmin(r1, r2), hi = fmax(r1, r2);
    double t = c2 > 0 ? lo : hi;
    return t > 0 ? t : INFINITY;
}

/* The moving floor's gap y(t) - r - offset(t) over [0, h] from time t0:
 * scanned at a twentieth of the period, then bisected; a gap that closes
 * and opens again within one scan interval is missed (docs). */
static double floor_exit(const gr_dsmc *d, double y, double vy, double r, double t0, double h)
{
    const gr_floor *f = &d->sc.floor;
    double step = fmin(h, 2 * M_PI / f->omega / 20);
    double a = 0, fa = y - r - gr_floor_offset(f, t0);
    if (fa < 0 && vy <= gr_floor_velocity(f, t0))
        return 0.0;
    for (double b = step; a < h; b = fmin(h, b + step)) {
        double fb = y + vy * b - 0.5 * d->g * b * b - r - gr_floor_offset(f, t0 + b);
        if (fb < 0 && fa >= 0) {
            for (int k = 0; k < 60; k++) {
                double m = 0.5 * (a + b);
                double fm = y + vy * m - 0.5 * d->g * m * m - r - gr_floor_offset(f, t0 + m);
                if (fm < 0) b = m; else a = m;
            }
            return b;
        }
        a = b, fa = fb;
    }
    return INFINITY;
}

/* High-frequency sine floor: the phase met is weighted by the approach
 * speed (the flux of collisions), as edmd draws it. */
static double hf_sine_velocity(gr_dsmc *d, double vy)
{
    double V0 = d->sc.floor.amplitude * d->sc.floor.omega;
    if (V0 <= 0.0 || vy >= 0.0)
        return 0.0;
    for (int k = 0; k < 1000; k++) {
        double vp = V0 * cos(2.0 * M_PI * gr_rng_uniform(d->floor_rng));
        if (gr_rng_uniform(d->floor_rng) * (V0 - vy) < vp - vy)
            return vp;
    }
    return 0.0;
}

static double floor_velocity(gr_dsmc *d, double t, double vy)
{
    const gr_floor *f = &d->sc.floor;
    switch (f->motion) {
    case GR_FLOOR_SINE_HF: return hf_sine_velocity(d, vy);
    case GR_FLOOR_SAWTOOTH_HF: return f->amplitude * f->omega;
    default: return gr_floor_velocity(f, t);
    }
}

/* Earliest wall met within h: its side and time. */
static int next_wall(const gr_dsmc *d, size_t i, double t0, double h, double *tw)
{
    const gr_bc *s = d->sc.side;
    double r = 0.5 * d->sigma, x = d->x[i], y = d->y[i], vx = d->vx[i], vy = d->vy[i], g = d->g;
    double tt[4] = {INFINITY, INFINITY, INFINITY, INFINITY};
    if (s[GR_LEFT] == GR_BC_WALL) tt[GR_LEFT] = first_exit(x - r, vx, 0);
    if (s[GR_RIGHT] == GR_BC_WALL) tt[GR_RIGHT] = first_exit(d->Lx - r - x, -vx, 0);
    if (s[GR_TOP] == GR_BC_WALL) tt[GR_TOP] = first_exit(d->Ly - r - y, -vy, 0.5 * g);
    if (s[GR_BOTTOM] == GR_BC_WALL) {
        int moving = d->sc.floor.motion == GR_FLOOR_SINE || d->sc.floor.motion == GR_FLOOR_SAWTOOTH;
        tt[GR_BOTTOM] = moving ? floor_exit(d, y, vy, r, t0, h) : first_exit(y - r, vy, -0.5 * g);
    }
    int w = -1;
    *tw = h;
    for (int k = 0; k < 4; k++)
        if (tt[k] <= *tw)
            *tw = tt[k], w = k;
    return w;
}

static void fly(gr_dsmc *d, size_t i, double h)
{
    d->x[i] += d->vx[i] * h;
    d->y[i] += d->vy[i] * h - 0.5 * d->g * h * h;
    d->vy[i] -= d->g * h;
}

/* What the flights of a slice give the counters and the wall pressure. */
typedef struct {
    uint64_t walls, lost;
    double wall_mom;
} wall_tally;

/* The wall's impulse, with infinite mass; its normal part feeds the wall
 * pressure (times W: each particle stands for W grains). */
static void bounce(gr_dsmc *d, wall_tally *y, size_t i, int w, double t)
{
    double nx = w == GR_LEFT ? 1 : w == GR_RIGHT ? -1 : 0, ny = w == GR_BOTTOM ? 1 : w == GR_TOP ? -1 : 0;
    double Vn = w == GR_BOTTOM ? floor_velocity(d, t, d->vy[i]) : 0.0;
    double gn = d->vx[i] * nx + d->vy[i] * ny - Vn;
    if (gn >= 0)
        return;
    double J = -(1.0 + d->alpha_w) * d->mass * gn;
    d->vx[i] += J * nx / d->mass;
    d->vy[i] += J * ny / d->mass;
    y->wall_mom += J * d->W;
    y->walls++;
    gr_dsmc_stress_wall(d, i, nx, ny, J);
}

/* Periodic wrap and exit through an open side (the centre leaves): 1
 * when it left. */
static int boundaries(gr_dsmc *d, size_t i)
{
    const gr_bc *s = d->sc.side;
    if (s[GR_LEFT] == GR_BC_PERIODIC)
        d->x[i] -= d->Lx * floor(d->x[i] / d->Lx);
    if (s[GR_BOTTOM] == GR_BC_PERIODIC)
        d->y[i] -= d->Ly * floor(d->y[i] / d->Ly);
    double x = d->x[i], y = d->y[i];
    if ((x < 0 && s[GR_LEFT] == GR_BC_OPEN) || (x > d->Lx && s[GR_RIGHT] == GR_BC_OPEN) ||
        (y < 0 && s[GR_BOTTOM] == GR_BC_OPEN) || (y > d->Ly && s[GR_TOP] == GR_BC_OPEN)) {
        d->rank[i] |= GR_DSMC_GONE;
        return 1;
    }
    return 0;
}

/* Too many bounces in one step: the particle rests on the wall (its normal
 * velocity is the wall's, zero) and slides along it for the rest of the
 * step, kept inside the domain. */
static void settle(gr_dsmc *d, size_t i, int w, double left)
{
    double r = 0.5 * d->sigma;
    if (w == GR_BOTTOM || w == GR_TOP)
        d->vy[i] = 0.0, d->x[i] += d->vx[i] * left;
    else
        d->vx[i] = 0.0, d->y[i] += d->vy[i] * left;
    d->x[i] = fmin(fmax(d->x[i], r), d->Lx - r);
    d->y[i] = fmin(fmax(d->y[i], r), d->Ly - r);
}

static void stream(gr_dsmc *d, wall_tally *y, size_t i, double t, double h)
{
    if (d->rank[i] & GR_DSMC_GONE)
        return;
    double left = h;
    for (int k = 0; left > 0; k++) {
        double tw;
        int w = next_wall(d, i, t, left, &tw);
        fly(d, i, tw);
        t += tw, left -= tw;
        if (w < 0)
            break;
        if (k == MAX_BOUNCES) {
            settle(d, i, w, left);
            break;
        }
        bounce(d, y, i, w, t);
    }
    y->lost += (uint64_t)boundaries(d, i);
}

/* The walls' share of a slice of particles: summed per slice, then over
 * the slices in order (the slices fixed, not the threads' count), so
 * that the sums do not depend on the threads. */
#define SLICE 4096

static int stream_slices(gr_dsmc *d, double t, double h, int T)
{
    size_t n = d->n, ns = (n + SLICE - 1) / SLICE;
    wall_tally sum = {0, 0, 0.0};
    if (T == 1) {
        for (size_t k = 0; k < ns; k++) {
            wall_tally y = {0, 0, 0.0};
            for (size_t i = k * SLICE; i < n && i < (k + 1) * SLICE; i++)
                stream(d, &y, i, t, h);
            sum.walls += y.walls, sum.lost += y.lost, sum.wall_mom += y.wall_mom;
        }
    } else {
        wall_tally *ys = calloc(ns, sizeof *ys);
        if (!ys)
            return stream_slices(d, t, h, 1);
#pragma omp parallel for schedule(static) num_threads(T)
        for (size_t k = 0; k < ns; k++)
            for (size_t i = k * SLICE; i < n && i < (k + 1) * SLICE; i++)
                stream(d, &ys[k], i, t, h);
        for (size_t k = 0; k < ns; k++)
            sum.walls += ys[k].walls, sum.lost += ys[k].lost, sum.wall_mom += ys[k].wall_mom;
        free(ys);
    }
    d->walls += sum.walls, d->lost += sum.lost, d->wall_mom += sum.wall_mom;
    return GR_OK;
}

/* Without walls nor gravity a flight is a straight line: the loop the
 * compiler vectorises over particles [lo, hi), then the periodic wrap and
 * the open sides; the particles lost. */
static uint64_t straight_flights(gr_dsmc *d, size_t lo, size_t hi, double h)
{
    double *restrict x = d->x, *restrict y = d->y;
    const double *restrict vx = d->vx, *restrict vy = d->vy;
    const gr_bc *s = d->sc.side;
    int torus = s[GR_LEFT] == GR_BC_PERIODIC && s[GR_BOTTOM] == GR_BC_PERIODIC;
    double Lx = d->Lx, Ly = d->Ly;
    uint64_t lost = 0;
    for (size_t i = lo; i < hi; i++)
        x[i] += vx[i] * h, y[i] += vy[i] * h;
    for (size_t i = lo; i < hi; i++) {
        /* the common case of a torus: at most one box length per step */
        if (torus && x[i] >= -Lx && x[i] < 2 * Lx && y[i] >= -Ly && y[i] < 2 * Ly) {
            x[i] += x[i] < 0 ? Lx : x[i] >= Lx ? -Lx : 0.0;
            y[i] += y[i] < 0 ? Ly : y[i] >= Ly ? -Ly : 0.0;
        } else if (!(d->rank[i] & GR_DSMC_GONE)) {
            lost += (uint64_t)boundaries(d, i);
        }
    }
    return lost;
}

/* Each particle's flight is its own: on the threads (one thread without a
 * parallel region, whose fixed cost is a small gas's whole step), but for
 * a floor that draws its phase from the instance's sequential stream
 * (sine-hf) and the open stress window (its accumulator is shared). */
void gr_dsmc_stream_all(gr_dsmc *d, double t, double h)
{
    int T = d->par.threads > 1 ? d->par.threads : 1;
    size_t n = d->n;
    if (d->walls_any || d->g != 0.0) {
        if (d->stress || d->sc.floor.motion == GR_FLOOR_SINE_HF)
            T = 1;
        (void)stream_slices(d, t, h, T);
        return;
    }
    if (T == 1) {
        d->lost += straight_flights(d, 0, n, h);
        return;
    }
    uint64_t lost = 0;
#pragma omp parallel num_threads(T) reduction(+ : lost)
    {
        int k = gr_dsmc_thread();
        lost += straight_flights(d, n * (size_t)k / (size_t)T, n * (size_t)(k + 1) / (size_t)T, h);
    }
    d->lost += lost;
}
