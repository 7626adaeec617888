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

/* ---- window averages of instantaneous collisions ---- */

/* Per cell: int m dt, int m v dt (2), int m v v dt (xx, xy, yy), then
 * sum l (x) J (xx, xy, yx, yy). */
enum { S_M, S_PX, S_PY, S_KXX, S_KXY, S_KYY, S_CXX, S_CXY, S_CYX, S_CYY };

gr_stress_acc *gr_stress_acc_create(double W, double H, int periodic_x, int periodic_y, int nx, int ny,
                                    double t0, gr_err *err)
{
    if (nx < 1 || ny < 1 || !(W > 0) || !(H > 0)) {
        gr_fail(err, GR_ERUN, "stress: a grid of %d x %d cells over %g x %g", nx, ny, W, H);
        return NULL;
    }
    gr_stress_acc *a = calloc(1, sizeof *a);
    if (a)
        a->sum = calloc((size_t)nx * (size_t)ny * GR_STRESS_ACC_N, sizeof *a->sum);
    if (!a || !a->sum) {
        gr_stress_acc_free(a);
        gr_fail(err, GR_ERUN, "out of memory for the stress of %d x %d cells", nx, ny);
        return NULL;
    }
    *a = (gr_stress_acc){nx, ny, W, H, periodic_x, periodic_y, t0, a->sum};
    return a;
}

void gr_stress_acc_free(gr_stress_acc *a)
{
    if (!a)
        return;
    free(a->sum);
    free(a);
}

static int acc_index(double x, double L, int n, int periodic)
{
    if (periodic)
        x -= L * floor(x / L);
    double k = floor(x / L * n);
    return k < 0 ? 0 : k >= n ? n - 1 : (int)k;
}

static double *acc_cell(gr_stress_acc *a, double x, double y)
{
    size_t ix = (size_t)acc_index(x, a->W, a->nx, a->px), iy = (size_t)acc_index(y, a->H, a->ny, a->py);
    return a->sum + (iy * (size_t)a->nx + ix) * GR_STRESS_ACC_N;
}

void gr_stress_acc_kinetic(gr_stress_acc *a, double x, double y, const double mom[6])
{
    double *c = acc_cell(a, x, y);
    for (int k = 0; k < 6; k++)
        c[S_M + k] += mom[k];
}

void gr_stress_acc_collision(gr_stress_acc *a, double xi, double yi, double xj, double yj, double share,
                             double lx, double ly, double Jx, double Jy)
{
    const double lf[4] = {lx * Jx, lx * Jy, ly * Jx, ly * Jy};
    double *ci = acc_cell(a, xi, yi);
    for (int k = 0; k < 4; k++)
        ci[S_CXX + k] += share * lf[k];
    if (share == 1.0)
        return;
    double *cj = acc_cell(a, xj, yj);
    for (int k = 0; k < 4; k++)
        cj[S_CXX + k] += (1.0 - share) * lf[k];
}

void gr_stress_acc_read(gr_stress_acc *a, double t, double global[4], double *cells)
{
    size_t nc = (size_t)a->nx * (size_t)a->ny;
    double T = t - a->t0, At = a->W / a->nx * a->H / a->ny * T;
    for (int q = 0; q < 4; q++)
        global[q] = T > 0 ? 0.0 : NAN;
    for (size_t c = 0; c < nc; c++) {
        const double *s = a->sum + c * GR_STRESS_ACC_N;
        double ux = s[S_M] > 0 ? s[S_PX] / s[S_M] : 0.0, uy = s[S_M] > 0 ? s[S_PY] / s[S_M] : 0.0;
        double kxx = s[S_KXX] - s[S_M] * ux * ux, kxy = s[S_KXY] - s[S_M] * ux * uy;
        double kyy = s[S_KYY] - s[S_M] * uy * uy;
        double v[4] = {kxx + s[S_CXX], kxy + s[S_CXY], kxy + s[S_CYX], kyy + s[S_CYY]};
        for (int q = 0; q < 4; q++) {
            v[q] = T > 0 ? v[q] / At : NAN;
            if (cells)
                cells[c * 4 + (size_t)q] = v[q];
            global[q] += v[q] / (double)nc;
        }
    }
    memset(a->sum, 0, nc * GR_STRESS_ACC_N * sizeof *a->sum);
    a->t0 = t;
}

/* Stored as {nx, ny, t0, sums...}. */
int gr_stress_acc_save(const gr_stress_acc *a, gr_ckpt *ck, const char *name, gr_err *err)
{
    size_t n = 3 + (size_t)a->nx * (size_t)a->ny * GR_STRESS_ACC_N;
    double *v = malloc(n * sizeof *v);
    if (!v)
        return gr_fail(err, GR_ERUN, "out of memory for the stress checkpoint");
    v[0] = a->nx, v[1] = a->ny, v[2] = a->t0;
    memcpy(v + 3, a->sum, (n - 3) * sizeof *v);
    int rc = gr_ckpt_put_f64(ck, name, v, n, err);
    free(v);
    return rc;
}

int gr_stress_acc_load(gr_stress_acc **a, gr_ckpt *ck, const char *name, double W, double H, int periodic_x,
                       int periodic_y, gr_err *err)
{
    gr_stress_acc_free(*a);
    *a = NULL;
    size_t n;
    gr_err none = {0};
    if (gr_ckpt_len(ck, name, &n, &none))
        return GR_OK;
    double *v = malloc((n ? n : 1) * sizeof *v);
    if (!v)
        return gr_fail(err, GR_ERUN, "out of memory for the stress checkpoint");
    int rc = gr_ckpt_get_f64(ck, name, v, n, err);
    int nx = n >= 3 && v[0] >= 1 && v[0] <= 1e6 ? (int)v[0] : 0, ny = n >= 3 && v[1] >= 1 && v[1] <= 1e6 ? (int)v[1] : 0;
    if (!rc && (!nx || !ny || n != 3 + (size_t)nx * (size_t)ny * GR_STRESS_ACC_N))
        rc = gr_fail(err, GR_EINPUT, "checkpoint: %s is malformed", name);
    if (!rc && !(*a = gr_stress_acc_create(W, H, periodic_x, periodic_y, nx, ny, v[2], err)))
        rc = err->code;
    if (!rc)
        memcpy((*a)->sum, v + 3, (n - 3) * sizeof *v);
    free(v);
    return rc;
}
