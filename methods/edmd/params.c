/* The [edmd] section: defaults and reading. */
#include <stdio.h>

#include "edmd.h"

static const char *const algo_names[] = {"tree", "naive", NULL};
static const char *const collapse_names[] = {"none", "tc", "threshold", NULL};
static const char *const yesno[] = {"no", "yes", NULL};
static const char *const queue_names[] = {"tree", "calendar", NULL};

void gr_edmd_params_default(gr_edmd_params *p)
{
    p->algorithm = GR_EDMD_TREE;
    p->cell = 0.0;
    p->collapse = GR_EDMD_COLLAPSE_NONE;
    p->tc = 1e-5;
    p->v_threshold = 1e-4;
    p->fields = 0;
    p->sort_every = -1.0;
    p->tree_arity = 2;
    p->calendar = 1;
}

int gr_edmd_params_read(const gr_scene *sc, gr_edmd_params *p, gr_err *err)
{
    gr_edmd_params_default(p);
    int v;
    if (gr_scene_get_choice(sc, "edmd", "algorithm", algo_names, 0, &v, err))
        return err->code;
    p->algorithm = (gr_edmd_algorithm)v;
    if (gr_scene_get_choice(sc, "edmd", "collapse", collapse_names, 0, &v, err))
        return err->code;
    p->collapse = (gr_edmd_collapse)v;
    if (gr_scene_get_choice(sc, "edmd", "fields", yesno, 0, &p->fields, err))
        return err->code;
    if (gr_scene_get_choice(sc, "edmd", "queue", queue_names, p->calendar, &p->calendar, err))
        return err->code;
    long arity = 2;
    if (gr_scene_get_long(sc, "edmd", "tree_arity", 2, &arity, err))
        return err->code;
    if (arity != 2 && arity != 4) {
        char where[1200];
        gr_scene_where(sc, "edmd", "tree_arity", where, sizeof where);
        return gr_fail(err, GR_EINPUT, "%s: [edmd] key 'tree_arity' must be 2 or 4, got %ld", where, arity);
    }
    p->tree_arity = (int)arity;
    if (gr_scene_get_double(sc, "edmd", "cell", 0.0, &p->cell, err) ||
        gr_scene_get_double(sc, "edmd", "tc", p->tc, &p->tc, err) ||
        gr_scene_get_double(sc, "edmd", "v_threshold", p->v_threshold, &p->v_threshold, err) ||
        gr_scene_get_double(sc, "edmd", "sort_every", p->sort_every, &p->sort_every, err))
        return err->code;
    const char *bad = !(p->cell >= 0) ? "cell" : !(p->tc >= 0) ? "tc" : !(p->v_threshold >= 0) ? "v_threshold" : NULL;
    if (bad) {
        char where[1200];
        gr_scene_where(sc, "edmd", bad, where, sizeof where);
        return gr_fail(err, GR_EINPUT, "%s: [edmd] key '%s' must be >= 0", where, bad);
    }
    return GR_OK;
}
