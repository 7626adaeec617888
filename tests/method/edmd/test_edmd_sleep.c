/* The sleep model (collapse = sleep): a bed of 200 disks settling under
 * gravity comes to rest at a bounded cost, its energy bookkeeping stays
 * exact across the sleeping grains, none overlaps, and a checkpoint taken
 * while some grains sleep and others move restarts bit for bit, and a
 * grain on one slanted support rolls off it rather than sleeping there.
 * The bed of the scene file is watched by tests/experiment/watch_check.sh
 * and tests/hard/hard_cases.py (at most 10 times the events of its first
 * unit of time); this one is dropped from the whole box, and its first
 * unit, in free fall, has few events (115): its bound is per grain. */
#include "test.h"

#include <stdlib.h>
#include <unistd.h>

#include "ckpt.h"
#include "edmd_int.h"
#include "edmd_test.h"

/* The bed of tests/experiment/watch_check.sh, built by hand: 20 x 40 box,
 * g = 1, alpha = 0.9, 200 disks on a lattice filling the box, speeds
 * sqrt(2) (the mean square of a unit gaussian per component) in random
 * directions. */
static gr_edmd *bed(gr_particles **p0)
{
    gr_scene sc = edmd_box(20, 40, 0, 0.9);
    sc.gravity = 1.0;
    gr_edmd_params prm;
    gr_edmd_params_default(&prm);
    prm.collapse = GR_EDMD_COLLAPSE_SLEEP;
    *p0 = edmd_lattice(200, 0, 0, 20, 40, sqrt(2.0), 0, 11);
    gr_err e = {0};
    gr_edmd *s = NULL;
    int rc = gr_edmd_create(&sc, *p0, &prm, NULL, &s, &e);
    if (rc)
        fprintf(stderr, "create: %s\n", e.msg);
    assert_int_equal(rc, GR_OK);
    return s;
}

/* The state's energy, with gravity g (0: the kinetic energy alone). */
static double energy_at(gr_edmd *s, double g)
{
    gr_err e = {0};
    gr_particles *p = gr_particles_create(0, &e);
    assert_int_equal(gr_edmd_snapshot(s, p, &e), GR_OK);
    double E = edmd_energy(p, g);
    gr_particles_free(p);
    return E;
}

static double energy_of(gr_edmd *s)
{
    return energy_at(s, 1.0);
}

static double kinetic_of(gr_edmd *s)
{
    return energy_at(s, 0.0);
}

/* At most 150 events per grain in any unit of time (measured 107: a grain
 * sleeps only where its supports hold it, so the bed's last grains roll
 * into place first); the bed reaches K < 1e-6 K0 by t = 60 with every
 * grain asleep; E(t) - E(0) = -dissipated (the energy of each grain put to
 * sleep counts as dissipated) to 1e-9 E0; no overlap beyond 1e-9. */
static void bed_comes_to_rest(void **st)
{
    (void)st;
    gr_particles *p0;
    gr_edmd *s = bed(&p0);
    gr_err e = {0};
    double K0 = kinetic_of(s), E0 = energy_of(s), first = 0, worst = 0, t_rest = -1;
    uint64_t prev = 0;
    for (int k = 1; k <= 60; k++) {
        assert_int_equal(gr_edmd_advance(s, k, 0, &e), GR_OK);
        double rate = (double)(s->steps - prev);
        prev = s->steps;
        if (k == 1)
            first = rate;
        else if (rate > worst)
            worst = rate;
        if (t_rest < 0 && kinetic_of(s) < 1e-6 * K0)
            t_rest = k;
    }
    double inj, diss;
    gr_edmd_energy_budget(s, &inj, &diss);
    double E1 = energy_of(s), K1 = kinetic_of(s);
    gr_particles *p = gr_particles_create(0, &e);
    assert_int_equal(gr_edmd_snapshot(s, p, &e), GR_OK);
    double ov = edmd_max_overlap(p, 0, 0);
    gr_edmd_counters c;
    gr_edmd_get_counters(s, &c);
    printf("# bed: events per tau %.0f first, %.0f at most after (%.2fx); K/K0 = %.3g at t = 60, "
           "below 1e-6 from t = %g; asleep %llu (%llu sleeps, %llu wakes); |E - E0 + diss|/E0 = %.2e; "
           "overlap %.2e\n",
           first, worst, worst / first, K1 / K0, t_rest, (unsigned long long)(c.sleeps - c.wakes),
           (unsigned long long)c.sleeps, (unsigned long long)c.wakes, fabs(E1 - E0 + diss - inj) / E0, ov);
    assert_true(worst <= 150.0 * 200);
    assert_true(c.sleeps - c.wakes == 200);
    assert_true(t_rest > 0 && K1 < 1e-6 * K0);
    assert_true(fabs(E1 - E0 + diss - inj) < 1e-9 * E0);
    assert_true(ov < 1e-9);
    gr_particles_free(p);
    gr_particles_free(p0);
    gr_edmd_free(s);
}

/* Save at t = 16 (some grains asleep, others moving), continue to 21; a
 * fresh state loads the file and continues: identical state, averages
 * and counters. */
static void sleeping_checkpoint(void **st)
{
    (void)st;
    gr_particles *p0, *p1;
    gr_edmd *a = bed(&p0);
    gr_err e = {0};
    char path[64];
    snprintf(path, sizeof path, "edmd_sleep_ckpt_%d.h5", (int)getpid());
    assert_int_equal(gr_edmd_advance(a, 16.0, 0, &e), GR_OK);
    gr_edmd_counters c;
    gr_edmd_get_counters(a, &c);
    assert_true(c.sleeps > c.wakes && c.sleeps - c.wakes < 200);
    gr_ckpt *ck = gr_ckpt_create(path, &e);
    assert_non_null(ck);
    assert_int_equal(gr_edmd_method.save(a, ck, &e), GR_OK);
    assert_int_equal(gr_ckpt_close(ck, &e), GR_OK);
    assert_int_equal(gr_edmd_advance(a, 21.0, 0, &e), GR_OK);
    gr_edmd *b = bed(&p1);
    ck = gr_ckpt_open(path, &e);
    assert_non_null(ck);
    assert_int_equal(gr_edmd_method.load(b, ck, &e), GR_OK);
    gr_ckpt_close(ck, &e);
    assert_int_equal(gr_edmd_advance(b, 21.0, 0, &e), GR_OK);
    gr_particles *pa = gr_particles_create(0, &e), *pb = gr_particles_create(0, &e);
    assert_int_equal(gr_edmd_snapshot(a, pa, &e), GR_OK);
    assert_int_equal(gr_edmd_snapshot(b, pb, &e), GR_OK);
    assert_memory_equal(pa->x, pb->x, pa->n * sizeof(double));
    assert_memory_equal(pa->y, pb->y, pa->n * sizeof(double));
    assert_memory_equal(pa->vy, pb->vy, pa->n * sizeof(double));
    gr_edmd_averages aa, ab;
    gr_edmd_get_averages(a, &aa);
    gr_edmd_get_averages(b, &ab);
    assert_memory_equal(&aa, &ab, sizeof aa);
    gr_edmd_counters ca, cb;
    gr_edmd_get_counters(a, &ca);
    gr_edmd_get_counters(b, &cb);
    assert_memory_equal(&ca, &cb, sizeof ca);
    printf("# checkpoint at t = 16 with %llu asleep: identical at t = 21 (%llu asleep)\n",
           (unsigned long long)(c.sleeps - c.wakes), (unsigned long long)(ca.sleeps - ca.wakes));
    unlink(path);
    gr_particles_free(pa);
    gr_particles_free(pb);
    gr_particles_free(p0);
    gr_particles_free(p1);
    gr_edmd_free(a);
    gr_edmd_free(b);
}

/* Grain B dropped on grain A, which rests on the floor, a third of a
 * diameter off A's top: a disk on one slanted support is no equilibrium,
 * so B rolls off A, then along the floor to the side wall (a rolling
 * disk loses nothing), which stops it beside A (the rule
 * that let a grain sleep on any support from below held it on A's
 * shoulder, 1.4 d up). */
static void rolls_off(void **st)
{
    (void)st;
    gr_scene sc = edmd_box(8, 10, 0, 0.5);
    sc.gravity = 1.0;
    gr_edmd_params prm;
    gr_edmd_params_default(&prm);
    gr_err e = {0};
    gr_particles *p0 = gr_particles_create(2, &e);
    gr_particles_push(p0, 5.0, 0.5, 0.5, 1.0, 0, 0, &e);
    gr_particles_push(p0, 5.3, 2.0, 0.5, 1.0, 0, 0, &e);
    gr_edmd *s = NULL;
    assert_int_equal(gr_edmd_create(&sc, p0, &prm, NULL, &s, &e), GR_OK);
    assert_int_equal(gr_edmd_advance(s, 300.0, 0, &e), GR_OK);
    gr_particles *p = gr_particles_create(0, &e);
    assert_int_equal(gr_edmd_snapshot(s, p, &e), GR_OK);
    gr_edmd_counters c;
    gr_edmd_get_counters(s, &c);
    printf("# grain dropped 0.3 d off another's top: at rest at (%.4f, %.6f), v %.3g %.3g w %.3g, A at %.4f, %llu asleep\n", p->x[1], p->y[1], p->vx[1], p->vy[1], p->omega[1], p->x[0],
           (unsigned long long)(c.sleeps - c.wakes));
    assert_true(fabs(p->y[1] - 0.5) < 1e-3 && fabs(p->x[1] - p->x[0]) >= 1.0 - 1e-9);
    assert_true(c.sleeps - c.wakes == 2);
    gr_particles_free(p);
    gr_particles_free(p0);
    gr_edmd_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(bed_comes_to_rest),
        cmocka_unit_test(sleeping_checkpoint),
        cmocka_unit_test(rolls_off),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
