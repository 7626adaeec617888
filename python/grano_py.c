/* The flat interface's scenes, registry and particles (grano_py.h). */
#include "grano_py.h"

#include <gsl/gsl_errno.h>

#include "h5md.h"

void gp_init(void)
{
    gsl_set_error_handler_off();
    gr_h5_no_exit_handler();
}

const char *gp_version(void) { return GRANO_VERSION; }

/* ---- scenes ---- */

gr_scene *gp_scene_load(const char *path, const char *const *sets, size_t n, gr_err *err)
{
    const char *names[GR_MAX_METHODS + 1];
    gr_method_names(names, GR_MAX_METHODS + 1);
    return gr_scene_load_set(path, names, sets, n, err);
}

gr_scene *gp_scene_parse(const char *text, const char *path, gr_err *err)
{
    const char *names[GR_MAX_METHODS + 1];
    gr_method_names(names, GR_MAX_METHODS + 1);
    return gr_scene_parse(text, path, names, err);
}

void gp_scene_free(gr_scene *sc) { gr_scene_free(sc); }
const char *gp_scene_text(const gr_scene *sc) { return sc->text; }
const char *gp_scene_path(const gr_scene *sc) { return sc->path; }
const char *gp_scene_name(const gr_scene *sc) { return sc->name; }
uint64_t gp_scene_seed(const gr_scene *sc) { return sc->seed; }
void gp_scene_set_seed(gr_scene *sc, uint64_t seed) { sc->seed = seed; }

void gp_scene_numbers(const gr_scene *sc, double out[6])
{
    const gr_runctl *r = &sc->run;
    out[0] = r->until, out[1] = r->output_every, out[2] = r->observe_every;
    out[3] = r->checkpoint_every, out[4] = sc->width, out[5] = sc->height;
}

void gp_scene_field_cells(const gr_scene *sc, int *nx, int *ny)
{
    *nx = sc->run.field_nx, *ny = sc->run.field_ny;
}

const char *gp_scene_value(const gr_scene *sc, const char *section, const char *key)
{
    const gr_scene_entry *e = gr_scene_find(sc, section, key);
    return e ? e->value : NULL;
}

/* ---- the registry ---- */

static const gr_method_type *method_at(int i) { return gr_method_all()[i]; }

int gp_method_count(void)
{
    int n = 0;
    while (gr_method_all()[n])
        n++;
    return n;
}

const char *gp_method_name(int i) { return method_at(i)->name; }
const char *gp_method_summary(int i) { return method_at(i)->summary; }
int gp_method_repr(int i) { return (int)method_at(i)->repr; }
unsigned gp_method_features(int i) { return method_at(i)->features; }
unsigned gp_method_ops(int i) { return gr_method_ops(method_at(i)); }
int gp_feature_count(void) { return GR_FEAT_COUNT; }
int gp_op_count(void) { return GR_OP_COUNT; }
const char *gp_feature_name(unsigned bit) { return gr_feature_name(bit); }
int gp_feature_known(unsigned bit) { return gr_feature_known(bit); }
const char *gp_op_name(unsigned bit) { return gr_op_name(bit); }
int gp_param_count(int i) { return gr_params_count(method_at(i)->params); }

const char *gp_param(int i, int k, int *type, double v[4], const char **unit, const char **doc)
{
    const gr_param *p = &method_at(i)->params[k];
    *type = (int)p->type;
    v[0] = p->def, v[1] = p->min, v[2] = p->max, v[3] = p->min_open;
    *unit = p->unit, *doc = p->doc;
    return p->name;
}

const char *gp_param_choice(int i, int k, int c)
{
    const gr_param *p = &method_at(i)->params[k];
    for (int j = 0; p->choices && p->choices[j]; j++)
        if (j == c)
            return p->choices[j];
    return NULL;
}

int gp_obs_count(int i) { return (int)gr_obs_count(gr_method_observables(method_at(i))); }

const char *gp_obs(int i, int k, const char **unit, int *ncomp, int *integer, const char **doc,
                   const char **key)
{
    const gr_obs_def *d = &gr_method_observables(method_at(i))[k];
    *unit = d->unit, *ncomp = d->ncomp, *integer = d->integer, *doc = d->doc, *key = d->key;
    return d->name;
}

/* ---- particles ---- */

size_t gp_particles_n(const gr_particles *p) { return p->n; }

void *gp_particles_data(const gr_particles *p, int which)
{
    void *const all[] = {p->x,    p->y,       p->vx,    p->vy, p->omega, p->radius,
                         p->mass, p->inertia, p->flags, p->id, p->species};
    return which >= 0 && which < (int)(sizeof all / sizeof all[0]) ? all[which] : NULL;
}

void gp_particles_free(gr_particles *p) { gr_particles_free(p); }
