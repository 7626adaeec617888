/* Validation 1: a disk on an incline (a segment at angle alpha, gravity
 * g = 1, released at rest in contact). It rolls without slipping iff
 * tan(alpha) <= 3 mu, at acceleration (2/3) g sin(alpha) with omega R = v;
 * otherwise it slides at g (sin(alpha) - mu cos(alpha)) and spins up at
 * 2 mu g cos(alpha) / R. theta = 0.5 integrates constant accelerations
 * exactly, so velocity, spin and distance are asserted to 1e-6 relative. */
#include "cd_test.h"

static void incline(double alpha_deg, double mu)
{
    double a = alpha_deg * M_PI / 180, R = 0.5, L = 80, y0 = 70;
    char text[1024];
    snprintf(text, sizeof text,
             "[domain]\nwidth = 100\nheight = 100\ngravity = 1\n"
             "[material]\ntangential = coulomb\nmu = %.17g\n[species]\ncount = 1\n"
             "[wall.slope]\nfrom = 0 %.17g\nto = %.17g %.17g\n[cd]\ndt = 1e-3\n",
             mu, y0, L * cos(a), y0 - L * sin(a));
    gr_scene *sc = ct_scene(text);
    gr_err e = {0};
    gr_particles *p = gr_particles_create(1, &e);
    double s0 = 10; /* distance along the slope */
    gr_particles_push(p, s0 * cos(a) + R * sin(a), y0 - s0 * sin(a) + R * cos(a), R, 1.0, 0, 0, &e);
    gr_sim *s = ct_sim(sc, p);
    long nstep = 500;
    ct_steps(s, nstep);
    gr_particles *q = gr_particles_create(1, &e);
    assert_int_equal(gr_sim_snapshot(s, q, &e), GR_OK);
    double t = gr_sim_time(s);
    double v = q->vx[0] * cos(a) - q->vy[0] * sin(a), vn = q->vx[0] * sin(a) + q->vy[0] * cos(a);
    double dist = (q->x[0] - p->x[0]) * cos(a) - (q->y[0] - p->y[0]) * sin(a);
    int rolls = tan(a) <= 3 * mu;
    double acc = rolls ? 2.0 / 3.0 * sin(a) : sin(a) - mu * cos(a);
    double spin = rolls ? acc / R : 2 * mu * cos(a) / R; /* clockwise rate, down the slope */
    printf("# alpha %g mu %g (tan/3mu %.3f): %s, v %.12g (want %.12g), omega %.12g (want %.12g), "
           "sliding contacts %llu\n",
           alpha_deg, mu, tan(a) / (3 * mu), rolls ? "rolls" : "slides", v, acc * t, -q->omega[0], spin * t,
           (unsigned long long)ct_counter(s, "sliding_contacts"));
    assert_rel(v, acc * t, 1e-6);
    assert_rel(-q->omega[0], spin * t, 1e-6);
    assert_rel(dist, 0.5 * acc * t * t, 1e-6);
    assert_true(fabs(vn) <= 1e-12);
    assert_int_equal(ct_counter(s, "sliding_contacts"), rolls ? 0 : 1);
    gr_particles_free(p), gr_particles_free(q);
    gr_sim_free(s);
    gr_scene_free(sc);
}

static void rolls_and_slides(void **unused)
{
    (void)unused;
    /* both sides of tan(alpha) = 3 mu for three friction coefficients */
    incline(20, 0.2);  /* 0.607: rolls */
    incline(40, 0.2);  /* 1.40: slides */
    incline(30, 0.3);  /* 0.642: rolls */
    incline(60, 0.3);  /* 1.92: slides */
    incline(45, 0.35); /* 0.952: rolls, near the threshold */
    incline(48, 0.35); /* 1.06: slides, near the threshold */
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(rolls_and_slides)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
