/* The [edmd] section: defaults and reading. */
#include <math.h>
#include <stdio.h>

#include "edmd.h"
#include "edmd_params.h"

static const char *const algo_names[] = {"tree", "naive", NULL};
static const char *const collapse_names[] = {"none", "tc", "threshold", "sleep", NULL};
static const char *const yesno[] = {"no", "yes", NULL};
static const char *const queue_names[] = {"tree", "calendar", NULL};

void gr_edmd_params_default(gr_edmd_params *p)
{
    p->algorithm = GR_EDMD_TREE;
    p->cell = 0.0;
    p->collapse = GR_EDMD_COLLAPSE_SLEEP;
    p->tc = 1e-5;
    p->v_threshold = 1e-4;
    p->v_sleep = 1e-2;
    p->v_wake = 0.3;
    p->fields = 0;
    p->sort_every = -1.0;
    p->tree_arity = 2;
    p->calendar = 1;
}

const gr_param gr_edmd_param_table[] = {
    {"algorithm", GR_PARAM_CHOICE, GR_EDMD_TREE, 0, 0, 0, algo_names, "",
     "tree: O(log N) per event; naive: the slides' v1.0, O(N^2)"},
    {"cell", GR_PARAM_REAL, 0.0, 0, INFINITY, 0, NULL, "d", "minimum cell side; 0: the largest diameter"},
    {"collapse", GR_PARAM_CHOICE, GR_EDMD_COLLAPSE_SLEEP, 0, 0, 0, collapse_names, "",
     "guard against inelastic collapse; sleep: and held grains come to rest (tc under algorithm = naive)"},
    {"tc", GR_PARAM_REAL, 1e-5, 0, INFINITY, 0, NULL, "tau",
     "TC model: elastic if a partner collided less than tc ago"},
    {"v_threshold", GR_PARAM_REAL, 1e-4, 0, INFINITY, 0, NULL, "d tau-1",
     "threshold model: elastic below this normal speed"},
    {"v_sleep", GR_PARAM_REAL, 1e-2, 0, INFINITY, 0, NULL, "d tau-1",
     "sleep model: a grain leaving a supported static contact slower than this sleeps"},
    {"v_wake", GR_PARAM_REAL, 0.3, 0, INFINITY, 0, NULL, "d tau-1",
     "sleep model: an impact faster than this wakes a sleeping grain"},
    {"fields", GR_PARAM_CHOICE, 0, 0, 0, 0, yesno, "", "accumulate hydrodynamic fields on the cells"},
    {"sort_every", GR_PARAM_REAL, -1.0, -INFINITY, INFINITY, 0, NULL, "1",
     "collisions per grain between spatial re-sorts; 0 never, < 0 automatic"},
    {"tree_arity", GR_PARAM_INT, 2, 2, 4, 0, NULL, "1",
     "2: the slides' binary tree; 4: every other level elided"},
    {"queue", GR_PARAM_CHOICE, 1, 0, 0, 0, queue_names, "",
     "calendar: Paul's calendar queue; tree: the binary tree (same events)"},
    {NULL, 0, 0, 0, 0, 0, NULL, NULL, NULL},
};

int gr_edmd_params_from(const gr_scene *sc, const gr_param_values *pv, gr_edmd_params *p,
                        gr_err *err)
{
    gr_edmd_params_default(p);
    p->algorithm = (gr_edmd_algorithm)gr_param_get(pv, "algorithm");
    p->cell = gr_param_get(pv, "cell");
    p->collapse = (gr_edmd_collapse)gr_param_get(pv, "collapse");
    p->tc = gr_param_get(pv, "tc");
    p->v_threshold = gr_param_get(pv, "v_threshold");
    p->v_sleep = gr_param_get(pv, "v_sleep");
    p->v_wake = gr_param_get(pv, "v_wake");
    p->fields = (int)gr_param_get(pv, "fields");
    p->sort_every = gr_param_get(pv, "sort_every");
    p->tree_arity = (int)gr_param_get(pv, "tree_arity");
    p->calendar = (int)gr_param_get(pv, "queue");
    /* the naive loop's pair times know no sleepers: its default is tc */
    if (p->collapse == GR_EDMD_COLLAPSE_SLEEP && p->algorithm == GR_EDMD_NAIVE && !gr_scene_find(sc, "edmd", "collapse"))
        p->collapse = GR_EDMD_COLLAPSE_TC;
    if (p->collapse == GR_EDMD_COLLAPSE_SLEEP && p->algorithm == GR_EDMD_NAIVE) {
        char where[1200];
        gr_scene_where(sc, "edmd", "collapse", where, sizeof where);
        return gr_fail(err, GR_EINPUT, "%s: sleep needs algorithm = tree (the naive loop's pair times know no "
                                           "sleeping grains)", where);
    }
    if (p->tree_arity == 3) {
        char where[1200];
        gr_scene_where(sc, "edmd", "tree_arity", where, sizeof where);
        return gr_fail(err, GR_EINPUT, "%s: [edmd] key 'tree_arity' must be 2 or 4, got 3", where);
    }
    return GR_OK;
}

int gr_edmd_params_read(const gr_scene *sc, gr_edmd_params *p, gr_err *err)
{
    gr_param_values pv;
    if (gr_params_read(sc, "edmd", gr_edmd_param_table, &pv, err))
        return err->code;
    return gr_edmd_params_from(sc, &pv, p, err);
}
