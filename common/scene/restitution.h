/* One dissipation for every method: the restitution a hard method takes
 * when the scene states the soft law's damping (kn, gamma_n) instead of
 * [material] restitution, the inverse of the soft DEM's derivation of
 * gamma_n from a restitution (methods/dem/dem_damping.c). */
#ifndef GR_RESTITUTION_H
#define GR_RESTITUTION_H

#include "particles.h"
#include "scene.h"

/* Restitution of one linear spring-dashpot contact (force kn xi - gamma
 * dxi/dt on the reduced mass meff); clip: no attractive force, so the
 * contact ends where the force vanishes (Schwager and Poeschel 2007). */
double gr_linear_restitution(double kn, double gamma, double meff, int clip);

/* Mean mass of the mobile grains (1 when there are none): the reference
 * pair is two of them (m_eff = m / 2), the reference wall contact one. */
double gr_mean_mobile_mass(const gr_particles *init);

typedef struct {
    double e, e_wall; /* NaN: the scene states none and derives none */
    int derived;      /* bit 0: e derived, bit 1: e_wall derived */
    char note[512];   /* what was derived and from what, for the run's log */
} gr_restitution;

/* The pairs' and walls' restitution of a hard method: [material]
 * restitution and wall_restitution where given; where not, and the file
 * gives gamma_n, the restitution the soft DEM's linear law gives the mean
 * pair (and one mean grain on a wall). Hertz with gamma_n has a
 * speed-dependent restitution: refused, naming the key to add. */
int gr_scene_restitution(const gr_scene *sc, const gr_particles *init, gr_restitution *r, gr_err *err);

#endif
