/* DSMC validations against kinetic theory of (inelastic) hard disks:
 * the equilibrium collision frequency (Boltzmann and Enskog rates), Maxwell
 * relaxation, Haff's law, and the barometric profile (the stationary a2:
 * test_dsmc_hcs.c). Tolerances in each test and in
 * docs/methods/dsmc.md. */
#include "dsmc_test.h"

/* A periodic box of 100 x 100 with 4000 unit disks: n = 0.4, eta = 0.314. */
#define BOX                                                                                                            \
    "[scene]\nseed = %d\n[domain]\nwidth = 100\nheight = 100\nleft = periodic\nright = periodic\n"                     \
    "bottom = periodic\ntop = periodic\n[material]\nrestitution = %g\n[species]\ncount = 4000\n"                       \
    "[init]\nkind = random\nvelocity = %s\nv0 = 1\n[dsmc]\ndt = %g\ncell = %g\nenskog = %s\n"

static gr_sim *box(int seed, double alpha, const char *vel, double dt, double cell, const char *enskog,
                   gr_scene **sc)
{
    char text[1024];
    snprintf(text, sizeof text, BOX, seed, alpha, vel, dt, cell, enskog);
    return ds_make(text, sc);
}

/* nu = 2 pairs / (N t) against 2 sqrt(pi) n sigma sqrt(T/m) (times chi):
 * about 1.5e5 collisions, statistical error 0.4 %; tolerance 1 %. */
static void frequency(const char *enskog)
{
    gr_scene *sc;
    gr_sim *s = box(5, 1.0, "gaussian", 0.1, 20, enskog, &sc);
    double T = ds_temp(s), t = 40.0;
    ds_run_to(s, t);
    double nu = 2.0 * (double)ds_counter(s, "pair_collisions") / (4000.0 * t);
    double n = 0.4, eta = n * M_PI / 4;
    double want = 2 * sqrt(M_PI) * n * sqrt(T) * (strcmp(enskog, "yes") ? 1.0 : gr_dsmc_chi(eta));
    print_message("# collision frequency (enskog = %s): %.5f, theory %.5f, ratio %.4f, T %.4f -> %.4f\n", enskog, nu,
                  want, nu / want, T, ds_temp(s));
    assert_true(fabs(nu / want - 1) < 0.01);
    gr_sim_free(s);
    gr_scene_free(sc);
}

static void test_frequency(void **st)
{
    (void)st;
    frequency("no");
}

static void test_frequency_enskog(void **st)
{
    (void)st;
    frequency("yes");
}

/* All speeds equal (a2 = -1/2) relax to a Maxwellian: a2 averaged over 20
 * snapshots one collision time apart, after 20 collision times, within 3
 * standard errors sqrt(5 / (N K)) of zero. */
static void test_maxwell(void **st)
{
    (void)st;
    gr_scene *sc;
    gr_sim *s = box(7, 1.0, "speed", 0.1, 20, "no", &sc);
    double a0 = ds_a2(gr_sim_state(s)), tau = 1.0 / (2 * sqrt(M_PI) * 0.4 * sqrt(ds_temp(s)));
    ds_run_to(s, 20 * tau);
    double sum = 0;
    for (int k = 1; k <= 20; k++) {
        ds_run_to(s, (20 + k) * tau);
        sum += ds_a2(gr_sim_state(s));
    }
    double a2 = sum / 20, err = sqrt(5.0 / (4000.0 * 20));
    print_message("# Maxwell relaxation: a2 %.4f at start, %.5f +- %.5f after 20 collision times\n", a0, a2, err);
    assert_true(fabs(a2) < 3 * err);
    gr_sim_free(s);
    gr_scene_free(sc);
}

/* Haff's law in one cell (no spatial correlations, so no clustering):
 * T(t) = T0 / (1 + zeta0 t / 2)^2 with the first-Sonine zeta0, to 2 %
 * while T falls to T0 / 10. */
static void test_haff(void **st)
{
    (void)st;
    double alpha = 0.9;
    gr_scene *sc;
    gr_sim *s = box(9, alpha, "gaussian", 0.05, 1000, "no", &sc);
    double T0 = ds_temp(s), a2 = exp_sonine_a2(alpha);
    double z0 = sqrt(M_PI) * (1 - alpha * alpha) * 0.4 * sqrt(T0) * (1 + 3 * a2 / 16);
    double worst = 0;
    for (int k = 1; k <= 8; k++) {
        double t = k * 2.0 / z0 * (sqrt(10.0) - 1) / 8;
        ds_run_to(s, t);
        double want = T0 / ((1 + z0 * t / 2) * (1 + z0 * t / 2)), got = ds_temp(s);
        worst = fmax(worst, fabs(got / want - 1));
    }
    print_message("# Haff (alpha %.2f): largest |T / T_Haff - 1| %.4f down to T0/10\n", alpha, worst);
    assert_true(worst < 0.02);
    gr_sim_free(s);
    gr_scene_free(sc);
}

/* An elastic gas on an elastic floor under g = 1: ln n(y) linear with
 * slope -m g / T, T the kinetic temperature; the fitted slope within 3 %.
 * Dilute (packing 0.03 on average) and the Boltzmann rate (enskog = no:
 * the ideal gas, which the law is for); T = 9
 * gives a scale height of 9 d, sampled in 10 bins of 3 d. */
static void test_barometric(void **st)
{
    (void)st;
    const char *text = "[scene]\nseed = 13\n[domain]\nwidth = 1000\nheight = 60\ngravity = 1\n"
                       "left = periodic\nright = periodic\n[material]\nrestitution = 1\n[species]\ncount = 2000\n"
                       "[init]\nkind = random\nvelocity = gaussian\nv0 = 3\n[dsmc]\ndt = 0.02\ncell = 10\nenskog = no\n";
    gr_scene *sc;
    gr_sim *s = ds_make(text, &sc);
    gr_dsmc *d = gr_sim_state(s);
    ds_run_to(s, 100);
    enum { NB = 10 };
    double h[NB] = {0}, Tsum = 0, dy = 3.0;
    for (int k = 1; k <= 200; k++) {
        ds_run_to(s, 100 + k * 0.5);
        Tsum += ds_temp(s);
        for (size_t i = 0; i < d->n; i++) {
            int b = (int)floor((d->y[i] - 0.5) / dy);
            if (b >= 0 && b < NB)
                h[b] += 1;
        }
    }
    double sx = 0, sy = 0, sxx = 0, sxy = 0, sw = 0;
    for (int b = 0; b < NB; b++) {
        double x = (b + 0.5) * dy, y = log(h[b]), w = h[b];
        sw += w, sx += w * x, sy += w * y, sxx += w * x * x, sxy += w * x * y;
    }
    double slope = (sw * sxy - sx * sy) / (sw * sxx - sx * sx), T = Tsum / 200;
    print_message("# barometric: slope %.4f, -m g / T = %.4f (T %.4f), ratio %.4f\n", slope, -1 / T, T, -slope * T);
    assert_true(fabs(-slope * T - 1) < 0.03);
    gr_sim_free(s);
    gr_scene_free(sc);
}

/* `freq ENSKOG ETA N DTF CELLF T`: the equilibrium (elastic) collision
 * frequency of N disks at packing ETA in a periodic square, dt = DTF mean
 * free times, cells of CELLF mean free paths, over T mean free times,
 * against 2 sqrt(pi) n sigma sqrt(T/m) (times chi): the rate of the Enskog
 * mode's thinning of pairs against dt (docs/methods/dsmc.md). */
static int freq_scan(char **argv)
{
    const char *ens = argv[2];
    double eta = atof(argv[3]), dtf = atof(argv[5]), cf = atof(argv[6]), tf = atof(argv[7]);
    int n = atoi(argv[4]);
    double L = sqrt(n * M_PI / 4 / eta), nd = n / (L * L), tau = 1 / (2 * sqrt(M_PI) * nd), lam = 1 / (2 * sqrt(2) * nd);
    char text[1024];
    snprintf(text, sizeof text,
             "[scene]\nseed = 3\n[domain]\nwidth = %.17g\nheight = %.17g\nleft = periodic\nright = periodic\n"
             "bottom = periodic\ntop = periodic\n[species]\ncount = %d\n[init]\nkind = random\nvelocity = gaussian\n"
             "v0 = 1\n[dsmc]\ndt = %.17g\ncell = %.17g\nenskog = %s\n",
             L, L, n, dtf * tau, cf * lam, ens);
    gr_scene *sc;
    gr_sim *s = ds_make(text, &sc);
    double T = ds_temp(s);
    ds_run_to(s, tf * tau / sqrt(T));
    double c = (double)ds_counter(s, "pair_collisions"), t = gr_sim_time(s);
    double want = 2 * sqrt(M_PI) * nd * sqrt(T) * (strcmp(ens, "yes") ? 1.0 : gr_dsmc_chi(eta));
    printf("freq enskog %s eta %g n %d dt %g tau cell %g lambda: nu/theory %.5f +- %.5f (%.0f collisions)\n", ens, eta,
           n, dtf, cf, 2 * c / (n * t) / want, 1 / sqrt(c), c);
    gr_sim_free(s);
    gr_scene_free(sc);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc == 8 && !strcmp(argv[1], "freq"))
        return freq_scan(argv);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_frequency), cmocka_unit_test(test_frequency_enskog),
        cmocka_unit_test(test_maxwell),   cmocka_unit_test(test_haff),
        cmocka_unit_test(test_barometric),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
