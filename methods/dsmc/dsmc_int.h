/* DSMC backend (Bird's no-time-counter scheme, inelastic smooth disks):
 * internal interface shared by the backend's files and its tests. */
#ifndef GR_DSMC_INT_H
#define GR_DSMC_INT_H

#include <stddef.h>
#include <stdint.h>

#include "ckpt.h"
#include "err.h"
#include "observe.h"
#include "params.h"
#include "particles.h"
#include "rng.h"
#include "scene.h"
#include "stress.h"

/* The [dsmc] section (docs/methods/dsmc.md). */
typedef struct {
    double dt, cell, ppc_min;
    int enskog, strict;
} gr_dsmc_params;

/* Which validity limits the scene breaks at create (bits). */
enum {
    GR_DSMC_BAD_DT = 1,
    GR_DSMC_BAD_CELL = 2,
    GR_DSMC_BAD_PPC = 4,
    GR_DSMC_BAD_ENSKOG_CELL = 8,
    GR_DSMC_BAD_RECOLLIDE = 16 /* cell side < GR_DSMC_SIDE_PER_W W sigma */
};

/* The smallest cell side, in W sigma, for which the collisions of partners
 * whose velocities are still correlated (they share the cell) slow the
 * cooling by no more than about 1 % (docs/methods/dsmc.md, validity). */
#define GR_DSMC_SIDE_PER_W 30.0
#define GR_DSMC_NLIMITS 5

/* A particle's rank (the order of its id) with this bit set has left the
 * domain through an open side. */
#define GR_DSMC_GONE 0x80000000u
#define GR_DSMC_RANK 0x7fffffffu

/* Particles are kept sorted by cell (the counting sort of each step moves
 * them), so that a cell's particles are contiguous in memory: the arrays
 * below are in that order, rank[k] names the grain. About 60 bytes per
 * particle (docs/methods/dsmc.md, Speed). */
typedef struct gr_dsmc {
    gr_scene sc;           /* shallow copy: pointers stay the caller's */
    gr_dsmc_params par;
    double alpha, alpha_w; /* grain-grain and wall normal restitution */
    double g, W;           /* gravity; real grains per simulated particle */
    double sigma, mass;    /* the one diameter and mass (monodisperse) */
    double Lx, Ly;         /* domain */
    int nx, ny;            /* cells */
    double cw, ch;         /* cell sides */
    int walls_any;         /* a side is a wall (else streaming is x += v h) */
    size_t n;              /* particles */
    double *x, *y, *vx, *vy, *tmp; /* tmp: the sort's gather buffer */
    uint32_t *rank, *cell, *order; /* cell: also the gather buffer of rank */
    int64_t *ids;          /* ids by rank (sorted) */
    uint32_t *start;       /* first particle of each cell; nc + 1: the gone */
    uint64_t key;          /* the collisions' counter-based stream (Philox) */
    gr_rng *floor_rng;
    gr_particles *view;    /* grains in id order for output, made when asked */
    uint64_t step, pairs, walls, cand, lost;
    unsigned bad;          /* GR_DSMC_BAD_* at create */
    double lim_val[GR_DSMC_NLIMITS], lim_max[GR_DSMC_NLIMITS]; /* what broke each limit: measured, limit */
    double t;
    double wall_mom, wall_time, wall_len;
    double virial;         /* sum of sigma J over collisions (collisional transfer) */
    gr_stress_acc *stress; /* the stress window (dsmc_stress.c), NULL until asked */
} gr_dsmc;

/* dsmc_params.c */
extern const gr_param gr_dsmc_param_table[];
void gr_dsmc_params_from(const gr_param_values *pv, gr_dsmc_params *p);

/* dsmc_stream.c: free flight of particle i over [t, t + h] with gravity,
 * walls and floor as for hard disks, periodic wrap, exit through open
 * sides. */
void gr_dsmc_stream(gr_dsmc *d, size_t i, double t, double h);
/* All particles over one step of length h from time t. */
void gr_dsmc_stream_all(gr_dsmc *d, double t, double h);

/* dsmc_collide.c: the collisions of one step, cell by cell. */
int gr_dsmc_collide(gr_dsmc *d, gr_err *err);

/* dsmc_step.c */
int gr_dsmc_step(gr_dsmc *d, gr_err *err);
int gr_dsmc_advance(gr_dsmc *d, double t_end, uint64_t max_steps, gr_err *err);

/* dsmc_state.c */
/* key: of the collisions' counter-based stream; floor_rng: the
 * high-frequency floor's phases. */
int gr_dsmc_create(const gr_scene *sc, const gr_particles *init, const gr_dsmc_params *par, uint64_t key,
                   gr_rng *floor_rng, gr_dsmc **out, gr_err *err);
void gr_dsmc_free(gr_dsmc *d);
int gr_dsmc_observe(gr_dsmc *d, gr_obs *o, gr_err *err);
/* The grains in id order (radius, mass and flags filled). */
int gr_dsmc_snapshot(gr_dsmc *d, gr_particles *out, gr_err *err);
void gr_dsmc_reset_window(gr_dsmc *d);
/* Bytes the state holds per particle (its arrays over n, the cells' shared
 * out), for grano bench dsmc. */
double gr_dsmc_bytes_per_particle(const gr_dsmc *d);

/* dsmc_ckpt.c */
int gr_dsmc_save(const gr_dsmc *d, gr_ckpt *ck, gr_err *err);
int gr_dsmc_load(gr_dsmc *d, gr_ckpt *ck, gr_err *err);

/* dsmc_stress.c: the window-averaged stress (the method table's stress):
 * the kinetic sample of a step of length h, and the window's read */
void gr_dsmc_stress_sample(gr_dsmc *d, double h);
int gr_dsmc_stress(gr_dsmc *d, int nx, int ny, double global[4], double *cells, gr_err *err);
/* The open window, if any, in a checkpoint; a load without one closes it. */
int gr_dsmc_stress_save(const gr_dsmc *d, gr_ckpt *ck, gr_err *err);
int gr_dsmc_stress_load(gr_dsmc *d, gr_ckpt *ck, gr_err *err);

/* The stress window's share of a collision (dsmc_collide.c), after the
 * velocities changed and before any displacement: the momentum the
 * collision moves across the pair, W times, half to each partner's cell.
 * With the Enskog displacement it is what the jumps carry, the partners'
 * new momenta over +-delta n: delta n (x) (p_j' - p_i'), whose normal part
 * is sigma J. Without it nothing carries it (point particles), and the
 * stress counts the hard disks' sigma n (x) J that the collision stands
 * for, the term the virial (`virial`) sums. k: the change of normal
 * velocity, J = m k. Inline, so that dsmc_collide.c calls no other file. */
static inline void gr_dsmc_stress_pair(gr_dsmc *d, size_t i, size_t j, double nx, double ny, double k)
{
    if (!d->stress)
        return;
    double lx, ly, Jx, Jy;
    if (d->par.enskog) {
        double delta = d->sigma * (1.0 + d->alpha) / (2.0 * d->alpha);
        lx = delta * nx, ly = delta * ny;
        Jx = d->W * d->mass * (d->vx[j] - d->vx[i]), Jy = d->W * d->mass * (d->vy[j] - d->vy[i]);
    } else {
        lx = d->sigma * nx, ly = d->sigma * ny;
        Jx = d->W * d->mass * k * nx, Jy = d->W * d->mass * k * ny;
    }
    gr_stress_acc_collision(d->stress, d->x[i], d->y[i], d->x[j], d->y[j], 0.5, lx, ly, Jx, Jy);
}

/* A wall's impulse J along its inward normal n on particle i
 * (dsmc_stream.c): r n (x) J n, W times, in the particle's cell. */
static inline void gr_dsmc_stress_wall(gr_dsmc *d, size_t i, double nx, double ny, double J)
{
    if (!d->stress)
        return;
    double r = 0.5 * d->sigma, WJ = d->W * J;
    gr_stress_acc_collision(d->stress, d->x[i], d->y[i], 0, 0, 1.0, r * nx, r * ny, WJ * nx, WJ * ny);
}

/* Henderson's pair correlation at contact for hard disks. */
static inline double gr_dsmc_chi(double eta) { return (1.0 - 7.0 * eta / 16.0) / ((1.0 - eta) * (1.0 - eta)); }

#endif
