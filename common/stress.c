#include "stress.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom.h"

/* Wall w's segment (domain sides first), the floor at its height at t. */
static int wall_segment(const gr_scene *sc, int64_t w, double t, gr_v2 *a, gr_v2 *b)
{
    double W = sc->width, H = sc->height, yf = gr_floor_offset(&sc->floor, t);
    const gr_v2 side[4][2] = {{{0, 0}, {0, H}}, {{W, 0}, {W, H}}, {{0, yf}, {W, yf}}, {{0, H}, {W, H}}};
    static const int order[4] = {GR_LEFT, GR_RIGHT, GR_BOTTOM, GR_TOP};
    for (int k = 0; k < 4; k++) {
        if (sc->side[order[k]] != GR_BC_WALL)
            continue;
        if (w-- == 0) {
            *a = side[k][0], *b = side[k][1];
            return 1;
        }
    }
    if (w >= sc->nsegments)
        return 0;
    const gr_segment *s = &sc->segments[w];
    double dy = s->vibrating ? yf : 0.0;
    *a = (gr_v2){s->x0, s->y0 + dy}, *b = (gr_v2){s->x1, s->y1 + dy};
    return 1;
}

static void deposit(double *cells, int nx, int ny, double W, double H, double x, double y, double share,
                    const double lf[4])
{
    if (!cells)
        return;
    int ix = (int)floor(x / W * nx), iy = (int)floor(y / H * ny);
    if (ix < 0 || iy < 0 || ix >= nx || iy >= ny)
        return; /* a grain outside the domain (leaving through an open side) */
    for (int k = 0; k < 4; k++)
        cells[((size_t)iy * (size_t)nx + (size_t)ix) * 4 + (size_t)k] += share * lf[k];
}

/* The branch vector l of row k and its grains' indices (j < 0: a wall). */
static int branch(const gr_scene *sc, const gr_particles *p, const gr_id_index *ix, const gr_contacts *c,
                  size_t k, double t, size_t *i, long *j, gr_v2 *l, gr_err *err)
{
    const gr_id_index *ei = gr_id_index_find(ix, p->n, c->i[k]);
    if (!ei)
        return gr_fail(err, GR_ERUN, "stress: contact with grain %lld, not in the snapshot", (long long)c->i[k]);
    *i = ei->i;
    gr_v2 xi = {p->x[*i], p->y[*i]};
    if (c->j[k] >= 0) {
        const gr_id_index *ej = gr_id_index_find(ix, p->n, c->j[k]);
        if (!ej)
            return gr_fail(err, GR_ERUN, "stress: contact with grain %lld, not in the snapshot", (long long)c->j[k]);
        *j = (long)ej->i;
        l->x = xi.x - p->x[ej->i], l->y = xi.y - p->y[ej->i];
        if (sc->side[GR_LEFT] == GR_BC_PERIODIC)
            l->x = gr_min_image(l->x, sc->width);
        if (sc->side[GR_BOTTOM] == GR_BC_PERIODIC)
            l->y = gr_min_image(l->y, sc->height);
        return GR_OK;
    }
    gr_v2 a, b;
    if (!wall_segment(sc, -1 - c->j[k], t, &a, &b))
        return gr_fail(err, GR_ERUN, "stress: contact with wall %lld, which the scene does not have",
                       (long long)(-1 - c->j[k]));
    double u;
    gr_v2 q = gr_seg_closest(a, b, xi, &u);
    *j = -1;
    l->x = xi.x - q.x, l->y = xi.y - q.y;
    return GR_OK;
}

int gr_stress_contacts(const gr_scene *sc, const gr_particles *p, const gr_contacts *c, double t, int nx,
                       int ny, double global[4], double *cells, gr_err *err)
{
    double W = sc->width, H = sc->height;
    memset(global, 0, 4 * sizeof *global);
    if (cells)
        memset(cells, 0, (size_t)nx * (size_t)ny * 4 * sizeof *cells);
    gr_id_index *ix = malloc((p->n ? p->n : 1) * sizeof *ix);
    if (!ix)
        return gr_fail(err, GR_ERUN, "out of memory");
    gr_id_index_sort(p->id, p->n, ix);
    int rc = GR_OK;
    for (size_t k = 0; k < c->n && !rc; k++) {
        size_t i = 0;
        long j = -1;
        gr_v2 l = {0, 0};
        if ((rc = branch(sc, p, ix, c, k, t, &i, &j, &l, err)))
            break;
        double len = hypot(l.x, l.y);
        if (!(len > 0))
            continue; /* coincident centres: no direction, no lever */
        double nxv = l.x / len, nyv = l.y / len;
        double Fx = c->fn[k] * nxv - c->ft[k] * nyv, Fy = c->fn[k] * nyv + c->ft[k] * nxv;
        double lf[4] = {l.x * Fx, l.x * Fy, l.y * Fx, l.y * Fy};
        for (int q = 0; q < 4; q++)
            global[q] += lf[q];
        double si = j >= 0 ? p->radius[i] / (p->radius[i] + p->radius[j]) : 1.0;
        deposit(cells, nx, ny, W, H, p->x[i], p->y[i], si, lf);
        if (j >= 0)
            deposit(cells, nx, ny, W, H, p->x[j], p->y[j], 1.0 - si, lf);
    }
    free(ix);
    for (int q = 0; q < 4; q++)
        global[q] /= W * H;
    double cell_area = W / nx * H / ny;
    for (size_t q = 0; cells && q < (size_t)nx * (size_t)ny * 4; q++)
        cells[q] /= cell_area;
    return rc;
}
