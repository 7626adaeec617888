/* The DSMC backend's table (methods/method.h). */
#include "dsmc_int.h"
#include "method.h"

static int m_create(const gr_method_ctx *ctx, const gr_particles *init, void **state, gr_err *err)
{
    gr_dsmc_params par;
    gr_dsmc_params_from(ctx->params, &par);
    /* stream 2: high-frequency floor phases (GSL, saved by the instance);
     * the collisions draw from Philox keyed by the seed and stream 0,
     * counted by step and cell, which needs no saved state */
    gr_rng *floor_rng = gr_sim_stream(ctx->sim, 2, err);
    if (!floor_rng)
        return err->code;
    uint64_t key = gr_rng_key(ctx->scene->seed, GR_STREAM_METHOD_BASE + 0);
    gr_dsmc *d;
    if (gr_dsmc_create(ctx->scene, init, &par, key, floor_rng, &d, err))
        return err->code;
    *state = d;
    return GR_OK;
}

static int m_advance(void *s, double t_end, uint64_t max_steps, gr_err *err)
{
    return gr_dsmc_advance(s, t_end, max_steps, err);
}

static int m_step(void *s, gr_err *err) { return gr_dsmc_step(s, err); }

static double m_time(const void *s) { return ((const gr_dsmc *)s)->t; }

static int m_snapshot(void *s, gr_particles *out, gr_err *err)
{
    return gr_dsmc_snapshot(s, out, err);
}

static int m_observe(void *s, gr_obs *o, gr_err *err) { return gr_dsmc_observe(s, o, err); }

static void m_reset_window(void *s) { gr_dsmc_reset_window(s); }

/* validity_warnings: the limits of docs/methods/dsmc.md the scene breaks
 * (bits: 1 dt, 2 cell, 4 particles per cell, 8 Enskog cells under 10 d,
 * 16 cells under 30 W d);
 * how the user sees them without strict = yes. */
static size_t m_counters(const void *s, gr_counter *out, size_t cap)
{
    const gr_dsmc *d = s;
    gr_counter c[] = {{"steps", d->step},
                      {"pair_collisions", d->pairs},
                      {"wall_collisions", d->walls},
                      {"candidates", d->cand},
                      {"lost", d->lost},
                      {"validity_warnings", d->bad}};
    return gr_counters_put(out, cap, c, sizeof c / sizeof c[0]);
}

static int m_stress(void *s, int nx, int ny, double global[4], double *cells, gr_err *err)
{
    return gr_dsmc_stress(s, nx, ny, global, cells, err);
}

/* The stress window, if one is open, is saved beside the state. */
static int m_save(const void *s, gr_ckpt *ck, gr_err *err)
{
    if (gr_dsmc_save(s, ck, err) || gr_dsmc_stress_save(s, ck, err))
        return err->code;
    return GR_OK;
}

static int m_load(void *s, gr_ckpt *ck, gr_err *err)
{
    if (gr_dsmc_load(s, ck, err) || gr_dsmc_stress_load(s, ck, err))
        return err->code;
    return GR_OK;
}

static void m_free(void *s)
{
    gr_dsmc *d = s;
    if (d)
        gr_stress_acc_free(d->stress);
    gr_dsmc_free(d);
}

const gr_method_type gr_dsmc_method = {
    .name = "dsmc",
    .summary = "direct simulation Monte Carlo (Bird's no-time-counter): inelastic smooth disks",
    .repr = GR_REPR_PARTICLES,
    .features = GR_FEAT_GRAVITY | GR_FEAT_PERIODIC | GR_FEAT_OPEN_SIDE | GR_FEAT_VIBRATING_FLOOR |
                GR_FEAT_HF_FLOOR | GR_FEAT_WEIGHTS | GR_FEAT_RESTITUTION,
    .params = gr_dsmc_param_table,
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
    .step = m_step,
    .stress = m_stress,
};
