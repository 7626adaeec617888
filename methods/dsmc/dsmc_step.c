/* One step: free flight of every particle over dt, then the collisions of
 * the new positions (Bird's splitting, first order in dt). */
#include <math.h>

#include "dsmc_int.h"

int gr_dsmc_step(gr_dsmc *d, gr_err *err)
{
    double h = d->par.dt;
    gr_dsmc_stream_all(d, d->t, h);
    if (gr_dsmc_collide(d, err))
        return err->code;
    gr_dsmc_stress_sample(d, h);
    d->step++;
    d->t = d->par.dt * (double)d->step;
    if (d->step % GR_DSMC_DENSE_EVERY == 0)
        gr_dsmc_dense_check(d);
    d->wall_time += h;
    return GR_OK;
}

/* Whole steps until t_end is reached (to a millionth of a step, so that
 * rounding of step * dt never adds one). */
int gr_dsmc_advance(gr_dsmc *d, double t_end, uint64_t max_steps, gr_err *err)
{
    for (uint64_t k = 0; (max_steps == 0 || k < max_steps) && d->t < t_end - 1e-6 * d->par.dt; k++)
        if (gr_dsmc_step(d, err))
            return err->code;
    return GR_OK;
}
