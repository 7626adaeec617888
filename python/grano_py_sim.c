/* The flat interface's simulations (grano_py.h): a gr_sim driven over the
 * sample times of `grano run`'s loop, so that a run from Python is the
 * CLI's run bit for bit, checkpoints included. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "grano_py.h"
#include "h5md.h"
#include "init.h"
#include "runio.h"

struct gp_sim {
    gr_sim *sim;
    gr_scene *sc;
    char **sets;      /* the --set lines the scene was read with */
    size_t nsets;
    const gr_method_type *m;
    double t0, eps, every[3];
    uint64_t k[3];    /* the next sample of each kind, as runio.c counts them */
    uint64_t warned;  /* validity limits already told, by declaration position */
    char warn[4096];
    /* the samples taken: time, steps, then the declared values */
    size_t nobs, rows, cap;
    double *time, *dval;
    uint64_t *steps;
    int64_t *ival;
};

static void set_clock(gp_sim *s)
{
    const gr_runctl *r = &s->sc->run;
    s->every[0] = r->observe_every, s->every[1] = r->output_every, s->every[2] = r->checkpoint_every;
    s->eps = 1e-9 * (r->until > 1 ? r->until : 1);
    s->nobs = gr_obs_count(gr_method_observables(s->m));
}

/* A message about the scene names a setting as --set does
 * (gr_scene_name_sets), not the line it became. */
static int named(const gp_sim *s, gr_err *err)
{
    gr_scene_name_sets(s->sc, (const char *const *)s->sets, s->nsets, err);
    return err->code;
}

static int keep_sets(gp_sim *s, const char *const *sets, size_t n, gr_err *err)
{
    if (n && !(s->sets = calloc(n, sizeof *s->sets)))
        return gr_fail(err, GR_ERUN, "out of memory");
    for (; s->nsets < n; s->nsets++)
        if (!(s->sets[s->nsets] = strdup(sets[s->nsets])))
            return gr_fail(err, GR_ERUN, "out of memory");
    return GR_OK;
}

gp_sim *gp_sim_create(const char *method, gr_scene *sc, const char *const *sets, size_t nsets,
                      const gr_particles *init, gr_err *err)
{
    const gr_method_type *m;
    gp_sim *s = NULL;
    gr_particles *p = NULL;
    if (gr_method_lookup(method, "method", &m, err) || gr_run_check(sc, err))
        goto fail;
    if (!init && (!(p = gr_particles_create(0, err)) || gr_init_particles(sc, p, err)))
        goto fail;
    if (!(s = calloc(1, sizeof *s))) {
        gr_fail(err, GR_ERUN, "out of memory");
        goto fail;
    }
    s->sc = sc, s->m = m;
    if (keep_sets(s, sets, nsets, err) || gr_sim_create(m, sc, init ? init : p, &s->sim, err))
        goto fail;
    gr_particles_free(p);
    set_clock(s);
    s->t0 = gr_sim_time(s->sim);
    s->k[2] = 1; /* the start is its own checkpoint, written before the loop */
    return s;
fail:
    gr_scene_name_sets(sc, sets, nsets, err);
    gr_particles_free(p);
    if (s)
        s->sc = NULL;
    gp_sim_free(s);
    gr_scene_free(sc);
    return NULL;
}

/* A stored string of the checkpoint, allocated. */
static char *stored(gr_ckpt *ck, const char *name, const char *path, gr_err *err)
{
    size_t n;
    char *v = NULL;
    if (gr_ckpt_len(ck, name, &n, err))
        gr_fail(err, GR_EINPUT, "%s: not a grano run checkpoint (no %s)", path, name);
    else if (!(v = calloc(n + 1, 1)))
        gr_fail(err, GR_ERUN, "out of memory");
    else if (gr_ckpt_get_bytes(ck, name, v, n, err)) {
        free(v);
        v = NULL;
    }
    return v;
}

/* The checkpoint's method and (want_scene) the scene it was written
 * with: its text, the path it was read from (the H5MD part holds it; a
 * lattice's checkpoint has none) and its seed. */
static int stored_run(const char *ckpt, int want_scene, char **method, gr_scene **sc, gr_err *err)
{
    gr_ckpt *ck = gr_ckpt_open(ckpt, err);
    if (!ck)
        return err->code;
    uint64_t seed = 0;
    char *text = NULL;
    *method = stored(ck, "run_method", ckpt, err);
    int rc = !*method || (want_scene && (!(text = stored(ck, "run_scene_text", ckpt, err)) ||
                                          gr_ckpt_get_u64(ck, "run_seed", &seed, 1, err)));
    gr_err ignore = {0};
    gr_ckpt_close(ck, &ignore);
    if (!rc && want_scene) {
        gr_h5md_reader *r = gr_h5md_open(ckpt, &ignore);
        const gr_h5md_info *in = r ? gr_h5md_info_of(r) : NULL;
        *sc = gp_scene_parse(text, in && in->scene_path && in->scene_path[0] ? in->scene_path : ckpt, err);
        gr_h5md_reader_free(r);
        if (*sc)
            (*sc)->seed = seed;
        rc = !*sc;
    }
    free(text);
    return rc ? (err->code ? err->code : GR_EINPUT) : GR_OK;
}

gp_sim *gp_sim_load(const char *ckpt, gr_scene *sc, const char *const *sets, size_t nsets, const char *method,
                    int branch, char *notes, size_t cap, gr_err *err)
{
    char *was_method = NULL;
    gr_scene *was_sc = NULL;
    if (stored_run(ckpt, !sc, &was_method, &was_sc, err)) {
        free(was_method);
        gr_scene_free(sc);
        return NULL;
    }
    gp_sim *s = gp_sim_create(method ? method : was_method, sc ? sc : was_sc, sets, nsets, NULL, err);
    free(was_method);
    if (!s)
        return NULL;
    gr_runctl was;
    gr_run_opts o = {.branch = branch, .notes = notes, .notes_cap = cap};
    if (notes && cap)
        notes[0] = '\0';
    if (gr_run_load(ckpt, s->sim, s->k, &o, &was, err)) {
        named(s, err);
        gp_sim_free(s);
        return NULL;
    }
    gr_run_resume_counters(s->sc, &was, gr_sim_time(s->sim), s->t0, branch, s->k);
    return s;
}

void gp_sim_free(gp_sim *s)
{
    if (!s)
        return;
    gr_sim_free(s->sim);
    gr_scene_free(s->sc);
    for (size_t i = 0; i < s->nsets; i++)
        free(s->sets[i]);
    free(s->sets);
    free(s->time);
    free(s->steps);
    free(s->dval);
    free(s->ival);
    free(s);
}

const char *gp_sim_method(const gp_sim *s) { return s->m->name; }

int gp_sim_method_index(const gp_sim *s)
{
    int i = 0;
    while (gr_method_all()[i] != s->m)
        i++;
    return i;
}

const gr_scene *gp_sim_scene(const gp_sim *s) { return s->sc; }
double gp_sim_time(const gp_sim *s) { return gr_sim_time(s->sim); }

/* The declared values of one sample, as gp_sim_observe gives them. */
static void extract(const gp_sim *s, const gr_obs *o, double *val, int64_t *ival)
{
    const gr_obs_def *d = gr_method_observables(s->m);
    for (size_t k = 0; k < s->nobs; k++) {
        const void *v = gr_obs_value(o, d, k);
        val[2 * k] = val[2 * k + 1] = NAN;
        ival[k] = 0;
        if (d[k].integer)
            ival[k] = (int64_t) * (const uint64_t *)v;
        else
            memcpy(val + 2 * k, v, (size_t)d[k].ncomp * sizeof(double));
    }
}

static int record(gp_sim *s, const gr_obs *o, gr_err *err)
{
    if (s->rows == s->cap) {
        size_t cap = s->cap ? 2 * s->cap : 64;
        double *t = realloc(s->time, cap * sizeof *t);
        if (t)
            s->time = t;
        uint64_t *st = realloc(s->steps, cap * sizeof *st);
        if (st)
            s->steps = st;
        double *dv = realloc(s->dval, cap * 2 * s->nobs * sizeof *dv + 1);
        if (dv)
            s->dval = dv;
        int64_t *iv = realloc(s->ival, cap * s->nobs * sizeof *iv + 1);
        if (iv)
            s->ival = iv;
        if (!t || !st || !dv || !iv)
            return gr_fail(err, GR_ERUN, "out of memory for the observables' history");
        s->cap = cap;
    }
    s->time[s->rows] = o->t;
    s->steps[s->rows] = o->steps;
    extract(s, o, s->dval + s->rows * 2 * s->nobs, s->ival + s->rows * s->nobs);
    s->rows++;
    return GR_OK;
}

static int due(const gp_sim *s, int j, double t)
{
    return t >= s->t0 + (double)s->k[j] * s->every[j] - s->eps;
}

/* What runio.c's loop does to the state at a sample time before it moves
 * on: the observables sampled (kept here) and a new window started. Its
 * frames, fields and writes read the state without changing it. */
static int take_samples(gp_sim *s, gr_err *err)
{
    double t = gr_sim_time(s->sim);
    if (due(s, 0, t)) {
        gr_obs o;
        gr_obs_clear(&o);
        if (gr_sim_observe(s->sim, &o, err) || record(s, &o, err))
            return err->code;
        gr_sim_reset_window(s->sim);
    }
    for (int j = 0; j < 3; j++)
        if (due(s, j, t))
            s->k[j] = gr_run_next_index(t, s->t0, s->every[j], s->eps);
    return GR_OK;
}

/* Each validity limit broken is told once, as grano run warns it; under
 * [run] strict = yes the first one fails the run. */
static int check_limits(gp_sim *s, gr_err *err)
{
    gr_diag dg[GR_OBS_MAX];
    size_t n = gr_sim_diagnostics(s->sim, dg, GR_OBS_MAX);
    for (size_t i = 0; i < n; i++) {
        if (s->warned & (1ull << dg[i].index))
            continue;
        s->warned |= 1ull << dg[i].index;
        char where[1200], msg[1800];
        gr_scene_where_key(s->sc, dg[i].key, where, sizeof where);
        snprintf(msg, sizeof msg, "%s: validity limit %s broken at t = %g: %s (%s changes it)", s->m->name,
                 dg[i].name, gr_sim_time(s->sim), dg[i].detail, where);
        if (s->sc->run.strict) {
            gr_scene_where(s->sc, "run", "strict", where, sizeof where);
            return gr_fail(err, GR_ERUN, "%s; stopped (%s = yes)", msg, where);
        }
        size_t used = strlen(s->warn);
        snprintf(s->warn + used, sizeof s->warn - used, "%s\n", msg);
    }
    return GR_OK;
}

size_t gp_sim_warnings(gp_sim *s, char *buf, size_t cap)
{
    size_t n = strlen(s->warn);
    if (cap)
        snprintf(buf, cap, "%s", s->warn);
    s->warn[0] = '\0';
    return n;
}

static uint64_t progress_count(const gp_sim *s)
{
    uint64_t v = 0;
    if (!gr_sim_counter(s->sim, "steps", &v))
        gr_sim_counter(s->sim, "events", &v);
    return v;
}

int gp_sim_advance(gp_sim *s, double t_end, uint64_t max_steps, int *done, gr_err *err)
{
    double t = gr_sim_time(s->sim);
    *done = 0;
    if (!isfinite(t_end))
        return gr_fail(err, GR_EINPUT, "advance: t = %g is not a finite time", t_end);
    if (t >= t_end - s->eps) {
        *done = 1;
        return GR_OK;
    }
    if (take_samples(s, err))
        return named(s, err);
    double target = t_end;
    for (int j = 0; j < 3; j++) {
        double next = s->t0 + (double)s->k[j] * s->every[j];
        target = next < target ? next : target;
    }
    uint64_t c = progress_count(s);
    if (gr_sim_advance(s->sim, target, max_steps, err) || check_limits(s, err))
        return named(s, err);
    /* A method that cannot get nearer (its steps overshoot) is there. */
    if (target == t_end && gr_sim_time(s->sim) == t && progress_count(s) == c)
        *done = 1;
    return GR_OK;
}

int gp_sim_step(gp_sim *s, uint64_t n, gr_err *err)
{
    for (uint64_t i = 0; i < n; i++) {
        if (take_samples(s, err) || gr_sim_step(s->sim, err))
            return named(s, err);
        double t = gr_sim_time(s->sim);
        for (int j = 0; j < 3; j++)
            if (t > s->t0 + (double)s->k[j] * s->every[j] + s->eps)
                s->k[j] = gr_run_next_index(t - 2 * s->eps, s->t0, s->every[j], s->eps);
    }
    /* as the run loop, once a stretch: the diagnostics count every counter */
    return check_limits(s, err) ? named(s, err) : GR_OK;
}

int gp_sim_observe(gp_sim *s, double *t, uint64_t *steps, double *val, int64_t *ival, uint64_t *skip,
                   gr_err *err)
{
    gr_obs o;
    gr_obs_clear(&o);
    if (gr_sim_observe(s->sim, &o, err))
        return named(s, err);
    *t = o.t, *steps = o.steps, *skip = gr_sim_obs_skip(s->sim);
    extract(s, &o, val, ival);
    return GR_OK;
}

int gp_sim_sample_due(const gp_sim *s) { return due(s, 0, gr_sim_time(s->sim)); }

uint64_t gp_sim_obs_skip(const gp_sim *s) { return gr_sim_obs_skip(s->sim); }

size_t gp_sim_history(const gp_sim *s, const double **time, const uint64_t **steps, const double **dval,
                      const int64_t **ival)
{
    *time = s->time, *steps = s->steps, *dval = s->dval, *ival = s->ival;
    return s->rows;
}

void gp_sim_history_clear(gp_sim *s) { s->rows = 0; }

gr_particles *gp_sim_snapshot(gp_sim *s, gr_err *err)
{
    gr_particles *p = gr_particles_create(0, err);
    if (p && gr_sim_snapshot(s->sim, p, err)) {
        named(s, err);
        gr_particles_free(p);
        p = NULL;
    }
    return p;
}

int gp_sim_fields(gp_sim *s, int nx, int ny, double *phi, double *v, double *T, gr_err *err)
{
    if (nx < 1 || ny < 1)
        return gr_fail(err, GR_EINPUT, "fields: a grid of %d x %d cells", nx, ny);
    gr_field *f = gr_field_create(nx, ny, 0, 0, s->sc->width / nx, s->sc->height / ny, err);
    size_t nc = (size_t)nx * (size_t)ny;
    double *vy = malloc(nc * sizeof *vy);
    int rc = !f ? err->code : !vy ? gr_fail(err, GR_ERUN, "out of memory") : gr_sim_fields(s->sim, f, 1.0, err);
    if (!rc) {
        gr_field_packing(f, phi);
        gr_field_velocity(f, T, vy); /* T as scratch for vx */
        for (size_t c = 0; c < nc; c++)
            v[2 * c] = T[c], v[2 * c + 1] = vy[c];
        gr_field_temperature(f, T);
    }
    free(vy);
    gr_field_free(f);
    return rc ? named(s, err) : GR_OK;
}

size_t gp_sim_counters(const gp_sim *s, const char **names, uint64_t *values, size_t cap)
{
    gr_counter c[GR_MAX_COUNTERS];
    size_t n = gr_sim_counters(s->sim, c, GR_MAX_COUNTERS);
    for (size_t i = 0; i < n && i < cap; i++)
        names[i] = c[i].name, values[i] = c[i].value;
    return n < cap ? n : cap;
}

int gp_sim_save(gp_sim *s, const char *path, gr_err *err)
{
    if (take_samples(s, err) || gr_run_save(path, s->sim, s->k, err))
        return named(s, err);
    return GR_OK;
}
