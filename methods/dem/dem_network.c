/* The contact network at the current state, for `[run] contacts = yes`
 * (docs/methods/dem.md, "Contact network"). It is evaluated from the
 * state when asked, not recorded inside the force loop: a run that does
 * not ask pays nothing, and the hot loop stays as it is. Reading only,
 * it leaves every bit of the state (and so the run) unchanged. */
#include <math.h>
#include <stdlib.h>

#include "dem.h"
#include "dem_contact.h"
#include "geom.h"
#include "grid.h"

typedef struct {
    int64_t i, j;
    double fn, ft;
} net_row;

typedef struct {
    const gr_dem *d;
    const double *x, *y, *vx, *vy, *w;
    dem_law law;
    dem_law law_w;
    net_row *row;
    size_t n, cap;
    gr_err *err;
} net_ctx;

static int push_row(net_ctx *c, int64_t i, int64_t j, double fn, double ft, gr_err *err)
{
    if (c->n == c->cap) {
        size_t cap = c->cap ? 2 * c->cap : 64;
        net_row *r = realloc(c->row, cap * sizeof *r);
        if (!r)
            return gr_fail(err, GR_ERUN, "out of memory in the contact network");
        c->row = r, c->cap = cap;
    }
    c->row[c->n++] = (net_row){i, j, fn, ft};
    return GR_OK;
}

/* The spring's stretch of a live contact, as the next evaluation would
 * find it (stamped by the last step), without claiming a slot. */
static double stretch(const gr_dem *d, size_t own, int32_t key)
{
    const gr_dem_hist *h = &d->hist;
    size_t base = own * (size_t)h->cap;
    for (int k = 0; k < h->cap; k++)
        if (h->partner[base + k] == key && h->stamp[base + k] == d->step)
            return h->z[base + k];
    return 0.0;
}

/* Pair a-b with b = a + (dx, dy), a the smaller id so that a row's bits do
 * not depend on the internal order (the law is symmetric in a and b). */
static int net_pair(net_ctx *c, size_t a, size_t b, double dx, double dy, gr_err *err)
{
    const gr_dem *d = c->d;
    double ra = d->rad[a], rb = d->rad[b], rs = ra + rb;
    double r2 = dx * dx + dy * dy;
    if (r2 >= rs * rs)
        return GR_OK;
    double r = sqrt(r2), inv = r > 0 ? 1.0 / r : 0.0;
    double nx = r > 0 ? dx * inv : 1.0, ny = dy * inv;
    double dvx = c->vx[b] - c->vx[a], dvy = c->vy[b] - c->vy[a];
    double wsum = d->rot ? c->w[a] * ra + c->w[b] * rb : 0.0;
    double zeta = 0.0;
    if (d->hist_on) {
        size_t own = d->tag[a] < d->tag[b] ? a : b;
        zeta = stretch(d, own, d->tag[own == a ? b : a]);
    }
    double Fx, Fy, Ft, el;
    dem_law_eval(&c->law, (int)d->normal, (int)d->tang, rs - r, nx, ny, dvx, dvy, wsum, &zeta, 0.0,
                 &Fx, &Fy, &Ft, &el);
    /* The law gives F = fn n + ft t on b, n from a to b: on a it is -F, whose
     * components along -n (from b to a) and -t are the same fn and ft. */
    return push_row(c, d->tag_id[d->tag[a]], d->tag_id[d->tag[b]], Fx * nx + Fy * ny, Ft, err);
}

/* A pair closer than the largest contact distance, i < j internally with
 * (dx, dy) from i to j (common/grid.h): skipped for two fixed grains, as
 * the force loop does; passed on with the smaller id first. */
static int net_pair_found(size_t i, size_t j, double dx, double dy, void *user)
{
    net_ctx *c = user;
    const gr_dem *d = c->d;
    if ((d->flags[i] & GR_PF_FIXED) && (d->flags[j] & GR_PF_FIXED))
        return GR_OK;
    if (d->tag_id[d->tag[i]] < d->tag_id[d->tag[j]])
        return net_pair(c, i, j, dx, dy, c->err);
    return net_pair(c, j, i, -dx, -dy, c->err);
}

/* Grain i against segment k, as the force loop sees it: n from the wall to
 * the grain, and the law's force (on its j) is the force on the grain. */
static int net_wall(net_ctx *c, size_t i, int k, double off, double vy, gr_err *err)
{
    const gr_dem *d = c->d;
    const gr_dem_seg *sg = &d->seg[k];
    double ax = sg->x0, ay = sg->y0 + off, r = d->rad[i], xi, nx, ny;
    if (!dem_seg_contact(ax, ay, sg->x1 - ax, sg->y1 + off - ay, c->x[i], c->y[i], r, &xi, &nx, &ny))
        return GR_OK;
    double wsum = d->rot ? c->w[i] * r : 0.0;
    double zeta = d->hist_on ? stretch(d, i, (int32_t)(d->ntag + (size_t)k)) : 0.0;
    double Fx, Fy, Ft, el;
    dem_law_eval(&c->law_w, (int)d->normal, (int)d->tang, xi, nx, ny, c->vx[i], c->vy[i] - vy,
                 wsum, &zeta, 0.0, &Fx, &Fy, &Ft, &el);
    return push_row(c, d->tag_id[d->tag[i]], -1 - (int64_t)k, Fx * nx + Fy * ny, Ft, err);
}

/* One axis of the grid of the current positions (the force loop's cells
 * and lists were built for earlier positions, with a skin, so they cannot
 * be trusted to hold every contact of this instant): periodic over
 * [0, L), else over the grains' span. */
static void grid_span(const double *p, size_t n, double L, double h, double *lo, double *len)
{
    if (L > 0) {
        *lo = 0.0, *len = L;
        return;
    }
    double a = p[0], b = p[0];
    for (size_t i = 1; i < n; i++)
        a = fmin(a, p[i]), b = fmax(b, p[i]);
    *lo = a, *len = fmax(b - a, h);
}

/* Every overlapping pair once, through the shared cell grid. */
static int net_pairs(net_ctx *c, gr_err *err)
{
    const gr_dem *d = c->d;
    size_t n = d->n;
    double h = 0.0, x0, y0, lx, ly;
    for (size_t i = 0; i < n; i++)
        h = fmax(h, 2.0 * d->rad[i]);
    grid_span(c->x, n, d->Lx, h, &x0, &lx);
    grid_span(c->y, n, d->Ly, h, &y0, &ly);
    /* sparse grains (a gas, or far apart): cells no smaller than needed
     * to keep the grid within a few cells per grain */
    double cell = h;
    while ((lx / cell) * (ly / cell) > 4.0 * (double)n + 64.0)
        cell *= 2.0;
    gr_grid *g = gr_grid_create(x0, y0, lx, ly, cell, d->Lx > 0, d->Ly > 0, err);
    if (!g || gr_grid_build(g, c->x, c->y, n, NULL, err)) {
        gr_grid_free(g);
        return err->code;
    }
    c->err = err;
    int rc = gr_grid_pairs(g, c->x, c->y, h, net_pair_found, c);
    gr_grid_free(g);
    return rc;
}

/* Mobile grains against the segments still closed at time t. */
static int net_walls(net_ctx *c, gr_err *err)
{
    const gr_dem *d = c->d;
    for (int k = 0; k < d->nseg; k++) {
        if (!(d->t < d->seg[k].open_time))
            continue;
        double off = 0.0, vy = 0.0;
        if (d->seg[k].vibrating) {
            off = gr_floor_offset(&d->sc.floor, d->t);
            vy = gr_floor_velocity(&d->sc.floor, d->t);
        }
        for (size_t i = 0; i < d->n; i++)
            if (!(d->flags[i] & GR_PF_FIXED) && net_wall(c, i, k, off, vy, err))
                return err->code;
    }
    return GR_OK;
}

static int row_order(const void *pa, const void *pb)
{
    const net_row *a = pa, *b = pb;
    if (a->i != b->i)
        return a->i < b->i ? -1 : 1;
    return a->j < b->j ? -1 : a->j > b->j;
}

int gr_dem_contacts(const gr_dem *d, gr_contacts *out, gr_err *err)
{
    int p = d->cur;
    net_ctx c = {
        .d = d, .x = d->f[F_X][p], .y = d->f[F_Y][p], .vx = d->f[F_VX][p], .vy = d->f[F_VY][p],
        .w = d->f[F_W][p], .law = {d->kn, d->gn, d->kt, d->gt, d->mu, d->par.dt, d->clip},
        .law_w = {d->kn, d->gw, d->kt, d->gt, d->mu, d->par.dt, d->clip},
    };
    out->n = 0;
    int rc = d->n ? net_pairs(&c, err) : GR_OK;
    if (!rc)
        rc = net_walls(&c, err);
    /* sorted by ids: the same rows whatever the internal order (restarts) */
    if (!rc && c.n)
        qsort(c.row, c.n, sizeof *c.row, row_order);
    for (size_t k = 0; !rc && k < c.n; k++)
        rc = gr_contacts_push(out, c.row[k].i, c.row[k].j, c.row[k].fn, c.row[k].ft, err);
    free(c.row);
    return rc;
}
