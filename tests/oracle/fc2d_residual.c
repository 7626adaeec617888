/* The solver-independent half of the oracle (definitions in fc2d.h): no
 * Siconos here, so methods/cd/'s tests can judge their answers with it on
 * any machine. */
#include "fc2d.h"

#include <math.h>
#include <stddef.h>

int gr_fc2d_check(int nc, const double *W, const double *q, const double *mu, gr_err *err)
{
    if (nc < 0)
        return gr_fail(err, GR_EINPUT, "fc2d: %d contacts", nc);
    size_t n = 2 * (size_t)nc;
    for (size_t k = 0; k < n * n; k++)
        if (!isfinite(W[k]))
            return gr_fail(err, GR_EINPUT, "fc2d: W[%zu] is not finite", k);
    for (int i = 0; i < nc; i++) {
        size_t a = 2 * (size_t)i;
        double nn = W[a * n + a], tt = W[(a + 1) * n + a + 1];
        double nt = W[a * n + a + 1], tn = W[(a + 1) * n + a];
        if (!isfinite(q[a]) || !isfinite(q[a + 1]) || !(mu[i] >= 0) || !isfinite(mu[i]))
            return gr_fail(err, GR_EINPUT, "fc2d: contact %d: q or mu not finite, or mu < 0", i);
        if (!(nn > 0) || !(tt > 0))
            return gr_fail(err, GR_EINPUT, "fc2d: contact %d: W_nn = %g, W_tt = %g (need > 0)",
                           i, nn, tt);
        /* fc2d_nsgs_dense takes W_tn from W_nt: an asymmetric block would be
         * solved as another problem. */
        if (fabs(nt - tn) > 1e-12 * sqrt(nn * tt))
            return gr_fail(err, GR_EINPUT, "fc2d: contact %d: W_nt = %g != W_tn = %g", i, nt, tn);
    }
    return GR_OK;
}

/* proj onto {(a, b): |b| <= mu a}, in place. */
static void proj_cone(double mu, double *a, double *b)
{
    double t = fabs(*b);
    if (t <= mu * *a)
        return;
    if (mu * t <= -*a) { /* in the polar cone */
        *a = 0;
        *b = 0;
        return;
    }
    double an = (*a + mu * t) / (1 + mu * mu);
    *a = an;
    *b = copysign(mu * an, *b);
}

/* (W r + q)_row, W row-major. */
static double wrq(size_t n, const double *W, const double *q, const double *r, size_t row)
{
    double s = q[row];
    for (size_t j = 0; j < n; j++)
        s += W[row * n + j] * r[j];
    return s;
}

int gr_fc2d_residual(int nc, const double *W, const double *q, const double *mu,
                     const double *r, const double *u, gr_fc2d_res *res, gr_err *err)
{
    int rc = gr_fc2d_check(nc, W, q, mu, err);
    if (rc)
        return rc;
    size_t n = 2 * (size_t)nc;
    double e2 = 0, q2 = 0, r2 = 0, d2 = 0, worst = -1;
    res->worst = -1;
    for (int i = 0; i < nc; i++) {
        size_t a = 2 * (size_t)i;
        double rho = 1 / W[a * n + a];
        double un = wrq(n, W, q, r, a), ut = wrq(n, W, q, r, a + 1);
        if (u) {
            d2 += rho * rho * ((u[a] - un) * (u[a] - un) + (u[a + 1] - ut) * (u[a + 1] - ut));
            un = u[a];
            ut = u[a + 1];
        }
        double xn = r[a] - rho * (un + mu[i] * fabs(ut)), xt = r[a + 1] - rho * ut;
        proj_cone(mu[i], &xn, &xt);
        double ei = (r[a] - xn) * (r[a] - xn) + (r[a + 1] - xt) * (r[a + 1] - xt);
        if (ei > worst) {
            worst = ei;
            res->worst = i;
        }
        e2 += ei;
        r2 += r[a] * r[a] + r[a + 1] * r[a + 1];
        q2 += rho * rho * (q[a] * q[a] + q[a + 1] * q[a + 1]);
    }
    double s = sqrt(fmax(r2, q2));
    res->scale = s;
    if (s == 0)
        s = 1;
    res->cone = sqrt(e2) / s;
    res->eq = sqrt(d2) / s;
    res->total = fmax(res->cone, res->eq);
    return GR_OK;
}
