/* Density waves in a vertical pipe (suite slow; Peng and Herrmann, Phys.
 * Rev. E 49, R1796 (1994) and 51, 1745 (1995)): 16 lanes between rough
 * walls, 1024 rows periodic, g = 0.005, dissipation p = stop = 0.3.
 *  - waves need dissipation and rough walls: the long-wave contrast of the
 *    density (lgca_pipe.h) above 30 with both, below 3 with p = stop = 0
 *    or b = 0 (smooth walls);
 *  - and a window of density: at occupation 0.2 above 30, at 0.05 and 0.4
 *    below a tenth of that;
 *  - the space-time density (every 4th step, bins of 4 rows) and the
 *    power spectrum of the particles in windows of 4 and 32 rows are
 *    written to lgca_pipe_spacetime.txt and lgca_pipe_spectrum.txt for
 *    tests/method/lgca/lgca_pipe_plot.py; the spectral power below
 *    f = 1e-3 per step with waves is above 10 times that without
 *    dissipation. The slope after the wave's peak is printed, not
 *    asserted: regular waves at 0.2 fall off as f^-2;
 *  - near the window's lower edge (occupation 0.15, 2048 rows) the
 *    irregular waves' spectrum falls as f^-alpha with alpha within 0.3 of
 *    Peng and Herrmann's 4/3. */
#include "lgca_pipe.h"

static lgca_pipe base(void) { return (lgca_pipe){0.2, 0.005, 0.3, 1, 0.3, 16, 1024, 2000, 8192}; }

static void waves_need_dissipation_and_roughness(void **unused)
{
    (void)unused;
    lgca_pipe q = base();
    double on = lgca_pipe_run(&q, NULL);
    q.p = q.stop = 0;
    double no_p = lgca_pipe_run(&q, NULL);
    q = base(), q.b = 0;
    double no_b = lgca_pipe_run(&q, NULL);
    printf("# long-wave contrast: %.2f with p, stop and b; %.2f with p = stop = 0; %.2f with b = 0\n", on, no_p, no_b);
    assert_true(on > 30 && no_p < 3 && no_b < 3);
}

static void density_window(void **unused)
{
    (void)unused;
    const double ds[] = {0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.4};
    double c[7];
    for (int k = 0; k < 7; k++) {
        lgca_pipe q = base();
        q.d = ds[k];
        c[k] = lgca_pipe_run(&q, NULL);
        printf("# occupation %.2f: long-wave contrast %.2f\n", ds[k], c[k]);
    }
    assert_true(c[3] > 30 && c[0] < c[3] / 10 && c[6] < c[3] / 10);
}

/* Power spectrum of the particles in windows of w rows (Hann-windowed
 * periodogram on log-spaced frequencies, averaged over the windows). */
static void spectrum(const float *rows, int T, int ni, int w, int stride, const double *f, int nf, double *P)
{
    int nwin = ni / w / stride;
    double *x = malloc(sizeof *x * (size_t)T);
    assert_non_null(x);
    for (int k = 0; k < nf; k++)
        P[k] = 0;
    for (int q = 0; q < nwin; q++) {
        double mu = 0;
        for (int t = 0; t < T; t++) {
            x[t] = 0;
            for (int i = q * stride * w; i < (q * stride + 1) * w; i++)
                x[t] += rows[(size_t)t * (size_t)ni + (size_t)i];
            mu += x[t] / T;
        }
        for (int k = 0; k < nf; k++) {
            double re = 0, im = 0;
            for (int t = 0; t < T; t++) {
                double v = (x[t] - mu) * (0.5 - 0.5 * cos(2 * M_PI * t / T));
                re += v * cos(2 * M_PI * f[k] * t), im += v * sin(2 * M_PI * f[k] * t);
            }
            P[k] += (re * re + im * im) / nwin;
        }
    }
    free(x);
}

static double slope(const double *f, const double *P, int nf, double lo, double hi)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0, n = 0;
    for (int k = 0; k < nf; k++)
        if (f[k] >= lo && f[k] <= hi) {
            double x = log(f[k]), y = log(P[k]);
            sx += x, sy += y, sxx += x * x, sxy += x * y, n++;
        }
    return -(n * sxy - sx * sy) / (n * sxx - sx * sx);
}

static void spacetime_and_spectrum(void **unused)
{
    (void)unused;
    enum { NF = 40 };
    lgca_pipe q = base();
    q.steps = 16384;
    int ni = q.rows;
    float *rows = malloc(sizeof *rows * (size_t)q.steps * (size_t)ni);
    assert_non_null(rows);
    double f[NF], P[4][NF], lowf[2] = {0};
    for (int k = 0; k < NF; k++)
        f[k] = exp(log(1.0 / q.steps) + log(q.steps / 4.0) * k / (NF - 1));
    for (int run = 0; run < 2; run++) {
        if (run)
            q.p = q.stop = 0;
        lgca_pipe_run(&q, rows);
        spectrum(rows, q.steps, ni, 4, 1, f, NF, P[2 * run]);
        spectrum(rows, q.steps, ni, 32, 1, f, NF, P[2 * run + 1]);
        for (int k = 0; k < NF; k++)
            lowf[run] += f[k] < 1e-3 ? P[2 * run][k] : 0;
        if (run)
            continue;
        FILE *st = fopen("lgca_pipe_spacetime.txt", "w");
        assert_non_null(st);
        fprintf(st, "# occupation per channel in bins of 4 rows (columns, upwards) every 4th step (lines)\n");
        for (int t = 0; t < 6000; t += 4) {
            for (int b = 0; b < ni / 4; b++)
                fprintf(st, "%.4f ", (rows[(size_t)t * ni + 4 * b] + rows[(size_t)t * ni + 4 * b + 1] +
                                      rows[(size_t)t * ni + 4 * b + 2] + rows[(size_t)t * ni + 4 * b + 3]) /
                                         (4.0 * 7 * q.lanes));
            fprintf(st, "\n");
        }
        fclose(st);
    }
    FILE *sp = fopen("lgca_pipe_spectrum.txt", "w");
    assert_non_null(sp);
    fprintf(sp, "# f (1/step), power: windows of 4 and 32 rows with p = stop = 0.3, then with p = stop = 0\n");
    for (int k = 0; k < NF; k++)
        fprintf(sp, "%.6g %.5g %.5g %.5g %.5g\n", f[k], P[0][k], P[1][k], P[2][k], P[3][k]);
    fclose(sp);
    printf("# spectrum slope after the wave's peak: windows of 4 rows %.2f (f in 5e-4..5e-3), %.2f (1e-3..1e-1); "
           "32 rows %.2f (1e-3..1e-1); Peng and Herrmann: about 4/3\n",
           slope(f, P[0], NF, 5e-4, 5e-3), slope(f, P[0], NF, 1e-3, 1e-1), slope(f, P[1], NF, 1e-3, 1e-1));
    printf("# power below f = 1e-3: %.3g with dissipation, %.3g without\n", lowf[0], lowf[1]);
    assert_true(lowf[0] > 10 * lowf[1]);
    free(rows);
}

/* Near the lower edge of the density window the waves are irregular:
 * occupation 0.15, 2048 rows; the spectrum of 4-row windows (every 4th)
 * fitted from twice the peak's frequency to 0.02 per step. */
static void spectrum_slope_irregular_waves(void **unused)
{
    (void)unused;
    enum { NF = 40 };
    lgca_pipe q = base();
    q.d = 0.15, q.rows = 2048, q.steps = 16384;
    float *rows = malloc(sizeof *rows * (size_t)q.steps * (size_t)q.rows);
    assert_non_null(rows);
    double f[NF], P[NF];
    for (int k = 0; k < NF; k++)
        f[k] = exp(log(1.0 / q.steps) + log(q.steps / 4.0) * k / (NF - 1));
    double c = lgca_pipe_run(&q, rows);
    spectrum(rows, q.steps, q.rows, 4, 4, f, NF, P);
    int peak = 0;
    for (int k = 1; k < NF; k++)
        peak = P[k] > P[peak] ? k : peak;
    double a = slope(f, P, NF, 2 * f[peak], 0.02);
    printf("# occupation 0.15, 2048 rows: contrast %.1f, spectral peak at f = %.2e, slope %.2f over [%.2e, 0.02] "
           "(Peng and Herrmann: about 4/3)\n", c, f[peak], a, 2 * f[peak]);
    assert_true(fabs(a - 4.0 / 3) < 0.3);
    free(rows);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(waves_need_dissipation_and_roughness),
        cmocka_unit_test(density_window),
        cmocka_unit_test(spacetime_and_spectrum),
        cmocka_unit_test(spectrum_slope_irregular_waves),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
