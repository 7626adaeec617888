/* The event-driven backend's table (methods/method.h). */
#include <math.h>
#include <stdio.h>

#include "edmd_int.h"
#include "edmd_params.h"
#include "observe.h"

static int m_create(const gr_method_ctx *ctx, const gr_particles *init, void **state, gr_err *err)
{
    gr_edmd_params prm;
    if (gr_edmd_params_from(ctx->scene, ctx->params, &prm, err))
        return err->code;
    gr_rng *rng = gr_sim_stream_id(ctx->sim, GR_STREAM_EDMD, err);
    gr_edmd *s;
    if (!rng || gr_edmd_create(ctx->scene, init, &prm, rng, &s, err))
        return err->code;
    gr_sim_note_restitution(ctx->sim, init);
    *state = s;
    return GR_OK;
}

static int m_advance(void *st, double t_end, uint64_t max_steps, gr_err *err)
{
    return gr_edmd_advance(st, t_end, max_steps, err);
}

static double m_time(const void *st) { return gr_edmd_time(st); }

static int m_snapshot(void *st, gr_particles *out, gr_err *err) { return gr_edmd_snapshot(st, out, err); }

/* Wall pressure: momentum given to the hard sides since the window opened,
 * per unit length and time. */
static int m_observe(void *st, gr_obs *o, gr_err *err)
{
    gr_edmd *s = st;
    gr_particles *p = gr_particles_create(s->n, err);
    if (!p)
        return err->code;
    if (gr_edmd_snapshot(s, p, err)) {
        gr_particles_free(p);
        return err->code;
    }
    gr_obs_from_particles(p, s->g, o);
    gr_particles_free(p);
    o->t = s->t;
    o->steps = s->steps;
    o->outflow = s->outflow;
    double len = 0.0, Ly = s->H - s->ybot;
    for (int k = 0; k < 4; k++)
        if (s->hard[k])
            len += k == GR_LEFT || k == GR_RIGHT ? Ly : s->W;
    double T = s->t - s->obs_t0;
    o->wall_pressure = len > 0.0 && T > 0.0 ? s->obs_mom / (len * T) : NAN;
    o->max_overlap = NAN;
    return GR_OK;
}

static void m_reset_window(void *st)
{
    gr_edmd *s = st;
    s->obs_t0 = s->t;
    s->obs_mom = 0.0;
}

static size_t m_counters(const void *st, gr_counter *out, size_t cap)
{
    gr_edmd_counters c;
    gr_edmd_get_counters(st, &c);
    gr_counter all[] = {{"events", ((const gr_edmd *)st)->steps},
                        {"pair_collisions", c.pair},
                        {"wall_collisions", c.wall},
                        {"floor_collisions", c.floor},
                        {"cell_crossings", c.crossing},
                        {"stale_events", c.stale},
                        {"elastic_guard", c.elastic_guard},
                        {"sleeps", c.sleeps},
                        {"wakes", c.wakes}};
    return gr_counters_put(out, cap, all, sizeof all / sizeof all[0]);
}

static int m_stress(void *st, int nx, int ny, double global[4], double *cells, gr_err *err)
{
    return gr_edmd_stress(st, nx, ny, global, cells, err);
}

static int m_save(const void *st, gr_ckpt *ck, gr_err *err) { return gr_edmd_save(st, ck, err); }
static int m_load(void *st, gr_ckpt *ck, gr_err *err) { return gr_edmd_load(st, ck, err); }
static void m_free(void *st) { gr_edmd_free(st); }

/* Hard disks never overlap: no max_overlap. */
static const gr_obs_def observables[] = {
    GR_OBS_N_MOBILE, GR_OBS_EKIN_TRANS, GR_OBS_EKIN_ROT, GR_OBS_EPOT_GRAV, GR_OBS_TEMPERATURE,
    GR_OBS_MOMENTUM, GR_OBS_OUTFLOW,    GR_OBS_WALL_PRESSURE,
    GR_OBS_DEF_COUNTER("events", "events processed since t = 0 (collisions, crossings, stale ones)"),
    GR_OBS_DEF_COUNTER("pair_collisions", "grain-grain collisions"),
    GR_OBS_DEF_COUNTER("wall_collisions", "grain-wall collisions"),
    GR_OBS_DEF_COUNTER("floor_collisions", "collisions with the vibrating floor"),
    GR_OBS_DEF_COUNTER("cell_crossings", "cell crossings (virtual-wall events)"),
    GR_OBS_DEF_COUNTER("stale_events", "events dropped because a partner collided since they were scheduled"),
    GR_OBS_DEF_LIMIT("elastic_guard", "edmd.collapse", "collisions made elastic by the inelastic-collapse guard"),
    GR_OBS_DEF_COUNTER("sleeps", "grains put to sleep at rest (collapse = sleep)"),
    GR_OBS_DEF_COUNTER("wakes", "sleeping grains woken by an impact (collapse = sleep)"),
    GR_OBS_DEF_END,
};

/* The guard keeps the run going where inelastic collapse would stop it,
 * at the price of elastic collisions the model does not have. */
static void m_diagnose(const void *st, const char *name, char *msg, size_t n)
{
    const gr_edmd *s = st;
    gr_edmd_counters c;
    gr_edmd_get_counters(s, &c);
    (void)name;
    /* the guard acts on wall and floor collisions too */
    unsigned long long all = (unsigned long long)(c.pair + c.wall + c.floor);
    if (s->prm.collapse == GR_EDMD_COLLAPSE_TC || s->prm.collapse == GR_EDMD_COLLAPSE_SLEEP)
        snprintf(msg, n, "%llu of %llu collisions made elastic (collapse = %s: a partner collided less than "
                 "tc = %g ago)", (unsigned long long)c.elastic_guard, all,
                 s->prm.collapse == GR_EDMD_COLLAPSE_SLEEP ? "sleep" : "tc", s->prm.tc);
    else
        snprintf(msg, n, "%llu of %llu collisions made elastic (collapse = threshold: normal speed below "
                 "v_threshold = %g)", (unsigned long long)c.elastic_guard, all,
                 s->prm.v_threshold);
}

const gr_method_type gr_edmd_method = {
    .name = "edmd",
    .summary = "event-driven inelastic hard disks (cells, event tree, exact averages)",
    .repr = GR_REPR_PARTICLES,
    .features = GR_FEAT_GRAVITY | GR_FEAT_FRICTION | GR_FEAT_PERIODIC | GR_FEAT_VIBRATING_FLOOR |
                GR_FEAT_HF_FLOOR | GR_FEAT_POLYDISPERSE | GR_FEAT_MIXTURE | GR_FEAT_SEGMENTS | GR_FEAT_ORIFICE |
                GR_FEAT_OPEN_SIDE | GR_FEAT_REINSERT | GR_FEAT_RESTITUTION,
    .params = gr_edmd_param_table,
    .observables = observables,
    .diagnose = m_diagnose,
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
    .stress = m_stress,
};
