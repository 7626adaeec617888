#include "view_net.h"

#include <math.h>
#include <stdlib.h>

struct vw_net {
    gr_h5md_reader *r;
    int draw;
    size_t nt;          /* frames holding a network */
    double *t;          /* their times */
    gr_contacts *c;
    gr_id_index *ix;
    size_t cap;         /* grains the per-grain arrays hold */
    double *count, *force;
    gr_plot_line *lines;
    double *fn;         /* |fn| per line */
    size_t nlines, lcap;
};

void vw_net_free(vw_net *n)
{
    if (!n)
        return;
    gr_contacts_free(n->c);
    free(n->t);
    free(n->ix);
    free(n->count);
    free(n->force);
    free(n->lines);
    free(n->fn);
    free(n);
}

vw_net *vw_net_open(gr_h5md_reader *r, const char *who, int lines, gr_err *err)
{
    vw_net *n = calloc(1, sizeof *n);
    if (!n || !(n->c = gr_contacts_create(0, err))) {
        if (!err->code)
            gr_fail(err, GR_ERUN, "out of memory");
        vw_net_free(n);
        return NULL;
    }
    n->r = r, n->draw = lines;
    if (gr_h5md_contact_frames(r, &n->nt, err))
        goto fail;
    if (!n->nt) {
        gr_fail(err, GR_EINPUT, "%s: %s holds no contact networks ([run] contacts = yes writes them with each "
                "frame, for a method that has them: grano methods lists 'contact networks')", who,
                gr_h5md_info_of(r)->path);
        goto fail;
    }
    if (!(n->t = malloc(n->nt * sizeof *n->t))) {
        gr_fail(err, GR_ERUN, "out of memory");
        goto fail;
    }
    if (gr_h5md_series_times(r, "contacts", n->nt, n->t, err))
        goto fail;
    return n;
fail:
    vw_net_free(n);
    return NULL;
}

static int grow(vw_net *n, size_t grains, gr_err *err)
{
    if (grains > n->cap) {
        free(n->ix), free(n->count), free(n->force);
        n->ix = malloc(grains * sizeof *n->ix);
        n->count = malloc(grains * sizeof *n->count);
        n->force = malloc(grains * sizeof *n->force);
        n->cap = grains;
        if (!n->ix || !n->count || !n->force) {
            n->cap = 0;
            return gr_fail(err, GR_ERUN, "out of memory");
        }
    }
    if (n->draw && n->c->n > n->lcap) {
        free(n->lines), free(n->fn);
        n->lines = malloc(n->c->n * sizeof *n->lines);
        n->fn = malloc(n->c->n * sizeof *n->fn);
        n->lcap = n->c->n;
        if (!n->lines || !n->fn) {
            n->lcap = 0;
            return gr_fail(err, GR_ERUN, "out of memory");
        }
    }
    return GR_OK;
}

/* The shortest way from a to b along an axis of length l. */
static double nearest(double a, double b, double l, int periodic)
{
    double d = b - a;
    if (periodic && l > 0 && fabs(d) > 0.5 * l)
        d -= copysign(l, d);
    return d;
}

static long index_of(const vw_net *n, size_t np, int64_t id)
{
    const gr_id_index *e = id >= 0 ? gr_id_index_find(n->ix, np, id) : NULL;
    return e ? (long)e->i : -1;
}

int vw_net_load(vw_net *n, const gr_particles *p, double t, const double box[2], const int periodic[2],
                gr_err *err)
{
    size_t k = 0;
    double eps = 1e-9 * fmax(1.0, fabs(t));
    while (k < n->nt && fabs(n->t[k] - t) > eps)
        k++;
    if (k == n->nt)
        return gr_fail(err, GR_EINPUT, "%s: the frame at t = %g has no contact network (%zu frames have one, "
                       "t = %g .. %g)", gr_h5md_info_of(n->r)->path, t, n->nt, n->t[0], n->t[n->nt - 1]);
    if (gr_h5md_read_contacts(n->r, k, n->c, NULL, NULL, err) || grow(n, p->n + 1, err))
        return err->code;
    gr_id_index_sort(p->id, p->n, n->ix);
    for (size_t i = 0; i < p->n; i++)
        n->count[i] = n->force[i] = 0;
    n->nlines = 0;
    for (size_t c = 0; c < n->c->n; c++) {
        long a = index_of(n, p->n, n->c->i[c]), b = index_of(n, p->n, n->c->j[c]);
        double f = fabs(n->c->fn[c]);
        if (a >= 0)
            n->count[a] += 1, n->force[a] += f;
        if (b >= 0)
            n->count[b] += 1, n->force[b] += f;
        if (!n->draw || a < 0 || b < 0 || ((p->flags[a] | p->flags[b]) & GR_PF_GONE))
            continue;
        gr_plot_line *l = &n->lines[n->nlines];
        *l = (gr_plot_line){p->x[a], p->y[a], nearest(p->x[a], p->x[b], box[0], periodic[0]),
                            nearest(p->y[a], p->y[b], box[1], periodic[1]), 1};
        n->fn[n->nlines++] = f;
    }
    return GR_OK;
}

double vw_net_count(const vw_net *n, size_t i)
{
    return n->count[i];
}

double vw_net_force(const vw_net *n, size_t i)
{
    return n->force[i];
}

void vw_net_forces(const vw_net *n, const double **fn, size_t *m)
{
    *fn = n && n->draw ? n->fn : NULL;
    *m = n && n->draw ? n->nlines : 0;
}

void vw_net_lines(vw_net *n, double fref, const gr_plot_line **lines, size_t *m)
{
    *lines = NULL, *m = 0;
    if (!n->draw)
        return;
    for (size_t k = 0; k < n->nlines; k++) {
        int c = fref > 0 ? 1 + (int)(GR_PLOT_LINE_CLASSES * n->fn[k] / fref) : 1;
        n->lines[k].cls = c > GR_PLOT_LINE_CLASSES ? GR_PLOT_LINE_CLASSES : c;
    }
    *lines = n->lines, *m = n->nlines;
}
