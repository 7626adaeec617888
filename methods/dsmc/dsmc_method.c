/* The DSMC backend's table (methods/method.h). */
#include "dsmc_int.h"
#include "method.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

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
    gr_sim_note_restitution(ctx->sim, init);
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

/* The observables' positions of the quantities dsmc fills itself. */
enum { OBS_A2 = 6 };

/* Sonine a2 = <c^4> / (2 <c^2>^2) - 1 of the peculiar velocities c (2-D):
 * 0 for a Maxwellian, the homogeneous cooling state's departure from it. */
static double sonine_a2(const gr_dsmc *d)
{
    double n = 0, ux = 0, uy = 0;
    for (size_t i = 0; i < d->n; i++)
        if (!(d->rank[i] & GR_DSMC_GONE))
            n++, ux += d->vx[i], uy += d->vy[i];
    if (n < 1)
        return NAN;
    ux /= n, uy /= n;
    double c2 = 0, c4 = 0;
    for (size_t i = 0; i < d->n; i++) {
        if (d->rank[i] & GR_DSMC_GONE)
            continue;
        double cx = d->vx[i] - ux, cy = d->vy[i] - uy, q = cx * cx + cy * cy;
        c2 += q, c4 += q * q;
    }
    c2 /= n, c4 /= n;
    return c2 > 0 ? c4 / (2 * c2 * c2) - 1 : NAN;
}

static int m_observe(void *s, gr_obs *o, gr_err *err)
{
    if (gr_dsmc_observe(s, o, err))
        return err->code;
    o->extra[OBS_A2][0] = sonine_a2(s);
    return GR_OK;
}

static void m_reset_window(void *s) { gr_dsmc_reset_window(s); }

/* validity_warnings: the limits of docs/methods/dsmc.md the scene breaks
 * (bits: 1 dt, 2 cell, 4 particles per cell, 8 Enskog cells under 10 d,
 * 16 cells under the limit of correlated partners);
 * how the user sees them without strict = yes. */
static size_t m_counters(const void *s, gr_counter *out, size_t cap)
{
    const gr_dsmc *d = s;
    gr_counter c[] = {{"steps", d->step},
                      {"pair_collisions", d->pairs},
                      {"wall_collisions", d->walls},
                      {"candidates", d->cand},
                      {"stand_ins", d->stand_ins},
                      {"lost", d->lost},
                      {"validity_warnings", d->bad | (d->dense_steps ? GR_DSMC_BAD_DENSE : 0u)},
                      {"limit_dt", d->bad & GR_DSMC_BAD_DT ? d->step : 0},
                      {"limit_cell", d->bad & GR_DSMC_BAD_CELL ? d->step : 0},
                      {"limit_ppc_min", d->bad & GR_DSMC_BAD_PPC ? d->step : 0},
                      {"limit_recollision", d->bad & GR_DSMC_BAD_RECOLLIDE ? d->step : 0},
                      {"limit_dense", d->dense_steps}};
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

/* Smooth disks that never overlap and leave through no orifice: no
 * ekin_rot, max_overlap or outflow. The limits are fixed at create, so each
 * counts every step (docs/methods/dsmc.md, validity). */
static const gr_obs_def observables[] = {
    GR_OBS_N_MOBILE, GR_OBS_EKIN_TRANS, GR_OBS_EPOT_GRAV, GR_OBS_TEMPERATURE, GR_OBS_MOMENTUM,
    GR_OBS_WALL_PRESSURE,
    GR_OBS_DEF_EXTRA("sonine_a2", "1", 1, "Sonine coefficient a2 = <c^4> / (2 <c^2>^2) - 1 of the peculiar velocities"),
    GR_OBS_DEF_COUNTER("steps", "time steps since t = 0"),
    GR_OBS_DEF_COUNTER("pair_collisions", "accepted grain-grain collisions"),
    GR_OBS_DEF_COUNTER("wall_collisions", "grain-wall collisions"),
    GR_OBS_DEF_COUNTER("candidates", "candidate pairs drawn (no-time-counter)"),
    GR_OBS_DEF_COUNTER("stand_ins", "candidates of two recent partners, one of whom met another particle instead"),
    GR_OBS_DEF_COUNTER("lost", "particles that left through an open side"),
    GR_OBS_DEF_COUNTER("validity_warnings", "the limits broken, as bits: 1 dt, 2 cell, 4 ppc_min, 16 recollision, 32 dense (8 unused)"),
    GR_OBS_DEF_LIMIT("limit_dt", "dsmc.dt", "steps with dt above half the mean free time"),
    GR_OBS_DEF_LIMIT("limit_cell", "dsmc.cell", "steps with the cell side above the mean free path"),
    GR_OBS_DEF_LIMIT("limit_ppc_min", "dsmc.ppc_min", "steps with fewer mean particles per cell than ppc_min"),
    GR_OBS_DEF_LIMIT("limit_recollision", "dsmc.cell", "steps with cells under 55 (1 - alpha^2) min(1, d / (0.36 lambda)) W d, where partners collide again correlated"),
    GR_OBS_DEF_LIMIT("limit_dense", "dsmc.gas_eta_max", "steps with a region of about 32 grains packed above gas_eta_max, beyond a Boltzmann-Enskog gas (a bed, a cluster: dem, edmd or cd model it)"),
    GR_OBS_DEF_END,
};

/* What each limit measured at create. */
static void m_diagnose(const void *s, const char *name, char *msg, size_t n)
{
    /* by the bit's place (GR_DSMC_BAD_*); 3 is no longer used */
    static const char *const names[GR_DSMC_NLIMITS] = {"limit_dt", "limit_cell", "limit_ppc_min", "",
                                                       "limit_recollision"};
    static const char *const what[GR_DSMC_NLIMITS] = {
        "dt is %g, above half the mean free time, %g", "the cell side is %g d, above the mean free path, %g d",
        "the mean of particles per cell is %g, below ppc_min = %g", "",
        "the cell side is %g d, below 30 W d = %g d (correlated recollisions)"};
    const gr_dsmc *d = s;
    if (!strcmp(name, "limit_dense")) {
        snprintf(msg, n,
                 "the packing fraction reaches %.3g in x %.4g .. %.4g, y %.4g .. %.4g d, above %g: not a gas "
                 "the method can compute (dem, edmd or cd model a bed)",
                 d->dense[0], d->dense[1] / d->sigma, d->dense[3] / d->sigma, d->dense[2] / d->sigma,
                 d->dense[4] / d->sigma, d->par.gas_eta_max);
        return;
    }
    for (int k = 0; k < GR_DSMC_NLIMITS; k++)
        if (names[k][0] && !strcmp(name, names[k]))
            snprintf(msg, n, what[k], d->lim_val[k] / (k == 0 || k == 2 ? 1 : d->sigma),
                     d->lim_max[k] / (k == 0 || k == 2 ? 1 : d->sigma));
}

const gr_method_type gr_dsmc_method = {
    .name = "dsmc",
    .summary = "direct simulation Monte Carlo (Bird's no-time-counter): inelastic smooth disks",
    .repr = GR_REPR_PARTICLES,
    .features = GR_FEAT_GRAVITY | GR_FEAT_PERIODIC | GR_FEAT_OPEN_SIDE | GR_FEAT_VIBRATING_FLOOR |
                GR_FEAT_HF_FLOOR | GR_FEAT_WEIGHTS | GR_FEAT_RESTITUTION,
    .params = gr_dsmc_param_table,
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
    .step = m_step,
    .stress = m_stress,
};
