/* A toy backend: grains in free flight under gravity, reflected by the
 * walls, wrapped by periodic sides, blind to one another. It lives only in
 * its test (test_toy.c) and is the proof that a backend outside
 * methods/registry.c passes the conformance battery with no other file
 * edited (docs/interface.md, Adding a backend). */
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

/* Whole steps only, so the path does not depend on where advance stops. */
static int toy_advance(void *state, double t_end, uint64_t max_steps, gr_err *err)
{
    toy *t = state;
    const gr_scene *sc = t->sc;
    double dt = t->dt, g = sc->gravity;
    for (uint64_t k = 0; (double)t->steps * dt < t_end && (!max_steps || k < max_steps); k++, t->steps++) {
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
    }
    (void)err;
    return GR_OK;
}

static double toy_time(const void *state) { return (double)((const toy *)state)->steps * ((const toy *)state)->dt; }

static int toy_observe(void *state, gr_obs *o, gr_err *err)
{
    toy *t = state;
    gr_obs_clear(o);
    gr_obs_from_particles(t->p, t->sc->gravity, o);
    o->t = toy_time(t), o->steps = t->steps;
    (void)err;
    return GR_OK;
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

const gr_method_type toy_method = {
    .name = "toy",
    .summary = "free flight under gravity, walls and periodic sides, no collisions (a test's backend)",
    .repr = GR_REPR_PARTICLES,
    .features = GR_FEAT_GRAVITY | GR_FEAT_PERIODIC,
    .params = toy_params,
    .create = toy_create, .advance = toy_advance, .time = toy_time, .observe = toy_observe,
    .save = toy_save, .load = toy_load, .free = toy_free, .snapshot = toy_snapshot,
};
