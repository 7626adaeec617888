/* A wave detector for the lgca pipe (lgca_pipe.h): from the particles per
 * bin of 4 rows at every step, three measures of density waves.
 *  - contrast: lgca_pipe_run's long-wave contrast (the structure factor's
 *    four longest wavelengths over those near 16 rows, every 16 steps);
 *  - the space-time density's travelling modes: a_k(t), the k-th Fourier
 *    mode of the bins every 4th step (Hann-windowed, its mean removed),
 *    and |a_k(omega)|^2 over k = 1..16: the dominant mode (the largest
 *    power, omega != 0), its speed and wavelength, and the share of the
 *    power of k = 1..4 that travels up the pipe (against the flow; 1/2
 *    for standing fluctuations, below for ones carried down);
 *  - the power spectrum of the particles in windows of 4 rows (every 4th
 *    window, every step, Hann-windowed, averaged over windows and over
 *    log-spaced bands): its peak and the slope alpha of f^-alpha fitted
 *    from twice the peak's frequency to 0.02 per step. */
#ifndef GR_LGCA_WAVES_H
#define GR_LGCA_WAVES_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    double contrast;
    double up, speed, wavelength; /* share up; rows per step (+: up), rows */
    double f_peak, alpha;         /* per step; NaN where the fit has < 3 bands */
} lgca_waves;

/* In-place radix-2 FFT of n = 2^m complex values (re, im), forward. */
static inline void lgca_fft(double *re, double *im, size_t n)
{
    for (size_t i = 1, j = 0; i < n; i++) {
        size_t bit = n >> 1;
        for (; j & bit; bit >>= 1)
            j ^= bit;
        j |= bit;
        if (i < j) {
            double t = re[i];
            re[i] = re[j], re[j] = t, t = im[i], im[i] = im[j], im[j] = t;
        }
    }
    for (size_t len = 2; len <= n; len <<= 1) {
        double a = -2 * M_PI / (double)len;
        for (size_t i = 0; i < n; i += len)
            for (size_t k = 0; k < len / 2; k++) {
                double c = cos(a * (double)k), s = sin(a * (double)k);
                double *ur = re + i + k, *ui = im + i + k, *vr = ur + len / 2, *vi = ui + len / 2;
                double xr = *vr * c - *vi * s, xi = *vr * s + *vi * c;
                *vr = *ur - xr, *vi = *ui - xi, *ur += xr, *ui += xi;
            }
    }
}

static inline int lgca_waves_cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* One frame's share of the long-wave contrast: the structure factor of
 * the bins v at the four longest wavelengths into *lo, near 16 rows into
 * *mid (the contrast is lo / mid summed over frames). */
static inline void lgca_waves_contrast_frame(const float *v, int nb, double *lo, double *mid)
{
    for (int k = 1; k < nb / 2; k++) {
        int low = k <= 4, near16 = k >= nb / 4 - 8 && k < nb / 4 + 8;
        if (!low && !near16)
            continue;
        double re = 0, im = 0;
        for (int b = 0; b < nb; b++)
            re += v[b] * cos(2 * M_PI * k * b / nb), im += v[b] * sin(2 * M_PI * k * b / nb);
        *(low ? lo : mid) += (re * re + im * im) / (low ? 4 : 16);
    }
}

static inline double lgca_waves_contrast(const float *bins, size_t T, size_t nb)
{
    double lo = 0, mid = 0;
    for (size_t t = 0; t < T; t += 16)
        lgca_waves_contrast_frame(bins + t * nb, (int)nb, &lo, &mid);
    return lo / mid;
}

/* The travelling modes of the bins sampled every 4th step. */
static inline void lgca_waves_mode(const float *bins, size_t T, size_t nb, lgca_waves *w)
{
    size_t N = T / 4, K = nb / 4 < 16 ? nb / 4 : 16;
    double *re = malloc(sizeof *re * N), *im = malloc(sizeof *im * N);
    w->speed = w->wavelength = NAN;
    double *cs = malloc(sizeof *cs * 2 * nb), best = -1, up = 0, all = 0;
    for (size_t k = 1; k <= K; k++) {
        for (size_t b = 0; b < nb; b++) {
            double ph = -2 * M_PI * (double)(k * b) / (double)nb;
            cs[2 * b] = cos(ph), cs[2 * b + 1] = sin(ph);
        }
        double mr = 0, mi = 0;
        for (size_t t = 0; t < N; t++) {
            double r = 0, i = 0;
            for (size_t b = 0; b < nb; b++) {
                double v = bins[4 * t * nb + b];
                r += v * cs[2 * b], i += v * cs[2 * b + 1];
            }
            re[t] = r, im[t] = i, mr += r / (double)N, mi += i / (double)N;
        }
        for (size_t t = 0; t < N; t++) {
            double h = 0.5 - 0.5 * cos(2 * M_PI * (double)t / (double)N);
            re[t] = (re[t] - mr) * h, im[t] = (im[t] - mi) * h;
        }
        lgca_fft(re, im, N);
        for (size_t m = 1; m < N; m++) {
            double p = re[m] * re[m] + im[m] * im[m];
            /* a_k ~ exp(-i 2 pi k c t / rows): a wave going up (c > 0) lies
             * at negative frequencies, m > N/2 */
            if (k <= 4)
                all += p, up += m > N / 2 ? p : m == N / 2 ? p / 2 : 0;
            if (p > best) {
                best = p;
                double ms = m < N / 2 ? (double)m : (double)m - (double)N;
                w->wavelength = (double)(4 * nb) / (double)k;
                w->speed = -ms / (4.0 * (double)N) * w->wavelength;
            }
        }
    }
    w->up = up / all;
    free(re), free(im), free(cs);
}

/* The spectrum of windows of 4 rows in NF log-spaced bands from 1/T to 1/4
 * per step, its peak and its slope beyond the peak. */
static inline void lgca_waves_spectrum(const float *bins, size_t T, size_t nb, lgca_waves *w)
{
    enum { NF = 40 };
    double *re = malloc(sizeof *re * T), *im = malloc(sizeof *im * T), *pw = calloc(T / 2, sizeof *pw);
    size_t nwin = 0;
    for (size_t b = 0; b < nb; b += 4, nwin++) {
        double mu = 0;
        for (size_t t = 0; t < T; t++)
            mu += bins[t * nb + b] / (double)T;
        for (size_t t = 0; t < T; t++)
            re[t] = (bins[t * nb + b] - mu) * (0.5 - 0.5 * cos(2 * M_PI * (double)t / (double)T)), im[t] = 0;
        lgca_fft(re, im, T);
        for (size_t m = 1; m < T / 2; m++)
            pw[m] += re[m] * re[m] + im[m] * im[m];
    }
    double f[NF], P[NF];
    int n[NF] = {0};
    for (int k = 0; k < NF; k++)
        f[k] = exp(log(1.0 / (double)T) + log((double)T / 4) * k / (NF - 1)), P[k] = 0;
    double half = 0.5 * log((double)T / 4) / (NF - 1);
    for (size_t m = 1; m < T / 2; m++) {
        int k = (int)floor((log((double)m / (double)T) - log(1.0 / (double)T)) / (2 * half) + 0.5);
        if (k >= 0 && k < NF)
            P[k] += pw[m] / (double)nwin, n[k]++;
    }
    int peak = -1;
    for (int k = 0; k < NF; k++) {
        if (!n[k])
            continue;
        P[k] /= n[k];
        peak = peak < 0 || P[k] > P[peak] ? k : peak;
    }
    w->f_peak = f[peak];
    double sx = 0, sy = 0, sxx = 0, sxy = 0, c = 0;
    for (int k = 0; k < NF; k++)
        if (n[k] && f[k] >= 2 * f[peak] && f[k] <= 0.02) {
            double x = log(f[k]), y = log(P[k]);
            sx += x, sy += y, sxx += x * x, sxy += x * y, c++;
        }
    w->alpha = c >= 3 ? -(c * sxy - sx * sy) / (c * sxx - sx * sx) : NAN;
    free(re), free(im), free(pw);
}

/* bins: T x nb particles per bin of 4 rows (T a power of 2, nb >= 8). */
static inline lgca_waves lgca_waves_measure(const float *bins, size_t T, size_t nb)
{
    lgca_waves w;
    w.contrast = lgca_waves_contrast(bins, T, nb);
    lgca_waves_mode(bins, T, nb, &w);
    lgca_waves_spectrum(bins, T, nb, &w);
    return w;
}

#endif
