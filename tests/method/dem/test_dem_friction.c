/* Validation 4 of docs/methods/dem.md, static friction with the tangential spring
 * (eqs. 2.10-2.12): a disk on a frictional incline rolls without slipping
 * below tan(theta) = 3 mu with acceleration (2/3) g sin(theta), and slips
 * above it with g (sin(theta) - mu cos(theta)); a disk pushed by a horizontal
 * force below mu m g stays put and above it slides with a = F/m - mu g
 * (rotation locked, so that it cannot roll: a free disk rolls, and does so
 * with a = 2F/3m, also checked). */
#include "dem_test.h"

#define MATERIAL                                                               \
    "[material]\nnormal = linear\ntangential = spring\nkn = 1e5\ngamma_n = 50\n" \
    "kt = 2e4\ngamma_t = 20\nmu = 0.5\n"

static gr_dem *one_disk(const char *extra, double x, double y)
{
    char text[2048];
    snprintf(text, sizeof text,
             "[domain]\nwidth = 30\nheight = 30\ngravity = 1\n" MATERIAL
             "[species]\ncount = 1\n[dem]\ndt = 2e-5\n%s", extra);
    gr_scene *sc = dt_scene(text);
    gr_err e = {0};
    gr_particles *p = gr_particles_create(1, &e);
    gr_particles_push(p, x, y, 0.5, 1.0, 0, 0, &e);
    gr_dem *d = dt_create(sc, p);
    gr_particles_free(p);
    gr_scene_free(sc); /* the state keeps what it needs */
    return d;
}

/* Acceleration along unit (ux, uy) by a least-squares line through the
 * velocity sampled every 0.01 over [t0, t1]; also the largest slip |v - w r|
 * relative to the speed at the end. */
static double measure(gr_dem *d, double ux, double uy, double t0, double t1, double *slip)
{
    dt_advance(d, t0);
    double st = 0, sv = 0, stt = 0, stv = 0;
    int n = 0;
    *slip = 0;
    while (d->t < t1 - 1e-9) {
        dt_advance(d, d->t + 0.01);
        double v = DVX(d, 0) * ux + DVY(d, 0) * uy;
        st += d->t, sv += v, stt += d->t * d->t, stv += d->t * v;
        n++;
        /* the contact point's velocity along the slope: v + w r (w > 0 is
         * counter-clockwise; rolling down to +x spins clockwise) */
        *slip = fmax(*slip, fabs(v + DW(d, 0) * 0.5));
    }
    *slip /= fabs(DVX(d, 0) * ux + DVY(d, 0) * uy) + 1e-300;
    return (n * stv - st * sv) / (n * stt - st * st);
}

static double incline(double theta_deg, double *slip)
{
    double th = theta_deg * M_PI / 180, c = cos(th), s = sin(th);
    double ax = 1, ay = 28, L = 28 / s < 40 ? 28 / s : 40;
    char seg[256];
    snprintf(seg, sizeof seg, "[wall.slope]\nfrom = %.17g %.17g\nto = %.17g %.17g\n", ax, ay, ax + L * c, ay - L * s);
    double xi0 = c / 1e5; /* resting overlap under m g cos(theta) */
    gr_dem *d = one_disk(seg, ax + 1.0 * c + (0.5 - xi0) * s, ay - 1.0 * s + (0.5 - xi0) * c);
    double a = measure(d, c, -s, 0.5, 2.0, slip);
    gr_dem_free(d);
    return a;
}

static void incline_rolls_below_3mu(void **state)
{
    (void)state;
    for (int k = 0; k < 2; k++) {
        double th = k ? 45 : 20, slip;
        double a = incline(th, &slip), want = 2.0 / 3.0 * sin(th * M_PI / 180);
        printf("# incline %g deg (tan = %.3f < 3 mu = 1.5): a = %.6f, (2/3) g sin = %.6f, rel. error %.2e, slip %.2e of v\n",
               th, tan(th * M_PI / 180), a, want, fabs(a / want - 1), slip);
        assert_true(fabs(a / want - 1) < 5e-3);
        assert_true(slip < 1e-2);
    }
}

static void incline_slips_above_3mu(void **state)
{
    (void)state;
    double th = 65, slip, r = th * M_PI / 180;
    double a = incline(th, &slip), want = sin(r) - 0.5 * cos(r);
    printf("# incline %g deg (tan = %.3f > 1.5): a = %.6f, g (sin - mu cos) = %.6f, rel. error %.2e, slip %.2f of v\n",
           th, tan(r), a, want, fabs(a / want - 1), slip);
    assert_true(fabs(a / want - 1) < 5e-3);
    assert_true(slip > 0.2);
}

static gr_dem *pushed(double F, int lock)
{
    gr_dem *d = one_disk("", 5, 0.5 - 1e-5);
    gr_err e = {0};
    assert_int_equal(gr_dem_set_external(d, 0, F, 0, &e), GR_OK);
    if (lock)
        gr_dem_lock_rotation(d, 0);
    return d;
}

static void push_below_mu_mg_holds(void **state)
{
    (void)state;
    gr_dem *d = pushed(0.3, 1);
    dt_advance(d, 1.0);
    double x1 = DX(d, 0);
    dt_advance(d, 3.0);
    double x3 = DX(d, 0), v = DVX(d, 0);
    printf("# pushed by 0.3 m g (locked rotation): moved %.2e from t = 1 to 3, speed %.2e, spring stretch F/kt = %.2e\n",
           fabs(x3 - x1), fabs(v), 0.3 / 2e4);
    assert_true(fabs(x3 - x1) < 1e-7);
    assert_true(fabs(v) < 1e-6);
    assert_true(fabs(x3 - 5) < 2 * 0.3 / 2e4);
    gr_dem_free(d);
}

static void push_above_mu_mg_slides(void **state)
{
    (void)state;
    double slip;
    gr_dem *d = pushed(0.8, 1);
    double a = measure(d, 1, 0, 0.5, 2.0, &slip);
    printf("# pushed by 0.8 m g (locked rotation): a = %.6f, F/m - mu g = 0.3, rel. error %.2e\n", a, fabs(a / 0.3 - 1));
    assert_true(fabs(a / 0.3 - 1) < 5e-3);
    gr_dem_free(d);
}

static void free_disk_rolls_when_pushed(void **state)
{
    (void)state;
    double slip;
    gr_dem *d = pushed(0.6, 0);
    double a = measure(d, 1, 0, 0.5, 2.0, &slip);
    printf("# free disk pushed by 0.6 m g: a = %.6f, 2F/3m = 0.4, rel. error %.2e\n", a, fabs(a / 0.4 - 1));
    assert_true(fabs(a / 0.4 - 1) < 5e-3);
    gr_dem_free(d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(incline_rolls_below_3mu),
        cmocka_unit_test(incline_slips_above_3mu),
        cmocka_unit_test(push_below_mu_mg_holds),
        cmocka_unit_test(push_above_mu_mg_slides),
        cmocka_unit_test(free_disk_rolls_when_pushed),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
