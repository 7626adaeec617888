/* The instance: a backend's table, its state and the scene it came from,
 * with the defaults of the optional operations (methods/method.h). */
#include "method.h"
#include "restitution.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_STREAMS 16

struct gr_sim {
    const gr_method_type *type;
    void *state;
    const gr_scene *scene;
    gr_param_values params;
    int nrng;
    uint64_t rng_id[MAX_STREAMS];
    gr_rng *rng[MAX_STREAMS];
    gr_particles *scratch; /* snapshots for the default fields */
    char notes[1024];
};

static const char *const op_names[GR_OP_COUNT] = {"snapshots", "fields", "counters",
                                                 "measurement windows", "single steps",
                                                 "contact networks", "window-averaged stress",
                                                 "advancing to a time", "observables"};

const char *gr_op_name(unsigned op)
{
    for (unsigned b = 0; b < GR_OP_COUNT; b++)
        if (op == 1u << b)
            return op_names[b];
    return "an unknown operation";
}

unsigned gr_method_ops(const gr_method_type *m)
{
    return (m->snapshot ? GR_OP_SNAPSHOT : 0) | (m->fields ? GR_OP_FIELDS : 0) |
           (m->counters ? GR_OP_COUNTERS : 0) | (m->reset_window ? GR_OP_RESET_WINDOW : 0) |
           (m->step ? GR_OP_STEP : 0) | (m->contacts ? GR_OP_CONTACTS : 0) | (m->stress ? GR_OP_STRESS : 0) |
           (m->advance ? GR_OP_ADVANCE : 0) | (m->observe ? GR_OP_OBSERVE : 0);
}

/* Operations a backend gives, itself or through a default. */
static unsigned ops_available(const gr_method_type *m)
{
    unsigned ops = gr_method_ops(m) | GR_OP_COUNTERS | GR_OP_RESET_WINDOW | GR_OP_STEP;
    if (m->snapshot)
        ops |= GR_OP_FIELDS | GR_OP_OBSERVE;
    if (m->step && m->dt)
        ops |= GR_OP_ADVANCE;
    return ops;
}

int gr_sim_require(const gr_method_type *m, unsigned ops, const char *who, gr_err *err)
{
    unsigned missing = ops & ~ops_available(m);
    for (unsigned b = 0; b < GR_OP_COUNT; b++)
        if (missing & (1u << b))
            return gr_fail(err, GR_EINPUT, "%s needs %s, which method '%s' does not give", who,
                           op_names[b], m->name);
    return GR_OK;
}

int gr_method_require_features(const gr_method_type *m, unsigned features, const char *who,
                               gr_err *err)
{
    unsigned missing = features & ~m->features;
    for (unsigned b = 0; b < GR_FEAT_COUNT; b++)
        if (missing & (1u << b))
            return gr_fail(err, GR_EINPUT, "%s needs %s, which method '%s' does not support", who,
                           gr_feature_name(1u << b), m->name);
    return GR_OK;
}

static int refuse_features(const gr_method_type *m, const gr_scene *sc, gr_err *err)
{
    char who[64];
    snprintf(who, sizeof who, "method '%s'", m->name);
    return gr_scene_refuse_features(sc, gr_scene_features(sc) & ~m->features, who, err);
}

/* A table the defaults cannot complete is the backend's bug, not the user's. */
static int check_type(const gr_method_type *m, gr_err *err)
{
    if (gr_sim_require(m, GR_OP_ADVANCE | GR_OP_OBSERVE, "the backend interface", err))
        return GR_ERUN;
    if (m->repr != GR_REPR_PARTICLES && !m->observables)
        return gr_fail(err, GR_ERUN, "method '%s': a lattice declares its observables", m->name);
    if (gr_obs_count(gr_method_observables(m)) > GR_OBS_MAX)
        return gr_fail(err, GR_ERUN, "method '%s' declares more than %d observables", m->name, GR_OBS_MAX);
    return GR_OK;
}

int gr_sim_create(const gr_method_type *m, const gr_scene *sc, const gr_particles *init,
                  gr_sim **out, gr_err *err)
{
    *out = NULL;
    if (check_type(m, err) || refuse_features(m, sc, err))
        return err->code;
    gr_sim *s = calloc(1, sizeof *s);
    if (!s)
        return gr_fail(err, GR_ERUN, "out of memory");
    s->type = m;
    s->scene = sc;
    if (gr_params_read(sc, m->name, m->params, &s->params, err)) {
        free(s);
        return err->code;
    }
    gr_method_ctx ctx = {sc, &s->params, s};
    if (m->create(&ctx, init, &s->state, err)) {
        gr_sim_free(s);
        return err->code;
    }
    *out = s;
    return GR_OK;
}

void gr_sim_free(gr_sim *s)
{
    if (!s)
        return;
    if (s->state)
        s->type->free(s->state);
    for (int k = 0; k < s->nrng; k++)
        gr_rng_free(s->rng[k]);
    gr_particles_free(s->scratch);
    free(s);
}

void gr_sim_note(gr_sim *s, const char *phrase)
{
    size_t n = strlen(s->notes);
    if (phrase[0])
        snprintf(s->notes + n, sizeof s->notes - n, "%s%s", n ? "; " : "", phrase);
}

const char *gr_sim_notes(const gr_sim *s) { return s->notes; }

void gr_sim_note_restitution(gr_sim *s, const gr_particles *init)
{
    gr_restitution r;
    gr_err ignore = {0}; /* create refused such a scene already */
    if (!gr_scene_restitution(s->scene, init, &r, &ignore))
        gr_sim_note(s, r.note);
}
const gr_method_type *gr_sim_type(const gr_sim *s) { return s->type; }
const gr_scene *gr_sim_scene(const gr_sim *s) { return s->scene; }
void *gr_sim_state(gr_sim *s) { return s->state; }
double gr_sim_time(const gr_sim *s) { return s->type->time(s->state); }

/* Whole steps until the time reaches t_end, to a millionth of a step (a
 * time that rounding leaves just short takes no extra step). */
static int advance_by_steps(gr_sim *s, double t_end, uint64_t max_steps, gr_err *err)
{
    const gr_method_type *m = s->type;
    double dt = m->dt(s->state);
    for (uint64_t n = 0; (!max_steps || n < max_steps) && m->time(s->state) < t_end - 1e-6 * dt; n++)
        if (m->step(s->state, err))
            return err->code;
    return GR_OK;
}

int gr_sim_advance(gr_sim *s, double t_end, uint64_t max_steps, gr_err *err)
{
    if (s->type->advance)
        return s->type->advance(s->state, t_end, max_steps, err);
    return advance_by_steps(s, t_end, max_steps, err);
}

int gr_sim_step(gr_sim *s, gr_err *err)
{
    if (s->type->step)
        return s->type->step(s->state, err);
    return s->type->advance(s->state, INFINITY, 1, err);
}

const gr_obs_def *gr_method_observables(const gr_method_type *m)
{
    return m->observables ? m->observables : gr_obs_particle_set;
}

const gr_obs_def *gr_sim_observables(const gr_sim *s) { return gr_method_observables(s->type); }

/* What the scene has of what an observable needs. */
static unsigned scene_has(const gr_scene *sc)
{
    unsigned has = 0, f = gr_scene_features(sc);
    if (f & GR_FEAT_FRICTION)
        has |= GR_OBS_NEEDS_ROTATION;
    if (sc->silo.present || (f & GR_FEAT_ORIFICE))
        has |= GR_OBS_NEEDS_ORIFICE;
    int walls = sc->nsegments > 0; /* the silo's, when made of segments, are among them */
    for (int k = 0; k < 4; k++)
        walls |= sc->side[k] == GR_BC_WALL;
    if (walls)
        has |= GR_OBS_NEEDS_WALLS;
    return has;
}

uint64_t gr_sim_obs_skip(const gr_sim *s)
{
    const gr_obs_def *d = gr_sim_observables(s);
    unsigned has = scene_has(s->scene);
    uint64_t skip = 0;
    for (size_t k = 0; d[k].name && k < GR_OBS_MAX; k++)
        if (d[k].needs & ~has)
            skip |= 1ull << k;
    return skip;
}

/* The counter of that name among c[0 .. n-1]: 1 and its value, else 0. */
static int find_counter(const gr_counter *c, size_t n, const char *name, uint64_t *value)
{
    for (size_t k = 0; k < n; k++) {
        if (!strcmp(c[k].name, name)) {
            *value = c[k].value;
            return 1;
        }
    }
    return 0;
}

/* The declared counters take their place in obs->count from the method's
 * counters of the same name. */
static void fill_counters(const gr_sim *s, gr_obs *obs)
{
    const gr_obs_def *d = gr_sim_observables(s);
    gr_counter c[GR_MAX_COUNTERS];
    size_t nc = gr_sim_counters(s, c, GR_MAX_COUNTERS);
    for (size_t k = 0; d[k].name && k < GR_OBS_MAX; k++)
        if (d[k].src == GR_OBS_COUNTER)
            find_counter(c, nc, d[k].name, &obs->count[k]);
}

/* The default observe: the kinematic set from the snapshot. */
static int observe_snapshot(gr_sim *s, gr_obs *obs, gr_err *err)
{
    if (!s->scratch && !(s->scratch = gr_particles_create(0, err)))
        return err->code;
    if (s->type->snapshot(s->state, s->scratch, err))
        return err->code;
    gr_obs_from_particles(s->scratch, s->scene->gravity, obs);
    obs->t = s->type->time(s->state);
    gr_counter c[GR_MAX_COUNTERS];
    size_t nc = gr_sim_counters(s, c, GR_MAX_COUNTERS);
    if (!find_counter(c, nc, "steps", &obs->steps))
        find_counter(c, nc, "events", &obs->steps);
    find_counter(c, nc, "outflow", &obs->outflow);
    return GR_OK;
}

int gr_sim_observe(gr_sim *s, gr_obs *obs, gr_err *err)
{
    if (s->type->observe ? s->type->observe(s->state, obs, err) : observe_snapshot(s, obs, err))
        return err->code;
    fill_counters(s, obs);
    return GR_OK;
}

size_t gr_sim_diagnostics(gr_sim *s, gr_diag *out, size_t cap)
{
    const gr_obs_def *d = gr_sim_observables(s);
    gr_counter c[GR_MAX_COUNTERS];
    size_t nc = gr_sim_counters(s, c, GR_MAX_COUNTERS), n = 0;
    for (size_t k = 0; d[k].name && n < cap; k++) {
        uint64_t v;
        if (!d[k].key || !find_counter(c, nc, d[k].name, &v) || !v)
            continue;
        gr_diag *g = &out[n++];
        g->index = k, g->name = d[k].name, g->key = d[k].key, g->doc = d[k].doc, g->count = v;
        if (s->type->diagnose)
            s->type->diagnose(s->state, d[k].name, g->detail, sizeof g->detail);
        else
            snprintf(g->detail, sizeof g->detail, "%s", d[k].doc);
    }
    return n;
}

void gr_sim_reset_window(gr_sim *s)
{
    if (s->type->reset_window)
        s->type->reset_window(s->state);
}

int gr_sim_snapshot(gr_sim *s, gr_particles *out, gr_err *err)
{
    if (!s->type->snapshot)
        return gr_sim_require(s->type, GR_OP_SNAPSHOT, "a snapshot", err);
    return s->type->snapshot(s->state, out, err);
}

int gr_sim_fields(gr_sim *s, gr_field *f, double w, gr_err *err)
{
    if (s->type->fields)
        return s->type->fields(s->state, f, w, err);
    if (!s->type->snapshot)
        return gr_sim_require(s->type, GR_OP_FIELDS, "coarse-grained fields", err);
    if (!s->scratch && !(s->scratch = gr_particles_create(0, err)))
        return err->code;
    if (s->type->snapshot(s->state, s->scratch, err))
        return err->code;
    return gr_field_add(f, s->scratch, GR_PF_FIXED | GR_PF_GONE, w, err);
}

int gr_sim_counter(const gr_sim *s, const char *name, uint64_t *value)
{
    gr_counter c[GR_MAX_COUNTERS];
    return find_counter(c, gr_sim_counters(s, c, GR_MAX_COUNTERS), name, value);
}

int gr_sim_contacts(gr_sim *s, gr_contacts *out, gr_err *err)
{
    if (!s->type->contacts)
        return gr_sim_require(s->type, GR_OP_CONTACTS, "a contact network", err);
    out->n = 0;
    return s->type->contacts(s->state, out, err);
}

int gr_sim_stress(gr_sim *s, int nx, int ny, double global[4], double *cells, gr_err *err)
{
    if (!s->type->stress)
        return gr_sim_require(s->type, GR_OP_STRESS, "a window-averaged stress", err);
    if (nx < 1 || ny < 1)
        return gr_fail(err, GR_ERUN, "stress: a grid of %d x %d cells", nx, ny);
    return s->type->stress(s->state, nx, ny, global, cells, err);
}

size_t gr_counters_put(gr_counter *out, size_t cap, const gr_counter *all, size_t n)
{
    size_t k = n < cap ? n : cap;
    for (size_t i = 0; i < k; i++)
        out[i] = all[i];
    return k;
}

size_t gr_sim_counters(const gr_sim *s, gr_counter *out, size_t cap)
{
    return s->type->counters ? s->type->counters(s->state, out, cap) : 0;
}

/* ---- random streams ---- */

/* A backend's stream k is stored as "<method>.stream<k>", a stream of the
 * common table as "<method>.common<id>". */
static void stream_name(const gr_sim *s, uint64_t id, char *buf, size_t n)
{
    if (id >= GR_STREAM_METHOD_BASE)
        snprintf(buf, n, "%s.stream%llu", s->type->name, (unsigned long long)(id - GR_STREAM_METHOD_BASE));
    else
        snprintf(buf, n, "%s.common%llu", s->type->name, (unsigned long long)id);
}

static gr_rng *stream_of(gr_sim *s, uint64_t id, gr_err *err)
{
    for (int i = 0; i < s->nrng; i++)
        if (s->rng_id[i] == id)
            return s->rng[i];
    if (s->nrng == MAX_STREAMS) {
        gr_fail(err, GR_ERUN, "%s: more than %d random streams", s->type->name, MAX_STREAMS);
        return NULL;
    }
    gr_rng *r = gr_rng_create(s->scene->seed, id, err);
    if (r) {
        s->rng_id[s->nrng] = id;
        s->rng[s->nrng++] = r;
    }
    return r;
}

gr_rng *gr_sim_stream(gr_sim *s, uint64_t k, gr_err *err)
{
    if (k >= GR_STREAM_METHOD_BASE) {
        gr_fail(err, GR_ERUN, "%s: stream %llu is not below %d", s->type->name,
                (unsigned long long)k, GR_STREAM_METHOD_BASE);
        return NULL;
    }
    return stream_of(s, GR_STREAM_METHOD_BASE + k, err);
}

gr_rng *gr_sim_stream_id(gr_sim *s, uint64_t id, gr_err *err) { return stream_of(s, id, err); }


/* ---- checkpoints ---- */

int gr_sim_save(const gr_sim *s, gr_ckpt *ck, gr_err *err)
{
    const gr_param_values *pv = &s->params;
    if (pv->n && gr_ckpt_put_f64(ck, "sim_params", pv->v, (size_t)pv->n, err))
        return err->code;
    for (int i = 0; i < s->nrng; i++) {
        char name[96];
        stream_name(s, s->rng_id[i], name, sizeof name);
        if (gr_rng_save(s->rng[i], ck, name, err))
            return err->code;
    }
    return s->type->save(s->state, ck, err);
}

/* The checkpoint's parameters must be the scene's, bit for bit: a restart
 * with another dt or tolerance would not continue the same run. */
static int compare_params(const gr_sim *s, gr_ckpt *ck, gr_err *err)
{
    const gr_param_values *pv = &s->params;
    if (!pv->n)
        return GR_OK;
    double v[GR_MAX_PARAMS];
    size_t n;
    gr_err none = {0};
    if (gr_ckpt_len(ck, "sim_params", &n, &none))
        return GR_OK; /* written before version 2: the run's scene text check guards it */
    if (n != (size_t)pv->n || gr_ckpt_get_f64(ck, "sim_params", v, n, err))
        return gr_fail(err, GR_EINPUT, "checkpoint: %zu parameter values, method '%s' has %d", n,
                       s->type->name, pv->n);
    for (int k = 0; k < pv->n; k++) {
        if (memcmp(&v[k], &pv->v[k], sizeof v[k]) == 0)
            continue;
        char a[64], b[64];
        gr_param_format(&pv->table[k], v[k], a, sizeof a);
        gr_param_format(&pv->table[k], pv->v[k], b, sizeof b);
        return gr_fail(err, GR_EINPUT, "checkpoint: written with [%s] %s = %s, the scene gives %s",
                       s->type->name, pv->table[k].name, a, b);
    }
    return GR_OK;
}

int gr_sim_load(gr_sim *s, gr_ckpt *ck, gr_err *err)
{
    if (compare_params(s, ck, err))
        return err->code;
    for (int i = 0; i < s->nrng; i++) {
        char name[96];
        stream_name(s, s->rng_id[i], name, sizeof name);
        if (gr_rng_load(s->rng[i], ck, name, err))
            return err->code;
    }
    return s->type->load(s->state, ck, err);
}
