/* Fits recover known parameters from synthetic noisy data within stated
 * multiples of their reported errors, and the reported errors are right
 * (pulls over many realisations have unit spread). */
#include "test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_fit.h>
#include <gsl/gsl_randist.h>

#include "rng.h"
#include "stats.h"

#define NSIG 4.0 /* "within 4 standard errors" */

static void assert_within(const gr_fit *f, size_t j, double truth, double max_rel_err)
{
    double pull = (f->p[j] - truth) / f->err[j];
    print_message("#   p[%zu] = %.6g +- %.3g (true %.6g, pull %+.2f)\n", j, f->p[j], f->err[j],
                  truth, pull);
    assert_true(f->err[j] > 0.0);
    assert_true(fabs(pull) < NSIG);
    /* the error itself must be small, or a wide error would pass anything */
    assert_true(f->err[j] < max_rel_err * fabs(truth));
}

/* Power law: weighted non-linear fit and log-log line, 30 points over two
 * decades with 2 % noise. */
static void power_law_recovered(void **state)
{
    (void)state;
    gr_err e = {0};
    gr_rng *r = gr_rng_create(7, 0, &e);
    double x[30], y[30], s[30], A = 2.5, p = 1.37;
    for (int i = 0; i < 30; i++) {
        x[i] = pow(10.0, 2.0 * i / 29.0);
        s[i] = 0.02 * A * pow(x[i], p);
        y[i] = A * pow(x[i], p) + gr_rng_gaussian(r, s[i]);
    }
    gr_fit f;
    print_message("# power law, weighted non-linear\n");
    assert_int_equal(gr_fit_power(x, y, s, 30, NULL, &f, &e), GR_OK);
    assert_within(&f, 0, A, 0.05);
    assert_within(&f, 1, p, 0.01);
    assert_false(f.scaled);
    assert_true(f.chi2_dof > 0.4 && f.chi2_dof < 1.8);
    print_message("# power law, log-log line\n");
    assert_int_equal(gr_fit_loglog(x, y, NULL, 30, &f, &e), GR_OK);
    assert_within(&f, 0, A, 0.05);
    assert_within(&f, 1, p, 0.01);
    assert_int_equal(gr_fit_loglog(x, y, s, 30, &f, &e), GR_OK);
    assert_within(&f, 1, p, 0.01);
    gr_rng_free(r);
}

/* Reported errors are calibrated: over 300 realisations of an unweighted
 * power-law fit (errors scaled by sqrt(chi2/dof)), the pulls of the exponent
 * have mean 0 and standard deviation 1 (Student t, 18 dof: 1.06). */
static void power_law_pulls_have_unit_spread(void **state)
{
    (void)state;
    gr_err e = {0};
    gr_rng *r = gr_rng_create(8, 0, &e);
    gr_moments *m = gr_moments_create(&e);
    gr_moments *ml = gr_moments_create(&e);
    for (int k = 0; k < 300; k++) {
        double x[20], y[20];
        for (int i = 0; i < 20; i++) {
            x[i] = 1.0 + i;
            y[i] = 0.8 * pow(x[i], 1.5) + gr_rng_gaussian(r, 0.5);
        }
        gr_fit f;
        assert_int_equal(gr_fit_power(x, y, NULL, 20, NULL, &f, &e), GR_OK);
        assert_true(f.scaled);
        gr_moments_add(m, (f.p[1] - 1.5) / f.err[1]);
        /* log-normal noise makes the log-log line an exact linear model */
        for (int i = 0; i < 20; i++)
            y[i] = 0.8 * pow(x[i], 1.5) * exp(gr_rng_gaussian(r, 0.05));
        assert_int_equal(gr_fit_loglog(x, y, NULL, 20, &f, &e), GR_OK);
        gr_moments_add(ml, (f.p[1] - 1.5) / f.err[1]);
    }
    print_message("# pulls: non-linear mean %.3f sd %.3f; log-log mean %.3f sd %.3f\n",
                  gr_moments_mean(m), gr_moments_sd(m), gr_moments_mean(ml), gr_moments_sd(ml));
    /* sd of the mean 0.06, of the sd 0.04 */
    assert_close(gr_moments_mean(m), 0.0, 0.25);
    assert_close(gr_moments_sd(m), 1.06, 0.17);
    assert_close(gr_moments_mean(ml), 0.0, 0.25);
    assert_close(gr_moments_sd(ml), 1.06, 0.17);
    gr_moments_free(m);
    gr_moments_free(ml);
    gr_rng_free(r);
}

static void exponential_recovered(void **state)
{
    (void)state;
    gr_err e = {0};
    gr_rng *r = gr_rng_create(9, 0, &e);
    double x[40], y[40], s[40];
    for (int i = 0; i < 40; i++) {
        x[i] = 0.2 * i;
        s[i] = 0.01;
        y[i] = 3.0 * exp(-0.7 * x[i]) + gr_rng_gaussian(r, s[i]);
    }
    gr_fit f;
    print_message("# exponential\n");
    assert_int_equal(gr_fit_exp(x, y, s, 40, NULL, &f, &e), GR_OK);
    assert_within(&f, 0, 3.0, 0.01);
    assert_within(&f, 1, -0.7, 0.01);
    gr_rng_free(r);
}

/* Beverloo 2D: flow for orifices 3..20 d with 1 % noise, rho = 0.8. */
static void beverloo_recovered(void **state)
{
    (void)state;
    gr_err e = {0};
    gr_rng *r = gr_rng_create(10, 0, &e);
    gr_beverloo_par par = {.rho = 0.8, .g = 1.0};
    gr_model m = gr_model_beverloo(&par);
    double C = 1.03, k = 1.4, D[18], W[18], s[18];
    for (int i = 0; i < 18; i++) {
        D[i] = 3.0 + i;
        double w = m.f(D[i], (double[]){C, k}, NULL, m.user);
        assert_close(w, C * 0.8 * pow(D[i] - k, 1.5), 1e-12 * w);
        s[i] = 0.01 * w;
        W[i] = w + gr_rng_gaussian(r, s[i]);
    }
    gr_fit f;
    print_message("# Beverloo, weighted\n");
    assert_int_equal(gr_fit_beverloo(&par, D, W, s, 18, NULL, &f, &e), GR_OK);
    assert_within(&f, 0, C, 0.02);
    assert_within(&f, 1, k, 0.05);
    print_message("# Beverloo, unweighted (errors from the scatter)\n");
    assert_int_equal(gr_fit_beverloo(&par, D, W, NULL, 18, NULL, &f, &e), GR_OK);
    assert_within(&f, 0, C, 0.05);
    assert_within(&f, 1, k, 0.2);
    /* flow that does not grow with D has no Beverloo start */
    double flat[18];
    for (int i = 0; i < 18; i++)
        flat[i] = 5.0 - 0.1 * i;
    assert_int_equal(gr_fit_beverloo(&par, D, flat, NULL, 18, NULL, &f, &e), GR_EINPUT);
    gr_rng_free(r);
}

/* Density law rho0 (1 - a exp(-b D)) and the modified flow law. */
static void density_and_modified_law_recovered(void **state)
{
    (void)state;
    gr_err e = {0};
    gr_rng *r = gr_rng_create(11, 0, &e);
    double D[19], y[19], s[19];
    for (int i = 0; i < 19; i++) {
        D[i] = 2.0 + i;
        s[i] = 0.002;
        y[i] = 0.82 * (1.0 - 0.3 * exp(-0.35 * D[i])) + gr_rng_gaussian(r, s[i]);
    }
    gr_fit f;
    print_message("# density law\n");
    assert_int_equal(gr_fit_density_law(D, y, s, 19, NULL, &f, &e), GR_OK);
    assert_within(&f, 0, 0.82, 0.01);
    assert_within(&f, 1, 0.3, 0.1);
    assert_within(&f, 2, 0.35, 0.15);

    gr_beverloo_par par = {.rho = 0.8, .g = 1.0};
    for (int i = 0; i < 19; i++) {
        double w = 1.1 * 0.8 * (1.0 - 0.5 * exp(-0.3 * D[i])) * pow(D[i], 1.5);
        s[i] = 0.01 * w;
        y[i] = w + gr_rng_gaussian(r, s[i]);
    }
    print_message("# modified Beverloo (eqs. 4.14-4.15)\n");
    assert_int_equal(gr_fit_beverloo_mod(&par, D, y, s, 19, NULL, &f, &e), GR_OK);
    assert_within(&f, 0, 1.1, 0.02);
    assert_within(&f, 1, 0.5, 0.1);
    assert_within(&f, 2, 0.3, 0.15);
    gr_rng_free(r);
}

/* A Gaussian fitted to the normalised histogram of N(0.3, 1.5) samples:
 * the amplitude is the normalisation 1/(sigma sqrt(2 pi)). */
/* The bounded density-law fit: the law itself is recovered inside the
 * range (exactly from exact data, within the errors from noisy data); a
 * straight line, which has no plateau, ends at the lower bound with a
 * flag instead of a failed iteration; an empty range is refused. */
static void density_law_bounded(void **state)
{
    (void)state;
    gr_err e = {0};
    double D[14], y[14], s[14];
    for (int i = 0; i < 14; i++) {
        D[i] = 3.0 + i;
        y[i] = 0.84 * (1.0 - 0.2 * exp(-0.5 * D[i]));
    }
    gr_fit f;
    int edge = -1;
    assert_int_equal(gr_fit_density_law_bounded(D, y, NULL, 14, 0.1, 2.0, &f, &edge, &e), GR_OK);
    print_message("# exact law: rho0 %.9f a %.9f b %.9f, at bound %d\n", f.p[0], f.p[1], f.p[2], edge);
    assert_int_equal(edge, 0);
    assert_true(fabs(f.p[0] - 0.84) < 1e-7 && fabs(f.p[1] - 0.2) < 1e-6 && fabs(f.p[2] - 0.5) < 1e-6);

    gr_rng *r = gr_rng_create(12, 0, &e);
    for (int i = 0; i < 14; i++) {
        s[i] = 0.002;
        y[i] = 0.82 * (1.0 - 0.3 * exp(-0.35 * D[i])) + gr_rng_gaussian(r, s[i]);
    }
    gr_rng_free(r);
    assert_int_equal(gr_fit_density_law_bounded(D, y, s, 14, log(10.0) / 16.0, log(100.0) / 3.0, &f, &edge, &e), GR_OK);
    assert_int_equal(edge, 0);
    assert_within(&f, 0, 0.82, 0.01);
    assert_within(&f, 1, 0.3, 0.15);
    assert_within(&f, 2, 0.35, 0.2);

    for (int i = 0; i < 14; i++)
        y[i] = 0.80 + 0.002 * D[i];
    assert_int_equal(gr_fit_density_law_bounded(D, y, NULL, 14, 0.15, 1.5, &f, &edge, &e), GR_OK);
    print_message("# straight line: rho0 %.4f a %.4f b %.4f, at bound %d\n", f.p[0], f.p[1], f.p[2], edge);
    assert_int_equal(edge, 1);
    assert_true(f.p[2] == 0.15 && isnan(f.err[2]) && f.dof == 12.0);
    assert_true(f.p[0] > 0.826 && f.p[1] > 0);

    assert_int_equal(gr_fit_density_law_bounded(D, y, NULL, 14, 1.0, 0.5, &f, &edge, &e), GR_EINPUT);
    assert_non_null(strstr(e.msg, "decay-rate range"));
}

static void gaussian_fit_of_histogram(void **state)
{
    (void)state;
    gr_err e = {0};
    gr_rng *r = gr_rng_create(12, 0, &e);
    gr_hist *h = gr_hist_create(40, -5.7, 6.3, &e);
    for (int i = 0; i < 50000; i++)
        gr_hist_add(h, 0.3 + gr_rng_gaussian(r, 1.5));
    double c[40], d[40], s[40], x[40], y[40], sy[40];
    gr_hist_density(h, c, d, s);
    size_t n = 0;
    for (int i = 0; i < 40; i++)
        if (s[i] > 0) {
            x[n] = c[i];
            y[n] = d[i];
            sy[n++] = s[i];
        }
    gr_fit f;
    print_message("# Gaussian on a histogram\n");
    assert_int_equal(gr_fit_gauss(x, y, sy, n, NULL, &f, &e), GR_OK);
    /* binning (width 0.3) widens the fitted sigma by ~0.3^2/(24 sigma) */
    assert_within(&f, 0, 1.0 / (1.5 * sqrt(2 * M_PI)), 0.02);
    assert_within(&f, 1, 0.3, 0.05);
    assert_within(&f, 2, 1.5, 0.02);
    assert_true(f.chi2_dof < 2.0);
    gr_hist_free(h);
    gr_rng_free(r);
}

/* The shape index c of eq. 3.8 from a unit-variance histogram of Student
 * t samples with nu = 5 (c = 5/2), standardised as the silo data are. */
static void tsallis_index_recovered(void **state)
{
    (void)state;
    gr_err e = {0};
    gr_rng *r = gr_rng_create(14, 0, &e);
    size_t n = 200000;
    double *x = malloc(n * sizeof *x);
    for (size_t i = 0; i < n; i++)
        x[i] = 0.2 + 3.0 * gsl_ran_tdist(gr_rng_gsl(r), 5.0);
    assert_int_equal(gr_standardize(x, n, 1, x, NULL, NULL, &e), GR_OK);
    gr_hist *h = gr_hist_create(48, -6.0, 6.0, &e);
    gr_hist_add_array(h, x, n);
    double c[48], d[48], s[48], xc[48], y[48], sy[48];
    gr_hist_density(h, c, d, s);
    size_t k = 0;
    for (int i = 0; i < 48; i++)
        if (s[i] > 0) {
            xc[k] = c[i];
            y[k] = d[i];
            sy[k++] = s[i];
        }
    gr_model m = gr_model_tsallis_unit();
    gr_fit f;
    print_message("# Tsallis index of t(5) data\n");
    assert_int_equal(gr_fit_nlin(&m, xc, y, sy, k, (double[]){1.8}, NULL, &f, &e), GR_OK);
    assert_within(&f, 0, 2.5, 0.05);
    /* other starts (below c ~ 1.05 lies a spurious minimum where the
     * spike of the law sits in the central bins) */
    gr_fit f2;
    for (double c0 = 1.3; c0 < 100.0; c0 *= 3.0) {
        assert_int_equal(gr_fit_nlin(&m, xc, y, sy, k, &c0, NULL, &f2, &e), GR_OK);
        print_message("#   from c = %.1f: %.6f in %zu iterations\n", c0, f2.p[0], f2.iter);
        assert_close(f2.p[0], f.p[0], 1e-3 * f.err[0]);
    }
    assert_int_equal(gr_fit_nlin(&m, xc, y, sy, k, (double[]){0.5}, NULL, &f2, &e), GR_EINPUT);
    assert_true(f.chi2_dof < 2.0);
    gr_hist_free(h);
    free(x);
    gr_rng_free(r);
}

static double line_f(double x, const double *p, double *g, void *u)
{
    (void)u;
    if (g) {
        g[0] = 1.0;
        g[1] = x;
    }
    return p[0] + p[1] * x;
}

/* On a linear model the non-linear fit must reproduce gsl_fit_linear's
 * parameters and (scatter-scaled) covariance exactly; finite differences
 * agree with the analytic Jacobian. */
static void covariance_convention_matches_linear_fit(void **state)
{
    (void)state;
    gr_err e = {0};
    gr_rng *r = gr_rng_create(13, 0, &e);
    double x[25], y[25], s[25];
    for (int i = 0; i < 25; i++) {
        x[i] = 0.4 * i;
        s[i] = 0.1 + 0.01 * i;
        y[i] = 1.0 - 2.0 * x[i] + gr_rng_gaussian(r, s[i]);
    }
    double c0, c1, c00, c01, c11, ss;
    gsl_fit_linear(x, 1, y, 1, 25, &c0, &c1, &c00, &c01, &c11, &ss);
    gr_model m = {.name = "line", .np = 2, .f = line_f, .analytic_jac = 1};
    gr_fit f;
    assert_int_equal(gr_fit_nlin(&m, x, y, NULL, 25, (double[]){0.0, 0.0}, NULL, &f, &e), GR_OK);
    assert_close(f.p[0], c0, 1e-9);
    assert_close(f.p[1], c1, 1e-9);
    assert_rel(f.cov[0][0], c00, 1e-7);
    assert_rel(f.cov[0][1], c01, 1e-7);
    assert_rel(f.cov[1][1], c11, 1e-7);
    assert_rel(f.chi2, ss, 1e-9);

    /* weighted: the covariance is (X^T W X)^-1, not scaled */
    double w[25];
    for (int i = 0; i < 25; i++)
        w[i] = 1.0 / (s[i] * s[i]);
    gsl_fit_wlinear(x, 1, w, 1, y, 1, 25, &c0, &c1, &c00, &c01, &c11, &ss);
    m.analytic_jac = 0;
    assert_int_equal(gr_fit_nlin(&m, x, y, s, 25, (double[]){0.0, 0.0}, NULL, &f, &e), GR_OK);
    assert_close(f.p[1], c1, 1e-8);
    assert_rel(f.cov[1][1], c11, 1e-6);
    assert_rel(f.chi2, ss, 1e-8);
    assert_false(f.scaled);
    gr_fit_opts o = {.scale = GR_FIT_SCALE_ALWAYS, .geodesic = 1};
    assert_int_equal(gr_fit_nlin(&m, x, y, s, 25, (double[]){0.0, 0.0}, &o, &f, &e), GR_OK);
    assert_true(f.scaled);
    assert_rel(f.err[1], sqrt(c11 * ss / 23.0), 1e-6);
    gr_rng_free(r);
}

static double log_f(double x, const double *p, double *g, void *u)
{
    (void)u;
    if (g)
        g[0] = 1.0 / p[0];
    return log(p[0] * x);
}

/* y = log(p x) from p = 100 towards p = 1: the first Gauss-Newton step
 * lands at p < 0, where the model is undefined; it must be rejected and the
 * fit converge, not abort. */
static void steps_outside_the_domain_are_rejected(void **state)
{
    (void)state;
    gr_err e = {0};
    double x[8], y[8];
    for (int i = 0; i < 8; i++) {
        x[i] = 1.0 + i;
        y[i] = log(x[i]) + 0.01 * ((i % 3) - 1.0);
    }
    gr_model m = {.name = "log", .np = 1, .f = log_f, .analytic_jac = 1};
    gr_fit f;
    assert_int_equal(gr_fit_nlin(&m, x, y, NULL, 8, (double[]){100.0}, NULL, &f, &e), GR_OK);
    print_message("# log model: p = %.6f +- %.2g after %zu iterations\n", f.p[0], f.err[0], f.iter);
    assert_close(f.p[0], 1.0, 0.01);
    assert_int_equal(gr_fit_nlin(&m, x, y, NULL, 8, (double[]){-1.0}, NULL, &f, &e), GR_EINPUT);
}

/* Noise-free data from the exact start (GSL reports no progress there)
 * converge; failures and bad input are reported through gr_err. */
static void exact_data_failures_and_bad_input(void **state)
{
    (void)state;
    gr_err e = {0};
    double x[10], y[10], s[10];
    for (int i = 0; i < 10; i++) {
        x[i] = 1.0 + i;
        y[i] = 2.0 * pow(x[i], 0.5);
        s[i] = 1.0;
    }
    gr_model m = gr_model_power();
    gr_fit f;
    int rc0 = gr_fit_nlin(&m, x, y, s, 10, (double[]){2.0, 0.5}, NULL, &f, &e);
    if (rc0)
        print_error("%s\n", e.msg);
    assert_int_equal(rc0, GR_OK);
    assert_close(f.p[1], 0.5, 1e-12);
    assert_int_equal(gr_fit_power(x, y, NULL, 10, NULL, &f, &e), GR_OK);
    assert_close(f.p[0], 2.0, 1e-9);

    /* one iteration from far away cannot converge */
    gr_fit_opts o = {.max_iter = 1};
    e.msg[0] = 0;
    assert_int_equal(gr_fit_nlin(&m, x, y, NULL, 10, (double[]){50.0, -3.0}, &o, &f, &e),
                     GR_ERUN);
    print_message("# %s\n", e.msg);
    assert_non_null(strstr(e.msg, "did not converge"));
    assert_non_null(strstr(e.msg, "power law"));

    /* a parameter the data cannot determine */
    double D[5] = {1, 2, 3, 4, 5}, W[5] = {1, 2, 3, 4, 5};
    gr_beverloo_par par = {.rho = 1, .g = 1};
    gr_model b = gr_model_beverloo(&par);
    int rc = gr_fit_nlin(&b, D, W, NULL, 5, (double[]){1.0, 9.0}, NULL, &f, &e);
    print_message("# %s\n", e.msg);
    assert_int_equal(rc, GR_ERUN);

    assert_int_equal(gr_fit_nlin(&m, x, y, NULL, 2, (double[]){1, 1}, NULL, &f, &e), GR_EINPUT);
    s[3] = 0.0;
    assert_int_equal(gr_fit_nlin(&m, x, y, s, 10, (double[]){1, 1}, NULL, &f, &e), GR_EINPUT);
    y[2] = NAN;
    assert_int_equal(gr_fit_nlin(&m, x, y, NULL, 10, (double[]){1, 1}, NULL, &f, &e), GR_EINPUT);
    y[2] = -1.0;
    assert_int_equal(gr_fit_loglog(x, y, NULL, 10, &f, &e), GR_EINPUT);
    assert_int_equal(gr_fit_nlin(&m, x, y, NULL, 10, (double[]){NAN, 1}, NULL, &f, &e), GR_EINPUT);
    x[0] = -1.0; /* x^p undefined at the start */
    y[2] = 1.0;
    assert_int_equal(gr_fit_nlin(&m, x, y, NULL, 10, (double[]){1, 0.5}, NULL, &f, &e), GR_EINPUT);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(power_law_recovered),
        cmocka_unit_test(power_law_pulls_have_unit_spread),
        cmocka_unit_test(exponential_recovered),
        cmocka_unit_test(beverloo_recovered),
        cmocka_unit_test(density_and_modified_law_recovered),
        cmocka_unit_test(density_law_bounded),
        cmocka_unit_test(gaussian_fit_of_histogram),
        cmocka_unit_test(tsallis_index_recovered),
        cmocka_unit_test(covariance_convention_matches_linear_fit),
        cmocka_unit_test(steps_outside_the_domain_are_rejected),
        cmocka_unit_test(exact_data_failures_and_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
