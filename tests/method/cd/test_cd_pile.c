/* Validation 5: warm start on a resting pile. 200 disks (unit diameter,
 * mu = 0.5, e = 0) settle in a box from random spots (tolerance 1e-3, then 1e-4 for 1 tau); then the mean sweeps
 * per step with warm start must be at least 3 times smaller than without
 * (20 steps with, then 10 without, on the same resting pile). Prints the
 * factor, the largest overlap left, and the speed in contact updates per
 * second of CPU time (a print, not an assertion). */
#include "cd_test.h"

#include <time.h>

#define T_SETTLE 15.0

static const char *const pile_text =
    "[scene]\nseed = 5\n[domain]\nwidth = 16\nheight = 40\ngravity = 1\n"
    "[material]\ntangential = coulomb\nmu = 0.5\n[species]\ncount = 200\n"
    "[init]\nkind = random\nregion = 0 0 16 24\n"
    "[cd]\ndt = 2e-3\ntol = 1e-4\nmax_iter = 5000\n";

/* Mean sweeps per step over n steps, and contact updates and CPU seconds. */
static double sweeps_per_step(gr_sim *s, long n, double *updates, double *cpu)
{
    uint64_t it0 = ct_counter(s, "iterations"), c = 0;
    clock_t t0 = clock();
    gr_err e = {0};
    for (long k = 0; k < n; k++) {
        uint64_t before = ct_counter(s, "iterations");
        assert_int_equal(gr_sim_step(s, &e), GR_OK);
        c += (ct_counter(s, "iterations") - before) * ct_counter(s, "contacts");
    }
    *cpu += (double)(clock() - t0) / CLOCKS_PER_SEC;
    *updates += (double)c;
    return (double)(ct_counter(s, "iterations") - it0) / (double)n;
}

static void warm_start(void **unused)
{
    (void)unused;
    gr_scene *sc = ct_scene(pile_text);
    gr_sim *s = ct_sim(sc, NULL);
    gr_err e = {0};
    gr_cd *d = ct_state(s);
    /* settling needs no accuracy: a loose tolerance until the measurement */
    d->par.tol = 1e-3;
    assert_int_equal(gr_sim_advance(s, T_SETTLE, 0, &e), GR_OK);
    d->par.tol = 1e-4;
    assert_int_equal(gr_sim_advance(s, T_SETTLE + 1.0, 0, &e), GR_OK);
    gr_obs o;
    assert_int_equal(gr_sim_observe(s, &o, &e), GR_OK);
    double warm, cold, upd = 0, cpu = 0, upd_c = 0, cpu_c = 0;
    /* warm first: a cold step converged to tol leaves the pile slightly
     * off its rest, which the next steps would have to undo */
    d->par.warm = 1;
    warm = sweeps_per_step(s, 20, &upd, &cpu);
    d->par.warm = 0;
    cold = sweeps_per_step(s, 10, &upd_c, &cpu_c);
    printf("# pile of 200 at t = %g, before the measurement: kinetic energy %.3g, %llu contacts (%llu active, %llu sliding), "
           "largest overlap %.3g d\n",
           o.t, o.ekin_trans + o.ekin_rot, (unsigned long long)ct_counter(s, "contacts"),
           (unsigned long long)ct_counter(s, "active_contacts"),
           (unsigned long long)ct_counter(s, "sliding_contacts"), o.max_overlap);
    printf("# sweeps per step: warm start %.1f, cold %.1f: factor %.2f (tol 1e-4)\n", warm, cold, cold / warm);
    printf("# speed: %.3g contact updates per CPU second without warm start (sweeps dominate), "
           "%.3g with it (detection dominates)\n", upd_c / cpu_c, upd / cpu);
    assert_true(cold >= 3 * warm);
    assert_true(o.ekin_trans + o.ekin_rot < 1e-2 * o.n_mobile);
    gr_sim_free(s);
    gr_scene_free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(warm_start)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
