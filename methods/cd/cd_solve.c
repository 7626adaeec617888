/* The exact single-contact Signorini-Coulomb solution and the non-linear
 * Gauss-Seidel sweeps over contacts, on body velocities (no Delassus
 * matrix is assembled), with their momentum. Calls cd_order.c. */
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
 * cycled to max_iter where plain Gauss-Seidel converges. Not momentum:
 * its restarts make eps go up and down, and dropping it after 50 such
 * sweeps took the silo at n = 500 from 121.9 to 173.7 sweeps per step. */
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
    c->flipped = closed != c->closed && c->closed >= 0;
    c->flips += c->flipped;
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

/* Nesterov's momentum on the impulses (accel = momentum): after a sweep
 * from y to r, the next starts from r + beta (r - r_last), projected on
 * the cone. Gauss-Seidel carries a load about one contact row per sweep,
 * so its error on a tall packing decays like a diffusion's; momentum
 * turns that into a wave. The sweep keeps its meaning: eps is still the
 * change one plain sweep makes, from wherever it starts.
 * d->racc holds per contact r_last (n, t) and y (n, t). */

/* The sweep's correction r - y against the momentum r - r_last, weighted
 * by W: negative when the momentum points against what the sweep wants
 * (O'Donoghue and Candes' gradient restart). */
static double momentum_dot(const gr_cd *d, size_t n)
{
    const double *a = d->racc;
    double g = 0;
    for (size_t k = 0; k < n; k++) {
        const gr_cd_contact *c = &d->cur.c[k];
        g += c->wn * c->wn * (c->rn - a[4 * k + 2]) * (c->rn - a[4 * k]) +
             c->wt * c->wt * (c->rt - a[4 * k + 3]) * (c->rt - a[4 * k + 1]);
    }
    return g;
}

/* Keep this sweep's impulses and move them on by beta times their change
 * over the sweep. A contact that was not pushing before the sweep, or
 * whose Jean decision the sweep changed, is left at its local solution:
 * pushed past it, it flips its neighbours' decisions, and a contact that
 * flips 8 times is left open for the step, a wrong answer (on the
 * flowing silo, more steps had one with momentum on every contact). */
static void extrapolate(gr_cd *d, size_t n, double beta)
{
    double *a = d->racc;
    for (size_t k = 0; k < n; k++) {
        gr_cd_contact *c = &d->cur.c[k];
        double rn0 = a[4 * k], rt0 = a[4 * k + 1];
        a[4 * k] = c->rn, a[4 * k + 1] = c->rt;
        if (beta > 0 && rn0 > 0 && !c->flipped) {
            double yn = fmax(0.0, c->rn + beta * (c->rn - rn0)), yt = c->rt + beta * (c->rt - rt0);
            double lim = d->mu * yn;
            yt = fmin(lim, fmax(-lim, yt));
            gr_cd_apply(d, c, yn - c->rn, yt - c->rt);
            c->rn = yn, c->rt = yt;
        }
        a[4 * k + 2] = c->rn, a[4 * k + 3] = c->rt;
    }
}

/* Nesterov's sequence t, restarted (t = 1, no momentum this sweep) when
 * eps grows or the momentum opposes the sweep's correction. */
typedef struct {
    double t, eps;
} momentum;

static void momentum_step(gr_cd *d, size_t n, momentum *m, double eps)
{
    int restart = eps > m->eps || momentum_dot(d, n) < 0;
    double t = restart ? 1.0 : m->t, t1 = 0.5 * (1 + sqrt(1 + 4 * t * t));
    extrapolate(d, n, restart ? 0.0 : (t - 1) / t1);
    m->t = t1, m->eps = eps;
}

static int grow(gr_cd *d, size_t n, gr_err *err)
{
    size_t *p = realloc(d->perm, n * sizeof *p);
    if (p)
        d->perm = p;
    gr_cd_key *y = p ? realloc(d->key, n * sizeof *y) : NULL;
    if (y)
        d->key = y;
    double *a = y ? realloc(d->racc, 4 * n * sizeof *a) : NULL;
    if (!a)
        return gr_fail(err, GR_ERUN, "out of memory for %zu contacts", n);
    d->racc = a, d->perm_cap = n;
    return GR_OK;
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
    *info = (gr_cd_solve_info){0, 1, 0.0, 0, 0, 0};
    if (!n)
        return GR_OK;
    if (check_local(d, err))
        return err->code;
    if (n > d->perm_cap && grow(d, n, err))
        return err->code;
    for (size_t k = 0; k < n; k++) {
        gr_cd_contact *c = &d->cur.c[k];
        c->closed = -1, c->flips = 0;
        d->racc[4 * k] = d->racc[4 * k + 2] = c->rn;
        d->racc[4 * k + 1] = d->racc[4 * k + 3] = c->rt;
    }
    info->converged = 0;
    double w = d->par.relax, best = INFINITY;
    long s_best = 0;
    int accel = d->par.accel;
    momentum m = {1.0, INFINITY};
    for (long s = 1; s <= d->par.max_iter; s++) {
        if (s == 1 || d->par.order != GR_CD_SEQUENTIAL)
            gr_cd_visit_order(d, n, s);
        double num = 0, den = 0;
        for (size_t k = 0; k < n; k++)
            local_solve(d, &d->cur.c[d->perm[k]], w, &num, &den);
        info->sweeps = s;
        double eps = den > 0 ? sqrt(num / den) : (num > 0 ? 1.0 : 0.0);
        if (eps < best)
            best = eps, s_best = s;
        else if (w != 1.0 && s - s_best >= GR_CD_STALL)
            w = 1.0;
        if (accel && eps > d->par.tol && s < d->par.max_iter)
            momentum_step(d, n, &m, eps);
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
        info->forced_open += c->flips >= GR_CD_MAX_FLIPS;
    }
    return GR_OK;
}
