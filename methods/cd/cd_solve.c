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

/* x moved from old towards target by the relaxation factor; exactly the
 * target at 1, so that plain Gauss-Seidel keeps its bits. */
static double relaxed(double old, double target, double w)
{
    return w == 1.0 ? target : old + w * (target - old);
}

/* One contact, the others' impulses fixed: the local velocity without its
 * own impulse, the predicted gap (positive: no impulse, Jean's rule), then
 * the formal velocities (u+ + e u-)/(1+e) under Signorini and Coulomb.
 * W is diagonal for disks, so the 2x2 problem decouples: open, stick, or
 * slide forward or backward at |r_t| = mu r_n. Over-relaxation moves the
 * unprojected impulses past the local solution and projects them back on
 * the cone (projected SOR); at relax = 1 it is the exact local solution.
 * Adds the squared changes of W r and of W r itself to num and den. */
/* Flips of Jean's rule after which a contact stays open for the rest of
 * the step. The rule is discontinuous in the others' impulses: a contact
 * at the edge of closing can make its neighbours reopen it, and they close
 * it again, a cycle Gauss-Seidel never leaves (measured on the flowing
 * silo: a 2-cycle of one contact held a step to max_iter). Open adds no
 * impulse: kept closed instead, such contacts held grains apart at a
 * distance, and the Janssen column (test_cd_janssen) hung on its walls. */
#define GR_CD_MAX_FLIPS 8

/* Sweeps without a new smallest change after which over-relaxation is
 * dropped for the rest of the step: projected SOR is not guaranteed to
 * converge with friction, and on the flowing silo at relax 1.6 some steps
 * cycled to max_iter where plain Gauss-Seidel converges. */
#define GR_CD_STALL 50

static void local_solve(gr_cd *d, gr_cd_contact *c, double w, double *num, double *den)
{
    double un, ut, th = d->par.theta;
    gr_cd_rel(d, c, &un, &ut);
    double ufn = un - c->wn * c->rn, uft = ut - c->wt * c->rt;
    double rn = 0, rt = 0;
    int st = GR_CD_OPEN;
    double gp = c->g + d->par.dt * ((1 - th) * c->un0 + th * ufn);
    double bn = ufn + c->en * c->un0;
    int closed = c->flips >= GR_CD_MAX_FLIPS ? 0 : gp <= 0;
    if (closed != c->closed && c->closed >= 0)
        c->flips++;
    c->closed = closed;
    if (closed && (bn < 0 || w < 1.0)) {
        rn = fmax(0.0, relaxed(c->rn, -bn / c->wn, w));
        rt = relaxed(c->rt, -(uft + c->et * c->ut0) / c->wt, w);
        double lim = d->mu * rn;
        st = rn > 0 ? GR_CD_STICK : GR_CD_OPEN;
        if (fabs(rt) > lim) {
            st = rn > 0 ? (rt > 0 ? GR_CD_SLIDE_BWD : GR_CD_SLIDE_FWD) : GR_CD_OPEN;
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
static void make_order(gr_cd *d, size_t n, int back)
{
    size_t *o = d->perm;
    if (d->par.order == GR_CD_RANDOM) {
        for (size_t k = 0; k < n; k++)
            o[k] = (size_t)gr_rng_below(d->order_rng, n);
        return;
    }
    for (size_t k = 0; k < n; k++)
        o[k] = k;
    if (d->par.order == GR_CD_SYMMETRIC && back) {
        for (size_t k = 0; k < n; k++)
            o[k] = n - 1 - k;
    }
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
    for (size_t k = 0; k < n; k++)
        d->cur.c[k].closed = -1, d->cur.c[k].flips = 0;
    info->converged = 0;
    double w = d->par.relax, best = INFINITY;
    long s_best = 0;
    for (long s = 1; s <= d->par.max_iter; s++) {
        if (s == 1 || d->par.order != GR_CD_SEQUENTIAL)
            make_order(d, n, s % 2 == 0);
        double num = 0, den = 0;
        for (size_t k = 0; k < n; k++)
            local_solve(d, &d->cur.c[d->perm[k]], w, &num, &den);
        info->sweeps = s;
        double eps = den > 0 ? sqrt(num / den) : (num > 0 ? 1.0 : 0.0);
        if (eps < best)
            best = eps, s_best = s;
        else if (w != 1.0 && s - s_best >= GR_CD_STALL)
            w = 1.0;
        if (s % d->par.check_every && s != d->par.max_iter)
            continue;
        info->residual = eps;
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
