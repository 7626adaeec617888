/* Histograms, moments, kurtosis, the eq. 3.4 law and the KS distance. */
#include "test.h"

#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_randist.h>

#include "rng.h"
#include "stats.h"

static double *gauss_samples(size_t n, uint64_t stream)
{
    gr_err e = {0};
    gr_rng *r = gr_rng_create(1234, stream, &e);
    assert_non_null(r);
    double *x = malloc(n * sizeof *x);
    assert_non_null(x);
    for (size_t i = 0; i < n; i++)
        x[i] = gr_rng_gaussian(r, 1.0);
    gr_rng_free(r);
    return x;
}

/* Samples of eq. 3.4: Student t with 3 degrees of freedom over sqrt(3). */
static double *eq34_samples(size_t n, uint64_t stream)
{
    gr_err e = {0};
    gr_rng *r = gr_rng_create(1234, stream, &e);
    assert_non_null(r);
    double *x = malloc(n * sizeof *x);
    assert_non_null(x);
    for (size_t i = 0; i < n; i++)
        x[i] = gsl_ran_tdist(gr_rng_gsl(r), 3.0) / sqrt(3.0);
    gr_rng_free(r);
    return x;
}

/* A histogram of N(0,1) samples is the Gaussian density: chi2 test passes
 * against the Gaussian and fails against eq. 3.4 (same unit variance). */
static void gaussian_histogram_matches_density(void **state)
{
    (void)state;
    gr_err e = {0};
    size_t n = 100000, nb = 40;
    double *x = gauss_samples(n, 1);
    gr_hist *h = gr_hist_create(nb, -4.0, 4.0, &e);
    assert_non_null(h);
    gr_hist_add_array(h, x, n);
    assert_int_equal(h->n_total, n);

    double c[40], d[40], s[40], integral = 0.0;
    gr_hist_density(h, c, d, s);
    for (size_t i = 0; i < nb; i++) {
        integral += d[i] * 0.2;
        /* each bin within 5 Poisson errors of the exact bin average */
        double exact = (gr_cdf_gauss_cb(c[i] + 0.1, NULL) - gr_cdf_gauss_cb(c[i] - 0.1, NULL)) / 0.2;
        if (d[i] > 0)
            assert_true(fabs(d[i] - exact) < 5.0 * s[i] + 1e-12);
    }
    double outside = (double)(h->n_below + h->n_above) / (double)n;
    assert_close(integral + outside, 1.0, 1e-12);
    assert_close(c[0], -3.9, 1e-12);

    double chi2, p;
    int dof;
    assert_int_equal(gr_hist_chi2(h, gr_cdf_gauss_cb, NULL, 5.0, &chi2, &dof, &p, &e), GR_OK);
    print_message("# gaussian vs gaussian: chi2 = %.1f, dof = %d, p = %.3f\n", chi2, dof, p);
    assert_true(dof >= 30);
    assert_true(p > 1e-3);
    assert_int_equal(gr_hist_chi2(h, gr_cdf_eq34_cb, NULL, 5.0, &chi2, &dof, &p, &e), GR_OK);
    print_message("# gaussian vs eq. 3.4: chi2 = %.1f, dof = %d, p = %.3g\n", chi2, dof, p);
    assert_true(p < 1e-10);

    /* merging doubles counts and keeps the density */
    gr_hist *h2 = gr_hist_create(nb, -4.0, 4.0, &e);
    gr_hist_add_array(h2, x, n);
    assert_int_equal(gr_hist_merge(h2, h, &e), GR_OK);
    double d2[40];
    gr_hist_density(h2, NULL, d2, NULL);
    for (size_t i = 0; i < nb; i++)
        assert_close(d2[i], d[i], 1e-15);
    gr_hist *h3 = gr_hist_create(nb + 1, -4.0, 4.0, &e);
    assert_int_equal(gr_hist_merge(h3, h, &e), GR_EINPUT);
    gr_hist_free(h3);
    gr_hist_free(h2);
    gr_hist_free(h);
    free(x);
}

static void histogram_from_data_and_edges(void **state)
{
    (void)state;
    gr_err e = {0};
    double x[] = {-1.0, 0.5, 2.0, 3.0, 3.0};
    gr_hist *h = gr_hist_from_data(x, 5, 4, 0, &e);
    assert_non_null(h);
    assert_int_equal(h->n_below + h->n_above, 0); /* the maximum is counted */
    assert_close(gsl_histogram_get(h->h, 3), 2.0, 0);
    gr_hist_free(h);
    h = gr_hist_from_data(x, 5, 6, 1, &e); /* symmetric: [-3, 3] */
    assert_close(gsl_histogram_min(h->h), -3.0, 1e-12);
    assert_int_equal(h->n_below + h->n_above, 0);
    gr_hist_add(h, NAN);
    gr_hist_add(h, -10.0);
    assert_int_equal(h->n_above, 1);
    assert_int_equal(h->n_below, 1);
    assert_int_equal(h->n_total, 7);
    gr_hist_free(h);
    double same[] = {1.0, 1.0};
    assert_null(gr_hist_from_data(same, 2, 4, 0, &e));
    assert_int_equal(e.code, GR_EINPUT);
    assert_null(gr_hist_create(0, 0.0, 1.0, &e));
    assert_null(gr_hist_create(4, 1.0, 1.0, &e));
    gr_hist_free(NULL);
}

static double integrand_pdf(double x, void *k)
{
    return pow(x, *(int *)k) * gr_pdf_eq34(x);
}

/* Eq. 3.4 as printed: unit area, unit variance, CDF consistent, and the
 * c = 3/2 member of the unit-variance Tsallis family. */
static void eq34_is_normalised_with_unit_variance(void **state)
{
    (void)state;
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(1000);
    gsl_function F = {integrand_pdf, NULL};
    double res, abserr;
    int k = 0;
    F.params = &k;
    assert_int_equal(gsl_integration_qagi(&F, 1e-12, 1e-12, 1000, w, &res, &abserr), 0);
    assert_close(res, 1.0, 1e-9);
    k = 2;
    assert_int_equal(gsl_integration_qagi(&F, 1e-12, 1e-12, 1000, w, &res, &abserr), 0);
    print_message("# eq. 3.4: variance integral = %.12f\n", res);
    assert_close(res, 1.0, 1e-8);
    gsl_integration_workspace_free(w);

    for (double x = -6.0; x <= 6.0; x += 0.37) {
        double h = 1e-5;
        double dcdf = (gr_cdf_eq34(x + h) - gr_cdf_eq34(x - h)) / (2 * h);
        assert_close(dcdf, gr_pdf_eq34(x), 1e-8);
        assert_close(gr_pdf_tsallis_unit(x, 1.5), gr_pdf_eq34(x), 1e-12);
        assert_close(gr_cdf_tsallis_unit(x, 1.5), gr_cdf_eq34(x), 1e-12);
        assert_close(gr_pdf_eq34_sd(2.0 * x, 2.0), 0.5 * gr_pdf_eq34(x), 1e-15);
        /* c -> infinity is the unit Gaussian */
        assert_close(gr_pdf_tsallis_unit(x, 1e7), gsl_ran_ugaussian_pdf(x), 1e-6);
    }
    assert_close(gr_cdf_eq34(0.0), 0.5, 1e-15);
    assert_close(gr_cdf_eq34(-INFINITY), 0.0, 0);
    assert_true(isnan(gr_pdf_tsallis_unit(0.0, 1.0)));
}

/* KS distance: Gaussian data accepted by the Gaussian CDF and rejected by
 * eq. 3.4; eq. 3.4 data accepted by eq. 3.4. */
static void ks_distance_discriminates(void **state)
{
    (void)state;
    gr_err e = {0};
    size_t n = 20000;
    double *g = gauss_samples(n, 2), *t = eq34_samples(n, 3), d;
    assert_int_equal(gr_ks_distance(g, n, gr_cdf_gauss_cb, NULL, &d, &e), GR_OK);
    print_message("# KS gauss/gauss D = %.4f p = %.3f\n", d, gr_ks_pvalue(d, n));
    assert_true(gr_ks_pvalue(d, n) > 0.01);
    assert_true(d < 1.63 / sqrt((double)n));
    assert_int_equal(gr_ks_distance(g, n, gr_cdf_eq34_cb, NULL, &d, &e), GR_OK);
    print_message("# KS gauss/eq34 D = %.4f p = %.3g\n", d, gr_ks_pvalue(d, n));
    assert_true(gr_ks_pvalue(d, n) < 1e-6);
    assert_int_equal(gr_ks_distance(t, n, gr_cdf_eq34_cb, NULL, &d, &e), GR_OK);
    print_message("# KS eq34/eq34 D = %.4f p = %.3f\n", d, gr_ks_pvalue(d, n));
    assert_true(gr_ks_pvalue(d, n) > 0.01);
    /* Kolmogorov distribution: Q(1.358) = 0.05 */
    assert_close(gr_ks_pvalue(1.358 / (sqrt(1e8) + 0.12 + 0.11 / sqrt(1e8)), 100000000),
                        0.05, 2e-4);
    free(g);
    free(t);
}

/* Excess kurtosis: 0 for a Gaussian, 3 for Laplace, -1.2 for uniform; the
 * thesis's kappa about zero is a third of it for zero-mean laws. */
static void kurtosis_of_known_laws(void **state)
{
    (void)state;
    gr_err e = {0};
    size_t n = 400000;
    gr_rng *r = gr_rng_create(99, 0, &e);
    gr_moments *g = gr_moments_create(&e), *l = gr_moments_create(&e), *u = gr_moments_create(&e);
    assert_non_null(g);
    double *lx = malloc(n * sizeof *lx);
    for (size_t i = 0; i < n; i++) {
        gr_moments_add(g, gr_rng_gaussian(r, 2.0));
        lx[i] = gsl_ran_laplace(gr_rng_gsl(r), 0.7);
        gr_moments_add(l, lx[i]);
        gr_moments_add(u, 2.0 * gr_rng_uniform(r) - 1.0);
    }
    print_message("# kappa: gauss %.4f laplace %.4f uniform %.4f\n", gr_moments_kappa_zero(g),
                  gr_moments_kappa_zero(l), gr_moments_kappa_zero(u));
    /* sd of the excess estimate: sqrt(24/n) = 0.008 (Gauss), about
     * 50/sqrt(n) = 0.08 (Laplace, from its 8th moment); kappa has a third */
    assert_close(gr_moments_kappa_zero(g), 0.0, 0.015);
    assert_close(gr_moments_kurtosis(g), 0.0, 0.04);
    assert_close(gr_moments_kappa_zero(l), 1.0, 0.1);
    assert_close(gr_moments_kurtosis(l), 3.0, 0.3);
    assert_close(gr_moments_kappa_zero(u), -0.4, 0.01);
    assert_close(gr_moments_kurtosis(u), -1.2, 0.02);
    assert_close(gr_kappa_zero(lx, n), gr_moments_kappa_zero(l), 1e-9);
    /* <x^2> of a Laplace law of scale b is 2 b^2 */
    assert_close(gr_moments_m2_zero(l), 2 * 0.49, 0.01);
    assert_close(gr_moments_sd(g), 2.0, 0.01);
    assert_close(gr_moments_mean(g), 0.0, 5 * gr_moments_sd_mean(g));
    assert_close(gr_moments_skew(l), 0.0, 0.1);
    assert_int_equal(gr_moments_n(u), n);
    assert_true(gr_moments_min(u) >= -1.0 && gr_moments_max(u) < 1.0);
    gr_moments_reset(g);
    assert_int_equal(gr_moments_n(g), 0);
    assert_true(isnan(gr_moments_mean(g)));
    free(lx);
    gr_moments_free(g);
    gr_moments_free(l);
    gr_moments_free(u);
    gr_moments_free(NULL);
    gr_rng_free(r);
}

static void exact_small_statistics(void **state)
{
    (void)state;
    gr_err e = {0};
    gr_moments *m = gr_moments_create(&e);
    double x[] = {1.0, 2.0, 3.0, 4.0};
    gr_moments_add_array(m, x, 4);
    assert_close(gr_moments_mean(m), 2.5, 1e-15);
    assert_close(gr_moments_variance(m), 5.0 / 3.0, 1e-14);
    assert_close(gr_moments_m2_zero(m), 7.5, 1e-14);
    assert_close(gr_moments_m4_zero(m), (1 + 16 + 81 + 256) / 4.0, 1e-12);
    gr_moments_free(m);

    double w[] = {1.0, 1.0, 2.0};
    assert_close(gr_wmean(w, x, 3), 2.25, 1e-15);
    double z[] = {0.0, 0.0};
    assert_true(isnan(gr_wmean(z, x, 2)));

    /* blocks of 100 equal values b = 0..9, plus a 50-sample tail dropped */
    double s[1050], bm[10], mean, sem;
    for (size_t i = 0; i < 1050; i++)
        s[i] = (double)(i / 100);
    assert_int_equal(gr_block_average(s, 1050, 100, bm, &mean, &sem), 10);
    assert_close(bm[7], 7.0, 0);
    assert_close(mean, 4.5, 1e-14);
    assert_close(sem, sqrt(55.0 / 6.0) / sqrt(10.0), 1e-12);
    assert_int_equal(gr_block_average(s, 1050, 600, NULL, &mean, &sem), 1);
    assert_true(isnan(sem));

    double y[] = {2.0, 4.0, 6.0, 8.0}, o[4], mu, sd;
    assert_int_equal(gr_standardize(y, 4, 1, o, &mu, &sd, &e), GR_OK);
    assert_close(mu, 5.0, 1e-15);
    assert_close(o[0], -3.0 / sd, 1e-15);
    assert_close(o[0] + o[1] + o[2] + o[3], 0.0, 1e-14);
    assert_int_equal(gr_standardize(y, 4, 0, o, NULL, &sd, &e), GR_OK);
    assert_close(sd, sqrt(30.0), 1e-14);
    assert_int_equal(gr_standardize(z, 2, 1, o, NULL, NULL, &e), GR_EINPUT);
    assert_int_equal(gr_reduce_by_mean(y, 4, o, &e), GR_OK);
    assert_close(o[3], 1.6, 1e-15);
    assert_int_equal(gr_reduce_by_mean(z, 2, o, &e), GR_EINPUT);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(gaussian_histogram_matches_density),
        cmocka_unit_test(histogram_from_data_and_edges),
        cmocka_unit_test(eq34_is_normalised_with_unit_variance),
        cmocka_unit_test(ks_distance_discriminates),
        cmocka_unit_test(kurtosis_of_known_laws),
        cmocka_unit_test(exact_small_statistics),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
