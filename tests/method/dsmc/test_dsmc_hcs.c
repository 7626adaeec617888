/* The homogeneous cooling state: the stationary a2(alpha) of DSMC against
 * the Boltzmann equation's (Sonine expansion to eighth order,
 * sonine_hcs.py), van Noije and Ernst's first-Sonine formula beside it, and
 * against edmd (a second, independent solver of the same dilute gas); the
 * cooling slope per collision against (1 - alpha^2)/2 (1 + 3 a2/16)/(1 -
 * a2/16) at the measured a2. With `slow`, longer averages. Tolerances in
 * each test and docs/methods/dsmc.md. `scan ALPHA N K DTF` prints one
 * scaled-HCS measurement (for the N dependence in the doc). */
#include "dsmc_test.h"

static int slow;

/* a2 of N = 4000 particles against the Boltzmann HCS (ds_sonine_best) within
 * 3 standard errors (blocks of 20 mean free times) + the band of the
 * Sonine orders + 0.3/N, after adding 1/N: the sample a2 of N particles
 * whose total energy and momentum are fixed is biased by -1/N exactly
 * in the elastic limit (uniform on the sphere), and measured so in the HCS:
 * a2(N) = a2 + b/N with b = -1.05 +- 0.08 at alpha 0.99, -0.73 +- 0.16 at
 * 0.8 (N = 500 to 16000), whence the 0.3/N. Printed beside it, van Noije
 * and Ernst's first-Sonine a2 and how far it is, in standard errors: the
 * departure of dsmc from it (-12 to +20 %) is the formula's truncation
 * (docs/methods/dsmc.md). The cooling per collision within 1 % of the
 * first-Sonine relation (1 - alpha^2)/2 (1 + 3 a2/16)/(1 - a2/16) at the
 * measured a2. Slow: alpha 0.5 to 0.99 over 20000 mean free times. */
static void test_hcs_a2(void **st)
{
    (void)st;
    const double quick[] = {0.6, 0.8, 0.9}, all[] = {0.5, 0.6, 0.7, 0.8, 0.9, 0.95, 0.99};
    const double *al = slow ? all : quick;
    int K = slow ? 20000 : 2000, na = slow ? 7 : 3, n = 4000;
    for (int k = 0; k < na; k++) {
        double a2, err, sl, vne = exp_sonine_a2(al[k]), best = NAN, band = 0;
        ds_sonine_best(al[k], &best, &band);
        ds_scaled_hcs(al[k], n, 0.07, K, &a2, &err, &sl);
        double sw = (1 - al[k] * al[k]) / 2 * (1 + 3 * a2 / 16) / (1 - a2 / 16), a2n = a2 + 1.0 / n;
        print_message("# HCS alpha %.2f: a2 %.5f +- %.5f (blocks of 20), + 1/N %.5f; Boltzmann (Sonine K 5-8) %.5f "
                      "+- %.5f, off by %.1f sigma; first Sonine %.5f, off by %.1f sigma (%+.0f %%); cooling per "
                      "collision / (1-a^2)/2 (1+3a2/16)/(1-a2/16) %.4f\n",
                      al[k], a2, err, a2n, best, band, (a2n - best) / err, vne, (a2n - vne) / err,
                      100 * (a2n / vne - 1), sl / sw);
        assert_true(fabs(sl / sw - 1) < 0.01);
        assert_true(fabs(a2n - best) < 3 * err + band + 0.3 / n);
    }
}

/* Free cooling, not rescaled, at packing 0.005 (chi 1.008), 2000 disks:
 * a2 from snapshots at every collision per particle from 11 to 30, four
 * seeds (slow: 16), blocks of 20 snapshots. dsmc's a2 + 1/N within 3
 * standard errors + the Sonine band + 0.3/N of the Boltzmann a2, as for
 * the scaled HCS; edmd's beside it, not asserted: its free cooling in a box
 * of 20 mean free paths departs from the Boltzmann HCS by more than its
 * error bar at alpha = 0.6 (5.5 standard errors, docs/methods/dsmc.md). */
static void free_a2(const char *method, double alpha, int n, int seeds, double *a2, double *err)
{
    enum { KMAX = 400 };
    double x[KMAX];
    int k = 0;
    for (int r = 0; r < seeds; r++) {
        gr_scene *sc;
        gr_sim *s = ds_gas(method, 41 + r, n, 0.005, alpha, 0.1, 0, "yes", &sc);
        gr_err e = {0};
        gr_particles *p = gr_particles_create(0, &e);
        for (int c = 1; c <= 30; c++) {
            while (2.0 * (double)ds_counter(s, "pair_collisions") / n < c) {
                double T = ds_temp(s), nd = n / (gr_sim_scene(s)->width * gr_sim_scene(s)->height);
                double tau = 1.0 / (2 * sqrt(M_PI) * nd * sqrt(T));
                ds_run_to(s, gr_sim_time(s) + 0.1 * tau);
            }
            if (c <= 10)
                continue;
            assert_int_equal(gr_sim_snapshot(s, p, &e), GR_OK);
            double mx = 0, my = 0, s2 = 0, s4 = 0;
            for (size_t i = 0; i < p->n; i++)
                mx += p->vx[i] / p->n, my += p->vy[i] / p->n;
            for (size_t i = 0; i < p->n; i++) {
                double ux = p->vx[i] - mx, uy = p->vy[i] - my, u2 = ux * ux + uy * uy;
                s2 += u2 / p->n, s4 += u2 * u2 / p->n;
            }
            if (k < KMAX)
                x[k++] = s4 / (2 * s2 * s2) - 1;
        }
        gr_particles_free(p);
        gr_sim_free(s);
        gr_scene_free(sc);
    }
    ds_block_stats(x, k, 20, a2, err);
}

static void test_free_a2_edmd(void **st)
{
    (void)st;
    const double al[] = {0.6, 0.8};
    int seeds = slow ? 16 : 4, n = 2000;
    for (int k = 0; k < 2; k++) {
        double a, ae, b, be;
        free_a2("dsmc", al[k], n, seeds, &a, &ae);
        free_a2("edmd", al[k], n, seeds, &b, &be);
        double best = NAN, band = NAN;
        ds_sonine_best(al[k], &best, &band);
        print_message("# free cooling alpha %.2f, eta 0.005: a2 dsmc %.5f +- %.5f, edmd %.5f +- %.5f, Boltzmann "
                      "%.5f (dsmc + 1/N off by %.1f sigma), first Sonine %.5f\n",
                      al[k], a, ae, b, be, best, (a + 1.0 / n - best) / ae, exp_sonine_a2(al[k]));
        assert_true(fabs(a + 1.0 / n - best) < 3 * ae + band + 0.3 / n);
    }
}

int main(int argc, char **argv)
{
    if (argc == 6 && !strcmp(argv[1], "scan")) {
        double a2, err, sl, al = atof(argv[2]), dtf = atof(argv[5]);
        int n = atoi(argv[3]), K = atoi(argv[4]);
        ds_scaled_hcs(al, n, dtf, K, &a2, &err, &sl);
        printf("scan alpha %.3f n %d K %d dtf %.3f: a2 %.6f +- %.6f slope %.6f\n", al, n, K, dtf, a2, err, sl);
        return 0;
    }
    slow = argc > 1 && !strcmp(argv[1], "slow");
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hcs_a2),
        cmocka_unit_test(test_free_a2_edmd),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
