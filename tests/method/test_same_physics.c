/* One dissipation on every method: a scene that states the soft law's
 * damping (kn, gamma_n) and no restitution gives the hard methods the
 * restitution the soft DEM's own collisions have (gr_scene_restitution).
 * Measured, not only computed: the soft DEM's phase-averaged head-on
 * collision and wall rebound against edmd's and cd's, dsmc's restitution
 * read from its state, and a bed on edmd that loses energy. */
#include "sim_test.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dsmc/dsmc_int.h"
#include "restitution.h"

static const char *const ext[] = {"dem", "edmd", "cd", "dsmc", NULL};

/* kn and gamma_n, no restitution; grains of mass 1.7 so that m_eff is
 * not 1/2 by chance. */
static gr_scene *law_scene(int clip)
{
    char text[512];
    snprintf(text, sizeof text,
             "[domain]\nwidth = 40\nheight = 40\n"
             "[material]\nnormal = linear\nkn = 1e4\ngamma_n = 25\nclip_attraction = %s\n"
             "[species]\ncount = 2\n[dem]\ndt = 5e-5\nneighbour = brute\n",
             clip ? "yes" : "no");
    return st_scene(text, "same-physics.ini", ext);
}

#define MASS 1.7

/* Two grains approaching at speed 1, first touching after gap / 1, or (one
 * grain) a grain moving to the left wall. */
static gr_particles *grains(int pair, double gap)
{
    gr_err e = {0};
    gr_particles *p = gr_particles_create(2, &e);
    if (pair) {
        gr_particles_push(p, 20 - 0.5 - 0.5 * gap, 20, 0.5, MASS, 0, 0, &e);
        gr_particles_push(p, 20 + 0.5 + 0.5 * gap, 20, 0.5, MASS, 0, 0, &e);
        p->vx[0] = 0.5, p->vx[1] = -0.5;
    } else {
        gr_particles_push(p, 0.5 + gap, 20, 0.5, MASS, 0, 0, &e);
        gr_particles_push(p, 30, 20, 0.5, MASS, 0, 0, &e);
        p->vx[0] = -1.0;
    }
    return p;
}

/* The rebound speed over the impact speed after the contact is over. */
static double rebound(const char *method, const gr_scene *sc, int pair, double gap)
{
    gr_particles *p = grains(pair, gap);
    gr_sim *s = st_sim(gr_method_find(method), sc, p);
    gr_err e = {0};
    assert_int_equal(gr_sim_advance(s, 0.2, 0, &e), GR_OK);
    assert_int_equal(gr_sim_snapshot(s, p, &e), GR_OK);
    double r = pair ? p->vx[1] - p->vx[0] : p->vx[0];
    gr_sim_free(s);
    gr_particles_free(p);
    return r;
}

/* The soft DEM's force jumps where a contact starts, so one collision is
 * off by O(dt); averaged over phases of the first step that term cancels
 * (as in dem_collision). */
static double dem_rebound(const gr_scene *sc, int pair)
{
    const int nph = 8;
    double dt = 5e-5, s = 0.0;
    for (int k = 0; k < nph; k++)
        s += rebound("dem", sc, pair, dt * (1.0 + (k + 0.5) / nph)) / nph;
    return s;
}

static void kn_gamma_n_gives_dem_restitution(void **state)
{
    (void)state;
    for (int clip = 0; clip < 2; clip++) {
        gr_scene *sc = law_scene(clip);
        gr_particles *p = grains(1, 0.1);
        gr_restitution r;
        gr_err e = {0};
        assert_int_equal(gr_scene_restitution(sc, p, &r, &e), GR_OK);
        assert_int_equal(r.derived, 3);
        double dem_pair = dem_rebound(sc, 1), dem_wall = dem_rebound(sc, 0);
        double edmd_pair = rebound("edmd", sc, 1, 0.1), edmd_wall = rebound("edmd", sc, 0, 0.1);
        double cd_pair = rebound("cd", sc, 1, 0.1), cd_wall = rebound("cd", sc, 0, 0.1);
        printf("# clip %d: derived e %.6f, e_wall %.6f; dem measured %.6f, %.6f; edmd %.6f, %.6f; cd %.6f, %.6f\n",
               clip, r.e, r.e_wall, dem_pair, dem_wall, edmd_pair, edmd_wall, cd_pair, cd_wall);
        assert_true(fabs(dem_pair - r.e) < 1e-3);
        assert_true(fabs(dem_wall - r.e_wall) < 1e-3);
        assert_true(fabs(edmd_pair - r.e) < 1e-9 && fabs(edmd_wall - r.e_wall) < 1e-9);
        assert_true(fabs(cd_pair - r.e) < 1e-9 && fabs(cd_wall - r.e_wall) < 1e-9);
        gr_sim *s = st_sim(gr_method_find("dsmc"), sc, p);
        const gr_dsmc *d = gr_sim_state(s);
        assert_true(d->alpha == r.e && d->alpha_w == r.e_wall);
        assert_non_null(strstr(gr_sim_notes(s), "derived"));
        gr_sim_free(s);
        gr_particles_free(p);
        gr_scene_free(sc);
    }
}

/* Kinetic plus potential energy of a bed under gravity: constant on edmd
 * with gamma_n = 0 (e = 1), falling with gamma_n = 20 (it stayed constant
 * when edmd ignored the damping). */
static void kn_gamma_n_bed_loses_energy_on_edmd(void **state)
{
    (void)state;
    for (int k = 0; k < 2; k++) {
        char text[512];
        snprintf(text, sizeof text,
                 "[domain]\nwidth = 20\nheight = 20\ngravity = 1\n"
                 "[material]\nkn = 1e4\ngamma_n = %d\n[species]\ncount = 100\n"
                 "[init]\nkind = random\nvelocity = gaussian\nv0 = 1\n",
                 k ? 20 : 0);
        gr_scene *sc = st_scene(text, "same-physics.ini", ext);
        gr_sim *s = st_sim(gr_method_find("edmd"), sc, NULL);
        gr_obs o0, o1;
        gr_err e = {0};
        assert_int_equal(gr_sim_observe(s, &o0, &e), GR_OK);
        assert_int_equal(gr_sim_advance(s, 1.0, 0, &e), GR_OK);
        assert_int_equal(gr_sim_observe(s, &o1, &e), GR_OK);
        double E0 = o0.ekin_trans + o0.epot_grav, E1 = o1.ekin_trans + o1.epot_grav;
        printf("# edmd bed, kn 1e4, gamma_n %d: E(0) %.6f, E(1) %.6f (initial kinetic %.4f)\n", k ? 20 : 0, E0,
               E1, o0.ekin_trans);
        if (k)
            assert_true(E0 - E1 > 0.1 * o0.ekin_trans);
        else
            assert_true(fabs(E0 - E1) < 1e-9 * E0);
        gr_sim_free(s);
        gr_scene_free(sc);
    }
}

/* Hertz's damped restitution depends on the impact speed: a hard method
 * refuses gamma_n with it, naming the key to add. */
static void hertz_gamma_n_refused(void **state)
{
    (void)state;
    gr_scene *sc = st_scene("[domain]\nwidth = 40\nheight = 40\n[material]\nnormal = hertz\nkn = 1e4\n"
                            "gamma_n = 25\n[species]\ncount = 2\n",
                            "same-physics.ini", ext);
    gr_particles *p = grains(1, 0.1);
    gr_restitution r;
    gr_err e = {0};
    assert_int_equal(gr_scene_restitution(sc, p, &r, &e), GR_EINPUT);
    printf("# %s\n", e.msg);
    assert_non_null(strstr(e.msg, "same-physics.ini:7"));
    assert_non_null(strstr(e.msg, "[material] restitution"));
    gr_particles_free(p);
    gr_scene_free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(kn_gamma_n_gives_dem_restitution),
        cmocka_unit_test(kn_gamma_n_bed_loses_energy_on_edmd),
        cmocka_unit_test(hertz_gamma_n_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
