/* [init] overlap = push: a soft packing (a settled bed of the soft DEM,
 * read from a file) made fit for hard disks, which never overlap. Each
 * sweep moves every overlapping pair apart along its line of centres (half
 * each, all of it for a grain against a fixed one) and every grain that
 * cuts a wall back inside, until nothing overlaps: the rigid limit of the
 * same bed, which grows by its elastic compression. Contacts are left a
 * gap (1e-6 of their contact distance) so that the last sweep overshoots
 * instead of creeping up to contact; where they cannot all have it (a row
 * that spans a box exactly) the gap shrinks tenfold a stage, to 1e-11. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "geom.h"
#include "grid.h"
#include "init.h"

#define GAP0 1e-6
#define STAGES 6         /* the gap shrinks tenfold a stage, for contacts that cannot all have it */
#define STAGE_SWEEPS 4000
#define TOL 1e-10        /* an overlap below this fraction of the contact distance is contact */
#define MAX_FRACTION 0.1 /* a larger overlap is no soft contact: refused */

typedef struct {
    const gr_scene *sc;
    gr_particles *p;
    double Lx, Ly;
    double worst;         /* largest overlap in the sweep, relative to the contact distance */
    double worst_abs;     /* the same in lengths */
    long wi, wj;          /* its grains (wj < 0: a wall, -1 - side, or -100 - segment) */
    int dry;              /* measure only: the overlaps as the file has them */
    double gap;           /* the gap a push leaves, relative to the contact distance */
} sweep;

static int fixed(const gr_particles *p, size_t i) { return (p->flags[i] & GR_PF_FIXED) != 0; }

static void note_worst(sweep *s, double ov, double sigma, long i, long j)
{
    if (ov / sigma > s->worst)
        s->worst = ov / sigma, s->worst_abs = ov, s->wi = i, s->wj = j;
}

static int push_pair(size_t i, size_t j, double dx, double dy, void *user)
{
    sweep *s = user;
    gr_particles *p = s->p;
    (void)dx, (void)dy; /* the cells' values are stale once grains move */
    if (fixed(p, i) && fixed(p, j))
        return 0;
    dx = gr_min_image(p->x[j] - p->x[i], s->Lx), dy = gr_min_image(p->y[j] - p->y[i], s->Ly);
    double dist = hypot(dx, dy), sigma = p->radius[i] + p->radius[j];
    if (dist >= sigma * (1.0 + 0.1 * s->gap))
        return 0;
    note_worst(s, sigma - dist, sigma, (long)i, (long)j);
    if (s->dry)
        return 0;
    double nx = dist > 0 ? dx / dist : 1.0, ny = dist > 0 ? dy / dist : 0.0;
    double move = sigma * (1.0 + s->gap) - dist;
    double wi = fixed(p, i) ? 0.0 : fixed(p, j) ? 1.0 : 0.5;
    p->x[i] -= wi * move * nx, p->y[i] -= wi * move * ny;
    p->x[j] += (1.0 - wi) * move * nx, p->y[j] += (1.0 - wi) * move * ny;
    return 0;
}

/* The domain's wall sides (the floor where it is at t = 0) and the
 * segments present at t = 0. */
static void push_walls(sweep *s, size_t i)
{
    const gr_scene *sc = s->sc;
    gr_particles *p = s->p;
    double r = p->radius[i], in = r * (1.0 + s->gap), tol = 0.1 * s->gap * r;
    double lo[4] = {0.0, sc->width, gr_floor_offset(&sc->floor, 0.0), sc->height};
    double *c[4] = {&p->x[i], &p->x[i], &p->y[i], &p->y[i]};
    for (int k = 0; k < 4; k++) {
        if (sc->side[k] != GR_BC_WALL)
            continue;
        double sgn = (k == GR_LEFT || k == GR_BOTTOM) ? 1.0 : -1.0;
        double depth = r - sgn * (*c[k] - lo[k]);
        if (depth > -tol) {
            note_worst(s, depth, 2.0 * r, (long)i, -1 - k);
            if (!s->dry)
                *c[k] = lo[k] + sgn * in;
        }
    }
    for (int k = 0; k < sc->nsegments; k++) {
        const gr_segment *g = &sc->segments[k];
        double ov;
        gr_v2 n, pt;
        if (!gr_segment_active(g, 0.0) ||
            !gr_disk_segment_contact((gr_v2){g->x0, g->y0}, (gr_v2){g->x1, g->y1}, (gr_v2){p->x[i], p->y[i]},
                                     in, &ov, &n, &pt))
            continue;
        note_worst(s, ov - s->gap * r, 2.0 * r, (long)i, -100 - k);
        if (!s->dry)
            p->x[i] += ov * n.x, p->y[i] += ov * n.y;
    }
}

static int one_sweep(sweep *s, gr_grid *g, double rmax, gr_err *err)
{
    gr_particles *p = s->p;
    s->worst = 0.0, s->worst_abs = 0.0, s->wi = s->wj = -1;
    if (gr_grid_build(g, p->x, p->y, p->n, NULL, err))
        return err->code;
    gr_grid_pairs(g, p->x, p->y, 2.0 * rmax * (1.0 + s->gap), push_pair, s);
    for (size_t i = 0; i < p->n; i++) {
        if (fixed(p, i))
            continue;
        push_walls(s, i);
        if (s->dry)
            continue;
        if (s->Lx > 0)
            p->x[i] = gr_wrap(p->x[i], s->Lx);
        if (s->Ly > 0)
            p->y[i] = gr_wrap(p->y[i], s->Ly);
    }
    return GR_OK;
}

/* A sweep that found nothing to push may still have moved grains a little
 * (those within the gap of contact): done only if a sweep that moves
 * nothing finds nothing either. */
static int check(sweep *s, gr_grid *g, double rmax, gr_err *err)
{
    s->dry = 1;
    int rc = one_sweep(s, g, rmax, err);
    s->dry = 0;
    return rc;
}

/* "grains 3 and 17" or "grain 3 and the left wall", numbered as in the file. */
static void name_worst(const sweep *s, char *buf, size_t n)
{
    static const char *const sides[4] = {"left wall", "right wall", "floor", "top wall"};
    if (s->wj >= 0)
        snprintf(buf, n, "grains %ld and %ld", s->wi + 1, s->wj + 1);
    else if (s->wj > -100)
        snprintf(buf, n, "grain %ld at (%.6g, %.6g) and the %s", s->wi + 1, s->p->x[s->wi], s->p->y[s->wi],
                 sides[-1 - s->wj]);
    else
        snprintf(buf, n, "grain %ld at (%.6g, %.6g) and the wall segment of line %d", s->wi + 1,
                 s->p->x[s->wi], s->p->y[s->wi], s->sc->segments[-100 - s->wj].line);
}

static int refuse(const gr_scene *sc, gr_err *err, const char *why, const sweep *s)
{
    char where[1200], who[200];
    gr_scene_where(sc, "init", "overlap", where, sizeof where);
    name_worst(s, who, sizeof who);
    return gr_fail(err, GR_EINPUT, "%s: %s%s%s: %s overlap by %.4g (%.3g of their contact distance): %s", where,
                   sc->init.kind == GR_INIT_FILE ? "'" : "", sc->init.kind == GR_INIT_FILE ? sc->init.file : "the initial grains",
                   sc->init.kind == GR_INIT_FILE ? "'" : "", who, s->worst_abs, s->worst, why);
}

static int relax(sweep *s, gr_grid *g, double rmax, gr_init_relax_report *rep, gr_err *err)
{
    if (check(s, g, rmax, err))
        return err->code;
    rep->overlap = s->worst_abs;
    name_worst(s, rep->where, sizeof rep->where);
    if (s->worst > MAX_FRACTION)
        return refuse(s->sc, err, "more than a soft packing's overlap (at most 0.1): check the file's diameters", s);
    s->gap = GAP0;
    for (int stage = 0; stage < STAGES && s->worst > TOL; stage++, s->gap *= 0.1)
        for (int k = 0; k < STAGE_SWEEPS && s->worst > TOL; k++, rep->sweeps++)
            if (one_sweep(s, g, rmax, err) || (s->worst <= TOL && check(s, g, rmax, err)))
                return err->code;
    if (s->worst > TOL)
        return refuse(s->sc, err, "still, after 24000 sweeps pushing overlapping grains apart (too dense for its walls?)",
                      s);
    return GR_OK;
}

int gr_init_push_apart(const gr_scene *sc, gr_particles *p, gr_init_relax_report *rep, gr_err *err)
{
    *rep = (gr_init_relax_report){0};
    if (!p->n)
        return GR_OK;
    double rmax = 0.0, *x0 = malloc(2 * p->n * sizeof *x0);
    if (!x0)
        return gr_fail(err, GR_ERUN, "out of memory");
    for (size_t i = 0; i < p->n; i++)
        x0[2 * i] = p->x[i], x0[2 * i + 1] = p->y[i], rmax = fmax(rmax, p->radius[i]);
    int px = sc->side[GR_LEFT] == GR_BC_PERIODIC, py = sc->side[GR_BOTTOM] == GR_BC_PERIODIC;
    sweep s = {sc, p, px ? sc->width : 0.0, py ? sc->height : 0.0, 0, 0, -1, -1, 0, GAP0};
    gr_grid *g = gr_grid_create(0.0, 0.0, sc->width, sc->height, 2.0 * rmax * (1.0 + 4 * GAP0), px, py, err);
    int rc = g ? relax(&s, g, rmax, rep, err) : err->code;
    for (size_t i = 0; i < p->n && !rc; i++) {
        double dx = gr_min_image(p->x[i] - x0[2 * i], s.Lx), dy = gr_min_image(p->y[i] - x0[2 * i + 1], s.Ly);
        rep->max_displacement = fmax(rep->max_displacement, hypot(dx, dy));
    }
    gr_grid_free(g);
    free(x0);
    return rc;
}
