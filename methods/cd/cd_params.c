/* The [cd] section: the parameter table and its values. */
#include <math.h>

#include "cd_int.h"

static const char *const orders[] = {"sequential", "shuffled", "random", "symmetric", "height", NULL};
static const char *const accels[] = {"none", "momentum", NULL};
static const char *const no_yes[] = {"no", "yes", NULL};
static const char *const yes_no[] = {"yes", "no", NULL};

const gr_param gr_cd_param_table[] = {
    {"dt", GR_PARAM_REAL, 1e-3, 0, INFINITY, 1, NULL, "tau", "time step"},
    {"theta", GR_PARAM_REAL, 0.5, 0.5, 1.0, 0, NULL, "1",
     "theta of the Moreau-Jean scheme (0.5: exact for constant accelerations)"},
    {"tol", GR_PARAM_REAL, 1e-6, 0, 1, 1, NULL, "1",
     "convergence: quadratic mean of the change of local velocities over a sweep / that of W r"},
    {"max_iter", GR_PARAM_INT, 2000, 1, 1e9, 0, NULL, "sweeps", "Gauss-Seidel sweeps per step at most"},
    {"check_every", GR_PARAM_INT, 1, 1, 1e6, 0, NULL, "sweeps", "test convergence every this many sweeps"},
    {"order", GR_PARAM_CHOICE, GR_CD_SEQUENTIAL, 0, 0, 0, orders, "",
     "contact order per sweep: detection order, a new permutation, draws with replacement, detection order "
     "forward and backward in turn, or by height of the contact point down and up in turn"},
    {"relax", GR_PARAM_REAL, 1.0, 0, 1.99, 1, NULL, "1",
     "over-relaxation: each local update moves the impulse by relax times the change to the local solution"},
    {"accel", GR_PARAM_CHOICE, 0, 0, 0, 0, accels, "",
     "acceleration of the sweeps: none, or Nesterov's momentum on the impulses with restart"},
    {"gap", GR_PARAM_REAL, 0.1, 0, INFINITY, 0, NULL, "d",
     "detection margin (largest diameter units); at least twice the largest free displacement"},
    {"strict", GR_PARAM_CHOICE, 0, 0, 0, 0, no_yes, "", "non-convergence at max_iter stops the run"},
    {"warm_start", GR_PARAM_CHOICE, 0, 0, 0, 0, yes_no, "",
     "start each step from the previous step's impulses, matched by contact identity"},
    {NULL, 0, 0, 0, 0, 0, NULL, NULL, NULL},
};

void gr_cd_params_from(const gr_param_values *pv, gr_cd_params *p)
{
    p->dt = gr_param_get(pv, "dt");
    p->theta = gr_param_get(pv, "theta");
    p->tol = gr_param_get(pv, "tol");
    p->max_iter = (long)gr_param_get(pv, "max_iter");
    p->check_every = (long)gr_param_get(pv, "check_every");
    p->order = (int)gr_param_get(pv, "order");
    p->gap = gr_param_get(pv, "gap");
    p->relax = gr_param_get(pv, "relax");
    p->accel = (int)gr_param_get(pv, "accel");
    p->strict = (int)gr_param_get(pv, "strict") == 1;
    p->warm = (int)gr_param_get(pv, "warm_start") == 0;
}
