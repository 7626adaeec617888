/* Observables every method can produce, so that methods compare on the same
 * scene. Quantities a method cannot produce are NaN and named in docs. */
#ifndef GR_OBSERVE_H
#define GR_OBSERVE_H

#include <stdint.h>

#include "particles.h"

typedef struct {
    double t;
    uint64_t steps;         /* time steps, or events for event-driven methods */
    uint64_t n_mobile;
    double ekin_trans, ekin_rot; /* totals over mobile grains */
    double epot_grav;            /* m g y summed over mobile grains */
    double temperature;     /* granular temperature: <m |v - <v>|^2> / 2 per grain */
    double px, py;          /* total momentum of mobile grains */
    uint64_t outflow;       /* grains that left through the orifice since t = 0 */
    double wall_pressure;   /* method-defined average since the last window reset; NaN if none */
    double max_overlap;     /* soft methods, in diameters; NaN otherwise */
} gr_obs;

/* Fill the kinematic observables from a particle snapshot; leaves t, steps,
 * outflow, wall_pressure, max_overlap untouched. */
void gr_obs_from_particles(const gr_particles *p, double gravity, gr_obs *o);
void gr_obs_clear(gr_obs *o);

#endif
