/* Helpers shared by the DEM validation tests: scenes from INI text, a
 * state with explicit [dem] parameters, and access to grains by tag. */
#ifndef GR_DEM_TEST_H
#define GR_DEM_TEST_H

#include "sim_test.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "dem/dem.h"
#include "init.h"

static inline gr_scene *dt_scene(const char *text)
{
    static const char *const ext[] = {"dem", NULL};
    return st_scene(text, "dem-test.ini", ext);
}

/* A state from the scene's [dem] section (checked like the method table),
 * or from init particles when given; aborts the test on failure. */
static inline gr_dem *dt_create(const gr_scene *sc, const gr_particles *init)
{
    gr_err e = {0};
    gr_particles *p = (gr_particles *)init;
    if (!p) {
        p = gr_particles_create(0, &e);
        assert_non_null(p);
        if (gr_init_particles(sc, p, &e))
            print_error("init: %s\n", e.msg);
        assert_int_equal(e.code, GR_OK);
    }
    gr_dem_params par;
    if (gr_dem_params_read(sc, &par, &e) || gr_dem_check_dt(sc, p, &par, &e))
        print_error("params: %s\n", e.msg);
    assert_int_equal(e.code, GR_OK);
    gr_dem *d = NULL;
    if (gr_dem_create(sc, p, &par, NULL, &d, &e))
        print_error("create: %s\n", e.msg);
    assert_non_null(d);
    if (!init)
        gr_particles_free(p);
    return d;
}

static inline void dt_step(gr_dem *d, long n)
{
    gr_err e = {0};
    for (long k = 0; k < n; k++) {
        if (gr_dem_step(d, &e)) {
            print_error("step: %s\n", e.msg);
            fail();
        }
    }
}

static inline void dt_advance(gr_dem *d, double t)
{
    gr_err e = {0};
    if (gr_dem_advance(d, t, 0, &e))
        print_error("advance: %s\n", e.msg);
    assert_int_equal(e.code, GR_OK);
}

#define DX(d, tag) ((d)->f[F_X][(d)->cur][gr_dem_index((d), (tag))])
#define DY(d, tag) ((d)->f[F_Y][(d)->cur][gr_dem_index((d), (tag))])
#define DVX(d, tag) ((d)->f[F_VX][(d)->cur][gr_dem_index((d), (tag))])
#define DVY(d, tag) ((d)->f[F_VY][(d)->cur][gr_dem_index((d), (tag))])
#define DW(d, tag) ((d)->f[F_W][(d)->cur][gr_dem_index((d), (tag))])

#endif
