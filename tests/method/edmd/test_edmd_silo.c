/* The silo of the scene with wall segments: closed until the gate opens,
 * grains flow out through the orifice, leave below the base and are gone
 * or reinserted at the top; no grain ever crosses a wall or another grain. */
#include "test.h"

#include <stdlib.h>

#include "edmd_int.h"
#include "edmd_test.h"
#include "geom.h"
#include "init.h"

static const char *const extra[] = {"edmd", NULL};

static gr_scene *silo_scene(int reinsert)
{
    char text[2048];
    snprintf(text, sizeof text,
             "[scene]\nname = edmd-silo\nseed = 5\n"
             "[domain]\nwidth = 22\nheight = 60\nbottom = open\ngravity = 1\n"
             "[material]\nrestitution = 0.9\ntangential_restitution = 0.5\nmu = 0.5\n"
             "[species]\ndiameter = 1\npolydispersity = 0.1\ncount = 250\n"
             "[silo]\nwidth = 20\nheight = 50\nleft = 1\nbase = 5\norifice = 6\nopen_time = 5\n"
             "walls = segments\nreinsert = %s\n"
             "[init]\nkind = lattice\nregion = 1 5 21 40\nspacing = 1.05\nvelocity = gaussian\nv0 = 0.5\n"
             "[edmd]\ncollapse = tc\ntc = 1e-4\n",
             reinsert ? "yes" : "no");
    gr_err e = {0};
    gr_scene *sc = gr_scene_parse(text, "silo-test.ini", extra, &e);
    if (!sc)
        fprintf(stderr, "%s\n", e.msg);
    assert_non_null(sc);
    return sc;
}

/* Largest penetration of a grain into another or into an active segment. */
static double worst_overlap(const gr_scene *sc, const gr_particles *p, double t)
{
    double worst = 0;
    for (size_t i = 0; i < p->n; i++) {
        if (p->flags[i] & GR_PF_GONE)
            continue;
        for (size_t j = i + 1; j < p->n; j++) {
            if (p->flags[j] & GR_PF_GONE)
                continue;
            double ov = p->radius[i] + p->radius[j] - hypot(p->x[j] - p->x[i], p->y[j] - p->y[i]);
            worst = fmax(worst, ov);
        }
        for (int k = 0; k < sc->nsegments; k++) {
            const gr_segment *q = &sc->segments[k];
            if (!gr_segment_active(q, t))
                continue;
            double d = gr_seg_distance(gr_v2_make(q->x0, q->y0), gr_v2_make(q->x1, q->y1), gr_v2_make(p->x[i], p->y[i]));
            worst = fmax(worst, p->radius[i] - d);
        }
    }
    return worst;
}

static void discharge(void **st)
{
    (void)st;
    for (int re = 0; re < 2; re++) {
        gr_scene *sc = silo_scene(re);
        gr_err e = {0};
        gr_particles *p = gr_particles_create(0, &e);
        assert_int_equal(gr_init_particles(sc, p, &e), GR_OK);
        gr_sim *sim = NULL;
        int rc = gr_sim_create(&gr_edmd_method, sc, p, &sim, &e);
        if (rc)
            fprintf(stderr, "%s\n", e.msg);
        assert_int_equal(rc, GR_OK);
        gr_edmd *s = gr_sim_state(sim);
        double worst = 0;
        rc = gr_edmd_advance(s, 4.99, 0, &e);
        if (rc)
            fprintf(stderr, "%s\n", e.msg);
        assert_int_equal(rc, GR_OK);
        assert_int_equal(gr_edmd_snapshot(s, p, &e), GR_OK);
        worst = fmax(worst, worst_overlap(sc, p, gr_edmd_time(s)));
        gr_obs o;
        gr_obs_clear(&o);
        assert_int_equal(gr_sim_observe(sim, &o, &e), GR_OK);
        assert_int_equal(o.outflow, 0); /* closed before the gate opens */
        for (int k = 1; k <= 6; k++) {
            rc = gr_edmd_advance(s, 5.0 + 5.0 * k, 0, &e);
            if (rc)
                fprintf(stderr, "%s\n", e.msg);
            assert_int_equal(rc, GR_OK);
            assert_int_equal(gr_edmd_snapshot(s, p, &e), GR_OK);
            worst = fmax(worst, worst_overlap(sc, p, gr_edmd_time(s)));
        }
        assert_int_equal(gr_sim_observe(sim, &o, &e), GR_OK);
        size_t gone = 0;
        for (size_t i = 0; i < p->n; i++) {
            if (p->flags[i] & GR_PF_GONE) {
                gone++;
                continue;
            }
            /* inside the silo (or just below the orifice, on its way out) */
            if (!(p->y[i] > sc->silo.exit_below - 1e-9))
                printf("# grain %zu at (%g, %g) v (%g, %g)\n", i, p->x[i], p->y[i], p->vx[i], p->vy[i]);
            assert_true(p->x[i] > 1.0 && p->x[i] < 21.0);
            assert_true(p->y[i] > sc->silo.exit_below - 1e-9);
        }
        gr_edmd_counters c;
        gr_edmd_get_counters(s, &c);
        printf("# silo, reinsert = %d: t = %g, outflow %llu, gone %zu, %llu collisions, worst overlap %.2e\n", re,
               gr_edmd_time(s), (unsigned long long)o.outflow, gone, (unsigned long long)(c.pair + c.wall), worst);
        assert_true(o.outflow > 50);
        if (re)
            assert_int_equal(gone, 0);
        else
            assert_int_equal(gone, o.outflow);
        assert_true(worst < 1e-9);
        gr_sim_free(sim);
        gr_particles_free(p);
        gr_scene_free(sc);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(discharge),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
