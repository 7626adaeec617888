/* A state of the edmd backend on one of grano compare's scenes
 * (experiments/scenes/compare/NAME) with --set style settings: the edmd
 * tests that replay a case's failure. */
#ifndef EDMD_COMPARE_H
#define EDMD_COMPARE_H

#include <stdio.h>
#include <stdlib.h>

#include "edmd.h"
#include "init.h"
#include "method.h"

/* Fills *sc, *p and *s (free them with gr_edmd_free, gr_particles_free,
 * gr_scene_free); returns GR_OK or an error with e set. */
static inline int edmd_compare_state(const char *name, const char **sets, int nset, gr_scene **sc,
                                     gr_particles **p, gr_edmd **s, gr_err *e)
{
    const char *root = getenv("GRANO_SOURCE_ROOT");
    if (!root)
        return gr_fail(e, GR_EINPUT, "GRANO_SOURCE_ROOT is not set");
    char path[1024];
    snprintf(path, sizeof path, "%s/experiments/scenes/compare/%s", root, name);
    const char *names[GR_MAX_METHODS + 1];
    gr_method_names(names, GR_MAX_METHODS + 1);
    gr_edmd_params prm;
    *sc = NULL;
    *p = NULL;
    *s = NULL;
    if (!(*sc = gr_scene_load_set(path, names, sets, nset, e)) || !(*p = gr_particles_create(0, e)) ||
        gr_init_particles(*sc, *p, e) || gr_edmd_params_read(*sc, &prm, e) || gr_edmd_create(*sc, *p, &prm, NULL, s, e))
        return e->code ? e->code : GR_ERUN;
    return GR_OK;
}

#endif
