#include "method.h"

#include <stdio.h>
#include <string.h>

/* One line per backend. */
extern const gr_method_type gr_edmd_method;
extern const gr_method_type gr_dem_method;
static const gr_method_type *const registry[] = {
    &gr_edmd_method,
    &gr_dem_method,
    NULL
};

const gr_method_type *const *gr_method_all(void) { return registry; }

void gr_method_names(const char **names, size_t cap)
{
    size_t k = 0;
    for (size_t i = 0; registry[i] && k + 1 < cap; i++)
        names[k++] = registry[i]->name;
    if (cap)
        names[k] = NULL;
}

const gr_method_type *gr_method_find(const char *name)
{
    for (size_t i = 0; registry[i]; i++)
        if (strcmp(registry[i]->name, name) == 0)
            return registry[i];
    return NULL;
}

int gr_method_create(const gr_method_type *m, const gr_scene *sc,
                     const gr_particles *init, void **state, gr_err *err)
{
    *state = NULL;
    unsigned missing = gr_scene_features(sc) & ~m->features;
    if (missing) {
        for (unsigned b = 0; b < GR_FEAT_COUNT; b++) {
            if (missing & (1u << b)) {
                char where[1200];
                gr_scene_feature_where(sc, 1u << b, where, sizeof where);
                return gr_fail(err, GR_EINPUT,
                               "%s: method '%s' does not support %s",
                               where, m->name, gr_feature_name(1u << b));
            }
        }
    }
    if (gr_scene_check_keys(sc, m->name, m->param_keys, err))
        return err->code;
    return m->create(sc, init, state, err);
}
