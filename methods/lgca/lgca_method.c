/* The lattice-gas backend's table (methods/method.h): a lattice, so no
 * snapshot; fields, observables and the stress from the node occupations. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lgca_int.h"
#include "method.h"

/* What the table cannot check: the probabilities against the rule set and
 * the scene's gravity. */
static int check(const gr_scene *sc, lgca_params *p, gr_err *err)
{
    char where[1200];
    if (p->rules == LGCA_RULES_FHP3 && p->p > 0) {
        gr_scene_where(sc, "lgca", "p", where, sizeof where);
        return gr_fail(err, GR_EINPUT, "%s: p = %g needs rules = granular (fhp3 conserves energy)", where, p->p);
    }
    if (p->rules == LGCA_RULES_FHP3 && p->stop > 0) {
        gr_scene_where(sc, "lgca", "stop", where, sizeof where);
        return gr_fail(err, GR_EINPUT, "%s: stop = %g needs rules = granular (fhp3 conserves energy)", where, p->stop);
    }
    if (isnan(p->g))
        p->g = sc->gravity * p->dt * p->dt / gr_scene_max_diameter(sc);
    else if (p->g > 0 && !(sc->gravity > 0)) {
        gr_scene_where(sc, "lgca", "g", where, sizeof where);
        return gr_fail(err, GR_EINPUT, "%s: g = %g needs [domain] gravity > 0", where, p->g);
    }
    if (p->g > 1) {
        gr_scene_where(sc, "lgca", "dt", where, sizeof where);
        return gr_fail(err, GR_EINPUT, "%s: gravity dt^2 / d = %g exceeds 1 (a probability per step); lower dt or give g",
                       where, p->g);
    }
    return GR_OK;
}

static int m_create(const gr_method_ctx *ctx, const gr_particles *init, void **state, gr_err *err)
{
    lgca_params par;
    lgca_params_from(ctx->params, &par);
    if (check(ctx->scene, &par, err))
        return err->code;
    /* stream 0: the Philox key; stream 1: the initial occupations */
    gr_rng *keys = gr_sim_stream(ctx->sim, 0, err), *occ;
    if (!keys || !(occ = gr_sim_stream(ctx->sim, 1, err)))
        return err->code;
    uint32_t key[2] = {(uint32_t)gr_rng_below(keys, 4294967295ul), (uint32_t)gr_rng_below(keys, 4294967295ul)};
    lgca *L;
    if (lgca_create(ctx->scene, &par, key, init, occ, &L, err))
        return err->code;
    *state = L;
    return GR_OK;
}

static int m_advance(void *s, double t_end, uint64_t max_steps, gr_err *err)
{
    lgca *L = s;
    double eps = isfinite(t_end) ? 1e-12 * (1 + fabs(t_end)) : 0;
    /* the first step count whose time reaches t_end */
    double need = isfinite(t_end) ? ceil((t_end - eps) / L->par.dt) : INFINITY;
    uint64_t n = need > (double)L->step ? (need > 1e18 ? UINT64_MAX : (uint64_t)need - L->step) : 0;
    if (max_steps && n > max_steps)
        n = max_steps;
    if (!L->stress)
        return lgca_steps(L, n, err);
    /* an open stress window samples every step */
    for (uint64_t k = 0; k < n; k++) {
        if (lgca_steps(L, 1, err))
            return err->code;
        lgca_stress_sample(L);
    }
    return GR_OK;
}

static int m_step(void *s, gr_err *err)
{
    int rc = lgca_steps(s, 1, err);
    if (!rc)
        lgca_stress_sample(s);
    return rc;
}

static int m_stress(void *s, int nx, int ny, double global[4], double *cells, gr_err *err)
{
    return lgca_stress(s, nx, ny, global, cells, err);
}

static double m_time(const void *s)
{
    const lgca *L = s;
    return (double)L->step * L->par.dt;
}

/* The observables' position of the mass, which lgca fills itself. */
enum { OBS_MASS = 0 };

static int m_observe(void *s, gr_obs *o, gr_err *err)
{
    (void)err;
    lgca_observe(s, o);
    o->extra[OBS_MASS][0] = ((const lgca *)s)->mass * (double)o->n_mobile;
    return GR_OK;
}

static int m_fields(void *s, gr_field *f, double w, gr_err *err) { return lgca_fields(s, f, w, err); }

static size_t m_counters(const void *s, gr_counter *out, size_t cap)
{
    const lgca *L = s;
    uint64_t moving, resting;
    lgca_populations(L, &moving, &resting);
    gr_counter c[] = {{"steps", L->step},         {"moving", moving},         {"resting", resting},
                      {"outflow", L->outflow},    {"reinserted", L->reinserted}, {"lost", L->lost}};
    return gr_counters_put(out, cap, c, sizeof c / sizeof c[0]);
}

static int m_save(const void *s, gr_ckpt *ck, gr_err *err)
{
    const lgca *L = s;
    uint64_t misc[6] = {L->step, L->outflow, L->reinserted, L->lost, (uint64_t)L->ni, (uint64_t)L->nj};
    size_t n = (size_t)L->nj * LGCA_CH * (size_t)L->nw, lw = LGCA_CH * (size_t)L->nw;
    uint64_t *all = malloc(n * sizeof *all);
    if (!all)
        return gr_fail(err, GR_ERUN, "out of memory for a checkpoint of %zu words", n);
    for (int j = 0; j < L->nj; j++)
        memcpy(all + (size_t)j * lw, L->lane[j], lw * sizeof *all);
    int rc = gr_ckpt_put_u64(ck, "lgca_misc", misc, 6, err) || gr_ckpt_put_u64(ck, "lgca_state", all, n, err) ||
             lgca_stress_save(L, ck, err);
    free(all);
    return rc ? err->code : GR_OK;
}

/* The gates are recomputed from the step by the next lgca_step. */
static int m_load(void *s, gr_ckpt *ck, gr_err *err)
{
    lgca *L = s;
    uint64_t misc[6];
    size_t n = (size_t)L->nj * LGCA_CH * (size_t)L->nw, len;
    if (gr_ckpt_get_u64(ck, "lgca_misc", misc, 6, err))
        return err->code;
    if (misc[4] != (uint64_t)L->ni || misc[5] != (uint64_t)L->nj)
        return gr_fail(err, GR_EINPUT, "checkpoint: a lattice of %llu x %llu nodes, the scene makes %d x %d",
                       (unsigned long long)misc[5], (unsigned long long)misc[4], L->nj, L->ni);
    if (gr_ckpt_len(ck, "lgca_state", &len, err))
        return err->code;
    if (len != n)
        return gr_fail(err, GR_EINPUT, "checkpoint: lattice state of %zu words, expected %zu", len, n);
    uint64_t *all = malloc(n * sizeof *all);
    if (!all)
        return gr_fail(err, GR_ERUN, "out of memory for a checkpoint of %zu words", n);
    if (gr_ckpt_get_u64(ck, "lgca_state", all, n, err)) {
        free(all);
        return err->code;
    }
    for (int j = 0; j < L->nj; j++)
        memcpy(L->lane[j], all + (size_t)j * LGCA_CH * (size_t)L->nw, LGCA_CH * (size_t)L->nw * sizeof *all);
    free(all);
    L->step = misc[0], L->outflow = misc[1], L->reinserted = misc[2], L->lost = misc[3];
    return lgca_stress_load(L, ck, err);
}

static void m_free(void *s) { lgca_free(s); }

/* Particles of mass m moving at a / dt along their channel (0 at rest);
 * no rotation, overlap or wall pressure. */
static const gr_obs_def observables[] = {
    GR_OBS_DEF_EXTRA("mass", "m", 1, "mass on the lattice, m times the particles (moving and resting)"),
    GR_OBS_MOMENTUM,
    GR_OBS_EKIN_TRANS,
    GR_OBS_EPOT_GRAV,
    GR_OBS_TEMPERATURE,
    GR_OBS_OUTFLOW,
    GR_OBS_DEF_COUNTER("moving", "particles in the six moving channels"),
    GR_OBS_DEF_COUNTER("resting", "particles in the rest channel"),
    GR_OBS_DEF_COUNTER("steps", "lattice updates (collision and propagation) since t = 0"),
    GR_OBS_DEF_COUNTER("reinserted", "particles put back at the top after leaving through the orifice"),
    GR_OBS_DEF_COUNTER("lost", "particles that left through an open side and were not reinserted"),
    GR_OBS_DEF_END,
};

const gr_method_type gr_lgca_method = {
    .name = "lgca",
    .summary = "granular lattice gas (FHP-III and Peng-Herrmann rules), 64 nodes per machine word",
    .repr = GR_REPR_LATTICE,
    .features = GR_FEAT_GRAVITY | GR_FEAT_PERIODIC | GR_FEAT_OPEN_SIDE | GR_FEAT_SEGMENTS |
                GR_FEAT_ORIFICE | GR_FEAT_REINSERT | GR_FEAT_LATTICE,
    .params = lgca_param_table,
    .observables = observables,
    .create = m_create,
    .advance = m_advance,
    .time = m_time,
    .observe = m_observe,
    .save = m_save,
    .load = m_load,
    .free = m_free,
    .fields = m_fields,
    .counters = m_counters,
    .step = m_step,
    .stress = m_stress,
};
