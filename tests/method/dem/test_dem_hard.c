/* Validation 7 of docs/methods/dem.md, hard cases: a time step just above the limit is
 * refused (naming file, line, key and the limit) and one just below runs a
 * dense stiff packing stably; a run pushed past stability stops with the
 * grain, overlap and time, leaving the last good state; a tall column at
 * rest presses on the floor with its weight within 0.1 %; grains jammed
 * over a small orifice do not tunnel through the wall grains. */
#include "dem_test.h"

#include <string.h>

#define PACK                                                                   \
    "[scene]\nseed = 2\n[domain]\nwidth = 14\nheight = 40\ngravity = 1\n"      \
    "[material]\nnormal = hertz\ntangential = regularised\nkn = 1e6\n"         \
    "gamma_n = 20\ngamma_t = 60\nmu = 0.5\n"                                   \
    "[species]\ncount = 200\npolydispersity = 0.15\n"                          \
    "[init]\nkind = lattice\nregion = 0 0 14 40\nvelocity = gaussian\nv0 = 0.2\n"

static double limit_of(const char *text)
{
    gr_scene *sc = dt_scene(text);
    gr_err e = {0};
    gr_particles *p = gr_particles_create(0, &e);
    assert_int_equal(gr_init_particles(sc, p, &e), GR_OK);
    gr_dem_params par;
    assert_int_equal(gr_dem_params_read(sc, &par, &e), GR_OK);
    assert_int_equal(gr_dem_check_dt(sc, p, &par, &e), GR_OK);
    double lim = par.dt_fraction * gr_dem_contact_time(sc, p, par.v_impact);
    gr_particles_free(p);
    gr_scene_free(sc);
    return lim;
}

static void dt_limit_refused_above_stable_below(void **state)
{
    (void)state;
    double lim = limit_of(PACK);
    char text[2048];
    snprintf(text, sizeof text, PACK "[dem]\ndt = %.9g\n", 1.01 * lim);
    gr_scene *sc = dt_scene(text);
    gr_err e = {0};
    gr_particles *p = gr_particles_create(0, &e);
    assert_int_equal(gr_init_particles(sc, p, &e), GR_OK);
    gr_dem_params par;
    assert_int_equal(gr_dem_params_read(sc, &par, &e), GR_OK);
    assert_int_equal(gr_dem_check_dt(sc, p, &par, &e), GR_EINPUT);
    printf("# dt = 1.01 x limit refused: %s\n", e.msg);
    assert_non_null(strstr(e.msg, "dem-test.ini:"));
    assert_non_null(strstr(e.msg, "[dem] key 'dt'"));
    char lims[64];
    snprintf(lims, sizeof lims, "%.6g", lim);
    assert_non_null(strstr(e.msg, lims));
    gr_particles_free(p);
    gr_scene_free(sc);

    snprintf(text, sizeof text, PACK "[dem]\ndt = %.9g\n", 0.99 * lim);
    sc = dt_scene(text);
    gr_dem *d = dt_create(sc, NULL);
    double ovl = 0;
    for (int k = 0; k < 30; k++) {
        dt_advance(d, d->t + 0.1);
        ovl = fmax(ovl, d->max_ovl);
    }
    double ek;
    gr_dem_energy(d, &ek, NULL);
    printf("# dt = 0.99 x limit = %.3g: 3 tau of a stiff (kn = 1e6) packing, largest overlap %.4f d, kinetic energy per grain %.2e\n",
           0.99 * lim, ovl, ek / d->nmobile);
    assert_true(ovl < 0.02);
    gr_dem_free(d);
    gr_scene_free(sc);
}

static void instability_stops_with_diagnostic(void **state)
{
    (void)state;
    double lim = limit_of(PACK);
    char text[2048];
    /* allow a step of 20 x the safe limit (2 contact times), with weak
     * damping so that only the contact-time check stands in the way */
    snprintf(text, sizeof text,
             "[scene]\nseed = 2\n[domain]\nwidth = 14\nheight = 40\ngravity = 1\n"
             "[material]\nnormal = hertz\ntangential = regularised\nkn = 1e6\n"
             "gamma_n = 0.1\ngamma_t = 0.3\nmu = 0.5\n"
             "[species]\ncount = 200\npolydispersity = 0.15\n"
             "[init]\nkind = lattice\nregion = 0 0 14 40\nvelocity = gaussian\nv0 = 0.2\n"
             "[dem]\ndt_fraction = 3\ndt = %.9g\n", 20 * lim);
    gr_scene *sc = dt_scene(text);
    /* past gr_dem_check_dt on purpose (its dense-packing bound refuses this
     * dt up front): what is tested is the run-time detection */
    gr_err e = {0};
    gr_particles *init = gr_particles_create(0, &e);
    assert_int_equal(gr_init_particles(sc, init, &e), GR_OK);
    gr_dem_params par;
    assert_int_equal(gr_dem_params_read(sc, &par, &e), GR_OK);
    assert_int_equal(gr_dem_check_dt(sc, init, &par, &e), GR_EINPUT);
    assert_non_null(strstr(e.msg, "dense packing"));
    e = (gr_err){0};
    par.dt = 20 * lim;
    gr_dem *d = NULL;
    assert_int_equal(gr_dem_create(sc, init, &par, NULL, &d, &e), GR_OK);
    gr_particles_free(init);
    int rc = GR_OK;
    double t_good = 0;
    for (int k = 0; k < 100000 && !rc; k++) {
        t_good = d->t;
        rc = gr_dem_step(d, &e);
    }
    printf("# dt = 20 x limit: %s\n", e.msg);
    assert_int_equal(rc, GR_ERUN);
    assert_non_null(strstr(e.msg, "grain id"));
    assert_non_null(strstr(e.msg, "t = "));
    /* the state is the last good step: finite, at the time before */
    assert_true(d->t == t_good);
    gr_particles *p = gr_particles_create(0, &e);
    assert_int_equal(gr_dem_snapshot(d, p, &e), GR_OK);
    for (size_t i = 0; i < p->n; i++)
        assert_true(isfinite(p->x[i]) && isfinite(p->vx[i]) && isfinite(p->y[i]) && isfinite(p->vy[i]));
    gr_particles_free(p);
    gr_dem_free(d);
    gr_scene_free(sc);
}

static void tall_column_weighs_on_floor(void **state)
{
    (void)state;
    enum { N = 60 };
    gr_scene *sc = dt_scene("[domain]\nwidth = 4\nheight = 70\ngravity = 1\n"
                            "[material]\nnormal = hertz\nkn = 1e5\ngamma_n = 100\n"
                            "[species]\ncount = 60\n[dem]\ndt = 1e-4\n");
    gr_err e = {0};
    gr_particles *p = gr_particles_create(N, &e);
    /* stacked in one file, each contact at its static Hertz overlap
     * (weight above)^(2/3) / kn^(2/3), so that the slow, weakly damped
     * modes of the column start small */
    double y = 0.5 - pow(N / 1e5, 2.0 / 3.0);
    for (int k = 0; k < N; k++) {
        gr_particles_push(p, 2.0, y, 0.5, 1.0, 0, 0, &e);
        y += 1.0 - pow((N - k - 1) / 1e5, 2.0 / 3.0);
    }
    gr_dem *d = dt_create(sc, p);
    dt_advance(d, 10.0);
    /* average the floor force over the last 2 tau */
    double fx = 0, fy = 0;
    int ns = 0;
    while (d->t < 12.0 - 1e-9) {
        dt_step(d, 10);
        for (int s = 0; s < d->nseg; s++) {
            double a, b;
            gr_dem_segment_force(d, s, &a, &b);
            fx += a, fy += b;
        }
        ns++;
    }
    fx /= ns, fy /= ns;
    double ek;
    gr_dem_energy(d, &ek, NULL);
    printf("# column of %d grains, 10 to 12 tau: mean force on the floor %.9f (weight %d, rel. error %.2e), kinetic energy %.2e\n",
           N, -fy, N, fabs(-fy / N - 1), ek);
    assert_true(fabs(-fy / N - 1) < 1e-3);
    assert_true(fabs(fx) < 1e-9);
    gr_dem_free(d);
    gr_particles_free(p);
    gr_scene_free(sc);
}

static void jammed_orifice_no_tunnelling(void **state)
{
    (void)state;
    gr_scene *sc = dt_scene("[scene]\nseed = 6\n"
                            "[domain]\nwidth = 12\nheight = 40\ngravity = 1\n"
                            "left = open\nright = open\nbottom = open\ntop = open\n"
                            "[material]\nnormal = hertz\ntangential = regularised\nkn = 1e5\n"
                            "gamma_n = 100\ngamma_t = 300\nmu = 0.5\n"
                            "[silo]\nwalls = grains\nwidth = 8\nheight = 36\nbase = 2\norifice = 2.2\n"
                            "exit_below = 0\n"
                            "[species]\ncount = 120\n"
                            "[init]\nkind = lattice\nregion = 2 12 10 38\nvelocity = gaussian\nv0 = 1\n"
                            "[dem]\ndt = 1.25e-4\n");
    gr_dem *d = dt_create(sc, NULL);
    double c = sc->silo.orifice_center, half = 0.5 * sc->silo.orifice;
    double xl = sc->silo.x0, xr = sc->silo.x0 + sc->silo.width, base = sc->silo.base;
    int bad = 0;
    for (int k = 0; k < 100; k++) {
        dt_advance(d, d->t + 0.1);
        int p = d->cur;
        for (size_t i = 0; i < d->n; i++) {
            if (d->flags[i] & GR_PF_FIXED)
                continue;
            double x = d->f[F_X][p][i], y = d->f[F_Y][p][i];
            int inside = x > xl && x < xr && y > base;
            int in_hole = fabs(x - c) < half && y <= base + 0.5;
            if (!inside && !in_hole)
                bad++;
        }
    }
    /* grains that left did so through the hole */
    int strays = 0;
    for (size_t t = 0; t < d->ntag; t++)
        if ((d->gone->flags[t] & GR_PF_GONE) && fabs(d->gone->x[t] - c) >= half)
            strays++;
    int arch = 0;
    for (size_t i = 0; i < d->n; i++)
        arch += !(d->flags[i] & GR_PF_FIXED) && fabs(d->f[F_X][d->cur][i] - c) < 2 &&
                d->f[F_Y][d->cur][i] < base + 1.5;
    printf("# orifice 2.2 d, 10 tau: %llu grains out, %d grains in the arch over the hole, %d grain-samples outside the container, %d left elsewhere\n",
           (unsigned long long)d->outflow, arch, bad, strays);
    assert_true(arch > 0);
    assert_int_equal(bad, 0);
    assert_int_equal(strays, 0);
    assert_true(d->outflow < 120); /* it jams */
    gr_dem_free(d);
    gr_scene_free(sc);
}

/* The dense-packing bound (docs/reliability.md): the figures of the
 * dynamical-matrix analysis there (linear springs, m = 1: kn = 1e5 with
 * gamma_n = 100 and 20, kn = 1e6 with gamma_n = 100), and a dt_fraction
 * raised so that dt passes the pair limit but not the dense one is refused
 * naming dt and the bound. */
static void dense_packing_bound(void **state)
{
    (void)state;
    const double cases[3][3] = {{1e5, 100, 1.77e-3}, {1e5, 20, 2.39e-3}, {1e6, 100, 7.2e-4}};
    gr_err e = {0};
    gr_particles *p = gr_particles_create(2, &e);
    gr_particles_push(p, 5, 5, 0.5, 1.0, 0, 0, &e);
    gr_particles_push(p, 8, 5, 0.5, 1.0, 0, 0, &e);
    for (int k = 0; k < 3; k++) {
        char text[512];
        snprintf(text, sizeof text, "[domain]\nwidth = 20\nheight = 20\n[material]\nkn = %g\ngamma_n = %g\n"
                 "[species]\ncount = 2\n", cases[k][0], cases[k][1]);
        gr_scene *sc = dt_scene(text);
        double b = gr_dem_dense_dt(sc, p, 1.0);
        printf("# kn = %g, gamma_n = %g: dense bound %.4g (docs: %.3g)\n", cases[k][0], cases[k][1], b, cases[k][2]);
        assert_true(fabs(b / cases[k][2] - 1) < 0.01);
        gr_scene_free(sc);
        snprintf(text + strlen(text), sizeof text - strlen(text), "[dem]\ndt_fraction = 1\ndt = %.9g\n", 1.05 * b);
        sc = dt_scene(text);
        gr_dem_params par;
        assert_int_equal(gr_dem_params_read(sc, &par, &e), GR_OK);
        assert_int_equal(gr_dem_check_dt(sc, p, &par, &e), GR_EINPUT);
        assert_non_null(strstr(e.msg, "dense packing"));
        assert_non_null(strstr(e.msg, "[dem] key 'dt'"));
        gr_scene_free(sc);
    }
    gr_particles_free(p);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(dense_packing_bound),
        cmocka_unit_test(dt_limit_refused_above_stable_below),
        cmocka_unit_test(instability_stops_with_diagnostic),
        cmocka_unit_test(tall_column_weighs_on_floor),
        cmocka_unit_test(jammed_orifice_no_tunnelling),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
