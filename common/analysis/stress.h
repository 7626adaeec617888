/* The contact stress of a contact network (Love-Weber): the average over
 * an area of sum over contacts of branch (x) force,
 *   sigma_ab = (1/A) sum_c l_a F_b,
 * l from j's centre to i's (a pair) or from the wall's nearest point to i's
 * centre (a wall), F the force on i. Compression is positive. Kinetic
 * (streaming) stress is not included: quasi-static packings, where it is
 * negligible, are what the contact network describes. */
#ifndef GR_STRESS_H
#define GR_STRESS_H

#include "ckpt.h"
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

/* The stress of instantaneous collisions (hard disks, DSMC), which leave
 * no contact network: a time average over a window [t0, t],
 *   sigma_ab = (1 / (A T)) [ int sum_i m (v - u)_a (v - u)_b dt
 *                            + sum_collisions l_a J_b ],
 * kinetic plus collisional, on nx x ny cells tiling [0, W] x [0, H] (1 x 1:
 * the domain). u is each cell's mass-weighted mean velocity over the
 * window, so a mean flow's momentum flux rho u u is not counted as stress;
 * J is the impulse on grain i, l the branch vector as in
 * gr_stress_contacts; compression is positive. A position outside the
 * domain is wrapped across a periodic side and otherwise counted in the
 * nearest cell, so the cells' mean is the domain's value. */
typedef struct {
    int nx, ny;
    double W, H;
    int px, py;    /* periodic in x, y */
    double t0;     /* the window's start */
    double *sum;   /* per cell GR_STRESS_ACC_N sums (stress.c) */
} gr_stress_acc;
#define GR_STRESS_ACC_N 10

gr_stress_acc *gr_stress_acc_create(double W, double H, int periodic_x, int periodic_y, int nx, int ny,
                                    double t0, gr_err *err);
void gr_stress_acc_free(gr_stress_acc *a);
/* A grain's time integrals over a flight, in the cell of (x, y):
 * mom = {int m dt, int m vx dt, int m vy dt, int m vx vx dt, int m vx vy dt,
 * int m vy vy dt}. */
void gr_stress_acc_kinetic(gr_stress_acc *a, double x, double y, const double mom[6]);
/* A collision's l (x) J: the fraction share in the cell of (xi, yi), the
 * rest in that of (xj, yj) (a wall: share 1). */
void gr_stress_acc_collision(gr_stress_acc *a, double xi, double yi, double xj, double yj, double share,
                             double lx, double ly, double Jx, double Jy);
/* The averages over [t0, t] into global[4] (xx, xy, yx, yy: l_x J_y is
 * xy) and, when cells is not NULL, cells[(iy * nx + ix) * 4 + c]; NaN for
 * an empty window. Then a new window starts at t. */
void gr_stress_acc_read(gr_stress_acc *a, double t, double global[4], double *cells);
/* A checkpoint holds the window under `name`; a load of a checkpoint
 * without it gives NULL and no error (the window then starts anew). */
int gr_stress_acc_save(const gr_stress_acc *a, gr_ckpt *ck, const char *name, gr_err *err);
int gr_stress_acc_load(gr_stress_acc **a, gr_ckpt *ck, const char *name, double W, double H, int periodic_x,
                       int periodic_y, gr_err *err);

#endif
