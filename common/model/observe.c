#include "observe.h"

#include <math.h>
#include <string.h>

const gr_obs_def gr_obs_particle_set[] = {
    GR_OBS_N_MOBILE,      GR_OBS_EKIN_TRANS, GR_OBS_EKIN_ROT,      GR_OBS_EPOT_GRAV,
    GR_OBS_TEMPERATURE,   GR_OBS_MOMENTUM,   GR_OBS_OUTFLOW,       GR_OBS_WALL_PRESSURE,
    GR_OBS_MAX_OVERLAP,   GR_OBS_DEF_END,
};

size_t gr_obs_count(const gr_obs_def *defs)
{
    size_t n = 0;
    while (defs && defs[n].name)
        n++;
    return n;
}

const void *gr_obs_value(const gr_obs *o, const gr_obs_def *defs, size_t k)
{
    const gr_obs_def *d = &defs[k];
    switch (d->src) {
    case GR_OBS_COUNTER:
        return &o->count[k];
    case GR_OBS_EXTRA:
        return o->extra[k];
    default:
        return (const char *)o + d->off;
    }
}

void gr_obs_clear(gr_obs *o)
{
    memset(o, 0, sizeof *o);
    o->wall_pressure = NAN;
    o->max_overlap = NAN;
}

void gr_obs_from_particles(const gr_particles *p, double gravity, gr_obs *o)
{
    double m = 0, px = 0, py = 0, et = 0, er = 0, eg = 0;
    uint64_t n = 0;
    for (size_t i = 0; i < p->n; i++) {
        if (p->flags[i] & (GR_PF_FIXED | GR_PF_GONE))
            continue;
        double mi = p->mass[i];
        n++;
        m += mi;
        px += mi * p->vx[i];
        py += mi * p->vy[i];
        et += 0.5 * mi * (p->vx[i] * p->vx[i] + p->vy[i] * p->vy[i]);
        er += 0.5 * p->inertia[i] * p->omega[i] * p->omega[i];
        eg += mi * gravity * p->y[i];
    }
    o->n_mobile = n;
    o->ekin_trans = et;
    o->ekin_rot = er;
    o->epot_grav = eg;
    o->px = px;
    o->py = py;
    /* Granular temperature in 2D: kinetic energy of the fluctuations
     * about the mean velocity, per grain (k_B = 1, two degrees of freedom). */
    o->temperature = n ? (et - 0.5 * (px * px + py * py) / m) / (double)n : 0.0;
}
