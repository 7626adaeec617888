/* grano compare SCENE.ini: a user's scene as a case of its own. Every
 * registered method that models the scene and declares the observable gets
 * a row; a method with a time step sweeps it from its default for this
 * scene (1, 1/2, 1/4 of it); the reference is the finest run of the most
 * accurate method (edmd where the scene gives a restitution, its hard-disk
 * model; dem where it gives a contact law; the user's --reference else). The
 * measured quantity is one observable, block-averaged over 10 instants of
 * the second half of the run; aux is its value at the end. */
#include <libgen.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmp.h"
#include "cmp_own.h"
#include "init.h"
#include "stats.h"

#define NBLOCKS 10

/* The methods' accuracy knobs: a time step. A lattice's dt maps a step to
 * tau by choice and is no knob; edmd is exact (its guard's tc matters only
 * under collapse = tc). */
static const char *knob_of(const char *method)
{
    static const char *const knobs[][2] = {{"dem", "dem.dt"}, {"cd", "cd.dt"}, {"dsmc", "dsmc.dt"}};
    for (size_t k = 0; k < sizeof knobs / sizeof knobs[0]; k++)
        if (!strcmp(knobs[k][0], method))
            return knobs[k][1];
    return NULL;
}

static int find_obs(const gr_obs_def *defs, const char *name)
{
    for (int k = 0; defs && defs[k].name; k++)
        if (!strcmp(defs[k].name, name))
            return k;
    return -1;
}

static double obs_number(const gr_obs *o, const gr_obs_def *defs, int k)
{
    const void *v = gr_obs_value(o, defs, (size_t)k);
    return defs[k].integer ? (double)*(const uint64_t *)v : *(const double *)v;
}

int cmp_measure_observable(const cmp_case *c, gr_sim *s, const gr_scene *sc, cmp_meas *out, gr_err *err)
{
    const gr_obs_def *defs = gr_sim_observables(s);
    int k = find_obs(defs, c->quantity);
    if (k < 0)
        return gr_fail(err, GR_ERUN, "%s has no observable '%s'", gr_sim_type(s)->name, c->quantity);
    double V[NBLOCKS], t0 = sc->run.until / 2;
    gr_obs o;
    int rc = cmp_advance(s, sc, out, t0, err);
    for (int b = 0; b < NBLOCKS && !rc; b++) {
        rc = cmp_advance(s, sc, out, t0 + (sc->run.until - t0) * (b + 1) / NBLOCKS, err) ||
             gr_sim_observe(s, &o, err);
        if (!rc)
            V[b] = obs_number(&o, defs, k);
    }
    if (rc)
        return err->code ? err->code : GR_ERUN;
    for (int b = 0; b < NBLOCKS; b++)
        if (!isfinite(V[b]))
            return gr_fail(err, GR_ERUN, "%s: observable %s is not finite at t = %g", gr_sim_type(s)->name,
                           c->quantity, t0 + (sc->run.until - t0) * (b + 1) / NBLOCKS);
    gr_block_average(V, NBLOCKS, 1, NULL, &out->value, &out->sem);
    out->aux = V[NBLOCKS - 1];
    out->steps = (double)o.steps;
    return GR_OK;
}

/* The method's default time step for the scene: the time one step of an
 * instance takes (a backend with an advance of its own gives no dt op).
 * NaN: it does not build or step. */
static double default_dt(const gr_method_type *m, const gr_scene *sc)
{
    gr_err e = {0};
    gr_particles *p = gr_particles_create(0, &e);
    gr_sim *s = NULL;
    double dt = NAN;
    if (p && !gr_init_particles(sc, p, &e) && !gr_sim_create(m, sc, p, &s, &e)) {
        double t0 = gr_sim_time(s);
        if (!gr_sim_advance(s, INFINITY, 1, &e) && gr_sim_time(s) > t0)
            dt = gr_sim_time(s) - t0;
    }
    gr_sim_free(s);
    gr_particles_free(p);
    return dt;
}

/* Whether m can run the scene and give the observable; notes why not. */
static int usable(const gr_method_type *m, const gr_scene *sc, const char *obs, cmp_own *own)
{
    gr_err e = {0};
    if (gr_method_require_features(m, gr_scene_features(sc), sc->path, &e))
        return 0; /* the plan notes it */
    if (find_obs(gr_method_observables(m), obs) < 0) {
        size_t n = strlen(own->notes);
        snprintf(own->notes + n, sizeof own->notes - n,
                 "# %s: %s: has no observable '%s' (grano methods %s lists its observables)\n", own->name, m->name,
                 obs, m->name);
        return 0;
    }
    return 1;
}

/* The reference method: the user's, else edmd for a scene with a
 * restitution, dem for one with a contact law, else the first usable. */
static int pick_reference(const cmp_own_opts *o, const gr_scene *sc, const int *use, const gr_method_type *const *ms,
                          int nm, gr_err *err)
{
    const char *want = o->reference ? o->reference : isfinite(sc->mat.restitution) ? "edmd" : "dem";
    for (int i = 0; i < nm; i++)
        if (use[i] && !strcmp(ms[i]->name, want))
            return i;
    if (o->reference)
        return gr_fail(err, GR_EINPUT, "--reference: method '%s' does not model %s (or is not in --methods)",
                       o->reference, sc->path), -1;
    for (int i = 0; i < nm; i++)
        if (use[i])
            return i;
    return gr_fail(err, GR_EINPUT, "--observable: no method (of --methods) models %s and gives '%s'", sc->path,
                   o->observable), -1;
}

/* The rows of method ms[i]: its knob from its default dt down to a
 * quarter; the reference method's finest setting is the reference row. */
static void add_rows(cmp_own *own, const gr_method_type *m, const gr_scene *sc, int is_ref, int *nr)
{
    const char *knob = knob_of(m->name);
    double dt = knob ? default_dt(m, sc) : NAN;
    char *coarse = own->values[*nr][0], *finest = own->values[*nr][1];
    if (knob && isfinite(dt))
        snprintf(coarse, 64, "%.3g,%.3g", dt, dt / 2), snprintf(finest, 64, "%.3g", dt / 4);
    else
        knob = NULL, coarse[0] = finest[0] = 0;
    cmp_row *r = &own->c[0].rows[(*nr)++];
    *r = (cmp_row){.method = m->name, .label = m->name, .knob = knob, .full = coarse, .quick = coarse,
                   .fixed = own->fixed[0] ? own->fixed : NULL, .role = CMP_SWEEP};
    if (knob && !is_ref) {
        snprintf(coarse + strlen(coarse), 64 - strlen(coarse), ",%s", finest);
        return;
    }
    if (!knob)
        r->role = is_ref ? CMP_REFERENCE : CMP_SWEEP;
    else {
        int k = (*nr)++;
        snprintf(own->labels[k], sizeof own->labels[0], "%s-finest", m->name);
        own->c[0].rows[k] = (cmp_row){.method = m->name, .label = own->labels[k], .knob = knob, .full = finest,
                                      .quick = finest, .fixed = r->fixed, .role = CMP_REFERENCE};
    }
}

int cmp_own_build(const cmp_own_opts *o, cmp_own *own, gr_err *err)
{
    memset(own, 0, sizeof *own);
    const char *names[GR_MAX_METHODS + 1];
    gr_method_names(names, GR_MAX_METHODS + 1);
    gr_scene *sc = gr_scene_load(o->scene, names, err);
    if (!sc)
        return err->code;
    char buf[2048], buf2[2048];
    snprintf(buf, sizeof buf, "%s", o->scene);
    snprintf(buf2, sizeof buf2, "%s", o->scene);
    snprintf(own->dir, sizeof own->dir, "%s", dirname(buf));
    snprintf(own->file, sizeof own->file, "%s", basename(buf2));
    snprintf(own->name, sizeof own->name, "%.*s", (int)strcspn(own->file, "."), own->file);
    snprintf(own->quantity, sizeof own->quantity, "%s",
             o->observable ? o->observable : sc->gravity > 0 ? "epot_grav" : "temperature");
    if (o->until > 0)
        snprintf(own->fixed, sizeof own->fixed, "run.until=%.17g", o->until);
    cmp_own_opts oo = *o;
    oo.observable = own->quantity;
    const gr_method_type *const *ms = gr_method_all();
    int nm = 0, use[GR_MAX_METHODS] = {0}, nr = 0;
    for (; ms[nm] && nm < GR_MAX_METHODS; nm++)
        use[nm] = cmp_listed(o->methods, ms[nm]->name) && usable(ms[nm], sc, own->quantity, own);
    int ref = pick_reference(&oo, sc, use, ms, nm, err);
    if (ref >= 0) {
        const gr_obs_def *defs = gr_method_observables(ms[ref]);
        snprintf(own->unit, sizeof own->unit, "%s", defs[find_obs(defs, own->quantity)].unit);
        own->c[0] = (cmp_case){.name = own->name, .scene = own->file, .quantity = own->quantity,
                               .aux = "its value at the end", .unit = own->unit, .aux_unit = own->unit,
                               .advisory = 1, .seeds_full = o->seeds > 0 ? o->seeds : 3, .seeds_quick = 1,
                               .tol = o->tolerance, .measure = cmp_measure_observable};
    }
    for (int i = 0; ref >= 0 && i < nm; i++)
        if (use[i] && nr + 2 < CMP_MAXROWS)
            add_rows(own, ms[i], sc, i == ref, &nr);
    gr_scene_free(sc);
    return ref < 0 ? err->code : GR_OK;
}
