/* The ready fit models of the silo studies and starting values computed
 * from the data (linearised forms), on top of gr_fit_nlin. */
#include "stats.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_fit.h>
#include <gsl/gsl_min.h>

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

/* ---------------------------------------------------------- fits with starts */

int gr_fit_power(const double *x, const double *y, const double *sigma, size_t n,
                 const double *p0, gr_fit *out, gr_err *err)
{
    gr_model m = gr_model_power();
    double s[2];
    if (!p0) {
        /* log-log line through the positive points (noise can push small
         * values below zero) */
        int rc = gr_fit_check_data(m.name, m.np, x, y, sigma, n, err);
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
        int rc = gr_fit_check_data(m.name, m.np, D, rho, sigma, n, err);
        if (rc)
            return rc;
        density_start(D, rho, n, s);
        p0 = s;
    }
    return gr_fit_nlin(&m, D, rho, sigma, n, p0, NULL, out, err);
}

/* At fixed b the density law is linear: rho = A + C (-e^{-bD}), A = rho0,
 * C = rho0 a. Weighted least squares by the 2 x 2 normal equations;
 * returns chi2 (INFINITY if singular) and fills A, C and their covariance. */
typedef struct {
    const double *D, *r, *sigma;
    size_t n;
} dl_data;

static double dl_profile(const dl_data *q, double b, double lin[2], double cov[3])
{
    double s11 = 0, s12 = 0, s22 = 0, t1 = 0, t2 = 0;
    for (size_t i = 0; i < q->n; i++) {
        double w = q->sigma ? 1.0 / (q->sigma[i] * q->sigma[i]) : 1.0, e = -exp(-b * q->D[i]);
        s11 += w, s12 += w * e, s22 += w * e * e;
        t1 += w * q->r[i], t2 += w * e * q->r[i];
    }
    double det = s11 * s22 - s12 * s12;
    if (!(det > 1e-14 * s11 * s22))
        return INFINITY;
    lin[0] = (s22 * t1 - s12 * t2) / det;
    lin[1] = (s11 * t2 - s12 * t1) / det;
    cov[0] = s22 / det, cov[1] = -s12 / det, cov[2] = s11 / det;
    double chi2 = 0;
    for (size_t i = 0; i < q->n; i++) {
        double w = q->sigma ? 1.0 / (q->sigma[i] * q->sigma[i]) : 1.0;
        double d = q->r[i] - lin[0] + lin[1] * exp(-b * q->D[i]);
        chi2 += w * d * d;
    }
    return chi2;
}

static double dl_chi2(double b, void *u)
{
    double lin[2], cov[3];
    return dl_profile(u, b, lin, cov);
}

/* The result at b with b held fixed: (rho0, a) and their errors from the
 * linear fit, b's error unknown. */
static void dl_fixed(const dl_data *q, double b, gr_fit *out)
{
    double lin[2], cov[3];
    double chi2 = dl_profile(q, b, lin, cov);
    memset(out, 0, sizeof *out);
    out->np = 3, out->n = q->n;
    out->dof = (double)q->n - 2.0;
    out->chi2 = chi2, out->chi2_dof = chi2 / out->dof;
    out->weighted = q->sigma != NULL;
    double A = lin[0], a = lin[1] / A, ga = -lin[1] / (A * A), gc = 1.0 / A;
    double scale = q->sigma ? 1.0 : out->chi2_dof;
    out->scaled = !q->sigma;
    out->p[0] = A, out->p[1] = a, out->p[2] = b;
    out->cov[0][0] = cov[0] * scale;
    out->cov[1][1] = (ga * ga * cov[0] + 2 * ga * gc * cov[1] + gc * gc * cov[2]) * scale;
    out->cov[0][1] = out->cov[1][0] = (ga * cov[0] + gc * cov[1]) * scale;
    out->err[0] = sqrt(out->cov[0][0]), out->err[1] = sqrt(out->cov[1][1]), out->err[2] = NAN;
    out->cov[2][2] = NAN;
}

int gr_fit_density_law_bounded(const double *D, const double *rho, const double *sigma, size_t n,
                               double bmin, double bmax, gr_fit *out, int *at_bound, gr_err *err)
{
    gr_model m = gr_model_density_law();
    int rc = gr_fit_check_data(m.name, m.np, D, rho, sigma, n, err);
    if (rc)
        return rc;
    if (!(bmin > 0 && bmax > bmin && isfinite(bmax)))
        return gr_fail(err, GR_EINPUT, "%s fit: decay-rate range [%g, %g] must satisfy 0 < bmin < bmax",
                       m.name, bmin, bmax);
    dl_data q = {D, rho, sigma, n};
    /* chi2(b) may have several minima: scan on a log grid first */
    enum { NG = 241 };
    double bg[NG], cg[NG];
    int k = 0;
    for (int g = 0; g < NG; g++) {
        bg[g] = bmin * pow(bmax / bmin, (double)g / (NG - 1));
        cg[g] = dl_chi2(bg[g], &q);
        if (cg[g] < cg[k])
            k = g;
    }
    if (!isfinite(cg[k]))
        return gr_fail(err, GR_ERUN, "%s fit: singular for every decay rate in [%g, %g]", m.name, bmin, bmax);
    *at_bound = k == 0 || k == NG - 1;
    double b = bg[k];
    if (!*at_bound) {
        gsl_function F = {dl_chi2, &q};
        gsl_min_fminimizer *s = gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent);
        gsl_error_handler_t *old = gsl_set_error_handler_off();
        if (s && gsl_min_fminimizer_set_with_values(s, &F, bg[k], cg[k], bg[k - 1], cg[k - 1], bg[k + 1],
                                                    cg[k + 1]) == GSL_SUCCESS) {
            for (int it = 0; it < 100; it++) {
                if (gsl_min_fminimizer_iterate(s))
                    break;
                double lo = gsl_min_fminimizer_x_lower(s), hi = gsl_min_fminimizer_x_upper(s);
                if (gsl_min_test_interval(lo, hi, 1e-12, 1e-10) == GSL_SUCCESS)
                    break;
            }
            b = gsl_min_fminimizer_x_minimum(s);
        }
        gsl_set_error_handler(old);
        gsl_min_fminimizer_free(s);
    }
    dl_fixed(&q, b, out);
    if (*at_bound)
        return GR_OK;
    /* inside the range: the full fit from there gives the covariance of all three */
    gr_fit full;
    gr_err e2 = {0};
    double p0[3] = {out->p[0], out->p[1], out->p[2]};
    if (gr_fit_nlin(&m, D, rho, sigma, n, p0, NULL, &full, &e2) == GR_OK && full.p[2] >= bmin &&
        full.p[2] <= bmax && full.chi2 <= out->chi2 * (1 + 1e-9) + 1e-300)
        *out = full;
    else
        out->dof = (double)n - 3.0, out->chi2_dof = out->chi2 / out->dof;
    return GR_OK;
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
        int rc = gr_fit_check_data(m.name, m.np, D, W, sigma, n, err);
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
        int rc = gr_fit_check_data(m.name, m.np, D, W, sigma, n, err);
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
