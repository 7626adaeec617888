/* Helpers shared by the DSMC validation tests: an instance from INI text
 * (dsmc, or edmd as the reference on the same scene), advancing, the
 * temperature, a2, counters; the reference laws from experiments/lib/refs.h. */
#ifndef GR_DSMC_TEST_H
#define GR_DSMC_TEST_H

#include "sim_test.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dsmc/dsmc_int.h"
#include "init.h"
#include "method.h"
#include "refs.h"

/* An instance of method `m` ("dsmc" or "edmd") on the scene; *scp gets the
 * scene, for gr_scene_free after gr_sim_free. */
static inline gr_sim *ds_make_method(const char *m, const char *text, gr_scene **scp)
{
    static const char *const ext[] = {"dsmc", "edmd", NULL};
    *scp = st_scene(text, "dsmc-test.ini", ext);
    return st_sim(gr_method_find(m), *scp, NULL);
}

static inline gr_sim *ds_make(const char *text, gr_scene **scp) { return ds_make_method("dsmc", text, scp); }

static inline void ds_run_to(gr_sim *s, double t)
{
    gr_err e = {0};
    if (gr_sim_advance(s, t, 0, &e))
        print_error("advance: %s\n", e.msg);
    assert_int_equal(e.code, GR_OK);
}

static inline uint64_t ds_counter(gr_sim *s, const char *name)
{
    uint64_t v = 0;
    if (!gr_sim_counter(s, name, &v))
        fail_msg("no counter %s", name);
    return v;
}

static inline gr_obs ds_observe(gr_sim *s)
{
    gr_obs o;
    gr_err e = {0};
    assert_int_equal(gr_sim_observe(s, &o, &e), GR_OK);
    return o;
}

static inline double ds_temp(gr_sim *s) { return ds_observe(s).temperature; }

/* a2 = <v^4> / (2 <v^2>^2) - 1 of the peculiar velocities (2-D). */
static inline double ds_a2(const gr_dsmc *d)
{
    double mx = 0, my = 0, s2 = 0, s4 = 0, n = (double)d->n;
    for (size_t i = 0; i < d->n; i++)
        mx += d->vx[i] / n, my += d->vy[i] / n;
    for (size_t i = 0; i < d->n; i++) {
        double ux = d->vx[i] - mx, uy = d->vy[i] - my, u2 = ux * ux + uy * uy;
        s2 += u2 / n, s4 += u2 * u2 / n;
    }
    return s4 / (2 * s2 * s2) - 1;
}

#endif
