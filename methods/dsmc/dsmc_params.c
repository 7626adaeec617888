/* The [dsmc] section: the parameter table and its values. */
#include <math.h>

#include "dsmc_int.h"

static const char *const no_yes[] = {"no", "yes", NULL};

const gr_param gr_dsmc_param_table[] = {
    {"dt", GR_PARAM_REAL, 0.01, 0, INFINITY, 1, NULL, "tau", "time step (at most half the mean free time)"},
    {"cell", GR_PARAM_REAL, 0, 0, INFINITY, 0, NULL, "d",
     "collision cell side in diameters; 0: the largest within the mean free path that the other limits allow"},
    {"ppc_min", GR_PARAM_REAL, 2, 0, INFINITY, 0, NULL, "1", "fewest mean particles per cell accepted as valid"},
    {"enskog", GR_PARAM_CHOICE, 1, 0, 0, 0, no_yes, "",
     "Enskog mode: the rate times Henderson's chi(eta) and the partners displaced (collisional transfer)"},
    {"gas_eta_max", GR_PARAM_REAL, 0.5, 0, 0.9, 1, NULL, "1",
     "packing fraction of a region of about 32 grains above which the run says it is no longer a gas"},
    {"threads", GR_PARAM_INT, 1, 1, 256, 0, NULL, "1", "threads (results do not depend on it)"},
    {"strict", GR_PARAM_CHOICE, 0, 0, 0, 0, no_yes, "",
     "a validity limit broken at create is an input error instead of a counted warning"},
    {NULL, 0, 0, 0, 0, 0, NULL, NULL, NULL},
};

void gr_dsmc_params_from(const gr_param_values *pv, gr_dsmc_params *p)
{
    p->dt = gr_param_get(pv, "dt");
    p->cell = gr_param_get(pv, "cell");
    p->ppc_min = gr_param_get(pv, "ppc_min");
    p->enskog = (int)gr_param_get(pv, "enskog") == 1;
    p->strict = (int)gr_param_get(pv, "strict") == 1;
    p->threads = (int)gr_param_get(pv, "threads");
    p->gas_eta_max = gr_param_get(pv, "gas_eta_max");
}
