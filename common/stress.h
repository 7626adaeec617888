/* The contact stress of a contact network (Love-Weber): the average over
 * an area of sum over contacts of branch (x) force,
 *   sigma_ab = (1/A) sum_c l_a F_b,
 * l from j's centre to i's (a pair) or from the wall's nearest point to i's
 * centre (a wall), F the force on i. Compression is positive. Kinetic
 * (streaming) stress is not included: quasi-static packings, where it is
 * negligible, are what the contact network describes. */
#ifndef GR_STRESS_H
#define GR_STRESS_H

#include "contacts.h"
#include "particles.h"
#include "scene.h"

/* sigma over the domain (global[4] = xx, xy, yx, yy, unit m tau-2 in 2-D)
 * and, when cells is not NULL, over each of nx x ny cells tiling the domain
 * (cells[(iy * nx + ix) * 4 + c]): each pair's term is shared between its
 * grains in proportion to their radii and goes to the cell of each centre.
 * p holds the grains by id (a snapshot); walls j = -1 - w are numbered as
 * the methods number them: the domain sides that are walls (left, right,
 * bottom, top), then the scene's segments. t picks the floor's position. */
int gr_stress_contacts(const gr_scene *sc, const gr_particles *p, const gr_contacts *c, double t, int nx,
                       int ny, double global[4], double *cells, gr_err *err);

#endif
