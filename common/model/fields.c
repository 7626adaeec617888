/* Coarse-grained fields, window displacements and mean square displacement. */
#include "fields.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom.h"

/* ------------------------------------------------ disk-rectangle overlap */

/* Antiderivative of sqrt(r^2 - t^2) on [-r, r]. */
static double chord_prim(double t, double r)
{
    double u = fmax(-1.0, fmin(1.0, t / r));
    return 0.5 * r * r * (u * sqrt(fmax(0.0, 1.0 - u * u)) + asin(u));
}

/* Area of the disk (radius r, centre 0) with X > a. */
static double half_area(double a, double r)
{
    if (a >= r)
        return 0.0;
    if (a <= -r)
        return M_PI * r * r;
    return 0.5 * M_PI * r * r - 2.0 * chord_prim(a, r);
}

/* Area of the disk with X > a and Y > b; negative bounds reduce to the
 * quadrant case by reflection. */
static double corner_area(double a, double b, double r)
{
    if (b < 0.0)
        return half_area(a, r) - corner_area(a, -b, r);
    if (a < 0.0)
        return half_area(b, r) - corner_area(-a, b, r);
    if (a * a + b * b >= r * r)
        return 0.0;
    double c = sqrt(r * r - b * b);
    return chord_prim(c, r) - chord_prim(a, r) - b * (c - a);
}

double gr_disk_rect_area(double xc, double yc, double r, double x1, double x2, double y1,
                         double y2)
{
    if (!(x2 > x1) || !(y2 > y1) || !(r > 0.0))
        return 0.0;
    x1 -= xc;
    x2 -= xc;
    y1 -= yc;
    y2 -= yc;
    if (x1 >= r || x2 <= -r || y1 >= r || y2 <= -r)
        return 0.0;
    double a = corner_area(x1, y1, r) - corner_area(x2, y1, r) - corner_area(x1, y2, r) +
               corner_area(x2, y2, r);
    return fmax(0.0, a);
}

/* ------------------------------------------------------------------ fields */

gr_field *gr_field_create(int nx, int ny, double x0, double y0, double cx, double cy,
                          gr_err *err)
{
    if (nx < 1 || ny < 1 || !(cx > 0.0) || !(cy > 0.0) || !isfinite(cx) || !isfinite(cy) ||
        !isfinite(x0) || !isfinite(y0)) {
        gr_fail(err, GR_EINPUT,
                "field grid: need nx, ny >= 1 and finite cell sizes > 0 (got %d x %d, %g x %g)",
                nx, ny, cx, cy);
        return NULL;
    }
    gr_field *f = calloc(1, sizeof *f);
    size_t nc = (size_t)nx * (size_t)ny;
    double *buf = f ? calloc(6 * nc, sizeof *buf) : NULL;
    if (!buf) {
        free(f);
        gr_fail(err, GR_ERUN, "field grid: out of memory (%d x %d cells)", nx, ny);
        return NULL;
    }
    *f = (gr_field){.nx = nx, .ny = ny, .x0 = x0, .y0 = y0, .cx = cx, .cy = cy,
                    .area = buf, .num = buf + nc, .mass = buf + 2 * nc, .px = buf + 3 * nc,
                    .py = buf + 4 * nc, .mv2 = buf + 5 * nc};
    return f;
}

void gr_field_free(gr_field *f)
{
    if (!f)
        return;
    free(f->area); /* one block holds every array */
    free(f);
}

void gr_field_clear(gr_field *f)
{
    memset(f->area, 0, 6 * gr_field_ncells(f) * sizeof(double));
    f->wsum = 0.0;
}

long gr_field_cell(const gr_field *f, double x, double y)
{
    double u = floor((x - f->x0) / f->cx), v = floor((y - f->y0) / f->cy);
    if (!(u >= 0.0 && u < f->nx && v >= 0.0 && v < f->ny))
        return -1;
    return (long)v * f->nx + (long)u;
}

void gr_field_cell_centre(const gr_field *f, long c, double *x, double *y)
{
    *x = f->x0 + ((double)(c % f->nx) + 0.5) * f->cx;
    *y = f->y0 + ((double)(c / f->nx) + 0.5) * f->cy;
}

/* Clamped range of cell indices touched by [lo, hi] along one axis. */
static int cell_span(double lo, double hi, double o, double h, int n, int *a, int *b)
{
    double u = floor((lo - o) / h), v = floor((hi - o) / h);
    if (v < 0.0 || u >= n)
        return 0;
    *a = u < 0.0 ? 0 : (int)u;
    *b = v >= n ? n - 1 : (int)v;
    return 1;
}

int gr_field_add(gr_field *f, const gr_particles *p, uint32_t skip_flags, double w,
                 gr_err *err)
{
    if (!(w > 0.0) || !isfinite(w))
        return gr_fail(err, GR_EINPUT, "field accumulate: weight %g must be finite and > 0", w);
    /* check first so that a bad snapshot leaves the sums untouched */
    for (size_t i = 0; i < p->n; i++)
        if (!(p->flags[i] & skip_flags) &&
            (!isfinite(p->x[i]) || !isfinite(p->y[i]) || !isfinite(p->vx[i]) ||
             !isfinite(p->vy[i]) || !(p->radius[i] >= 0.0) || !isfinite(p->mass[i])))
            return gr_fail(err, GR_ERUN, "field accumulate: grain %zu (id %lld) is not finite",
                           i, (long long)p->id[i]);
    for (size_t i = 0; i < p->n; i++) {
        if (p->flags[i] & skip_flags)
            continue;
        double x = p->x[i], y = p->y[i], r = p->radius[i];
        long c = gr_field_cell(f, x, y);
        if (c >= 0) {
            double m = p->mass[i], vx = p->vx[i], vy = p->vy[i];
            f->num[c] += w;
            f->mass[c] += w * m;
            f->px[c] += w * m * vx;
            f->py[c] += w * m * vy;
            f->mv2[c] += w * m * (vx * vx + vy * vy);
        }
        if (f->packing_mode == GR_FIELD_CENTRES) {
            if (c >= 0)
                f->area[c] += w * M_PI * r * r;
            continue;
        }
        int ia, ib, ja, jb;
        if (!cell_span(x - r, x + r, f->x0, f->cx, f->nx, &ia, &ib) ||
            !cell_span(y - r, y + r, f->y0, f->cy, f->ny, &ja, &jb))
            continue;
        double cx1 = f->x0 + ia * f->cx, cy1 = f->y0 + ja * f->cy;
        if (ia == ib && ja == jb && x - r >= cx1 && x + r <= cx1 + f->cx && y - r >= cy1 &&
            y + r <= cy1 + f->cy) {
            f->area[(size_t)ja * f->nx + ia] += w * M_PI * r * r; /* inside one cell */
            continue;
        }
        for (int jy = ja; jy <= jb; jy++) {
            double y1 = f->y0 + jy * f->cy, y2 = y1 + f->cy;
            for (int ix = ia; ix <= ib; ix++) {
                double x1 = f->x0 + ix * f->cx;
                f->area[(size_t)jy * f->nx + ix] +=
                    w * gr_disk_rect_area(x, y, r, x1, x1 + f->cx, y1, y2);
            }
        }
    }
    f->wsum += w;
    return GR_OK;
}

int gr_field_merge(gr_field *dst, const gr_field *src, gr_err *err)
{
    if (dst->nx != src->nx || dst->ny != src->ny || dst->x0 != src->x0 ||
        dst->y0 != src->y0 || dst->cx != src->cx || dst->cy != src->cy)
        return gr_fail(err, GR_EINPUT, "field merge: different grids");
    size_t n = 6 * gr_field_ncells(dst);
    for (size_t i = 0; i < n; i++)
        dst->area[i] += src->area[i];
    dst->wsum += src->wsum;
    return GR_OK;
}

void gr_field_packing(const gr_field *f, double *phi)
{
    double s = f->wsum > 0 ? 1.0 / (f->wsum * f->cx * f->cy) : NAN;
    for (size_t c = 0; c < gr_field_ncells(f); c++)
        phi[c] = f->area[c] * s;
}

void gr_field_number(const gr_field *f, double *per_cell, double *per_area)
{
    double s = f->wsum > 0 ? 1.0 / f->wsum : NAN;
    for (size_t c = 0; c < gr_field_ncells(f); c++) {
        if (per_cell)
            per_cell[c] = f->num[c] * s;
        if (per_area)
            per_area[c] = f->num[c] * s / (f->cx * f->cy);
    }
}

void gr_field_velocity(const gr_field *f, double *vx, double *vy)
{
    for (size_t c = 0; c < gr_field_ncells(f); c++) {
        double m = f->mass[c];
        if (vx)
            vx[c] = m > 0 ? f->px[c] / m : NAN;
        if (vy)
            vy[c] = m > 0 ? f->py[c] / m : NAN;
    }
}

void gr_field_velocity_xy(const gr_field *f, double *v)
{
    for (size_t c = 0; c < gr_field_ncells(f); c++) {
        double m = f->mass[c];
        v[2 * c] = m > 0 ? f->px[c] / m : NAN;
        v[2 * c + 1] = m > 0 ? f->py[c] / m : NAN;
    }
}

void gr_field_temperature(const gr_field *f, double *T)
{
    for (size_t c = 0; c < gr_field_ncells(f); c++) {
        double m = f->mass[c];
        if (!(m > 0)) {
            T[c] = NAN;
            continue;
        }
        /* sum m |v - V|^2 = sum m v^2 - |P|^2 / M; rounding can make a cold
         * cell slightly negative */
        double fluct = f->mv2[c] - (f->px[c] * f->px[c] + f->py[c] * f->py[c]) / m;
        T[c] = fmax(0.0, fluct) / (2.0 * f->num[c]);
    }
}

/* ----------------------------------------------------------- displacements */

int gr_disp_window(const double *xa, const double *ya, const double *xb, const double *yb,
                   const uint32_t *flags, size_t n, const gr_disp_opts *o, double *dx,
                   double *dy, size_t *m, gr_err *err)
{
    if (!(o->x1 > o->x0) || !(o->y1 > o->y0))
        return gr_fail(err, GR_EINPUT, "displacement window [%g,%g) x [%g,%g) is empty", o->x0,
                       o->x1, o->y0, o->y1);
    if (o->subtract_y < 0)
        return gr_fail(err, GR_EINPUT, "displacements: subtract_y = %d must be >= 0",
                       o->subtract_y);
    int ncol = o->subtract_y > 1 ? o->subtract_y : 1;
    double *cs = o->subtract_y > 0 ? calloc(2 * (size_t)ncol, sizeof *cs) : NULL;
    int *col = o->subtract_y > 1 ? malloc((n ? n : 1) * sizeof *col) : NULL;
    if ((o->subtract_y > 0 && !cs) || (o->subtract_y > 1 && !col)) {
        free(cs);
        free(col);
        return gr_fail(err, GR_ERUN, "displacements: out of memory");
    }
    double *cn = cs ? cs + ncol : NULL;
    double jump2 = o->max_jump > 0 ? o->max_jump * o->max_jump : INFINITY, sx = 0.0;
    size_t k = 0;
    for (size_t i = 0; i < n; i++) {
        if ((flags && (flags[i] & o->skip_flags)) || !(xa[i] >= o->x0 && xa[i] < o->x1) ||
            !(ya[i] >= o->y0 && ya[i] < o->y1))
            continue;
        double ddx = gr_min_image(xb[i] - xa[i], o->period_x);
        double ddy = gr_min_image(yb[i] - ya[i], o->period_y);
        if (!isfinite(ddx) || !isfinite(ddy)) {
            free(cs);
            free(col);
            return gr_fail(err, GR_ERUN, "displacements: grain %zu has a non-finite position", i);
        }
        if (ddx * ddx + ddy * ddy > jump2)
            continue;
        int j = 0;
        if (ncol > 1) {
            j = (int)((xa[i] - o->x0) / (o->x1 - o->x0) * ncol);
            j = j < 0 ? 0 : (j >= ncol ? ncol - 1 : j);
            col[k] = j;
        }
        if (cs) {
            cs[j] += ddy;
            cn[j] += 1.0;
        }
        sx += ddx;
        dx[k] = ddx;
        dy[k++] = ddy;
    }
    if (o->subtract_x && k > 0) {
        double mx = sx / (double)k;
        for (size_t i = 0; i < k; i++)
            dx[i] -= mx;
    }
    if (cs) {
        for (int j = 0; j < ncol; j++)
            cs[j] = cn[j] > 0 ? cs[j] / cn[j] : 0.0;
        for (size_t i = 0; i < k; i++)
            dy[i] -= cs[ncol > 1 ? col[i] : 0];
    }
    free(cs);
    free(col);
    *m = k;
    return GR_OK;
}

int gr_disp_particles(const gr_particles *a, const gr_particles *b, const gr_disp_opts *o,
                      double *dx, double *dy, size_t *m, gr_err *err)
{
    size_t n = a->n;
    int same = a->n == b->n;
    for (size_t i = 0; same && i < n; i++)
        same = a->id[i] == b->id[i];
    if (same) {
        /* the usual case: no reordering between the snapshots */
        uint32_t *fl = malloc((n ? n : 1) * sizeof *fl);
        if (!fl)
            return gr_fail(err, GR_ERUN, "displacements: out of memory");
        for (size_t i = 0; i < n; i++)
            fl[i] = a->flags[i] | b->flags[i];
        int rc = gr_disp_window(a->x, a->y, b->x, b->y, fl, n, o, dx, dy, m, err);
        free(fl);
        return rc;
    }
    gr_id_index *ix = malloc((b->n ? b->n : 1) * sizeof *ix);
    double *buf = malloc((n ? 4 * n : 1) * sizeof *buf);
    uint32_t *fl = malloc((n ? n : 1) * sizeof *fl);
    int rc = GR_OK;
    if (!ix || !buf || !fl) {
        rc = gr_fail(err, GR_ERUN, "displacements: out of memory");
        goto done;
    }
    gr_id_index_sort(b->id, b->n, ix);
    /* Compact the grains present in both snapshots. */
    double *xa = buf, *ya = buf + n, *xb = buf + 2 * n, *yb = buf + 3 * n;
    size_t k = 0;
    for (size_t i = 0; i < n; i++) {
        const gr_id_index *hit = gr_id_index_find(ix, b->n, a->id[i]);
        if (!hit)
            continue;
        xa[k] = a->x[i];
        ya[k] = a->y[i];
        xb[k] = b->x[hit->i];
        yb[k] = b->y[hit->i];
        fl[k++] = a->flags[i] | b->flags[hit->i];
    }
    rc = gr_disp_window(xa, ya, xb, yb, fl, k, o, dx, dy, m, err);
done:
    free(ix);
    free(buf);
    free(fl);
    return rc;
}

/* --------------------------------------------- mean square displacement */

gr_msd *gr_msd_create(size_t nlag, gr_err *err)
{
    if (nlag == 0) {
        gr_fail(err, GR_EINPUT, "MSD: need at least one lag slot");
        return NULL;
    }
    gr_msd *s = calloc(1, sizeof *s);
    double *buf = s ? calloc(6 * nlag, sizeof *buf) : NULL;
    if (!buf) {
        free(s);
        gr_fail(err, GR_ERUN, "MSD: out of memory (%zu lags)", nlag);
        return NULL;
    }
    *s = (gr_msd){.nlag = nlag, .lag = buf, .n = buf + nlag, .sx2 = buf + 2 * nlag,
                  .sx4 = buf + 3 * nlag, .sy2 = buf + 4 * nlag, .sy4 = buf + 5 * nlag};
    for (size_t k = 0; k < nlag; k++)
        s->lag[k] = NAN;
    return s;
}

void gr_msd_free(gr_msd *s)
{
    if (!s)
        return;
    free(s->lag);
    free(s);
}

static int lag_check(gr_msd *s, size_t k, double lag, gr_err *err)
{
    if (k >= s->nlag)
        return gr_fail(err, GR_EINPUT, "MSD: slot %zu out of %zu", k, s->nlag);
    if (!isfinite(lag))
        return gr_fail(err, GR_EINPUT, "MSD: lag %g is not finite", lag);
    if (isnan(s->lag[k]))
        s->lag[k] = lag;
    else if (fabs(s->lag[k] - lag) > 1e-9 * fmax(fabs(lag), fabs(s->lag[k])))
        return gr_fail(err, GR_EINPUT, "MSD: slot %zu holds lag %.17g, not %.17g", k, s->lag[k],
                       lag);
    return GR_OK;
}

int gr_msd_add(gr_msd *s, size_t k, double lag, const double *dx, const double *dy, size_t n,
               gr_err *err)
{
    int rc = lag_check(s, k, lag, err);
    if (rc)
        return rc;
    for (size_t i = 0; i < n; i++) {
        double x2 = dx[i] * dx[i], y2 = dy[i] * dy[i];
        s->sx2[k] += x2;
        s->sx4[k] += x2 * x2;
        s->sy2[k] += y2;
        s->sy4[k] += y2 * y2;
    }
    s->n[k] += (double)n;
    return GR_OK;
}

int gr_msd_merge(gr_msd *dst, const gr_msd *src, gr_err *err)
{
    if (dst->nlag != src->nlag)
        return gr_fail(err, GR_EINPUT, "MSD merge: %zu lag slots against %zu", dst->nlag,
                       src->nlag);
    for (size_t k = 0; k < src->nlag; k++) {
        if (isnan(src->lag[k]))
            continue;
        int rc = lag_check(dst, k, src->lag[k], err);
        if (rc)
            return rc;
    }
    for (size_t i = src->nlag; i < 6 * src->nlag; i++)
        dst->lag[i] += src->lag[i]; /* the sums follow lag[] in one block */
    return GR_OK;
}

void gr_msd_result(const gr_msd *s, double *msd_x, double *msd_y, double *err_x,
                   double *err_y, double *kappa_x, double *kappa_y)
{
    for (size_t k = 0; k < s->nlag; k++) {
        double n = s->n[k], inv = n > 0 ? 1.0 / n : NAN;
        double x2 = s->sx2[k] * inv, x4 = s->sx4[k] * inv;
        double y2 = s->sy2[k] * inv, y4 = s->sy4[k] * inv;
        if (msd_x)
            msd_x[k] = x2;
        if (msd_y)
            msd_y[k] = y2;
        if (err_x)
            err_x[k] = sqrt(fmax(0.0, x4 - x2 * x2) * inv);
        if (err_y)
            err_y[k] = sqrt(fmax(0.0, y4 - y2 * y2) * inv);
        if (kappa_x)
            kappa_x[k] = x4 / (3.0 * x2 * x2) - 1.0;
        if (kappa_y)
            kappa_y[k] = y4 / (3.0 * y2 * y2) - 1.0;
    }
}
