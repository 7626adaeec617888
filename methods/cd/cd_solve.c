/* The exact single-contact Signorini-Coulomb solution and the non-linear
 * Gauss-Seidel sweeps over contacts, on body velocities (no Delassus
 * matrix is assembled). Bottom layer: calls no other file of the backend. */
#include <math.h>
#include <stdlib.h>

#include "cd_int.h"

void gr_cd_apply(gr_cd *d, const gr_cd_contact *c, double dn, double dtn)
{
    const double *r = d->p->radius;
    size_t i = (size_t)c->i, j = (size_t)c->j;
    double px = dn * c->nx - dtn * c->ny, py = dn * c->ny + dtn * c->nx;
    d->vx[i] += d->im[i] * px;
    d->vy[i] += d->im[i] * py;
    d->w[i] -= r[i] * dtn * d->iI[i];
    if (j < d->n) {
        d->vx[j] -= d->im[j] * px;
        d->vy[j] -= d->im[j] * py;
        d->w[j] -= r[j] * dtn * d->iI[j];
    }
}

/* One contact, the others' impulses fixed: the local velocity without its
 * own impulse, the predicted gap (positive: no impulse, Jean's rule), then
 * the formal velocities (u+ + e u-)/(1+e) under Signorini and Coulomb.
 * W is diagonal for disks, so the 2x2 problem decouples: open, stick, or
 * slide forward or backward at |r_t| = mu r_n. Adds the squared changes
 * of W r and of W r itself to num and den. */
static void local_solve(gr_cd *d, gr_cd_contact *c, double *num, double *den)
{
    double un, ut, th = d->par.theta;
    gr_cd_rel(d, c, &un, &ut);
    double ufn = un - c->wn * c->rn, uft = ut - c->wt * c->rt;
    double rn = 0, rt = 0;
    int st = GR_CD_OPEN;
    double gp = c->g + d->par.dt * ((1 - th) * c->un0 + th * ufn);
    double bn = ufn + c->en * c->un0;
    if (gp <= 0 && bn < 0) {
        rn = -bn / c->wn;
        rt = -(uft + c->et * c->ut0) / c->wt;
        double lim = d->mu * rn;
        st = GR_CD_STICK;
        if (fabs(rt) > lim) {
            st = rt > 0 ? GR_CD_SLIDE_BWD : GR_CD_SLIDE_FWD;
            rt = rt > 0 ? lim : -lim;
        }
    }
    double dn = rn - c->rn, dtn = rt - c->rt;
    if (dn != 0 || dtn != 0)
        gr_cd_apply(d, c, dn, dtn);
    c->rn = rn, c->rt = rt, c->status = st;
    double a = c->wn * dn, b = c->wt * dtn, e = c->wn * rn, f = c->wt * rt;
    *num += a * a + b * b;
    *den += e * e + f * f;
}

/* The visiting order of one sweep. */
static void make_order(gr_cd *d, size_t n)
{
    size_t *o = d->perm;
    if (d->par.order == GR_CD_RANDOM) {
        for (size_t k = 0; k < n; k++)
            o[k] = (size_t)gr_rng_below(d->order_rng, n);
        return;
    }
    for (size_t k = 0; k < n; k++)
        o[k] = k;
    if (d->par.order == GR_CD_SHUFFLED) {
        for (size_t k = n; k > 1; k--) {
            size_t m = (size_t)gr_rng_below(d->order_rng, k), t = o[k - 1];
            o[k - 1] = o[m], o[m] = t;
        }
    }
}

static int check_local(const gr_cd *d, gr_err *err)
{
    for (size_t k = 0; k < d->cur.n; k++) {
        const gr_cd_contact *c = &d->cur.c[k];
        if (!(c->wn > 0) || !(c->wt > 0) || !isfinite(c->wn) || !isfinite(c->wt))
            return gr_fail(err, GR_ERUN,
                           "contact of grain %lld with %s %lld at t = %.9g: singular local problem (W_nn %g, W_tt %g)",
                           (long long)d->p->id[c->i], (size_t)c->j < d->n ? "grain" : "wall",
                           (long long)((size_t)c->j < d->n ? d->p->id[c->j] : c->j - (int64_t)d->n), d->t,
                           c->wn, c->wt);
    }
    return GR_OK;
}

int gr_cd_solve(gr_cd *d, gr_cd_solve_info *info, gr_err *err)
{
    size_t n = d->cur.n;
    *info = (gr_cd_solve_info){0, 1, 0.0, 0, 0};
    if (!n)
        return GR_OK;
    if (check_local(d, err))
        return err->code;
    if (n > d->perm_cap) {
        size_t *p = realloc(d->perm, n * sizeof *p);
        if (!p)
            return gr_fail(err, GR_ERUN, "out of memory for %zu contacts", n);
        d->perm = p, d->perm_cap = n;
    }
    info->converged = 0;
    for (long s = 1; s <= d->par.max_iter; s++) {
        if (s == 1 || d->par.order != GR_CD_SEQUENTIAL)
            make_order(d, n);
        double num = 0, den = 0;
        for (size_t k = 0; k < n; k++)
            local_solve(d, &d->cur.c[d->perm[k]], &num, &den);
        info->sweeps = s;
        if (s % d->par.check_every && s != d->par.max_iter)
            continue;
        info->residual = den > 0 ? sqrt(num / den) : (num > 0 ? 1.0 : 0.0);
        if (info->residual <= d->par.tol) {
            info->converged = 1;
            break;
        }
    }
    for (size_t k = 0; k < n; k++) {
        const gr_cd_contact *c = &d->cur.c[k];
        info->active += c->rn > 0;
        info->sliding += c->rn > 0 && (c->status == GR_CD_SLIDE_FWD || c->status == GR_CD_SLIDE_BWD);
    }
    return GR_OK;
}
