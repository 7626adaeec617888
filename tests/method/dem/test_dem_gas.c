/* Validation 3 of docs/methods/dem.md: an elastic frictionless gas in a periodic box
 * conserves total momentum to round-off, and velocity Verlet's relative
 * energy drift stays below 1e-4 over 1e5 steps at dt = t_c/50. */
#include "dem_test.h"

static void momentum(gr_dem *d, double *px, double *py, double *scale)
{
    double a = 0, b = 0, s = 0;
    for (size_t i = 0; i < d->n; i++) {
        a += d->mass[i] * d->f[F_VX][d->cur][i];
        b += d->mass[i] * d->f[F_VY][d->cur][i];
        s += d->mass[i] * hypot(d->f[F_VX][d->cur][i], d->f[F_VY][d->cur][i]);
    }
    *px = a, *py = b, *scale = s;
}

static void elastic_gas_conserves(void **state)
{
    (void)state;
    double kn = 1e4, tc = M_PI / sqrt(kn / 0.5);
    char text[1024];
    snprintf(text, sizeof text,
             "[scene]\nseed = 5\n"
             "[domain]\nwidth = 20\nheight = 20\nleft = periodic\nright = periodic\nbottom = periodic\ntop = periodic\n"
             "[material]\nkn = %g\ngamma_n = 0\n"
             "[species]\ncount = 120\n"
             "[init]\nkind = random\nvelocity = gaussian\nv0 = 1\n"
             "[dem]\ndt = %.17g\nskin = 0.3\n", kn, tc / 50);
    gr_scene *sc = dt_scene(text);
    gr_dem *d = dt_create(sc, NULL);
    double ek, eel, px0, py0, s0;
    gr_dem_energy(d, &ek, &eel);
    double e0 = ek + eel;
    momentum(d, &px0, &py0, &s0);
    double worst_p = 0, worst_e = 0;
    for (int block = 0; block < 100; block++) {
        dt_step(d, 1000);
        double px, py, s;
        momentum(d, &px, &py, &s);
        worst_p = fmax(worst_p, fmax(fabs(px - px0), fabs(py - py0)) / s0);
        gr_dem_energy(d, &ek, &eel);
        worst_e = fmax(worst_e, fabs((ek + eel) / e0 - 1));
    }
    gr_dem_energy(d, &ek, &eel);
    double drift = fabs((ek + eel) / e0 - 1);
    printf("# %llu steps at dt = t_c/50, %llu list builds: momentum change %.2e of sum m|v|, energy drift %.2e (largest excursion %.2e)\n",
           (unsigned long long)d->step, (unsigned long long)d->builds, worst_p, drift, worst_e);
    assert_int_equal(d->step, 100000);
    assert_true(worst_p < 1e-13);
    assert_true(drift < 1e-4);
    gr_dem_free(d);
    gr_scene_free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(elastic_gas_conserves),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
