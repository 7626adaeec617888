/* A toy backend: grains in free flight under gravity, reflected by the
 * walls, wrapped by periodic sides, blind to one another. It lives only in
 * its test (test_toy.c) and is the proof that a backend outside
 * methods/registry.c passes the conformance battery with no other file
 * edited (docs/interface.md, Adding a backend). It gives one step and its
 * dt, and takes the interface's defaults for advance and observe. */
#include <math.h>
#include <stdlib.h>

#include "method.h"

typedef struct {
    gr_particles *p;
    const gr_scene *sc;
    double dt;
    uint64_t steps;
} toy;

static const gr_param toy_params[] = {
    {"dt", GR_PARAM_REAL, 0.01, 0, 1, 1, NULL, "tau", "time step"},
    {NULL, 0, 0, 0, 0, 0, NULL, NULL, NULL},
};

static int toy_create(const gr_method_ctx *ctx, const gr_particles *init, void **state, gr_err *err)
{
    if (!gr_particles_count_mobile(init))
        return gr_scene_no_grains(ctx->scene, err);
    toy *t = calloc(1, sizeof *t);
    if (!t || !(t->p = gr_particles_create(0, err)) || gr_particles_copy(t->p, init, err)) {
        if (t)
            gr_particles_free(t->p);
        free(t);
        return err->code ? err->code : gr_fail(err, GR_ERUN, "out of memory");
    }
    t->sc = ctx->scene, t->dt = gr_param_get(ctx->params, "dt");
    *state = t;
    return GR_OK;
}

/* One side pair: wrapped when periodic, else reflected off the walls. */
static void bound(double *x, double *v, double r, double len, int periodic)
{
    if (periodic)
        *x -= len * floor(*x / len);
    else if (*x < r)
        *x = 2 * r - *x, *v = -*v;
    else if (*x > len - r)
        *x = 2 * (len - r) - *x, *v = -*v;
}

static int toy_step(void *state, gr_err *err)
{
    toy *t = state;
    const gr_scene *sc = t->sc;
    double dt = t->dt, g = sc->gravity;
    gr_particles *p = t->p;
    for (size_t i = 0; i < p->n; i++) {
        if (p->flags[i] & (GR_PF_FIXED | GR_PF_GONE))
            continue;
        p->x[i] += p->vx[i] * dt;
        p->y[i] += p->vy[i] * dt - 0.5 * g * dt * dt;
        p->vy[i] -= g * dt;
        bound(&p->x[i], &p->vx[i], p->radius[i], sc->width, sc->side[GR_LEFT] == GR_BC_PERIODIC);
        bound(&p->y[i], &p->vy[i], p->radius[i], sc->height, sc->side[GR_BOTTOM] == GR_BC_PERIODIC);
    }
    t->steps++;
    (void)err;
    return GR_OK;
}

/* Time as steps times dt, so that it does not drift. */
static double toy_time(const void *state) { return (double)((const toy *)state)->steps * ((const toy *)state)->dt; }

static double toy_dt(const void *state) { return ((const toy *)state)->dt; }

static size_t toy_counters(const void *state, gr_counter *out, size_t cap)
{
    gr_counter c[] = {{"steps", ((const toy *)state)->steps}};
    return gr_counters_put(out, cap, c, 1);
}

static int toy_save(const void *state, gr_ckpt *ck, gr_err *err)
{
    const toy *t = state;
    size_t n = t->p->n;
    if (gr_ckpt_put_u64(ck, "toy.steps", &t->steps, 1, err) || gr_ckpt_put_f64(ck, "toy.x", t->p->x, n, err) ||
        gr_ckpt_put_f64(ck, "toy.y", t->p->y, n, err) || gr_ckpt_put_f64(ck, "toy.vx", t->p->vx, n, err))
        return err->code;
    return gr_ckpt_put_f64(ck, "toy.vy", t->p->vy, n, err);
}

static int toy_load(void *state, gr_ckpt *ck, gr_err *err)
{
    toy *t = state;
    size_t n = t->p->n;
    if (gr_ckpt_get_u64(ck, "toy.steps", &t->steps, 1, err) || gr_ckpt_get_f64(ck, "toy.x", t->p->x, n, err) ||
        gr_ckpt_get_f64(ck, "toy.y", t->p->y, n, err) || gr_ckpt_get_f64(ck, "toy.vx", t->p->vx, n, err))
        return err->code;
    return gr_ckpt_get_f64(ck, "toy.vy", t->p->vy, n, err);
}

static void toy_free(void *state)
{
    toy *t = state;
    if (t)
        gr_particles_free(t->p);
    free(t);
}

/* The scene's grains keep their id order: the initial state has it. */
static int toy_snapshot(void *state, gr_particles *out, gr_err *err)
{
    return gr_particles_copy(out, ((toy *)state)->p, err);
}

/* No collisions, walls that take no momentum, no rotation. */
static const gr_obs_def toy_observables[] = {
    GR_OBS_N_MOBILE, GR_OBS_EKIN_TRANS, GR_OBS_EPOT_GRAV, GR_OBS_TEMPERATURE, GR_OBS_MOMENTUM,
    GR_OBS_DEF_COUNTER("steps", "time steps since t = 0"),
    GR_OBS_DEF_END,
};

const gr_method_type toy_method = {
    .name = "toy",
    .summary = "free flight under gravity, walls and periodic sides, no collisions (a test's backend)",
    .repr = GR_REPR_PARTICLES,
    .features = GR_FEAT_GRAVITY | GR_FEAT_PERIODIC,
    .params = toy_params,
    .observables = toy_observables,
    .create = toy_create, .time = toy_time, .step = toy_step, .dt = toy_dt,
    .save = toy_save, .load = toy_load, .free = toy_free, .snapshot = toy_snapshot, .counters = toy_counters,
};
