/* The window-averaged stress of the DSMC backend (methods/method.h,
 * common/stress.h): the kinetic part sampled once a step, the collisional
 * part at the collisions (gr_dsmc_stress_pair and gr_dsmc_stress_wall in
 * dsmc_int.h). Calls no other file of the backend. */
#include "dsmc_int.h"

/* Each particle after the step's collisions, weighted by the step: the
 * time integral of its moments over the step (W grains of mass m). */
void gr_dsmc_stress_sample(gr_dsmc *d, double h)
{
    if (!d->stress)
        return;
    double mh = d->W * d->mass * h;
    for (size_t i = 0; i < d->n; i++) {
        if (d->rank[i] & GR_DSMC_GONE)
            continue;
        double vx = d->vx[i], vy = d->vy[i];
        const double mom[6] = {mh, mh * vx, mh * vy, mh * vx * vx, mh * vx * vy, mh * vy * vy};
        gr_stress_acc_kinetic(d->stress, d->x[i], d->y[i], mom);
    }
}

static int periodic_x(const gr_dsmc *d) { return d->sc.side[GR_LEFT] == GR_BC_PERIODIC; }
static int periodic_y(const gr_dsmc *d) { return d->sc.side[GR_BOTTOM] == GR_BC_PERIODIC; }

int gr_dsmc_stress(gr_dsmc *d, int nx, int ny, double global[4], double *cells, gr_err *err)
{
    gr_stress_acc *a = d->stress;
    if (!a || a->nx != nx || a->ny != ny) {
        gr_stress_acc_free(a);
        if (!(a = d->stress = gr_stress_acc_create(d->Lx, d->Ly, periodic_x(d), periodic_y(d), nx, ny, d->t, err)))
            return err->code;
    }
    gr_stress_acc_read(a, d->t, global, cells);
    return GR_OK;
}

int gr_dsmc_stress_save(const gr_dsmc *d, gr_ckpt *ck, gr_err *err)
{
    return d->stress ? gr_stress_acc_save(d->stress, ck, "dsmc_stress", err) : GR_OK;
}

int gr_dsmc_stress_load(gr_dsmc *d, gr_ckpt *ck, gr_err *err)
{
    return gr_stress_acc_load(&d->stress, ck, "dsmc_stress", d->Lx, d->Ly, periodic_x(d), periodic_y(d), err);
}
