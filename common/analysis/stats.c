/* Histograms, moments, block averages, distributions and the KS distance;
 * the fits are in fit.c. */
#include "stats.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_math.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rstat.h>
#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>

/* ---------------------------------------------------------------- histograms */

gr_hist *gr_hist_create(size_t nbins, double lo, double hi, gr_err *err)
{
    if (nbins == 0 || !isfinite(lo) || !isfinite(hi) || !(hi > lo)) {
        gr_fail(err, GR_EINPUT, "histogram: need nbins >= 1 and finite lo < hi (got %zu, %g, %g)",
                nbins, lo, hi);
        return NULL;
    }
    gr_hist *h = calloc(1, sizeof *h);
    if (h)
        h->h = gsl_histogram_calloc_uniform(nbins, lo, hi);
    if (!h || !h->h) {
        free(h);
        gr_fail(err, GR_ERUN, "histogram: out of memory (%zu bins)", nbins);
        return NULL;
    }
    return h;
}

gr_hist *gr_hist_from_data(const double *x, size_t n, size_t nbins, int symmetric,
                           gr_err *err)
{
    if (n == 0) {
        gr_fail(err, GR_EINPUT, "histogram from data: no samples");
        return NULL;
    }
    double lo = x[0], hi = x[0], amax = 0.0;
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(x[i])) {
            gr_fail(err, GR_EINPUT, "histogram from data: sample %zu is not finite", i);
            return NULL;
        }
        lo = fmin(lo, x[i]);
        hi = fmax(hi, x[i]);
        amax = fmax(amax, fabs(x[i]));
    }
    if (symmetric) {
        lo = -amax;
        hi = amax;
    }
    if (!(hi > lo)) {
        gr_fail(err, GR_EINPUT, "histogram from data: all %zu samples equal %g", n, x[0]);
        return NULL;
    }
    /* GSL bins are half open; widen a hair so that the maximum is counted. */
    hi += 1e-9 * (hi - lo);
    gr_hist *h = gr_hist_create(nbins, lo, hi, err);
    if (h)
        gr_hist_add_array(h, x, n);
    return h;
}

void gr_hist_free(gr_hist *h)
{
    if (!h)
        return;
    gsl_histogram_free(h->h);
    free(h);
}

void gr_hist_reset(gr_hist *h)
{
    gsl_histogram_reset(h->h);
    h->n_total = h->n_below = h->n_above = 0;
}

void gr_hist_add(gr_hist *h, double x)
{
    h->n_total++;
    /* Decided here rather than by GSL: its bin search is undefined for NaN. */
    if (x < gsl_histogram_min(h->h))
        h->n_below++;
    else if (!(x < gsl_histogram_max(h->h)))
        h->n_above++;
    else
        gsl_histogram_increment(h->h, x);
}

void gr_hist_add_array(gr_hist *h, const double *x, size_t n)
{
    for (size_t i = 0; i < n; i++)
        gr_hist_add(h, x[i]);
}

int gr_hist_merge(gr_hist *dst, const gr_hist *src, gr_err *err)
{
    if (!gsl_histogram_equal_bins_p(dst->h, src->h))
        return gr_fail(err, GR_EINPUT, "histogram merge: different binning");
    gsl_histogram_add(dst->h, src->h);
    dst->n_total += src->n_total;
    dst->n_below += src->n_below;
    dst->n_above += src->n_above;
    return GR_OK;
}

size_t gr_hist_bins(const gr_hist *h) { return gsl_histogram_bins(h->h); }

void gr_hist_density(const gr_hist *h, double *centre, double *density, double *error)
{
    size_t nb = gsl_histogram_bins(h->h);
    for (size_t i = 0; i < nb; i++) {
        double lo, hi;
        gsl_histogram_get_range(h->h, i, &lo, &hi);
        double c = gsl_histogram_get(h->h, i);
        double norm = h->n_total ? 1.0 / ((double)h->n_total * (hi - lo)) : 0.0;
        if (centre)
            centre[i] = 0.5 * (lo + hi);
        if (density)
            density[i] = c * norm;
        if (error)
            error[i] = sqrt(c) * norm;
    }
}

int gr_hist_chi2(const gr_hist *h, gr_cdf_fn cdf, void *user, double min_expected,
                 double *chi2, int *dof, double *pvalue, gr_err *err)
{
    size_t nb = gsl_histogram_bins(h->h);
    double n = (double)h->n_total;
    if (h->n_total == 0)
        return gr_fail(err, GR_EINPUT, "histogram chi2: no samples");
    if (min_expected <= 0)
        min_expected = 5.0;
    /* Bins 0 and nb+1 are the out-of-range tails. */
    double s = 0.0, go = 0.0, ge = 0.0, last_o = 0.0, last_e = 0.0;
    int groups = 0;
    double fprev = 0.0;
    for (size_t i = 0; i <= nb + 1; i++) {
        double o, fnext;
        if (i == 0) {
            o = (double)h->n_below;
            fnext = cdf(gsl_histogram_min(h->h), user);
        } else if (i <= nb) {
            double lo, hi;
            gsl_histogram_get_range(h->h, i - 1, &lo, &hi);
            o = gsl_histogram_get(h->h, i - 1);
            fnext = cdf(hi, user);
        } else {
            o = (double)h->n_above;
            fnext = 1.0;
        }
        if (!isfinite(fnext))
            return gr_fail(err, GR_EINPUT, "histogram chi2: CDF is not finite at bin %zu", i);
        go += o;
        ge += n * (fnext - fprev);
        fprev = fnext;
        if (ge >= min_expected) {
            if (groups > 0)
                s += (last_o - last_e) * (last_o - last_e) / last_e;
            last_o = go;
            last_e = ge;
            groups++;
            go = ge = 0.0;
        }
    }
    if (groups < 2)
        return gr_fail(err, GR_EINPUT,
                       "histogram chi2: fewer than 2 bins with %g expected counts", min_expected);
    /* The short remainder joins the last full group. */
    last_o += go;
    last_e += ge;
    s += (last_o - last_e) * (last_o - last_e) / last_e;
    *chi2 = s;
    *dof = groups - 1;
    if (pvalue)
        *pvalue = gsl_cdf_chisq_Q(s, groups - 1);
    return GR_OK;
}

/* ------------------------------------------------------------------ moments */

struct gr_moments {
    gsl_rstat_workspace *rs;
    double s2, s4; /* raw power sums about zero */
};

gr_moments *gr_moments_create(gr_err *err)
{
    gr_moments *m = calloc(1, sizeof *m);
    if (m)
        m->rs = gsl_rstat_alloc();
    if (!m || !m->rs) {
        free(m);
        gr_fail(err, GR_ERUN, "moments: out of memory");
        return NULL;
    }
    return m;
}

void gr_moments_free(gr_moments *m)
{
    if (!m)
        return;
    gsl_rstat_free(m->rs);
    free(m);
}

void gr_moments_reset(gr_moments *m)
{
    gsl_rstat_reset(m->rs);
    m->s2 = m->s4 = 0.0;
}

void gr_moments_add(gr_moments *m, double x)
{
    gsl_rstat_add(x, m->rs);
    double x2 = x * x;
    m->s2 += x2;
    m->s4 += x2 * x2;
}

void gr_moments_add_array(gr_moments *m, const double *x, size_t n)
{
    for (size_t i = 0; i < n; i++)
        gr_moments_add(m, x[i]);
}

size_t gr_moments_n(const gr_moments *m) { return gsl_rstat_n(m->rs); }

/* GSL's values for fewer samples than a moment needs are 0, not NaN. */
static int has(const gr_moments *m, size_t k) { return gsl_rstat_n(m->rs) >= k; }

double gr_moments_mean(const gr_moments *m) { return has(m, 1) ? gsl_rstat_mean(m->rs) : NAN; }
double gr_moments_variance(const gr_moments *m)
{
    return has(m, 2) ? gsl_rstat_variance(m->rs) : NAN;
}
double gr_moments_sd(const gr_moments *m) { return has(m, 2) ? gsl_rstat_sd(m->rs) : NAN; }
double gr_moments_sd_mean(const gr_moments *m)
{
    return has(m, 2) ? gsl_rstat_sd_mean(m->rs) : NAN;
}
double gr_moments_skew(const gr_moments *m) { return has(m, 2) ? gsl_rstat_skew(m->rs) : NAN; }
double gr_moments_kurtosis(const gr_moments *m)
{
    return has(m, 2) ? gsl_rstat_kurtosis(m->rs) : NAN;
}
double gr_moments_min(const gr_moments *m) { return has(m, 1) ? gsl_rstat_min(m->rs) : NAN; }
double gr_moments_max(const gr_moments *m) { return has(m, 1) ? gsl_rstat_max(m->rs) : NAN; }

double gr_moments_m2_zero(const gr_moments *m)
{
    size_t n = gsl_rstat_n(m->rs);
    return n ? m->s2 / (double)n : NAN;
}

double gr_moments_m4_zero(const gr_moments *m)
{
    size_t n = gsl_rstat_n(m->rs);
    return n ? m->s4 / (double)n : NAN;
}

double gr_moments_kappa_zero(const gr_moments *m)
{
    double m2 = gr_moments_m2_zero(m);
    return gr_moments_m4_zero(m) / (3.0 * m2 * m2) - 1.0;
}

double gr_kappa_zero(const double *x, size_t n)
{
    if (n == 0)
        return NAN;
    double s2 = 0.0, s4 = 0.0;
    for (size_t i = 0; i < n; i++) {
        double x2 = x[i] * x[i];
        s2 += x2;
        s4 += x2 * x2;
    }
    s2 /= (double)n;
    s4 /= (double)n;
    return s4 / (3.0 * s2 * s2) - 1.0;
}

double gr_wmean(const double *w, const double *x, size_t n)
{
    double sw = 0.0;
    for (size_t i = 0; i < n; i++)
        sw += w[i];
    if (n == 0 || sw == 0.0)
        return NAN;
    return gsl_stats_wmean(w, 1, x, 1, n);
}

size_t gr_block_average(const double *x, size_t n, size_t block, double *out,
                        double *mean, double *sem)
{
    size_t nb = block ? n / block : 0;
    double *bm = out ? out : (nb ? malloc(nb * sizeof *bm) : NULL);
    if (nb && !bm)
        nb = 0; /* out of memory: reported as no blocks */
    for (size_t b = 0; b < nb; b++)
        bm[b] = gsl_stats_mean(x + b * block, 1, block);
    double mu = nb ? gsl_stats_mean(bm, 1, nb) : NAN;
    double se = nb > 1 ? gsl_stats_sd_m(bm, 1, nb, mu) / sqrt((double)nb) : NAN;
    if (mean)
        *mean = mu;
    if (sem)
        *sem = se;
    if (bm != out)
        free(bm);
    return nb;
}

int gr_standardize(const double *x, size_t n, int center, double *out, double *mean,
                   double *sd, gr_err *err)
{
    if (n < 2)
        return gr_fail(err, GR_EINPUT, "standardize: need at least 2 samples (got %zu)", n);
    double mu = gsl_stats_mean(x, 1, n);
    double s;
    if (center) {
        s = gsl_stats_sd_m(x, 1, n, mu);
    } else {
        s = 0.0;
        for (size_t i = 0; i < n; i++)
            s += x[i] * x[i];
        s = sqrt(s / (double)n);
    }
    if (!(s > 0.0) || !isfinite(s))
        return gr_fail(err, GR_EINPUT, "standardize: scale is %g", s);
    double c = center ? mu : 0.0;
    for (size_t i = 0; i < n; i++)
        out[i] = (x[i] - c) / s;
    if (mean)
        *mean = mu;
    if (sd)
        *sd = s;
    return GR_OK;
}

int gr_reduce_by_mean(const double *x, size_t n, double *out, gr_err *err)
{
    if (n == 0)
        return gr_fail(err, GR_EINPUT, "reduce by mean: no samples");
    double mu = gsl_stats_mean(x, 1, n);
    if (!(mu != 0.0) || !isfinite(mu))
        return gr_fail(err, GR_EINPUT, "reduce by mean: mean is %g", mu);
    for (size_t i = 0; i < n; i++)
        out[i] = x[i] / mu;
    return GR_OK;
}

/* ---------------------------------------------------- distributions, KS test */

double gr_pdf_eq34(double x)
{
    double u = 1.0 + x * x;
    return M_2_PI / (u * u);
}

double gr_cdf_eq34(double x)
{
    if (isinf(x))
        return x > 0 ? 1.0 : 0.0;
    return 0.5 + (atan(x) + x / (1.0 + x * x)) / M_PI;
}

double gr_pdf_eq34_sd(double x, double sigma) { return gr_pdf_eq34(x / sigma) / sigma; }

double gr_pdf_tsallis_unit(double x, double c)
{
    if (!(c > 1.0))
        return NAN;
    if (isinf(c))
        return gsl_ran_ugaussian_pdf(x);
    double nu = 2.0 * c, s = sqrt((nu - 2.0) / nu);
    return gsl_ran_tdist_pdf(x / s, nu) / s;
}

double gr_cdf_tsallis_unit(double x, double c)
{
    if (!(c > 1.0))
        return NAN;
    if (isinf(c))
        return gsl_cdf_ugaussian_P(x);
    double nu = 2.0 * c, s = sqrt((nu - 2.0) / nu);
    return gsl_cdf_tdist_P(x / s, nu);
}

double gr_cdf_eq34_cb(double x, void *user)
{
    (void)user;
    return gr_cdf_eq34(x);
}

double gr_cdf_gauss_cb(double x, void *sigma)
{
    return gsl_cdf_gaussian_P(x, sigma ? *(const double *)sigma : 1.0);
}

int gr_ks_distance(const double *x, size_t n, gr_cdf_fn cdf, void *user, double *d,
                   gr_err *err)
{
    if (n == 0)
        return gr_fail(err, GR_EINPUT, "KS distance: no samples");
    double *s = malloc(n * sizeof *s);
    if (!s)
        return gr_fail(err, GR_ERUN, "KS distance: out of memory (%zu samples)", n);
    memcpy(s, x, n * sizeof *s);
    gsl_sort(s, 1, n);
    double dmax = 0.0, fn = 1.0 / (double)n;
    int bad = 0;
    for (size_t i = 0; i < n && !bad; i++) {
        double f = cdf(s[i], user);
        if (!isfinite(f) || !isfinite(s[i]))
            bad = 1;
        dmax = fmax(dmax, fmax(f - (double)i * fn, (double)(i + 1) * fn - f));
    }
    free(s);
    if (bad)
        return gr_fail(err, GR_EINPUT, "KS distance: a sample or its CDF is not finite");
    *d = dmax;
    return GR_OK;
}

double gr_ks_pvalue(double d, size_t n)
{
    double rn = sqrt((double)n);
    double lam = (rn + 0.12 + 0.11 / rn) * d;
    if (lam < 0.2)
        return 1.0; /* Q(0.2) = 1 - 5e-13; the series would cancel badly */
    double sum = 0.0, sign = 1.0;
    for (int j = 1; j <= 100; j++) {
        double term = exp(-2.0 * j * j * lam * lam);
        sum += sign * term;
        if (term < 1e-12 * fabs(sum))
            break;
        sign = -sign;
    }
    return fmin(1.0, fmax(0.0, 2.0 * sum));
}
