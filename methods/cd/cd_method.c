/* The contact dynamics backend's table (methods/method.h). */
#include "cd_int.h"
#include "method.h"

#include <stdio.h>

static int m_create(const gr_method_ctx *ctx, const gr_particles *init, void **state, gr_err *err)
{
    gr_cd_params par;
    gr_cd_params_from(ctx->params, &par);
    /* stream 0: contact orders; stream 1: reinsertion spots */
    gr_rng *order = gr_sim_stream(ctx->sim, 0, err);
    gr_rng *reins = order ? gr_sim_stream(ctx->sim, 1, err) : NULL;
    if (!reins)
        return err->code;
    gr_cd *d;
    if (gr_cd_create(ctx->scene, init, &par, order, reins, &d, err))
        return err->code;
    gr_sim_note_restitution(ctx->sim, init);
    *state = d;
    return GR_OK;
}

static int m_advance(void *s, double t_end, uint64_t max_steps, gr_err *err)
{
    return gr_cd_advance(s, t_end, max_steps, err);
}

static int m_step(void *s, gr_err *err) { return gr_cd_step(s, err); }

static double m_time(const void *s) { return ((const gr_cd *)s)->t; }

static int m_snapshot(void *s, gr_particles *out, gr_err *err) { return gr_cd_snapshot(s, out, err); }

static int m_observe(void *s, gr_obs *o, gr_err *err) { return gr_cd_observe(s, o, err); }

static void m_reset_window(void *s) { gr_cd_reset_window(s); }

static size_t m_counters(const void *s, gr_counter *out, size_t cap)
{
    const gr_cd *d = s;
    gr_counter c[] = {{"steps", d->step},
                      {"contacts", d->prev.n},
                      {"active_contacts", d->last_active},
                      {"sliding_contacts", d->last_sliding},
                      {"iterations", d->sweeps},
                      {"nonconverged_steps", d->nonconv},
                      {"outflow", d->outflow},
                      {"lost", d->lost}};
    return gr_counters_put(out, cap, c, sizeof c / sizeof c[0]);
}

static int m_save(const void *s, gr_ckpt *ck, gr_err *err) { return gr_cd_save(s, ck, err); }

static int m_load(void *s, gr_ckpt *ck, gr_err *err) { return gr_cd_load(s, ck, err); }

static void m_free(void *s) { gr_cd_free(s); }

static int m_contacts(void *s, gr_contacts *out, gr_err *err) { return gr_cd_contacts(s, out, err); }

static const gr_obs_def observables[] = {
    GR_OBS_N_MOBILE,    GR_OBS_EKIN_TRANS, GR_OBS_EKIN_ROT, GR_OBS_EPOT_GRAV,     GR_OBS_TEMPERATURE,
    GR_OBS_MOMENTUM,    GR_OBS_OUTFLOW,    GR_OBS_WALL_PRESSURE, GR_OBS_MAX_OVERLAP,
    GR_OBS_DEF_COUNTER("steps", "time steps since t = 0"),
    GR_OBS_DEF_COUNTER("contacts", "candidate contacts of the last step (gap below [cd] gap)"),
    GR_OBS_DEF_COUNTER("active_contacts", "contacts of the last step that carry a force"),
    GR_OBS_DEF_COUNTER("sliding_contacts", "contacts of the last step at the Coulomb limit"),
    GR_OBS_DEF_COUNTER("iterations", "Gauss-Seidel sweeps since t = 0"),
    GR_OBS_DEF_LIMIT("nonconverged_steps", "cd.max_iter", "steps that reached max_iter sweeps without converging to tol"),
    GR_OBS_DEF_COUNTER("lost", "grains that left through an open side"),
    GR_OBS_DEF_END,
};

/* The limit's measure: the sweeps it allowed and the tolerance missed. */
static void m_diagnose(const void *s, const char *name, char *msg, size_t n)
{
    const gr_cd *d = s;
    (void)name;
    snprintf(msg, n, "%llu of %llu steps stopped at max_iter = %ld sweeps with the residual above tol = %g",
             (unsigned long long)d->nonconv, (unsigned long long)d->step, d->par.max_iter, d->par.tol);
}

const gr_method_type gr_cd_method = {
    .name = "cd",
    .summary = "contact dynamics (Moreau-Jean): rigid disks, Signorini-Coulomb by non-linear Gauss-Seidel",
    .repr = GR_REPR_PARTICLES,
    .features = GR_FEAT_GRAVITY | GR_FEAT_FRICTION | GR_FEAT_PERIODIC | GR_FEAT_OPEN_SIDE | GR_FEAT_SEGMENTS |
                GR_FEAT_WALL_GRAINS | GR_FEAT_ORIFICE | GR_FEAT_VIBRATING_FLOOR | GR_FEAT_REINSERT |
                GR_FEAT_POLYDISPERSE | GR_FEAT_MIXTURE | GR_FEAT_RESTITUTION,
    .params = gr_cd_param_table,
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
    .contacts = m_contacts,
    .step = m_step,
};
