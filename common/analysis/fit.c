/* Least-squares fits: gsl_multifit_nlinear for non-linear models,
 * gsl_fit_(w)linear for straight lines in log-log. The ready models and
 * their starting values are in fit_models.c. */
#include "stats.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_blas.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_fit.h>
#include <gsl/gsl_multifit_nlinear.h>

typedef struct {
    const gr_model *m;
    const double *x, *y;
} fit_data;

static int residual_cb(const gsl_vector *p, void *params, gsl_vector *f)
{
    const fit_data *d = params;
    for (size_t i = 0; i < f->size; i++) {
        double v = d->m->f(d->x[i], p->data, NULL, d->m->user);
        /* A trial step outside the model's domain gets a huge but finite
         * residual, so the trust region rejects it and shrinks instead of
         * aborting (the start is checked to be inside the domain). */
        gsl_vector_set(f, i, isfinite(v) ? v - d->y[i] : 1e100);
    }
    return GSL_SUCCESS;
}

static int jacobian_cb(const gsl_vector *p, void *params, gsl_matrix *J)
{
    const fit_data *d = params;
    double g[GR_FIT_MAXP];
    for (size_t i = 0; i < J->size1; i++) {
        d->m->f(d->x[i], p->data, g, d->m->user);
        for (size_t j = 0; j < J->size2; j++) {
            if (!isfinite(g[j]))
                return GSL_EDOM;
            gsl_matrix_set(J, i, j, g[j]);
        }
    }
    return GSL_SUCCESS;
}

static const char *pname(const gr_model *m, size_t j, char buf[24])
{
    if (m->pnames[j])
        return m->pnames[j];
    snprintf(buf, 24, "p%zu", j);
    return buf;
}

int gr_fit_check_data(const char *what, size_t np, const double *x, const double *y,
                      const double *sigma, size_t n, gr_err *err)
{
    if (np == 0 || np > GR_FIT_MAXP)
        return gr_fail(err, GR_EINPUT, "%s: %zu parameters (1 to %d supported)", what, np,
                       GR_FIT_MAXP);
    if (n <= np)
        return gr_fail(err, GR_EINPUT, "%s: %zu points for %zu parameters (need more points)",
                       what, n, np);
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(x[i]) || !isfinite(y[i]))
            return gr_fail(err, GR_EINPUT, "%s: point %zu is not finite (%g, %g)", what, i,
                           x[i], y[i]);
        if (sigma && !(sigma[i] > 0.0 && isfinite(sigma[i])))
            return gr_fail(err, GR_EINPUT, "%s: sigma[%zu] = %g must be finite and > 0", what,
                           i, sigma[i]);
    }
    return GR_OK;
}

static int check_start(const gr_model *m, const char *name, const double *x, size_t n,
                       const double *p0, gr_err *err)
{
    for (size_t j = 0; j < m->np; j++)
        if (!isfinite(p0[j]))
            return gr_fail(err, GR_EINPUT, "%s fit: start value %zu is not finite", name, j);
    for (size_t i = 0; i < n; i++) {
        double v = m->f(x[i], p0, NULL, m->user);
        if (!isfinite(v))
            return gr_fail(err, GR_EINPUT, "%s fit: model undefined at the start values (x = %g)",
                           name, x[i]);
    }
    return GR_OK;
}

static gr_fit_opts opts_or_defaults(const gr_fit_opts *opt)
{
    gr_fit_opts o = opt ? *opt : (gr_fit_opts){0};
    if (o.max_iter == 0)
        o.max_iter = 500;
    if (o.xtol <= 0)
        o.xtol = 1e-10;
    if (o.gtol <= 0)
        o.gtol = 1e-10;
    if (o.ftol <= 0)
        o.ftol = 1e-12;
    return o;
}

/* What the restarts of the GSL driver end with. */
typedef struct {
    int st, info;
    size_t iter, nfev;
} fit_run;

/* GSL's gradient test at the driver's current position q. */
static int gradient_small(gsl_multifit_nlinear_workspace *w, const double *q, size_t np,
                          double gtol)
{
    double gmax = 0.0, phi = 0.0;
    gsl_blas_ddot(w->f, w->f, &phi);
    for (size_t j = 0; j < np; j++)
        gmax = fmax(gmax, fabs(gsl_vector_get(w->g, j)) * fmax(fabs(q[j]), 1.0));
    return gmax <= gtol * fmax(0.5 * phi, 1.0);
}

/* GSL's step-size test also fires when rejected steps (outside the
 * domain, or a poor model of the cost) have shrunk the trust region to
 * nothing: restart from where it stopped, with a fresh region, until a
 * restart no longer moves. cur holds the start and receives the end. */
static int restart_until_still(gsl_multifit_nlinear_workspace *w, gsl_multifit_nlinear_fdf *fdf,
                               const gsl_vector *wts, const gr_fit_opts *o, double *cur,
                               const char *name, fit_run *r, gr_err *err)
{
    size_t np = fdf->p;
    int prev_info = 0;
    for (int round = 0; round < 20; round++) {
        gsl_vector_view start = gsl_vector_view_array(cur, np);
        r->st = wts ? gsl_multifit_nlinear_winit(&start.vector, wts, fdf, w)
                    : gsl_multifit_nlinear_init(&start.vector, fdf, w);
        if (r->st)
            return gr_fail(err, GR_ERUN, "%s fit: model evaluation failed (%s)", name,
                           gsl_strerror(r->st));
        r->st = gsl_multifit_nlinear_driver(o->max_iter, o->xtol, o->gtol, o->ftol, NULL, NULL,
                                            &r->info, w);
        r->iter += gsl_multifit_nlinear_niter(w);
        r->nfev += fdf->nevalf;
        /* GSL stops with "no progress" (GSL_EMAXITER after one iteration,
         * info GSL_ENOPROG) when it finds no step that lowers the cost from
         * the start. On a restart that confirms the previous optimum; on
         * the first round (e.g. noise-free data from the exact start) accept
         * it only where GSL's gradient test holds (its step test would look
         * at a rejected step). */
        const double *q = gsl_multifit_nlinear_position(w)->data;
        int noprog = r->st == GSL_EMAXITER && r->info == GSL_ENOPROG;
        if (noprog && round > 0) {
            r->st = GSL_SUCCESS;
            r->info = prev_info;
        } else if (r->st != GSL_SUCCESS && gradient_small(w, q, np, o->gtol)) {
            r->st = GSL_SUCCESS;
            r->info = 2;
        }
        int moved = 0;
        for (size_t j = 0; j < np; j++)
            moved |= fabs(q[j] - cur[j]) > 1e-7 * fmax(fabs(cur[j]), 1e-7);
        memcpy(cur, q, np * sizeof *cur);
        if (r->st != GSL_SUCCESS || !moved || r->iter >= o->max_iter)
            break;
        prev_info = r->info;
    }
    return GR_OK;
}

static int store_covariance(const gr_model *m, const char *name,
                            gsl_multifit_nlinear_workspace *w, gsl_matrix *cov,
                            const gr_fit_opts *o, int weighted, gr_fit *out, gr_err *err)
{
    size_t np = m->np;
    gsl_multifit_nlinear_covar(gsl_multifit_nlinear_jac(w), 0.0, cov);
    out->scaled = o->scale == GR_FIT_SCALE_ALWAYS || (o->scale == GR_FIT_SCALE_AUTO && !weighted);
    double s2 = out->scaled ? out->chi2_dof : 1.0;
    for (size_t i = 0; i < np; i++)
        for (size_t j = 0; j < np; j++)
            out->cov[i][j] = s2 * gsl_matrix_get(cov, i, j);
    for (size_t j = 0; j < np; j++) {
        /* GSL zeroes the rows of parameters the Jacobian does not fix, so
         * an unscaled variance that is not positive means undetermined. */
        double v = gsl_matrix_get(cov, j, j);
        out->err[j] = sqrt(out->cov[j][j]);
        if (!(v > 0.0) || !isfinite(v) || !isfinite(out->p[j])) {
            char buf[24];
            return gr_fail(err, GR_ERUN,
                           "%s fit: parameter %s is not determined by the data (variance %g)",
                           name, pname(m, j, buf), v);
        }
    }
    return GR_OK;
}

/* Runs the driver from out->p on workspaces already allocated and fills
 * out with the optimum, its cost and covariance. */
static int solve(const gr_model *m, const char *name, gsl_multifit_nlinear_fdf *fdf,
                 gsl_multifit_nlinear_workspace *w, const gsl_vector *wts, gsl_matrix *cov,
                 const gr_fit_opts *o, gr_fit *out, gr_err *err)
{
    size_t np = m->np;
    double cur[GR_FIT_MAXP];
    memcpy(cur, out->p, np * sizeof *cur);
    fit_run r = {0};
    int rc = restart_until_still(w, fdf, wts, o, cur, name, &r, err);
    if (rc)
        return rc;
    memcpy(out->p, cur, np * sizeof(double));
    out->iter = r.iter;
    out->nfev = r.nfev;
    out->info = r.info;
    gsl_vector *f = gsl_multifit_nlinear_residual(w);
    gsl_blas_ddot(f, f, &out->chi2);
    out->chi2_dof = out->chi2 / out->dof;
    if (r.st != GSL_SUCCESS) {
        const char *why = r.st == GSL_EMAXITER && r.info == GSL_ENOPROG
                              ? "no step lowers the cost from the start"
                              : gsl_strerror(r.st);
        return gr_fail(err, GR_ERUN, "%s fit did not converge after %zu iterations: %s (chi2 = %g)",
                       name, out->iter, why, out->chi2);
    }
    return store_covariance(m, name, w, cov, o, wts != NULL, out, err);
}

int gr_fit_nlin(const gr_model *m, const double *x, const double *y, const double *sigma,
                size_t n, const double *p0, const gr_fit_opts *opt, gr_fit *out, gr_err *err)
{
    const char *name = m->name ? m->name : "model";
    int rc = gr_fit_check_data(name, m->np, x, y, sigma, n, err);
    if (!rc)
        rc = check_start(m, name, x, n, p0, err);
    if (rc)
        return rc;
    size_t np = m->np;
    gr_fit_opts o = opts_or_defaults(opt);

    memset(out, 0, sizeof *out);
    out->np = np;
    out->n = n;
    out->dof = (double)(n - np);
    out->weighted = sigma != NULL;
    memcpy(out->p, p0, np * sizeof *p0);

    fit_data d = {m, x, y};
    gsl_multifit_nlinear_fdf fdf = {0};
    fdf.f = residual_cb;
    fdf.df = m->analytic_jac ? jacobian_cb : NULL;
    fdf.n = n;
    fdf.p = np;
    fdf.params = &d;
    gsl_multifit_nlinear_parameters par = gsl_multifit_nlinear_default_parameters();
    par.trs = o.geodesic ? gsl_multifit_nlinear_trs_lmaccel : gsl_multifit_nlinear_trs_lm;
    par.fdtype = GSL_MULTIFIT_NLINEAR_CTRDIFF;

    gsl_multifit_nlinear_workspace *w = gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust,
                                                                   &par, n, np);
    gsl_vector *wts = sigma ? gsl_vector_alloc(n) : NULL;
    gsl_matrix *cov = gsl_matrix_alloc(np, np);
    if (!w || !cov || (sigma && !wts)) {
        rc = gr_fail(err, GR_ERUN, "%s fit: out of memory (%zu points)", name, n);
    } else {
        for (size_t i = 0; sigma && i < n; i++)
            gsl_vector_set(wts, i, 1.0 / (sigma[i] * sigma[i]));
        rc = solve(m, name, &fdf, w, wts, cov, &o, out, err);
    }
    gsl_multifit_nlinear_free(w);
    gsl_vector_free(wts);
    gsl_matrix_free(cov);
    return rc;
}

/* ----------------------------------------------------------------- log-log */

int gr_fit_loglog(const double *x, const double *y, const double *sigma, size_t n,
                  gr_fit *out, gr_err *err)
{
    int rc = gr_fit_check_data("log-log fit", 2, x, y, sigma, n, err);
    if (rc)
        return rc;
    double *lx = malloc(3 * n * sizeof *lx);
    if (!lx)
        return gr_fail(err, GR_ERUN, "log-log fit: out of memory (%zu points)", n);
    double *ly = lx + n, *w = ly + n;
    for (size_t i = 0; i < n; i++) {
        if (!(x[i] > 0.0) || !(y[i] > 0.0)) {
            free(lx);
            return gr_fail(err, GR_EINPUT, "log-log fit: point %zu (%g, %g) is not positive", i,
                           x[i], y[i]);
        }
        lx[i] = log(x[i]);
        ly[i] = log(y[i]);
        if (sigma)
            w[i] = (y[i] / sigma[i]) * (y[i] / sigma[i]);
    }
    double c0, c1, c00, c01, c11, ss;
    int st = sigma ? gsl_fit_wlinear(lx, 1, w, 1, ly, 1, n, &c0, &c1, &c00, &c01, &c11, &ss)
                   : gsl_fit_linear(lx, 1, ly, 1, n, &c0, &c1, &c00, &c01, &c11, &ss);
    free(lx);
    if (st || !isfinite(c1))
        return gr_fail(err, GR_EINPUT, "log-log fit: degenerate data (all x equal?)");
    memset(out, 0, sizeof *out);
    double A = exp(c0);
    out->np = 2;
    out->n = n;
    out->p[0] = A;
    out->p[1] = c1;
    /* ln A -> A: the Jacobian is diag(A, 1). gsl_fit_linear already scales
     * its covariance by the scatter, gsl_fit_wlinear does not. */
    out->cov[0][0] = A * A * c00;
    out->cov[0][1] = out->cov[1][0] = A * c01;
    out->cov[1][1] = c11;
    out->err[0] = sqrt(out->cov[0][0]);
    out->err[1] = sqrt(c11);
    out->chi2 = ss;
    out->dof = (double)(n - 2);
    out->chi2_dof = ss / out->dof;
    out->weighted = sigma != NULL;
    out->scaled = sigma == NULL;
    return GR_OK;
}
