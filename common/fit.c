/* Least-squares fits: gsl_multifit_nlinear for the non-linear models,
 * gsl_fit_(w)linear for straight lines in log-log. */
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

static int check_data(const char *what, size_t np, const double *x, const double *y,
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

int gr_fit_nlin(const gr_model *m, const double *x, const double *y, const double *sigma,
                size_t n, const double *p0, const gr_fit_opts *opt, gr_fit *out, gr_err *err)
{
    const char *name = m->name ? m->name : "model";
    int rc = check_data(name, m->np, x, y, sigma, n, err);
    if (rc)
        return rc;
    size_t np = m->np;
    for (size_t j = 0; j < np; j++)
        if (!isfinite(p0[j]))
            return gr_fail(err, GR_EINPUT, "%s fit: start value %zu is not finite", name, j);
    for (size_t i = 0; i < n; i++) {
        double v = m->f(x[i], p0, NULL, m->user);
        if (!isfinite(v))
            return gr_fail(err, GR_EINPUT, "%s fit: model undefined at the start values (x = %g)",
                           name, x[i]);
    }
    gr_fit_opts o = opt ? *opt : (gr_fit_opts){0};
    if (o.max_iter == 0)
        o.max_iter = 500;
    if (o.xtol <= 0)
        o.xtol = 1e-10;
    if (o.gtol <= 0)
        o.gtol = 1e-10;
    if (o.ftol <= 0)
        o.ftol = 1e-12;

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
        goto done;
    }
    if (sigma)
        for (size_t i = 0; i < n; i++)
            gsl_vector_set(wts, i, 1.0 / (sigma[i] * sigma[i]));
    /* GSL's step-size test also fires when rejected steps (outside the
     * domain, or a poor model of the cost) have shrunk the trust region to
     * nothing: restart from where it stopped, with a fresh region, until a
     * restart no longer moves. */
    double cur[GR_FIT_MAXP];
    memcpy(cur, p0, np * sizeof *cur);
    int st, info = 0;
    size_t iter = 0;
    for (int round = 0; round < 20; round++) {
        gsl_vector_view start = gsl_vector_view_array(cur, np);
        st = sigma ? gsl_multifit_nlinear_winit(&start.vector, wts, &fdf, w)
                   : gsl_multifit_nlinear_init(&start.vector, &fdf, w);
        if (st) {
            rc = gr_fail(err, GR_ERUN, "%s fit: model evaluation failed (%s)", name,
                         gsl_strerror(st));
            goto done;
        }
        st = gsl_multifit_nlinear_driver(o.max_iter, o.xtol, o.gtol, o.ftol, NULL, NULL, &info,
                                         w);
        iter += gsl_multifit_nlinear_niter(w);
        /* GSL stops with "no progress" (as GSL_EMAXITER after one
         * iteration) when the start is already the optimum, e.g. noise-free
         * data: accept a stop where the convergence test holds. */
        if (st != GSL_SUCCESS && round > 0) {
            int info2 = 0;
            if (gsl_multifit_nlinear_test(o.xtol, o.gtol, o.ftol, &info2, w) == GSL_SUCCESS) {
                st = GSL_SUCCESS;
                info = info2;
            }
        }
        const double *q = gsl_multifit_nlinear_position(w)->data;
        int moved = 0;
        for (size_t j = 0; j < np; j++)
            moved |= fabs(q[j] - cur[j]) > 1e-7 * fmax(fabs(cur[j]), 1e-7);
        memcpy(cur, q, np * sizeof *cur);
        if (st != GSL_SUCCESS && round == 0 && st == GSL_EMAXITER && info == GSL_ENOPROG)
            st = GSL_SUCCESS; /* no first step found: let the restart decide */
        if (st != GSL_SUCCESS || !moved || iter >= o.max_iter)
            break;
    }
    memcpy(out->p, cur, np * sizeof(double));
    out->iter = iter;
    out->nfev = fdf.nevalf;
    out->info = info;
    gsl_vector *f = gsl_multifit_nlinear_residual(w);
    gsl_blas_ddot(f, f, &out->chi2);
    out->chi2_dof = out->chi2 / out->dof;
    if (st != GSL_SUCCESS) {
        rc = gr_fail(err, GR_ERUN,
                     "%s fit did not converge after %zu iterations: %s (chi2 = %g)", name,
                     out->iter, gsl_strerror(st), out->chi2);
        goto done;
    }
    gsl_multifit_nlinear_covar(gsl_multifit_nlinear_jac(w), 0.0, cov);
    out->scaled = o.scale == GR_FIT_SCALE_ALWAYS || (o.scale == GR_FIT_SCALE_AUTO && !sigma);
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
            rc = gr_fail(err, GR_ERUN,
                         "%s fit: parameter %s is not determined by the data (variance %g)",
                         name, pname(m, j, buf), v);
            goto done;
        }
    }
    rc = GR_OK;
done:
    gsl_multifit_nlinear_free(w);
    gsl_vector_free(wts);
    gsl_matrix_free(cov);
    return rc;
}

/* ------------------------------------------------------------------ models */

static double power_f(double x, const double *p, double *g, void *u)
{
    (void)u;
    double xp = pow(x, p[1]), v = p[0] * xp;
    if (g) {
        g[0] = xp;
        g[1] = v * log(x);
    }
    return v;
}

static double exp_f(double x, const double *p, double *g, void *u)
{
    (void)u;
    double e = exp(p[1] * x), v = p[0] * e;
    if (g) {
        g[0] = e;
        g[1] = v * x;
    }
    return v;
}

static double gauss_f(double x, const double *p, double *g, void *u)
{
    (void)u;
    double s = p[2], z = (x - p[1]) / s, e = exp(-0.5 * z * z), v = p[0] * e;
    if (g) {
        g[0] = e;
        g[1] = v * z / s;
        g[2] = v * z * z / s;
    }
    return v;
}

static double density_f(double x, const double *p, double *g, void *u)
{
    (void)u;
    double e = exp(-p[2] * x), v = p[0] * (1.0 - p[1] * e);
    if (g) {
        g[0] = 1.0 - p[1] * e;
        g[1] = -p[0] * e;
        g[2] = p[0] * p[1] * x * e;
    }
    return v;
}

static double bev_expo(const gr_beverloo_par *b) { return b->exponent > 0 ? b->exponent : 1.5; }

static double beverloo_f(double D, const double *p, double *g, void *u)
{
    const gr_beverloo_par *b = u;
    double e = bev_expo(b), pre = b->rho * sqrt(b->g), h = D - p[1];
    if (h <= 0.0) {
        if (g)
            g[0] = g[1] = 0.0;
        return 0.0;
    }
    double he = pow(h, e), v = p[0] * pre * he;
    if (g) {
        g[0] = pre * he;
        g[1] = -e * v / h;
    }
    return v;
}

static double beverloo_mod_f(double D, const double *p, double *g, void *u)
{
    const gr_beverloo_par *b = u;
    double pre = b->rho * sqrt(b->g) * pow(D, bev_expo(b));
    double E = exp(-p[2] * D), r = 1.0 - p[1] * E, v = p[0] * pre * r;
    if (g) {
        g[0] = pre * r;
        g[1] = -p[0] * pre * E;
        g[2] = p[0] * pre * p[1] * D * E;
    }
    return v;
}

gr_model gr_model_power(void)
{
    return (gr_model){.name = "power law A x^p", .np = 2, .f = power_f, .analytic_jac = 1,
                      .pnames = {"A", "p"}};
}

gr_model gr_model_exp(void)
{
    return (gr_model){.name = "exponential A exp(b x)", .np = 2, .f = exp_f,
                      .analytic_jac = 1, .pnames = {"A", "b"}};
}

gr_model gr_model_gauss(void)
{
    return (gr_model){.name = "Gaussian", .np = 3, .f = gauss_f, .analytic_jac = 1,
                      .pnames = {"A", "mu", "sigma"}};
}

gr_model gr_model_density_law(void)
{
    return (gr_model){.name = "density law rho0 (1 - a exp(-b D))", .np = 3, .f = density_f,
                      .analytic_jac = 1, .pnames = {"rho0", "a", "b"}};
}

static double tsallis_f(double x, const double *p, double *g, void *u)
{
    (void)u;
    (void)g;
    return gr_pdf_tsallis_unit(x, p[0]);
}

gr_model gr_model_tsallis_unit(void)
{
    return (gr_model){.name = "unit-variance Tsallis law (eq. 3.8)", .np = 1, .f = tsallis_f,
                      .analytic_jac = 0, .pnames = {"c"}};
}

gr_model gr_model_beverloo(const gr_beverloo_par *par)
{
    return (gr_model){.name = "Beverloo C rho sqrt(g) (D - k)^e", .np = 2, .f = beverloo_f,
                      .analytic_jac = 1, .user = (void *)par, .pnames = {"C", "k"}};
}

gr_model gr_model_beverloo_mod(const gr_beverloo_par *par)
{
    return (gr_model){.name = "modified Beverloo C rho (1 - a exp(-b D)) sqrt(g) D^e", .np = 3,
                      .f = beverloo_mod_f, .analytic_jac = 1, .user = (void *)par,
                      .pnames = {"C", "a", "b"}};
}

/* ------------------------------------------------------- log-log and starts */

int gr_fit_loglog(const double *x, const double *y, const double *sigma, size_t n,
                  gr_fit *out, gr_err *err)
{
    int rc = check_data("log-log fit", 2, x, y, sigma, n, err);
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

int gr_fit_power(const double *x, const double *y, const double *sigma, size_t n,
                 const double *p0, gr_fit *out, gr_err *err)
{
    gr_model m = gr_model_power();
    double s[2];
    if (!p0) {
        /* log-log line through the positive points (noise can push small
         * values below zero) */
        int rc = check_data(m.name, m.np, x, y, sigma, n, err);
        if (rc)
            return rc;
        double *buf = malloc(3 * n * sizeof *buf);
        if (!buf)
            return gr_fail(err, GR_ERUN, "power-law fit: out of memory");
        size_t k = 0;
        for (size_t i = 0; i < n; i++)
            if (x[i] > 0.0 && y[i] > 0.0) {
                buf[k] = x[i];
                buf[n + k] = y[i];
                buf[2 * n + k++] = sigma ? sigma[i] : 1.0;
            }
        rc = k > 2 ? gr_fit_loglog(buf, buf + n, sigma ? buf + 2 * n : NULL, k, out, err)
                   : gr_fail(err, GR_EINPUT, "fewer than 3 points with x, y > 0");
        free(buf);
        if (rc)
            return gr_err_prefix(err, "power-law start: ");
        s[0] = out->p[0];
        s[1] = out->p[1];
        p0 = s;
    }
    return gr_fit_nlin(&m, x, y, sigma, n, p0, NULL, out, err);
}

int gr_fit_exp(const double *x, const double *y, const double *sigma, size_t n,
               const double *p0, gr_fit *out, gr_err *err)
{
    gr_model m = gr_model_exp();
    double s[2];
    if (!p0) {
        /* ln y = ln A + b x on the positive points */
        double *lx = malloc(2 * n * sizeof *lx);
        if (!lx)
            return gr_fail(err, GR_ERUN, "exponential fit: out of memory");
        double *ly = lx + n, c0 = 0, c1 = 0, c00, c01, c11, ss;
        size_t k = 0;
        for (size_t i = 0; i < n; i++)
            if (y[i] > 0.0 && isfinite(x[i]) && isfinite(y[i])) {
                lx[k] = x[i];
                ly[k++] = log(y[i]);
            }
        if (k < 2 || gsl_fit_linear(lx, 1, ly, 1, k, &c0, &c1, &c00, &c01, &c11, &ss) ||
            !isfinite(c1)) {
            c0 = 0.0;
            c1 = 0.0;
        }
        free(lx);
        s[0] = exp(c0);
        s[1] = c1;
        p0 = s;
    }
    return gr_fit_nlin(&m, x, y, sigma, n, p0, NULL, out, err);
}

int gr_fit_gauss(const double *x, const double *y, const double *sigma, size_t n,
                 const double *p0, gr_fit *out, gr_err *err)
{
    gr_model m = gr_model_gauss();
    double s[3];
    if (!p0) {
        double sw = 0, sx = 0, sxx = 0, ymax = 0;
        for (size_t i = 0; i < n; i++)
            if (y[i] > 0.0) {
                sw += y[i];
                sx += y[i] * x[i];
                ymax = fmax(ymax, y[i]);
            }
        double mu = sw > 0 ? sx / sw : 0.0;
        for (size_t i = 0; i < n; i++)
            if (y[i] > 0.0)
                sxx += y[i] * (x[i] - mu) * (x[i] - mu);
        s[0] = ymax;
        s[1] = mu;
        s[2] = sw > 0 && sxx > 0 ? sqrt(sxx / sw) : 1.0;
        p0 = s;
    }
    return gr_fit_nlin(&m, x, y, sigma, n, p0, NULL, out, err);
}

/* Start for r(D) = r0 (1 - a exp(-b D)): for a few trial plateaus r0 just
 * above the largest r, the line ln(1 - r/r0) = ln a - b D; keep the start
 * with the smallest sum of squares. */
static void density_start(const double *D, const double *r, size_t n, double s[3])
{
    double rmax = -INFINITY, dmin = INFINITY, dmax = -INFINITY;
    for (size_t i = 0; i < n; i++) {
        rmax = fmax(rmax, r[i]);
        dmin = fmin(dmin, D[i]);
        dmax = fmax(dmax, D[i]);
    }
    s[0] = rmax;
    s[1] = 0.5;
    s[2] = dmax > dmin ? 3.0 / (dmax - dmin) : 1.0;
    double *lx = malloc(2 * n * sizeof *lx);
    if (!lx || !(rmax > 0.0)) {
        free(lx);
        return;
    }
    double *ly = lx + n, best = INFINITY;
    static const double plateau[] = {1.002, 1.01, 1.03, 1.1, 1.3};
    for (size_t t = 0; t < sizeof plateau / sizeof plateau[0]; t++) {
        double r0 = plateau[t] * rmax, c0, c1, c00, c01, c11, ss;
        size_t k = 0;
        for (size_t i = 0; i < n; i++) {
            lx[k] = D[i];
            ly[k++] = log(1.0 - r[i] / r0);
        }
        if (gsl_fit_linear(lx, 1, ly, 1, k, &c0, &c1, &c00, &c01, &c11, &ss) || !(c1 < 0.0))
            continue;
        double p[3] = {r0, exp(c0), -c1}, sse = 0.0;
        for (size_t i = 0; i < n; i++) {
            double d = density_f(D[i], p, NULL, NULL) - r[i];
            sse += d * d;
        }
        if (sse < best) {
            best = sse;
            memcpy(s, p, sizeof p);
        }
    }
    free(lx);
}

int gr_fit_density_law(const double *D, const double *rho, const double *sigma, size_t n,
                       const double *p0, gr_fit *out, gr_err *err)
{
    gr_model m = gr_model_density_law();
    double s[3];
    if (!p0) {
        int rc = check_data(m.name, m.np, D, rho, sigma, n, err);
        if (rc)
            return rc;
        density_start(D, rho, n, s);
        p0 = s;
    }
    return gr_fit_nlin(&m, D, rho, sigma, n, p0, NULL, out, err);
}

int gr_fit_beverloo(const gr_beverloo_par *par, const double *D, const double *W,
                    const double *sigma, size_t n, const double *p0, gr_fit *out, gr_err *err)
{
    gr_model m = gr_model_beverloo(par);
    double s[2];
    double pre = par->rho * sqrt(par->g), e = bev_expo(par);
    if (!(pre > 0.0) || !isfinite(pre))
        return gr_fail(err, GR_EINPUT, "Beverloo fit: rho sqrt(g) = %g must be > 0", pre);
    if (!p0) {
        int rc = check_data(m.name, m.np, D, W, sigma, n, err);
        if (rc)
            return rc;
        /* W^(1/e) = (C pre)^(1/e) (D - k) is a line in D. */
        double *lx = malloc(2 * n * sizeof *lx);
        if (!lx)
            return gr_fail(err, GR_ERUN, "Beverloo fit: out of memory");
        double *ly = lx + n, c0, c1, c00, c01, c11, ss;
        size_t k = 0;
        for (size_t i = 0; i < n; i++)
            if (W[i] > 0.0) {
                lx[k] = D[i];
                ly[k++] = pow(W[i], 1.0 / e);
            }
        int bad = k < 2 || gsl_fit_linear(lx, 1, ly, 1, k, &c0, &c1, &c00, &c01, &c11, &ss) ||
                  !(c1 > 0.0);
        free(lx);
        if (bad)
            return gr_fail(err, GR_EINPUT,
                           "Beverloo fit: flow does not grow with D; give a start p0");
        s[0] = pow(c1, e) / pre;
        s[1] = -c0 / c1;
        p0 = s;
    }
    return gr_fit_nlin(&m, D, W, sigma, n, p0, NULL, out, err);
}

int gr_fit_beverloo_mod(const gr_beverloo_par *par, const double *D, const double *W,
                        const double *sigma, size_t n, const double *p0, gr_fit *out,
                        gr_err *err)
{
    gr_model m = gr_model_beverloo_mod(par);
    double s[3];
    double pre = par->rho * sqrt(par->g), e = bev_expo(par);
    if (!(pre > 0.0) || !isfinite(pre))
        return gr_fail(err, GR_EINPUT, "modified Beverloo fit: rho sqrt(g) = %g must be > 0",
                       pre);
    if (!p0) {
        int rc = check_data(m.name, m.np, D, W, sigma, n, err);
        if (rc)
            return rc;
        /* W / (pre D^e) = C (1 - a exp(-b D)) has the density law's shape. */
        double *r = malloc(n * sizeof *r);
        if (!r)
            return gr_fail(err, GR_ERUN, "modified Beverloo fit: out of memory");
        for (size_t i = 0; i < n; i++)
            r[i] = D[i] > 0.0 ? W[i] / (pre * pow(D[i], e)) : 0.0;
        density_start(D, r, n, s);
        free(r);
        p0 = s;
    }
    return gr_fit_nlin(&m, D, W, sigma, n, p0, NULL, out, err);
}
