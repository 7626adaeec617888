/* A grain rolling over a segment's end under gravity (docs/methods/edmd.md,
 * "Grains over an edge"): the compare silo's orifice edge, where the TC
 * guard's elastic bounces, worn down by round-off below the resolution of
 * the contact function, turned into a Zeno sequence of contacts without
 * impulse and stopped the run as an inelastic collapse (silo.ini,
 * tc = 1e-5: grain 338 at t = 7.697). */
#include "test.h"

#include "edmd_compare.h"
#include "edmd_int.h"

/* The state of grain 338 on the orifice edge E = (8, 5) before the stop:
 * centre at R along n = (0.0881, 0.996), tangential speed 0.63 (v^2 / R =
 * 0.79 < g n_y: it stays on the edge), leaving at 1e-9. Contacts are
 * predicted by edmd_point_time and resolved elastically (the guard), as
 * the engine would: time must advance by the slack time per contact at
 * least, not shrink geometrically, and the grain stay within the slack
 * depth of the edge. */
static void leaving_an_edge(void **st)
{
    (void)st;
    static gr_edmd s; /* only g is read */
    s.g = 1.0;
    double ex = 8.0, ey = 5.0, R = 0.5, nx = 0.0881, ny = sqrt(1.0 - 0.0881 * 0.0881);
    double t0 = 7.6972;
    edmd_p p = {.x = ex + R * nx, .y = ey + R * ny, .r = R, .t = t0};
    p.vx = 0.63 * ny + 1e-9 * nx;
    p.vy = -0.63 * nx + 1e-9 * ny;
    double t = t0, deepest = 0.0;
    int events = 2000;
    for (int k = 0; k < events; k++) {
        double tn = edmd_point_time(&s, &p, ex, ey, t, t + 0.1);
        assert_true(tn >= t && tn < t + 0.1);
        t = tn;
        edmd_advance_p(&p, t, s.g);
        double qx = p.x - ex, qy = p.y - ey, q = hypot(qx, qy);
        deepest = fmin(deepest, q - R);
        double gn = (p.vx * qx + p.vy * qy) / q;
        if (gn < 0.0) { /* elastic */
            p.vx -= 2.0 * gn * qx / q;
            p.vy -= 2.0 * gn * qy / q;
        }
    }
    printf("# %d contacts in %.3e (slack time %.3e); deepest %.2e\n", events, t - t0,
           sqrt(2.0 * 2.0 * R * EDMD_SLACK / 2.0), deepest);
    /* the Zeno sequence: 2000 contacts within 1e-8 of t0 */
    assert_true(t - t0 > 1e-3);
    assert_true(deepest > -2.0 * EDMD_SLACK);
}

/* The compare silo, tc = 1e-5, to t = 8 (the stop was at 7.70). */
static void compare_silo_tc5(void **st)
{
    (void)st;
    const char *sets[2] = {"edmd.collapse=tc", "edmd.tc=1e-5"};
    gr_err e = {0};
    gr_scene *sc = NULL;
    gr_particles *p = NULL;
    gr_edmd *s = NULL;
    if (edmd_compare_state("silo.ini", sets, 2, &sc, &p, &s, &e))
        fail_msg("setup: %s", e.msg);
    int rc = gr_edmd_advance(s, 8.0, 0, &e);
    gr_edmd_counters c;
    gr_edmd_get_counters(s, &c);
    printf("# silo.ini, tc = 1e-5: %s at t = %.6g, %llu collisions\n", rc ? e.msg : "ran", gr_edmd_time(s),
           (unsigned long long)(c.pair + c.wall));
    assert_int_equal(rc, GR_OK);
    assert_true(gr_edmd_time(s) == 8.0);
    gr_edmd_free(s);
    gr_particles_free(p);
    gr_scene_free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(leaving_an_edge),
        cmocka_unit_test(compare_silo_tc5),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
