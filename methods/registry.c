/* The registry: one line per backend. */
#include "method.h"

#include <stdio.h>
#include <string.h>

extern const gr_method_type gr_edmd_method;
extern const gr_method_type gr_dem_method;
extern const gr_method_type gr_cd_method;
extern const gr_method_type gr_dsmc_method;
extern const gr_method_type gr_lgca_method;
static const gr_method_type *const registry[] = {
    &gr_edmd_method,
    &gr_dem_method,
    &gr_cd_method,
    &gr_dsmc_method,
    &gr_lgca_method,
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

int gr_method_lookup(const char *name, const char *who, const gr_method_type **out, gr_err *err)
{
    if ((*out = gr_method_find(name)))
        return GR_OK;
    const char *names[GR_MAX_METHODS + 1];
    gr_method_names(names, GR_MAX_METHODS + 1);
    char list[256] = "";
    size_t o = 0;
    for (size_t i = 0; names[i] && o + 2 < sizeof list; i++)
        o += (size_t)snprintf(list + o, sizeof list - o, "%s%s", i ? ", " : "", names[i]);
    const char *near = gr_nearest(name, names);
    if (near && strcmp(near, name))
        return gr_fail(err, GR_EINPUT, "%s: unknown method '%s'; did you mean '%s'? (methods: %s)",
                       who, name, near, list);
    return gr_fail(err, GR_EINPUT, "%s: unknown method '%s' (methods: %s)", who, name, list);
}
