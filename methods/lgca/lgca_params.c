/* The [lgca] section: the parameter table and its values. */
#include <math.h>

#include "lgca_int.h"

static const char *const rule_names[] = {"fhp3", "granular", NULL};
static const char *const gravity_names[] = {"rest", "movers", "alternate", NULL};

const gr_param lgca_param_table[] = {
    {"dt", GR_PARAM_REAL, 0.1, 0, INFINITY, 1, NULL, "tau",
     "time per step: a moving particle goes one lattice spacing (one grain diameter) per step"},
    {"rules", GR_PARAM_CHOICE, LGCA_RULES_GRANULAR, 0, 0, 0, rule_names, "",
     "fhp3: FHP-III, mass and momentum conserving; granular: Peng-Herrmann, dissipative with probability p"},
    {"p", GR_PARAM_REAL, 0, 0, 1, 0, NULL, "1",
     "dissipation: probability that a collision able to make a rest particle does (granular rules)"},
    {"g", GR_PARAM_REAL, NAN, 0, 1, 0, NULL, "1",
     "gravity: probability per node and step of one unit of downward momentum; default gravity dt^2 / d"},
    {"gravity_order", GR_PARAM_CHOICE, LGCA_GRAV_REST, 0, 0, 0, gravity_names, "",
     "which particle gravity turns first: rest (the rest particle, then up-right, then up-left), movers (up-right, "
     "up-left, then the rest particle), alternate (the rest particle, then the side the step's parity says)"},
    {"b", GR_PARAM_REAL, 0, 0, 1, 0, NULL, "1",
     "wall roughness: probability that a wall bounces a particle back instead of reflecting it"},
    {"stop", GR_PARAM_REAL, 0, 0, 1, 0, NULL, "1",
     "rest collision: probability that a head-on pair meeting a rest particle comes to rest, two rest particles "
     "hopping to neighbours (granular rules)"},
    {"threads", GR_PARAM_INT, 1, 1, 256, 0, NULL, "1", "threads (results do not depend on it)"},
    {NULL, 0, 0, 0, 0, 0, NULL, NULL, NULL},
};

void lgca_params_from(const gr_param_values *pv, lgca_params *p)
{
    p->dt = gr_param_get(pv, "dt");
    p->rules = (int)gr_param_get(pv, "rules");
    p->p = gr_param_get(pv, "p");
    p->g = gr_param_get(pv, "g");
    p->gravity = (int)gr_param_get(pv, "gravity_order");
    p->b = gr_param_get(pv, "b");
    p->stop = gr_param_get(pv, "stop");
    p->threads = (int)gr_param_get(pv, "threads");
}
