/* The event-driven backend's table (methods/method.h). */
#include <math.h>

#include "edmd_int.h"
#include "observe.h"

static const char *const param_keys[] = {"algorithm",  "cell",       "collapse",   "tc", "v_threshold",
                                         "fields",     "sort_every", "tree_arity", "queue", NULL};

static int m_create(const gr_scene *sc, const gr_particles *init, void **state, gr_err *err)
{
    gr_edmd_params prm;
    if (gr_edmd_params_read(sc, &prm, err))
        return err->code;
    gr_edmd *s;
    if (gr_edmd_create(sc, init, &prm, &s, err))
        return err->code;
    *state = s;
    return GR_OK;
}
static int m_advance(void *st, double t_end, uint64_t max_steps, gr_err *err)
{
    return gr_edmd_advance(st, t_end, max_steps, err);
}
static double m_time(const void *st) { return gr_edmd_time(st); }
static int m_snapshot(void *st, gr_particles *out, gr_err *err) { return gr_edmd_snapshot(st, out, err); }

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
    s->obs_t0 = s->t;
    s->obs_mom = 0.0;
    return GR_OK;
}
static int m_save(const void *st, gr_ckpt *ck, gr_err *err) { return gr_edmd_save(st, ck, err); }
static int m_load(void *st, gr_ckpt *ck, gr_err *err) { return gr_edmd_load(st, ck, err); }
static void m_free(void *st) { gr_edmd_free(st); }

const gr_method_type gr_edmd_method = {
    .name = "edmd",
    .summary = "event-driven inelastic hard disks (cells, event tree, exact averages)",
    .features = GR_FEAT_GRAVITY | GR_FEAT_FRICTION | GR_FEAT_PERIODIC | GR_FEAT_VIBRATING_FLOOR |
                GR_FEAT_HF_FLOOR | GR_FEAT_POLYDISPERSE | GR_FEAT_MIXTURE | GR_FEAT_SEGMENTS | GR_FEAT_ORIFICE |
                GR_FEAT_OPEN_SIDE | GR_FEAT_REINSERT,
    .param_keys = param_keys,
    .create = m_create,
    .advance = m_advance,
    .time = m_time,
    .snapshot = m_snapshot,
    .observe = m_observe,
    .save = m_save,
    .load = m_load,
    .free = m_free,
};
