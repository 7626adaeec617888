/* Statistics and fits on GSL: histograms as probability densities, running
 * moments (with the thesis's kurtosis about zero), block averages, the
 * Kolmogorov-Smirnov distance, the displacement law of the silo studies
 * (thesis eq. 3.4 / 4.4), and non-linear least squares with parameter
 * errors (gsl_multifit_nlinear) with the models of the silo experiments.
 *
 * GSL's default error handler aborts; programs that call these functions
 * should install gsl_set_error_handler_off() in main (library code never
 * touches that global). Every failure is reported through gr_err. */
#ifndef GR_STATS_H
#define GR_STATS_H

#include <stddef.h>

#include <gsl/gsl_histogram.h>

#include "err.h"

/* ---------------------------------------------------------------- histograms */

/* A gsl_histogram of counts plus the samples that fell outside its range,
 * so that the density is normalised by every sample seen: a density that
 * integrates to the fraction of samples in range, which is the unbiased
 * estimate of the underlying pdf on each bin. */
typedef struct {
    gsl_histogram *h;
    size_t n_total;          /* every sample offered, in range or not */
    size_t n_below, n_above; /* out of range; NaN samples count as above */
} gr_hist;

/* nbins uniform bins on [lo, hi). */
gr_hist *gr_hist_create(size_t nbins, double lo, double hi, gr_err *err);
/* nbins uniform bins spanning the data: [min, max] (max included), or
 * [-m, m] with m = max |x| when symmetric != 0 (displacements, flow
 * fluctuations). The samples are added. n >= 1 finite values required. */
gr_hist *gr_hist_from_data(const double *x, size_t n, size_t nbins, int symmetric,
                           gr_err *err);
void gr_hist_free(gr_hist *h);
void gr_hist_reset(gr_hist *h);
void gr_hist_add(gr_hist *h, double x);
void gr_hist_add_array(gr_hist *h, const double *x, size_t n);
/* Add the counts of src (same binning) to dst, e.g. over realisations. */
int gr_hist_merge(gr_hist *dst, const gr_hist *src, gr_err *err);
size_t gr_hist_bins(const gr_hist *h);
/* Per bin: centre, density count / (n_total width), and its Poisson error
 * sqrt(count) / (n_total width). Any output may be NULL. With no samples
 * the density and error are 0. */
void gr_hist_density(const gr_hist *h, double *centre, double *density, double *error);
/* Pearson chi2 of the counts against the distribution with CDF cdf:
 * expected count n_total (F(hi) - F(lo)) per bin; bins with expected count
 * below min_expected (5 if <= 0) are pooled with the next ones, left to
 * right (a short last group joins the previous one). The samples below and
 * above the range are two more bins, so expected counts sum to n_total and
 * dof = groups - 1. *pvalue (may be NULL) from gsl_cdf_chisq_Q. */
typedef double (*gr_cdf_fn)(double x, void *user);
int gr_hist_chi2(const gr_hist *h, gr_cdf_fn cdf, void *user, double min_expected,
                 double *chi2, int *dof, double *pvalue, gr_err *err);

/* ------------------------------------------------------------------ moments */

/* Running moments on gsl_rstat (mean, variance, skewness, excess kurtosis,
 * all about the mean) plus raw sums about zero for the thesis's kurtosis
 * kappa = <x^4> / (3 <x^2>^2) - 1 of a zero-mean component (displacements
 * with the flow subtracted). Note kappa is the usual excess kurtosis
 * <x^4>/<x^2>^2 - 3 divided by 3: zero for a Gaussian, but 1 (not 3) for a
 * Laplace law and -0.4 (not -1.2) for a uniform one; the thesis calls it
 * "exceso de curtosis" (fig. 3.6), so compare its values with kappa. */
typedef struct gr_moments gr_moments;

gr_moments *gr_moments_create(gr_err *err);
void gr_moments_free(gr_moments *m);
void gr_moments_reset(gr_moments *m);
void gr_moments_add(gr_moments *m, double x);
void gr_moments_add_array(gr_moments *m, const double *x, size_t n);
size_t gr_moments_n(const gr_moments *m);
double gr_moments_mean(const gr_moments *m);
double gr_moments_variance(const gr_moments *m); /* unbiased, n - 1 */
double gr_moments_sd(const gr_moments *m);
double gr_moments_sd_mean(const gr_moments *m);  /* sd / sqrt(n) */
double gr_moments_skew(const gr_moments *m);
double gr_moments_kurtosis(const gr_moments *m); /* excess, about the mean */
double gr_moments_min(const gr_moments *m);
double gr_moments_max(const gr_moments *m);
double gr_moments_m2_zero(const gr_moments *m);  /* <x^2> about zero */
double gr_moments_m4_zero(const gr_moments *m);  /* <x^4> about zero */
double gr_moments_kappa_zero(const gr_moments *m); /* <x^4>/(3<x^2>^2) - 1 */

/* One-shot versions on an array (NaN for n == 0). */
double gr_kappa_zero(const double *x, size_t n);
/* sum w x / sum w through gsl_stats_wmean; NaN if the weights sum to 0. */
double gr_wmean(const double *w, const double *x, size_t n);

/* Blocks of `block` consecutive samples (the tail that does not fill a
 * block is dropped): block means into out (may be NULL, room for n/block),
 * their mean and the standard error of that mean from the scatter of the
 * block means (needs at least two blocks; NaN otherwise). Returns the
 * number of blocks. The flow-rate series of silo-flow is one use. */
size_t gr_block_average(const double *x, size_t n, size_t block, double *out,
                        double *mean, double *sem);

/* out[i] = (x[i] - mean) / sd (center != 0) or x[i] / sd about zero
 * (center == 0: sd is then sqrt(<x^2>)), the scale of the thesis's
 * normalised distributions. out may equal x. *mean, *sd may be NULL.
 * Fails (GR_EINPUT) if n < 2 or the scale is zero. */
int gr_standardize(const double *x, size_t n, int center, double *out, double *mean,
                   double *sd, gr_err *err);
/* out[i] = x[i] / mean(x): the reduced flow w = W / <W> of thesis eq. 4.2. */
int gr_reduce_by_mean(const double *x, size_t n, double *out, gr_err *err);

/* ---------------------------------------------------- distributions, KS test */

/* Thesis eq. 3.4 (and 4.4): P(x) = (2/pi) / (1 + x^2)^2. Checked: as
 * printed it is already a normalised density (integral of 1/(1+x^2)^2 is
 * pi/2) with unit variance (integral of x^2/(1+x^2)^2 is pi/2), so it is
 * drawn without any fit against data scaled to unit standard deviation, as
 * the thesis does. It is Student's t with 3 degrees of freedom divided by
 * sqrt(3) (the member c = 3/2, b = 2 of eq. 3.8): its fourth moment
 * diverges, so its excess kurtosis is infinite and the sample kurtosis of
 * such data grows with the sample size. CDF: 1/2 + (atan x + x/(1+x^2))/pi. */
double gr_pdf_eq34(double x);
double gr_cdf_eq34(double x);
/* The same law at standard deviation sigma: P(x/sigma)/sigma. */
double gr_pdf_eq34_sd(double x, double sigma);
/* Eq. 3.8 at unit variance for any c > 1 (Student t, nu = 2c, rescaled);
 * c = 3/2 is eq. 3.4, c -> infinity the unit Gaussian. Tsallis index
 * q = 1 + 1/(c + 1/2). NaN for c <= 1. */
double gr_pdf_tsallis_unit(double x, double c);
double gr_cdf_tsallis_unit(double x, double c);
/* Callback adaptors (user ignored / user points to a double sigma or c). */
double gr_cdf_eq34_cb(double x, void *user);
double gr_cdf_gauss_cb(double x, void *sigma); /* NULL: sigma = 1 */

/* Kolmogorov-Smirnov distance sup |F_n(x) - F(x)| of n samples (copied and
 * sorted; x is not modified) against the CDF. */
int gr_ks_distance(const double *x, size_t n, gr_cdf_fn cdf, void *user, double *d,
                   gr_err *err);
/* Asymptotic probability of a distance >= d under the null hypothesis
 * (Kolmogorov series with Stephens' small-n correction). */
double gr_ks_pvalue(double d, size_t n);

/* --------------------------------------------------------------------- fits */

#define GR_FIT_MAXP 8

/* A model y = f(x; p). When dydp is non-NULL (only if the model declares
 * an analytic Jacobian) it receives the np partial derivatives. A model
 * returns a non-finite value where it is undefined: at the start that is
 * GR_EINPUT, during the iteration the trial step is rejected. */
typedef double (*gr_model_fn)(double x, const double *p, double *dydp, void *user);

typedef struct {
    const char *name;
    size_t np;                      /* <= GR_FIT_MAXP */
    gr_model_fn f;
    int analytic_jac;               /* 0: central finite differences */
    void *user;
    const char *pnames[GR_FIT_MAXP]; /* for messages; may be NULL */
} gr_model;

enum { GR_FIT_SCALE_AUTO = 0, GR_FIT_SCALE_ALWAYS = 1, GR_FIT_SCALE_NEVER = 2 };

typedef struct {
    size_t max_iter;     /* 0: 500 */
    double xtol, gtol, ftol; /* <= 0: 1e-10, 1e-10, 1e-12 */
    int scale;           /* GR_FIT_SCALE_*: AUTO scales the errors by
                            sqrt(chi2/dof) when no sigma is given */
    int geodesic;        /* 1: Levenberg-Marquardt with geodesic
                            acceleration; 0: plain LM trust region */
} gr_fit_opts;

typedef struct {
    size_t np, n;
    double p[GR_FIT_MAXP];
    double err[GR_FIT_MAXP];             /* standard errors */
    double cov[GR_FIT_MAXP][GR_FIT_MAXP]; /* covariance (scaled like err) */
    double chi2;     /* sum of squared residuals, weighted by 1/sigma^2 */
    double dof;      /* n - np */
    double chi2_dof;
    int weighted;    /* sigma was given */
    int scaled;      /* errors were multiplied by sqrt(chi2/dof) */
    size_t iter, nfev;
    int info;        /* GSL stop reason: 1 step size, 2 gradient (0 linear) */
} gr_fit;

/* Weighted (sigma[i] > 0, may be NULL) non-linear least squares from the
 * start p0 with gsl_multifit_nlinear (trust region, Levenberg-Marquardt,
 * QR solver). The covariance is (J^T W J)^{-1} at the optimum. Errors:
 * GR_EINPUT for bad data (n <= np, non-finite x/y, sigma <= 0, np too
 * large), GR_ERUN when the iteration does not converge (the message names
 * the model and GSL's reason; *out then holds the last iterate). opt may be
 * NULL. */
int gr_fit_nlin(const gr_model *m, const double *x, const double *y, const double *sigma,
                size_t n, const double *p0, const gr_fit_opts *opt, gr_fit *out,
                gr_err *err);

/* The input checks of gr_fit_nlin (GR_EINPUT naming `what`): 1 <= np <=
 * GR_FIT_MAXP, n > np, finite x and y, finite sigma > 0 when given. */
int gr_fit_check_data(const char *what, size_t np, const double *x, const double *y,
                      const double *sigma, size_t n, gr_err *err);

/* Ready models (fit_models.c). Parameter order is the order in p[]. */
gr_model gr_model_power(void);       /* A x^p: {A, p} */
gr_model gr_model_exp(void);         /* A exp(b x): {A, b} */
gr_model gr_model_gauss(void);       /* A exp(-(x-mu)^2 / (2 s^2)): {A, mu, s} */
gr_model gr_model_density_law(void); /* rho0 (1 - a exp(-b D)): {rho0, a, b}, eq. 4.7 */
/* gr_pdf_tsallis_unit(x, c): {c}, for a histogram of data scaled to unit
 * standard deviation; c = 3/2 is eq. 3.4, large c Gaussian (finite
 * differences for the Jacobian). */
gr_model gr_model_tsallis_unit(void);

/* Beverloo in 2D, W = C rho sqrt(g) (D - k)^e with e = 3/2, free {C, k}
 * (d = 1, so k is in diameters; eq. 4.1 prints sqrt(g rho), but
 * dimensional analysis and eq. 4.6 give rho sqrt(g)); rho (number density
 * or packing fraction, as the caller measures W) and g are fixed. W = 0 for
 * D <= k. The modified law of eqs. 4.14-4.15, W = C rho (1 - a exp(-b D))
 * sqrt(g) D^e (v ~ sqrt(g D)), free {C, a, b}. exponent <= 0 means 3/2
 * (5/2 gives the 3D law). The model keeps a pointer to par: it must
 * outlive the model. */
typedef struct {
    double rho, g, exponent;
} gr_beverloo_par;
gr_model gr_model_beverloo(const gr_beverloo_par *par);
gr_model gr_model_beverloo_mod(const gr_beverloo_par *par);

/* Straight line in log-log, ln y = ln A + p ln x, by gsl_fit_linear (or
 * gsl_fit_wlinear with sigma_ln y = sigma / y when sigma is given); out->p
 * = {A, p} with errors and covariance carried to A. Needs x, y > 0. The
 * way to read a mean-square-displacement exponent off a log-log plot. */
int gr_fit_loglog(const double *x, const double *y, const double *sigma, size_t n,
                  gr_fit *out, gr_err *err);

/* Fits with the ready models; p0 may be NULL for a start computed from the
 * data (log-log line, log-linear line, moments, linearised Beverloo). */
int gr_fit_power(const double *x, const double *y, const double *sigma, size_t n,
                 const double *p0, gr_fit *out, gr_err *err);
int gr_fit_exp(const double *x, const double *y, const double *sigma, size_t n,
               const double *p0, gr_fit *out, gr_err *err);
int gr_fit_gauss(const double *x, const double *y, const double *sigma, size_t n,
                 const double *p0, gr_fit *out, gr_err *err);
int gr_fit_density_law(const double *D, const double *rho, const double *sigma, size_t n,
                       const double *p0, gr_fit *out, gr_err *err);
/* The density law with its decay rate confined to [bmin, bmax]: at fixed b
 * it is linear in rho0 and rho0 a, so chi2 is minimised over b alone (a
 * log-grid scan, Brent, then gr_fit_nlin from there for the covariance of
 * all three). It converges whatever the data. *at_bound = 1 says the best
 * b is an end of the range: the data do not show a saturating exponential
 * inside it; b is then that end, err[2] NaN and dof = n - 2. */
int gr_fit_density_law_bounded(const double *D, const double *rho, const double *sigma, size_t n,
                               double bmin, double bmax, gr_fit *out, int *at_bound, gr_err *err);
int gr_fit_beverloo(const gr_beverloo_par *par, const double *D, const double *W,
                    const double *sigma, size_t n, const double *p0, gr_fit *out,
                    gr_err *err);
int gr_fit_beverloo_mod(const gr_beverloo_par *par, const double *D, const double *W,
                        const double *sigma, size_t n, const double *p0, gr_fit *out,
                        gr_err *err);

#endif
