/* The soft DEM backend's table (methods/method.h). */
#include <math.h>
#include <stdio.h>

#include "dem.h"
#include "dem_params.h"
#include "method.h"

/* The damping derived from a restitution, for the run's log. */
static void note_damping(gr_sim *sim, const gr_scene *sc, const gr_dem *d)
{
    const gr_material *m = &sc->mat;
    if (isnan(m->restitution) && isnan(m->wall_restitution))
        return;
    char pair[96], wall[96], note[400];
    int given = gr_scene_find(sc, "material", "gamma_n") != NULL;
    if (given || isnan(m->restitution))
        snprintf(pair, sizeof pair, "as given");
    else
        snprintf(pair, sizeof pair, "derived from restitution %g", m->restitution);
    if (!isnan(m->wall_restitution))
        snprintf(wall, sizeof wall, "derived from wall_restitution %g", m->wall_restitution);
    else if (given)
        snprintf(wall, sizeof wall, "gamma_n as given");
    else
        snprintf(wall, sizeof wall, "derived from restitution %g", m->restitution);
    snprintf(note, sizeof note, "gamma_n %.6g on pairs (%s), %.6g on walls (%s), for grains of the mean mass",
             d->gn, pair, d->gw, wall);
    gr_sim_note(sim, note);
}

static int m_create(const gr_method_ctx *ctx, const gr_particles *init, void **state, gr_err *err)
{
    gr_dem_params par;
    gr_dem_params_from(ctx->params, &par);
    if (gr_dem_check_dt(ctx->scene, init, &par, err))
        return err->code;
    const gr_scene *sc = ctx->scene;
    gr_rng *reinsert = NULL;
    if (sc->silo.present && sc->silo.reinsert && !(reinsert = gr_sim_stream_id(ctx->sim, GR_STREAM_DEM_REINSERT, err)))
        return err->code;
    gr_dem *d;
    if (gr_dem_create(sc, init, &par, reinsert, &d, err))
        return err->code;
    note_damping(ctx->sim, sc, d);
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

static int m_contacts(void *s, gr_contacts *out, gr_err *err) { return gr_dem_contacts(s, out, err); }

static void m_reset_window(void *s) { gr_dem_reset_window(s); }

static size_t m_counters(const void *s, gr_counter *out, size_t cap)
{
    const gr_dem *d = s;
    gr_counter c[] = {{"steps", d->step}, {"outflow", d->outflow}};
    return gr_counters_put(out, cap, c, sizeof c / sizeof c[0]);
}

static int m_save(const void *s, gr_ckpt *ck, gr_err *err) { return gr_dem_save(s, ck, err); }

static int m_load(void *s, gr_ckpt *ck, gr_err *err) { return gr_dem_load(s, ck, err); }

static void m_free(void *s) { gr_dem_free(s); }

static const gr_obs_def observables[] = {
    GR_OBS_N_MOBILE,    GR_OBS_EKIN_TRANS, GR_OBS_EKIN_ROT, GR_OBS_EPOT_GRAV,     GR_OBS_TEMPERATURE,
    GR_OBS_MOMENTUM,    GR_OBS_OUTFLOW,    GR_OBS_WALL_PRESSURE, GR_OBS_MAX_OVERLAP,
    GR_OBS_DEF_COUNTER("steps", "time steps since t = 0"),
    GR_OBS_DEF_END,
};

const gr_method_type gr_dem_method = {
    .name = "dem",
    .summary = "soft-particle DEM: linear/Hertz contacts, four friction laws, Verlet/Gear/Euler/CVODE",
    .repr = GR_REPR_PARTICLES,
    .features = GR_FEAT_GRAVITY | GR_FEAT_FRICTION | GR_FEAT_CONTACT_HISTORY | GR_FEAT_PERIODIC |
                GR_FEAT_OPEN_SIDE | GR_FEAT_SEGMENTS | GR_FEAT_WALL_GRAINS | GR_FEAT_ORIFICE |
                GR_FEAT_VIBRATING_FLOOR | GR_FEAT_REINSERT | GR_FEAT_POLYDISPERSE | GR_FEAT_MIXTURE |
                GR_FEAT_HERTZ | GR_FEAT_RESTITUTION | GR_FEAT_SOFT_TANGENTIAL,
    .params = gr_dem_param_table,
    .observables = observables,
    .create = m_create,
    .advance = m_advance,
    .time = m_time,
    .observe = m_observe,
    .save = m_save,
    .load = m_load,
    .free = m_free,
    .snapshot = m_snapshot,
    .counters = m_counters,
    .reset_window = m_reset_window,
    .contacts = m_contacts,
};
