/* The soft DEM backend's table (methods/method.h). */
#include "dem.h"
#include "method.h"

static const char *const dem_keys[] = {
    "dt", "dt_fraction", "v_impact", "integrator", "neighbour", "skin", "threads",
    "max_overlap", "energy_jump", "sort_every", "cvode_rtol", "cvode_atol", NULL};

static int m_create(const gr_scene *sc, const gr_particles *init, void **state, gr_err *err)
{
    gr_dem_params par;
    if (gr_dem_params_read(sc, &par, err) || gr_dem_check_dt(sc, init, &par, err))
        return err->code;
    gr_dem *d;
    if (gr_dem_create(sc, init, &par, &d, err))
        return err->code;
    *state = d;
    return GR_OK;
}

static int m_advance(void *s, double t_end, uint64_t max_steps, gr_err *err)
{
    return gr_dem_advance(s, t_end, max_steps, err);
}

static double m_time(const void *s) { return ((const gr_dem *)s)->t; }

static int m_snapshot(void *s, gr_particles *out, gr_err *err) { return gr_dem_snapshot(s, out, err); }

static int m_observe(void *s, gr_obs *o, gr_err *err) { return gr_dem_observe(s, o, err); }

static int m_save(const void *s, gr_ckpt *ck, gr_err *err) { return gr_dem_save(s, ck, err); }

static int m_load(void *s, gr_ckpt *ck, gr_err *err) { return gr_dem_load(s, ck, err); }

static void m_free(void *s) { gr_dem_free(s); }

const gr_method_type gr_dem_method = {
    .name = "dem",
    .summary = "soft-particle DEM: linear/Hertz contacts, four friction laws, Verlet/Gear/Euler/CVODE",
    .features = GR_FEAT_GRAVITY | GR_FEAT_FRICTION | GR_FEAT_CONTACT_HISTORY | GR_FEAT_PERIODIC |
                GR_FEAT_OPEN_SIDE | GR_FEAT_SEGMENTS | GR_FEAT_WALL_GRAINS | GR_FEAT_ORIFICE |
                GR_FEAT_VIBRATING_FLOOR | GR_FEAT_REINSERT | GR_FEAT_POLYDISPERSE | GR_FEAT_MIXTURE |
                GR_FEAT_HERTZ,
    .param_keys = dem_keys,
    .create = m_create,
    .advance = m_advance,
    .time = m_time,
    .snapshot = m_snapshot,
    .observe = m_observe,
    .save = m_save,
    .load = m_load,
    .free = m_free,
};
