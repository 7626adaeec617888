/* Validations 1 and 2 of docs/methods/dem.md: the two-disk head-on collision.
 * 1. Linear spring-dashpot: restitution and contact time equal eqs. 2.2-2.3
 *    within 0.1 % at dt = t_c/100; velocity Verlet's error falls by ~4 when
 *    dt halves.
 * 2. Hertz: undamped contact time scales as v^(-1/5) (fitted exponent within
 *    2 %) and the trajectory matches the CVODE reference; with damping the
 *    restitution decreases with impact speed. */
#include "dem_test.h"

#include <string.h>

typedef struct {
    double e, tc, ximax;
} collision;

static gr_scene *pair_scene(const char *normal, double kn, double gn, int clip, double dt,
                            const char *integrator)
{
    char text[2048];
    snprintf(text, sizeof text,
             "[domain]\nwidth = 40\nheight = 40\n"
             "[material]\nnormal = %s\nkn = %.17g\ngamma_n = %.17g\nclip_attraction = %s\n"
             "[species]\ncount = 2\n"
             "[dem]\ndt = %.17g\nintegrator = %s\nneighbour = brute\nv_impact = 8\n",
             normal, kn, gn, clip ? "yes" : "no", dt, integrator);
    return dt_scene(text);
}

/* Disks of unit mass and diameter approaching at speed v, first touching
 * at t = dt (1 + phase). */
static collision collide(gr_scene *sc, double v, double phase)
{
    gr_err e = {0};
    gr_particles *p = gr_particles_create(2, &e);
    double dt;
    {
        gr_dem_params par;
        assert_int_equal(gr_dem_params_read(sc, &par, &e), GR_OK);
        dt = par.dt;
    }
    double gap = v * dt * (1.0 + phase);
    gr_particles_push(p, 20 - 0.5 - 0.5 * gap, 20, 0.5, 1.0, 0, 0, &e);
    gr_particles_push(p, 20 + 0.5 + 0.5 * gap, 20, 0.5, 1.0, 0, 0, &e);
    p->vx[0] = 0.5 * v;
    p->vx[1] = -0.5 * v;
    gr_dem *d = dt_create(sc, p);
    collision c = {0, 0, 0};
    double xi_prev = -gap, t_on = -1, t_off = -1;
    for (long k = 0; k < 1000000 && t_off < 0; k++) {
        dt_step(d, 1);
        double xi = 1.0 - (DX(d, 1) - DX(d, 0));
        c.ximax = fmax(c.ximax, xi);
        if (xi_prev <= 0 && xi > 0)
            t_on = d->t - dt + dt * (-xi_prev) / (xi - xi_prev);
        if (xi_prev > 0 && xi <= 0 && t_on >= 0)
            t_off = d->t - dt + dt * xi_prev / (xi_prev - xi);
        xi_prev = xi;
    }
    dt_step(d, 2);
    c.tc = t_off - t_on;
    c.e = (DVX(d, 1) - DVX(d, 0)) / v;
    gr_dem_free(d);
    gr_particles_free(p);
    return c;
}

/* Phase-averaged collision: the force jumps when the contact starts and
 * ends, which gives each single collision an O(dt) error depending on where
 * in a step the contact begins; averaged over equally spaced phases that
 * term cancels and the second-order error of the integrator remains. */
static collision averaged_on(gr_scene *sc, double v, int nphase)
{
    collision a = {0, 0, 0};
    for (int k = 0; k < nphase; k++) {
        collision c = collide(sc, v, (k + 0.5) / nphase);
        a.e += c.e / nphase;
        a.tc += c.tc / nphase;
        a.ximax = fmax(a.ximax, c.ximax);
    }
    gr_scene_free(sc);
    return a;
}

static collision averaged(const char *normal, double kn, double gn, int clip, double dt,
                          const char *integ, double v, int nphase)
{
    return averaged_on(pair_scene(normal, kn, gn, clip, dt, integ), v, nphase);
}

/* [material] restitution alone: the soft DEM derives gamma_n (dem_damping.c)
 * so that the binary collision rebounds with e, clipped (Schwager and
 * Poeschel 2007) or not (the damped oscillator). */
static gr_scene *restitution_scene(double e, int clip, const char *extra)
{
    char text[1024];
    snprintf(text, sizeof text,
             "[domain]\nwidth = 40\nheight = 40\n"
             "[material]\nkn = 1e4\nrestitution = %.17g\nclip_attraction = %s\n%s"
             "[species]\ncount = 2\n[dem]\ndt = 5e-5\nneighbour = brute\n",
             e, clip ? "yes" : "no", extra);
    return dt_scene(text);
}

static void linear_restitution_from_scene(void **state)
{
    (void)state;
    const double es[5] = {0.99, 0.9, 0.6, 0.3, 0.05};
    for (int clip = 0; clip < 2; clip++) {
        for (int k = 0; k < 5; k++) {
            collision c = averaged_on(restitution_scene(es[k], clip, ""), 1.0, 8);
            printf("# restitution = %g, clip_attraction = %s: measured e = %.6f (error %.1e)\n", es[k],
                   clip ? "yes" : "no", c.e, c.e - es[k]);
            assert_true(fabs(c.e - es[k]) < 1e-3);
        }
    }
    /* without clipping e = 0 is critical damping: the pair sticks */
    collision c = averaged_on(restitution_scene(0.0, 0, ""), 1.0, 2);
    printf("# restitution = 0, clip_attraction = no: measured e = %.2e\n", c.e);
    assert_true(fabs(c.e) < 1e-3);
}

/* One grain of unit mass against the left wall at speed v: the wall's own
 * restitution, from its own damping (m_eff = m, not m / 2). */
static void wall_restitution_from_scene(void **state)
{
    (void)state;
    const double cases[3][2] = {{0.9, NAN}, {0.9, 0.6}, {0.5, 1.0}};
    for (int k = 0; k < 3; k++) {
        char extra[64] = "";
        if (!isnan(cases[k][1]))
            snprintf(extra, sizeof extra, "wall_restitution = %g\n", cases[k][1]);
        gr_scene *sc = restitution_scene(cases[k][0], 1, extra);
        gr_err e = {0};
        gr_particles *p = gr_particles_create(2, &e);
        gr_particles_push(p, 0.5 + 0.0123, 20, 0.5, 1.0, 0, 0, &e);
        gr_particles_push(p, 30, 20, 0.5, 1.0, 0, 0, &e);
        p->vx[0] = -1.0;
        gr_dem *d = dt_create(sc, p);
        dt_advance(d, 0.1);
        double want = isnan(cases[k][1]) ? cases[k][0] : cases[k][1];
        printf("# restitution %g, wall_restitution %g: wall rebound %.6f\n", cases[k][0], cases[k][1],
               DVX(d, 0));
        assert_true(fabs(DVX(d, 0) - want) < 2e-3);
        gr_dem_free(d);
        gr_particles_free(p);
        gr_scene_free(sc);
    }
}

/* What the soft DEM cannot honour is refused naming the key. */
static void restitution_refusals(void **state)
{
    (void)state;
    const char *bad[3][2] = {
        {"normal = hertz\n", "hertz"},
        {"gamma_n = 100\n", "disagrees"},
        {"", "out of reach"},
    };
    for (int k = 0; k < 3; k++) {
        gr_scene *sc = restitution_scene(k == 2 ? 0.0 : 0.9, 1, bad[k][0]);
        gr_err e = {0};
        gr_particles *p = gr_particles_create(2, &e);
        gr_particles_push(p, 10, 20, 0.5, 1.0, 0, 0, &e);
        gr_particles_push(p, 30, 20, 0.5, 1.0, 0, 0, &e);
        gr_dem_params par;
        assert_int_equal(gr_dem_params_read(sc, &par, &e), GR_OK);
        assert_int_equal(gr_dem_check_dt(sc, p, &par, &e), GR_EINPUT);
        printf("# refused: %s\n", e.msg);
        assert_non_null(strstr(e.msg, bad[k][1]));
        assert_non_null(strstr(e.msg, "dem-test.ini:"));
        gr_particles_free(p);
        gr_scene_free(sc);
    }
}

static void linear_restitution_and_contact_time(void **state)
{
    (void)state;
    double kn = 1e5, gn = 20, me = 0.5;
    double w2 = kn / me - pow(gn / (2 * me), 2);
    double tc = M_PI / sqrt(w2);                 /* eq. 2.2 */
    double e_th = exp(-gn / (2 * me) * tc);      /* eq. 2.3 */
    double err_e[3], err_t[3];
    const double div[3] = {50, 100, 200};
    for (int k = 0; k < 3; k++) {
        collision c = averaged("linear", kn, gn, 0, tc / div[k], "verlet", 1.0, 16);
        err_e[k] = fabs(c.e / e_th - 1);
        err_t[k] = fabs(c.tc / tc - 1);
        printf("# linear dt = t_c/%g: e = %.8f (eq. 2.3: %.8f, rel. error %.2e), t_c = %.8f (eq. 2.2: %.8f, rel. error %.2e)\n",
               div[k], c.e, e_th, err_e[k], c.tc, tc, err_t[k]);
    }
    assert_true(err_e[1] < 1e-3);
    assert_true(err_t[1] < 1e-3);
    double re = err_e[0] / err_e[1], rt = err_t[0] / err_t[1];
    double re2 = err_e[1] / err_e[2], rt2 = err_t[1] / err_t[2];
    printf("# error ratio when dt halves: restitution %.2f, %.2f; contact time %.2f, %.2f (second order: 4)\n",
           re, re2, rt, rt2);
    assert_true(re > 3.0 && re < 5.5);
    assert_true(re2 > 3.0 && re2 < 5.5);
    assert_true(rt > 3.0 && rt < 5.5);
}

static void linear_single_collision_phase_error(void **state)
{
    (void)state;
    /* without averaging, each collision is still within 0.5 % at t_c/100 */
    double kn = 1e5, gn = 20, me = 0.5;
    double tc = M_PI / sqrt(kn / me - pow(gn / (2 * me), 2)), e_th = exp(-gn / (2 * me) * tc);
    gr_scene *sc = pair_scene("linear", kn, gn, 0, tc / 100, "verlet");
    double worst = 0;
    for (int k = 0; k < 8; k++)
        worst = fmax(worst, fabs(collide(sc, 1.0, k / 8.0).e / e_th - 1));
    printf("# single collisions at t_c/100: worst restitution error %.2e\n", worst);
    assert_true(worst < 5e-3);
    gr_scene_free(sc);
}

static void hertz_contact_time_scaling(void **state)
{
    (void)state;
    double kn = 1e5, me = 0.5;
    const double v[6] = {0.25, 0.5, 1, 2, 4, 8};
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int k = 0; k < 6; k++) {
        double tc_th = 3.21 * pow(me / kn, 0.4) * pow(v[k], -0.2); /* eq. 2.5 */
        collision c = averaged("hertz", kn, 0, 1, tc_th / 200, "verlet", v[k], 4);
        printf("# hertz v = %g: t_c = %.8f (eq. 2.5: %.8f), e = %.8f\n", v[k], c.tc, tc_th, c.e);
        assert_true(fabs(c.tc / tc_th - 1) < 5e-3); /* 3.21 is the rounded 3.2181 */
        assert_true(fabs(c.e - 1) < 1e-4);
        double lx = log(v[k]), ly = log(c.tc);
        sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
    }
    double slope = (6 * sxy - sx * sy) / (6 * sxx - sx * sx);
    printf("# fitted exponent %.6f (theory -0.2, rel. error %.2e)\n", slope, fabs(slope / -0.2 - 1));
    assert_true(fabs(slope / -0.2 - 1) < 0.02);
}

/* Overlap history of one collision sampled at fixed times. */
static void sample(gr_scene *sc, double v, double gap, const double *ts, int nt, double *xi)
{
    gr_err e = {0};
    gr_particles *p = gr_particles_create(2, &e);
    gr_particles_push(p, 19.5 - 0.5 * gap, 20, 0.5, 1.0, 0, 0, &e);
    gr_particles_push(p, 20.5 + 0.5 * gap, 20, 0.5, 1.0, 0, 0, &e);
    p->vx[0] = 0.5 * v;
    p->vx[1] = -0.5 * v;
    gr_dem *d = dt_create(sc, p);
    for (int k = 0; k < nt; k++) {
        dt_advance(d, ts[k]);
        assert_true(fabs(d->t - ts[k]) < 1e-9);
        xi[k] = 1.0 - (DX(d, 1) - DX(d, 0));
    }
    gr_dem_free(d);
    gr_particles_free(p);
}

static void hertz_matches_cvode_reference(void **state)
{
    (void)state;
    double kn = 1e5, v = 1.0, tc = 3.21 * pow(0.5 / kn, 0.4);
    /* sample on the Verlet grid: dt = tc/400, times multiples of 8 dt */
    double dt = tc / 400;
    enum { NT = 80 };
    double ts[NT], a[NT], b[NT];
    for (int k = 0; k < NT; k++)
        ts[k] = dt * 8 * (k + 1);
    gr_scene *s1 = pair_scene("hertz", kn, 0, 1, dt, "verlet");
    gr_scene *s2 = pair_scene("hertz", kn, 0, 1, dt, "cvode");
    sample(s1, v, 0.2 * tc * v, ts, NT, a);
    sample(s2, v, 0.2 * tc * v, ts, NT, b);
    double worst = 0, ximax = 0;
    for (int k = 0; k < NT; k++) {
        worst = fmax(worst, fabs(a[k] - b[k]));
        ximax = fmax(ximax, b[k]);
    }
    printf("# hertz v = 1, dt = t_c/400: max |xi_verlet - xi_cvode| = %.3e (%.2e of the peak overlap %.4e)\n",
           worst, worst / ximax, ximax);
    assert_true(worst < 2e-3 * ximax);
    gr_scene_free(s1);
    gr_scene_free(s2);
}

/* With the thesis's constant gamma_n (eq. 2.4) the damping impulse over a
 * contact, relative to m v, scales as gamma_n v^(-1/5): the restitution
 * depends on the impact speed, and for weak damping ln(1/e) v^(1/5) is a
 * constant. (The issue expected e to fall with v; that holds for damping
 * growing with the overlap, not for this law: see docs/methods/dem.md.) */
static void hertz_damped_restitution_depends_on_speed(void **state)
{
    (void)state;
    const double v[5] = {0.25, 0.5, 1, 2, 4};
    double prev = 0, s0 = 0;
    for (int k = 0; k < 5; k++) {
        double tc = 3.21 * pow(0.5 / 1e5, 0.4) * pow(v[k], -0.2);
        collision c = averaged("hertz", 1e5, 2, 0, tc / 200, "verlet", v[k], 4);
        double s = log(1 / c.e) * pow(v[k], 0.2);
        if (k == 0)
            s0 = s;
        printf("# damped hertz v = %g: e = %.6f, ln(1/e) v^(1/5) = %.6f\n", v[k], c.e, s);
        assert_true(c.e > prev + 1e-4);
        assert_true(c.e > 0 && c.e < 1);
        assert_true(fabs(s / s0 - 1) < 0.03);
        prev = c.e;
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(linear_restitution_and_contact_time),
        cmocka_unit_test(linear_single_collision_phase_error),
        cmocka_unit_test(hertz_contact_time_scaling),
        cmocka_unit_test(hertz_matches_cvode_reference),
        cmocka_unit_test(hertz_damped_restitution_depends_on_speed),
        cmocka_unit_test(linear_restitution_from_scene),
        cmocka_unit_test(wall_restitution_from_scene),
        cmocka_unit_test(restitution_refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
