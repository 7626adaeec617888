/* Contact detection with a gap margin on a cell grid, the contact list in
 * identity order, and the warm start from the previous step's impulses.
 * Bottom layer: calls no other file of the backend. */
#include <math.h>
#include <stdlib.h>

#include "cd_int.h"
#include "geom.h"

static int push(gr_cd_list *l, gr_err *err)
{
    if (l->n < l->cap)
        return GR_OK;
    size_t cap = l->cap ? 2 * l->cap : 256;
    gr_cd_contact *c = realloc(l->c, cap * sizeof *c);
    if (!c)
        return gr_fail(err, GR_ERUN, "out of memory for %zu contacts", cap);
    l->c = c;
    l->cap = cap;
    return GR_OK;
}

/* Fill the parts every contact shares: W's diagonal, restitutions, the
 * relative velocity at the start of the step (state velocities). */
static void finish(const gr_cd *d, gr_cd_contact *c)
{
    const gr_particles *p = d->p;
    size_t i = (size_t)c->i, j = (size_t)c->j;
    double ri = p->radius[i], dvx = p->vx[i], dvy = p->vy[i], spin = p->omega[i] * ri;
    c->wn = d->im[i];
    c->wt = d->im[i] + ri * ri * d->iI[i];
    if (j < d->n) {
        double rj = p->radius[j];
        c->wn += d->im[j];
        c->wt += d->im[j] + rj * rj * d->iI[j];
        dvx -= p->vx[j], dvy -= p->vy[j];
        spin += p->omega[j] * rj;
        c->en = d->en, c->et = d->et;
        c->dmin = 2 * fmin(ri, rj);
    } else {
        dvx -= c->vwx, dvy -= c->vwy;
        c->en = d->enw, c->et = d->etw;
        c->dmin = 2 * ri;
    }
    c->un0 = dvx * c->nx + dvy * c->ny;
    c->ut0 = -dvx * c->ny + dvy * c->nx - spin;
    c->rn = c->rt = 0;
}

typedef struct {
    gr_cd *d;
    double margin;
    gr_err *err;
} pair_ctx;

static int on_pair(size_t i, size_t j, double dx, double dy, void *user)
{
    pair_ctx *pc = user;
    gr_cd *d = pc->d;
    if (d->im[i] == 0 && d->im[j] == 0)
        return 0;
    double dist = sqrt(dx * dx + dy * dy);
    double g = dist - d->p->radius[i] - d->p->radius[j];
    if (!(g < pc->margin) || !(dist > 0))
        return 0;
    if (push(&d->cur, pc->err))
        return 1;
    gr_cd_contact *c = &d->cur.c[d->cur.n++];
    *c = (gr_cd_contact){.i = (int64_t)i, .j = (int64_t)j, .nx = -dx / dist, .ny = -dy / dist, .g = g};
    finish(d, c);
    return 0;
}

/* Walls present at t, each mobile grain against each (walls are few). */
static int wall_contacts(gr_cd *d, double margin, gr_err *err)
{
    const gr_particles *p = d->p;
    double dt = d->par.dt, off0 = gr_floor_offset(&d->sc.floor, d->t);
    double vfloor = (gr_floor_offset(&d->sc.floor, d->t + dt) - off0) / dt;
    for (int k = 0; k < d->nwall; k++) {
        const gr_cd_wall *s = &d->wall[k];
        if (!(d->t < s->open_time))
            continue;
        double oy = s->vibrating ? off0 : 0.0;
        gr_v2 a = {s->x0, s->y0 + oy}, b = {s->x1, s->y1 + oy};
        for (size_t i = 0; i < d->n; i++) {
            if (d->skip[i] || d->im[i] == 0)
                continue;
            double u;
            gr_v2 c0 = {p->x[i], p->y[i]}, q = gr_seg_closest(a, b, c0, &u);
            double dx = c0.x - q.x, dy = c0.y - q.y, dist = sqrt(dx * dx + dy * dy);
            double g = dist - p->radius[i];
            if (!(g < margin) || !(dist > 0))
                continue;
            if (push(&d->cur, err))
                return err->code;
            gr_cd_contact *c = &d->cur.c[d->cur.n++];
            *c = (gr_cd_contact){.i = (int64_t)i, .j = (int64_t)d->n + k, .nx = dx / dist, .ny = dy / dist,
                                 .g = g, .vwy = s->vibrating ? vfloor : 0.0};
            finish(d, c);
        }
    }
    return GR_OK;
}

static int by_identity(const void *a, const void *b)
{
    const gr_cd_contact *x = a, *y = b;
    if (x->i != y->i)
        return x->i < y->i ? -1 : 1;
    return x->j < y->j ? -1 : x->j > y->j;
}

/* A grid whose cells are at least rcut wide (made again when a margin
 * grows past them). */
static int ensure_grid(gr_cd *d, double rcut, gr_err *err)
{
    if (d->grid && fmin(d->grid->cx, d->grid->cy) >= rcut)
        return GR_OK;
    gr_grid_free(d->grid);
    d->grid = gr_grid_create(0, 0, d->sc.width, d->sc.height, rcut, d->Lx > 0, d->Ly > 0, err);
    return d->grid ? GR_OK : err->code;
}

int gr_cd_detect(gr_cd *d, double margin, gr_err *err)
{
    d->cur.n = 0;
    double rcut = d->dmax + margin;
    if (ensure_grid(d, rcut, err) ||
        gr_grid_build(d->grid, d->p->x, d->p->y, d->n, d->skip, err))
        return err->code;
    pair_ctx pc = {d, margin, err};
    if (gr_grid_pairs(d->grid, d->p->x, d->p->y, rcut, on_pair, &pc))
        return err->code;
    if (wall_contacts(d, margin, err))
        return err->code;
    qsort(d->cur.c, d->cur.n, sizeof *d->cur.c, by_identity);
    return GR_OK;
}

void gr_cd_warm_start(gr_cd *d)
{
    const gr_cd_list *o = &d->prev;
    size_t k = 0;
    /* both lists are in identity order: one merge */
    for (size_t m = 0; m < d->cur.n; m++) {
        gr_cd_contact *c = &d->cur.c[m];
        while (k < o->n && by_identity(&o->c[k], c) < 0)
            k++;
        if (k < o->n && by_identity(&o->c[k], c) == 0) {
            c->rn = o->c[k].rn;
            c->rt = o->c[k].rt;
        }
    }
}
