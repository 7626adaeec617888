/* Longer validations (suite 'slow'): the elastic gas of validation 3 over
 * a million steps; a thesis-sized bed (2000 grains, thesis constants)
 * settling: its mean overlap stays well below 1 % of d, and its largest,
 * on the strongest force chain (contact forces in a granular bed are
 * spread roughly exponentially: the largest of a few thousand is about 9
 * times the mean, an overlap 9^(2/3) ~ 4 times the mean), below 2.5 %. */
#include "dem_test.h"

static void gas_million_steps(void **state)
{
    (void)state;
    double kn = 1e4, tc = M_PI / sqrt(kn / 0.5);
    char text[1024];
    snprintf(text, sizeof text,
             "[scene]\nseed = 12\n"
             "[domain]\nwidth = 30\nheight = 30\nleft = periodic\nright = periodic\nbottom = periodic\ntop = periodic\n"
             "[material]\nkn = %g\ngamma_n = 0\n"
             "[species]\ncount = 300\n"
             "[init]\nkind = random\nvelocity = gaussian\nv0 = 1\n"
             "[dem]\ndt = %.17g\nskin = 0.3\n", kn, tc / 50);
    gr_scene *sc = dt_scene(text);
    gr_dem *d = dt_create(sc, NULL);
    double ek, eel;
    gr_dem_energy(d, &ek, &eel);
    double e0 = ek + eel;
    dt_step(d, 1000000);
    gr_dem_energy(d, &ek, &eel);
    double drift = fabs((ek + eel) / e0 - 1);
    printf("# 300-grain elastic gas, 1e6 steps at t_c/50: energy drift %.2e\n", drift);
    assert_true(drift < 1e-3);
    gr_dem_free(d);
    gr_scene_free(sc);
}

static void thesis_bed_settles(void **state)
{
    (void)state;
    gr_scene *sc = dt_scene("[scene]\nseed = 13\n[domain]\nwidth = 50\nheight = 80\ngravity = 1\n"
                            "left = open\nright = open\nbottom = open\ntop = open\n"
                            "[silo]\nwalls = grains\nwidth = 46\nheight = 76\nbase = 2\norifice = 4\n"
                            "[material]\nnormal = hertz\ntangential = regularised\nkn = 1e5\n"
                            "gamma_n = 100\ngamma_t = 300\nmu = 0.5\n"
                            "[species]\ncount = 2000\n"
                            "[init]\nkind = lattice\nregion = 2 2 48 78\nvelocity = gaussian\nv0 = 0.1\n"
                            "[dem]\ndt = 1.25e-4\n");
    gr_dem *d = dt_create(sc, NULL);
    double ovl = 0, ek = 0;
    for (int k = 0; k < 20; k++) {
        dt_advance(d, d->t + 1.0);
        if (d->t > 10 - 1e-9)
            ovl = fmax(ovl, d->max_ovl);
    }
    gr_dem_energy(d, &ek, NULL);
    double sum = 0;
    long nc = 0;
    const double *x = d->f[F_X][d->cur], *y = d->f[F_Y][d->cur];
    for (size_t i = 0; i < d->n; i++)
        for (size_t j = i + 1; j < d->n; j++) {
            double xi = d->rad[i] + d->rad[j] - hypot(x[j] - x[i], y[j] - y[i]);
            if (xi > 0 && !((d->flags[i] & d->flags[j]) & GR_PF_FIXED))
                sum += xi, nc++;
        }
    printf("# 2000 grains, thesis constants, t = 20: kinetic energy per grain %.2e, %ld contacts, mean overlap %.4f d, largest since t = 10: %.4f d\n",
           ek / d->nmobile, nc, sum / nc, ovl);
    assert_true(sum / nc < 0.005);
    assert_true(ovl < 0.025);
    assert_true(ek / d->nmobile < 1e-3);
    gr_dem_free(d);
    gr_scene_free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(gas_million_steps),
        cmocka_unit_test(thesis_bed_settles),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
