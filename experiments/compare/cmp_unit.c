/* One run of grano compare: the case's scene with the unit's settings,
 * a fresh instance of the row's method, the case's measurement, timed; its
 * result goes to a part file (experiments/lib/sweep.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmp.h"
#include "init.h"
#include "parts.h"
#include "progress.h"

/* Apply "section.key=value;..." to *text (replaced by the new text). */
static int apply_settings(char **text, const char *settings, const char *where, gr_err *err)
{
    char buf[1024];
    snprintf(buf, sizeof buf, "%s", settings);
    for (char *save = NULL, *s = strtok_r(buf, ";", &save); s; s = strtok_r(NULL, ";", &save)) {
        char *dot = strchr(s, '.'), *eq = strchr(s, '=');
        if (!dot || !eq || eq < dot)
            return gr_fail(err, GR_EINPUT, "%s: setting '%s' is not section.key=value", where, s);
        *dot = *eq = 0;
        char *t = gr_scene_text_set(*text, s, dot + 1, eq + 1, err);
        if (!t)
            return err->code;
        free(*text);
        *text = t;
    }
    return GR_OK;
}

/* A knob of several keys moved together ("species.count+species.weight")
 * takes a value per key ("256:4"). */
static int apply_knob(char **text, const char *knob, const char *value, gr_err *err)
{
    char keys[128], vals[64], set[256];
    snprintf(keys, sizeof keys, "%s", knob);
    snprintf(vals, sizeof vals, "%s", value);
    char *sk = NULL, *sv = NULL, *k = strtok_r(keys, "+", &sk), *v = strtok_r(vals, ":", &sv);
    for (; k && v; k = strtok_r(NULL, "+", &sk), v = strtok_r(NULL, ":", &sv)) {
        snprintf(set, sizeof set, "%s=%s", k, v);
        if (apply_settings(text, set, "the row's knob", err))
            return err->code;
    }
    if (k || v)
        return gr_fail(err, GR_EINPUT, "knob %s: value '%s' has not one part per key", knob, value);
    return GR_OK;
}

static char *read_text(const char *path, gr_err *err)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        gr_fail(err, GR_EINPUT, "%s: cannot read the case's scene", path);
        return NULL;
    }
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    rewind(f);
    char *t = n >= 0 ? malloc((size_t)n + 1) : NULL;
    if (t && fread(t, 1, (size_t)n, f) == (size_t)n)
        t[n] = 0;
    else {
        free(t);
        t = NULL;
        gr_fail(err, GR_EINPUT, "%s: cannot read the case's scene", path);
    }
    fclose(f);
    return t;
}

static gr_scene *parse(const char *text, const char *path, gr_err *err)
{
    const char *names[GR_MAX_METHODS + 1];
    gr_method_names(names, GR_MAX_METHODS + 1);
    return gr_scene_parse(text, path, names, err);
}

gr_scene *cmp_scene_with(const gr_scene *sc, const char *settings, gr_err *err)
{
    char *text = strdup(sc->text);
    if (!text) {
        gr_fail(err, GR_ERUN, "out of memory");
        return NULL;
    }
    gr_scene *out = apply_settings(&text, settings, sc->path, err) ? NULL : parse(text, sc->path, err);
    free(text);
    return out;
}

gr_scene *cmp_unit_scene(const cmp_plan *pl, const cmp_unit *u, gr_err *err)
{
    char path[2048], set[128];
    snprintf(path, sizeof path, "%s/%s", pl->scenes, u->row->scene ? u->row->scene : u->c->scene);
    char *text = read_text(path, err);
    int rc = !text;
    if (!rc && pl->quick && u->c->quick_set)
        rc = apply_settings(&text, u->c->quick_set, "the case's quick settings", err);
    if (!rc && u->row->fixed)
        rc = apply_settings(&text, u->row->fixed, "the row's settings", err);
    if (!rc && u->row->knob && u->value[0])
        rc = apply_knob(&text, u->row->knob, u->value, err);
    if (!rc) {
        snprintf(set, sizeof set, "scene.seed=%d", u->seed);
        rc = apply_settings(&text, set, "the seed", err);
    }
    gr_scene *sc = rc ? NULL : parse(text, path, err);
    free(text);
    return sc;
}

/* The validity limits the run broke, "name count in N steps (key), ...",
 * and for a run that failed, where it stopped: what a row that meets its
 * method's limit reports beside the failure. */
static void diagnose(gr_sim *s, int failed, cmp_meas *m, gr_err *err)
{
    gr_diag dg[GR_OBS_MAX];
    size_t n = gr_sim_diagnostics(s, dg, GR_OBS_MAX), k = 0;
    uint64_t steps = 0;
    const char *unit = "steps";
    if (!gr_sim_counter(s, "steps", &steps) && gr_sim_counter(s, "events", &steps))
        unit = "events";
    for (size_t i = 0; i < n && k + 1 < sizeof m->diag; i++)
        k += (size_t)snprintf(m->diag + k, sizeof m->diag - k, "%s%s %llu in %llu %s (%s)", i ? "; " : "",
                              dg[i].name, (unsigned long long)dg[i].count, (unsigned long long)steps, unit,
                              dg[i].key);
    if (failed) {
        size_t e = strlen(err->msg);
        snprintf(err->msg + e, sizeof err->msg - e, " [stopped at t = %.4g after %llu %s]", gr_sim_time(s),
                 (unsigned long long)steps, unit);
        m->steps = (double)steps;
    }
}

int cmp_advance(gr_sim *s, const gr_scene *sc, const cmp_meas *m, double t, gr_err *err)
{
    return m->watch ? exp_watch_advance(m->watch, s, sc, t, NULL, err) : gr_sim_advance(s, t, 0, err);
}

/* Measure the unit: scene, initial grains, instance, measurement; the
 * wall time covers the instance and the measurement (not the preparation). */
static int measure(const cmp_plan *pl, const cmp_unit *u, cmp_meas *m, double *wall, gr_err *err)
{
    const gr_method_type *mt;
    if (gr_method_lookup(u->row->method, "the case table", &mt, err))
        return err->code;
    gr_scene *sc = cmp_unit_scene(pl, u, err);
    gr_particles *p = sc ? gr_particles_create(0, err) : NULL;
    int rc = !p;
    if (!rc)
        rc = u->c->prepare && !u->row->measure ? u->c->prepare(sc, p, err) : gr_init_particles(sc, p, err);
    gr_sim *s = NULL;
    double t0 = gr_wall_seconds();
    exp_watch w;
    if (!rc && !(rc = gr_sim_create(mt, sc, p, &s, err))) {
        exp_watch_init(&w, s, &sc->run);
        m->watch = &w;
        rc = (u->row->measure ? u->row->measure : u->c->measure)(u->c, s, sc, m, err);
        m->watch = NULL;
    }
    *wall = gr_wall_seconds() - t0;
    if (s)
        diagnose(s, rc, m, err);
    gr_sim_free(s);
    gr_particles_free(p);
    gr_scene_free(sc);
    return rc ? (err->code ? err->code : GR_ERUN) : GR_OK;
}

/* The part: key, ok, value, sem, aux, steps, wall (an own row's run, its
 * own answers beside them); a failed run leaves its
 * message (a method may go unstable at a coarse setting: that is a result),
 * and the run its broken validity limits. The wall time and steps of a
 * failed run are those to the failure. */
int cmp_run_unit(size_t unit, const char *part, const char *key, void *ctx, volatile double *progress,
                 gr_err *err)
{
    const cmp_plan *pl = ctx;
    cmp_meas m = {.value = NAN, .sem = NAN, .aux = NAN, .own = NAN, .own_aux = NAN, .steps = NAN};
    double wall = NAN;
    gr_err run_err = {0};
    int rc = measure(pl, &pl->units[unit], &m, &wall, &run_err);
    if (rc == GR_EINPUT) {
        *err = run_err;
        return rc;
    }
    gr_ckpt *ck = gr_ckpt_create(part, err);
    if (!ck)
        return err->code;
    double v[6] = {rc ? 0 : 1, m.value, m.sem, m.aux, m.steps, wall};
    int w = gr_ckpt_put_bytes(ck, "key", key, strlen(key), err) || gr_ckpt_put_f64(ck, "result", v, 6, err) ||
            (rc && gr_ckpt_put_bytes(ck, "message", run_err.msg, strlen(run_err.msg) + 1, err)) ||
            (m.diag[0] && gr_ckpt_put_bytes(ck, "diag", m.diag, strlen(m.diag) + 1, err)) ||
            (!rc && m.nprof && gr_ckpt_put_f64(ck, "profile", m.prof, (size_t)m.nprof, err)) ||
            (!rc && isfinite(m.own) && gr_ckpt_put_f64(ck, "own", (double[2]){m.own, m.own_aux}, 2, err));
    if (w) {
        gr_ckpt_discard(ck);
        return err->code;
    }
    *progress = 1;
    return gr_ckpt_close(ck, err);
}

void cmp_unit_label(size_t unit, void *ctx, char *label, size_t n)
{
    const cmp_unit *u = &((const cmp_plan *)ctx)->units[unit];
    snprintf(label, n, "%s-%s-%s-s%d", u->c->name, u->row->label, u->value[0] ? u->value : "none", u->seed);
}

/* The unit's settings and a hash of its whole scene text, so that a part
 * made from an edited scene file is redone. */
void cmp_unit_key(size_t unit, void *ctx, char *key, size_t n)
{
    const cmp_plan *pl = ctx;
    const cmp_unit *u = &pl->units[unit];
    gr_err e = {0};
    gr_scene *sc = cmp_unit_scene(pl, u, &e);
    unsigned long long h = 5381;
    for (const char *t = sc ? sc->text : ""; *t; t++)
        h = h * 33 + (unsigned char)*t;
    gr_scene_free(sc);
    snprintf(key, n, "compare v4 %s %s %s %s scene %016llx", u->c->name, u->row->label, u->row->method,
             pl->quick ? "quick" : "full", h);
}
