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

typedef struct {
    int64_t i, j;
    double fn, ft;
} net_row;

typedef struct {
    const gr_dem *d;
    const double *x, *y, *vx, *vy, *w;
    dem_law law;
    net_row *row;
    size_t n, cap;
} net_ctx;

/* Cells of the current positions: the force loop's own cells and lists
 * were built for earlier positions (with a skin), so they cannot be
 * trusted to hold every contact of this instant. */
typedef struct {
    int nc[2], per[2];
    double lo[2], w[2];
    int32_t *start, *idx;
} net_grid;

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

static int net_pair_ordered(net_ctx *c, size_t i, size_t j, gr_err *err)
{
    const gr_dem *d = c->d;
    double dx = gr_min_image(c->x[j] - c->x[i], d->Lx);
    double dy = gr_min_image(c->y[j] - c->y[i], d->Ly);
    if (d->tag_id[d->tag[i]] < d->tag_id[d->tag[j]])
        return net_pair(c, i, j, dx, dy, err);
    return net_pair(c, j, i, -dx, -dy, err);
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
    dem_law_eval(&c->law, (int)d->normal, (int)d->tang, xi, nx, ny, c->vx[i], c->vy[i] - vy,
                 wsum, &zeta, 0.0, &Fx, &Fy, &Ft, &el);
    return push_row(c, d->tag_id[d->tag[i]], -1 - (int64_t)k, Fx * nx + Fy * ny, Ft, err);
}

/* One axis of the grid: periodic over [0, L), else over the grains' span. */
static void grid_axis(net_grid *g, int a, const double *p, size_t n, double L, double h)
{
    g->per[a] = L > 0;
    if (L > 0) {
        g->lo[a] = 0.0;
        g->nc[a] = L / h >= 1.0 ? (int)(L / h) : 1;
        g->w[a] = L / g->nc[a];
        return;
    }
    double lo = p[0], hi = p[0];
    for (size_t i = 1; i < n; i++)
        lo = fmin(lo, p[i]), hi = fmax(hi, p[i]);
    g->lo[a] = lo;
    g->w[a] = h;
    g->nc[a] = (int)((hi - lo) / h) + 1;
}

static int cell_of(const net_grid *g, int a, double p)
{
    double u = p - g->lo[a];
    if (g->per[a])
        u -= g->w[a] * g->nc[a] * floor(u / (g->w[a] * g->nc[a]));
    int k = (int)(u / g->w[a]);
    return k < 0 ? 0 : k >= g->nc[a] ? g->nc[a] - 1 : k;
}

static int grid_build(net_grid *g, const net_ctx *c, gr_err *err)
{
    const gr_dem *d = c->d;
    size_t n = d->n;
    double h = 0.0;
    for (size_t i = 0; i < n; i++)
        h = fmax(h, 2.0 * d->rad[i]);
    /* sparse grains (a gas, or far apart): coarser cells keep the grid small */
    do {
        grid_axis(g, 0, c->x, n, d->Lx, h);
        grid_axis(g, 1, c->y, n, d->Ly, h);
        h *= 2.0;
    } while ((double)g->nc[0] * g->nc[1] > 4.0 * (double)n + 64.0);
    size_t nc = (size_t)g->nc[0] * (size_t)g->nc[1];
    g->start = calloc(nc + 1, sizeof *g->start);
    g->idx = malloc((n ? n : 1) * sizeof *g->idx);
    int32_t *cell = malloc((n ? n : 1) * sizeof *cell), *pos = malloc(nc * sizeof *pos);
    if (!g->start || !g->idx || !cell || !pos) {
        free(cell), free(pos);
        return gr_fail(err, GR_ERUN, "out of memory in the contact network");
    }
    for (size_t i = 0; i < n; i++) {
        cell[i] = cell_of(g, 1, c->y[i]) * g->nc[0] + cell_of(g, 0, c->x[i]);
        g->start[cell[i] + 1]++;
    }
    for (size_t k = 0; k < nc; k++)
        g->start[k + 1] += g->start[k];
    for (size_t k = 0; k < nc; k++)
        pos[k] = g->start[k];
    for (size_t i = 0; i < n; i++)
        g->idx[pos[cell[i]]++] = (int32_t)i;
    free(cell), free(pos);
    return GR_OK;
}

/* The distinct cells around (cx, cy), itself included: with one or two
 * cells along a periodic axis the offsets -1 and +1 name the same cell. */
static int around(const net_grid *g, int cx, int cy, int32_t out[9])
{
    int m = 0;
    for (int oy = -1; oy <= 1; oy++) {
        for (int ox = -1; ox <= 1; ox++) {
            int x = cx + ox, y = cy + oy;
            if ((x < 0 || x >= g->nc[0]) && !g->per[0])
                continue;
            if ((y < 0 || y >= g->nc[1]) && !g->per[1])
                continue;
            x = (x + g->nc[0]) % g->nc[0], y = (y + g->nc[1]) % g->nc[1];
            int32_t k = y * g->nc[0] + x, seen = 0;
            for (int q = 0; q < m; q++)
                seen |= out[q] == k;
            if (!seen)
                out[m++] = k;
        }
    }
    return m;
}

/* Every overlapping pair once (internal i < j), skipping two fixed grains
 * as the force loop does. */
static int net_pairs(net_ctx *c, const net_grid *g, gr_err *err)
{
    const gr_dem *d = c->d;
    for (size_t i = 0; i < d->n; i++) {
        int fi = (d->flags[i] & GR_PF_FIXED) != 0;
        int32_t nb[9];
        int m = around(g, cell_of(g, 0, c->x[i]), cell_of(g, 1, c->y[i]), nb);
        for (int q = 0; q < m; q++) {
            for (int32_t b = g->start[nb[q]]; b < g->start[nb[q] + 1]; b++) {
                size_t j = (size_t)g->idx[b];
                if (j <= i || (fi && (d->flags[j] & GR_PF_FIXED)))
                    continue;
                if (net_pair_ordered(c, i, j, err))
                    return err->code;
            }
        }
    }
    return GR_OK;
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
    };
    net_grid g = {0};
    out->n = 0;
    int rc = d->n ? grid_build(&g, &c, err) : GR_OK;
    if (!rc && d->n)
        rc = net_pairs(&c, &g, err);
    if (!rc)
        rc = net_walls(&c, err);
    free(g.start), free(g.idx);
    /* sorted by ids: the same rows whatever the internal order (restarts) */
    if (!rc && c.n)
        qsort(c.row, c.n, sizeof *c.row, row_order);
    for (size_t k = 0; !rc && k < c.n; k++)
        rc = gr_contacts_push(out, c.row[k].i, c.row[k].j, c.row[k].fn, c.row[k].ft, err);
    free(c.row);
    return rc;
}
