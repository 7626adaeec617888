/* Walls and boundaries: a grain resting on a floor vibrating below
 * A w^2 = g follows it; a grain on a gate segment falls once the gate
 * opens; a grain crossing an open side leaves (outflow, flagged gone);
 * domain walls and wall segments hold grains with the same contact law
 * as grains (a wall is a grain of infinite mass and zero radius). */
#include "dem_test.h"

#include <string.h>

static gr_dem *one(const char *text, double x, double y, double vx, double vy)
{
    gr_scene *sc = dt_scene(text);
    gr_err e = {0};
    gr_particles *p = gr_particles_create(1, &e);
    gr_particles_push(p, x, y, 0.5, 1.0, 0, 0, &e);
    p->vx[0] = vx;
    p->vy[0] = vy;
    gr_dem *d = dt_create(sc, p);
    gr_particles_free(p);
    gr_scene_free(sc);
    return d;
}

static void rides_a_slow_vibrating_floor(void **state)
{
    (void)state;
    /* A w^2 = 0.5 g: the grain never takes off */
    double A = 0.02, w = 5.0;
    char text[1024];
    snprintf(text, sizeof text,
             "[domain]\nwidth = 10\nheight = 10\ngravity = 1\n"
             "[floor]\nmotion = sine\namplitude = %g\nomega = %g\n"
             "[material]\nnormal = linear\nkn = 1e5\ngamma_n = 50\n"
             "[species]\ncount = 1\n[dem]\ndt = 1e-4\n", A, w);
    double xi0 = 1.0 / 1e5;
    gr_dem *d = one(text, 5, A + 0.5 - xi0, 0, 0);
    double worst = 0;
    while (d->t < 4.0 - 1e-9) {
        dt_advance(d, d->t + 0.01);
        if (d->t > 1.0) {
            /* the floor's acceleration adds m A w^2 cos(w t) to the load */
            double want = A * cos(w * d->t) + 0.5 - xi0 * (1.0 - A * w * w * cos(w * d->t));
            worst = fmax(worst, fabs(DY(d, 0) - want));
        }
    }
    printf("# grain on a floor vibrating at A w^2 = 0.5 g: largest distance to the floor's rest position %.2e d\n", worst);
    assert_true(worst < 2e-5);
    gr_dem_free(d);
}

static void gate_opens(void **state)
{
    (void)state;
    gr_dem *d = one("[domain]\nwidth = 10\nheight = 10\ngravity = 1\nbottom = open\n"
                    "[wall.gate]\nfrom = 2 5\nto = 8 5\nopen_time = 1\n"
                    "[material]\nnormal = linear\nkn = 1e5\ngamma_n = 50\n"
                    "[species]\ncount = 1\n[dem]\ndt = 1e-4\n",
                    5, 5.5 - 1e-5, 0, 0);
    dt_advance(d, 0.99);
    double y1 = DY(d, 0);
    dt_advance(d, 1.5);
    double y2 = DY(d, 0), fall = 0.5 * 0.5 * 0.5; /* g t^2 / 2 over 0.5 */
    printf("# gate open at t = 1: rests at %.6f before, has fallen %.6f by t = 1.5 (free fall %.6f)\n", y1,
           y1 - y2, fall);
    assert_true(fabs(y1 - (5.5 - 1e-5)) < 1e-4);
    assert_true(fabs((y1 - y2) / fall - 1) < 1e-3);
    dt_advance(d, 5.0);
    /* it crossed the open bottom side (y = 0 at t = 1 + sqrt(11)) */
    assert_int_equal(d->outflow, 1);
    assert_int_equal(d->n, 0);
    gr_err e = {0};
    gr_particles *p = gr_particles_create(0, &e);
    assert_int_equal(gr_dem_snapshot(d, p, &e), GR_OK);
    assert_int_equal(p->n, 1);
    assert_true(p->flags[0] & GR_PF_GONE);
    assert_true(p->y[0] < 0);
    gr_particles_free(p);
    gr_dem_free(d);
}

static void walls_hold_like_grains(void **state)
{
    (void)state;
    /* head-on on a side wall (m_eff = m) and on a wall grain of the same
     * law: the same restitution, that of eq. 2.3 with m_eff = m */
    const char *box = "[domain]\nwidth = 10\nheight = 10\n"
                      "[material]\nnormal = linear\nkn = 1e5\ngamma_n = 20\nclip_attraction = no\n"
                      "[species]\ncount = 1\n[dem]\ndt = 2e-5\n";
    gr_dem *d = one(box, 0.5 + 0.01, 5, -1, 0);
    dt_advance(d, 0.2);
    double e_wall = DVX(d, 0);
    gr_dem_free(d);
    gr_scene *sc = dt_scene(box);
    gr_err e = {0};
    gr_particles *p = gr_particles_create(2, &e);
    gr_particles_push(p, 5, 5, 0.5, 1.0, GR_PF_FIXED, 0, &e);
    gr_particles_push(p, 6 + 0.01, 5, 0.5, 1.0, 0, 0, &e);
    p->vx[1] = -1;
    d = dt_create(sc, p);
    dt_advance(d, 0.2);
    double e_grain = DVX(d, 1);
    double me = 1.0, tc = M_PI / sqrt(1e5 / me - pow(20 / (2 * me), 2)), e_th = exp(-20 / (2 * me) * tc);
    printf("# restitution on a wall %.6f, on a wall grain %.6f, eq. 2.3 with m_eff = m: %.6f\n", e_wall, e_grain, e_th);
    assert_true(fabs(e_wall / e_th - 1) < 5e-3);
    assert_true(fabs(e_grain / e_th - 1) < 5e-3);
    gr_dem_free(d);
    gr_particles_free(p);
    gr_scene_free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(rides_a_slow_vibrating_floor),
        cmocka_unit_test(gate_opens),
        cmocka_unit_test(walls_hold_like_grains),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
