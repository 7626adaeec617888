/* DSMC backend (Bird's no-time-counter scheme, inelastic smooth disks):
 * internal interface shared by the backend's files and its tests. */
#ifndef GR_DSMC_INT_H
#define GR_DSMC_INT_H

#include <math.h>
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
    double dt, cell, ppc_min, gas_eta_max;
    int enskog, strict, threads;
} gr_dsmc_params;

/* Which validity limits the scene breaks at create (bits). */
enum {
    GR_DSMC_BAD_DT = 1,
    GR_DSMC_BAD_CELL = 2,
    GR_DSMC_BAD_PPC = 4,
    /* 8: no longer used (cells under 10 d in the Enskog mode, whose
     * displacement of partners thinned the pairs of small cells) */
    GR_DSMC_BAD_RECOLLIDE = 16, /* cell side under the pool limit (GR_DSMC_POOL_K) */
    GR_DSMC_BAD_DENSE = 32      /* during the run: a region packed beyond a gas (dsmc_dense.c) */
};

/* A region of about 32 grains packed above [dsmc] gas_eta_max (0.5) is no
 * longer the Boltzmann-Enskog gas the method computes: the Enskog mode's
 * pressure is already 9 % above the hard-disk fluid's at 0.385
 * (docs/course.md), and a bed at rest packs at 0.8 and more. Checked every
 * GR_DSMC_DENSE_EVERY steps. */
#define GR_DSMC_DENSE_EVERY 16

/* The smallest cell side for which partners that shared cells, colliding
 * again while their velocities are still correlated, slow the cooling by
 * at most about 1 %: K (1 - alpha^2) min(1, sigma / (L lambda)) W sigma,
 * from the cell scan of docs/methods/dsmc.md (cells): 20 W sigma at
 * alpha = 0.8 from packing 0.1 (lambda = 2.8 sigma) up, 4 W sigma at 0.02. */
#define GR_DSMC_POOL_K 55.0
#define GR_DSMC_POOL_LAMBDA 0.36
#define GR_DSMC_NLIMITS 5

/* A particle's rank (the order of its id) with this bit set has left the
 * domain through an open side. */
#define GR_DSMC_GONE 0x80000000u
#define GR_DSMC_RANK 0x7fffffffu

/* Particles are kept sorted by cell (the counting sort of each step moves
 * them), so that a cell's particles are contiguous in memory: the arrays
 * below are in that order, rank[k] names the grain. About 68 bytes per
 * particle (docs/methods/dsmc.md, Speed). */
typedef struct gr_dsmc {
    gr_scene sc;           /* shallow copy: pointers stay the caller's */
    gr_dsmc_params par;
    double alpha, alpha_w; /* grain-grain and wall normal restitution */
    double g, W;           /* gravity; real grains per simulated particle */
    double sigma, mass;    /* the one diameter and mass (monodisperse) */
    double Lx, Ly;         /* domain */
    int nx, ny;            /* cells of a side's length */
    double cw, ch;         /* cell sides */
    int gx, gy;            /* the shifted grid: nx, or nx + 1 along a side that is not periodic */
    double ox, oy;         /* this step's shift of the grid, in [0, cw) x [0, ch) */
    int walls_any;         /* a side is a wall (else streaming is x += v h) */
    size_t n;              /* particles */
    double *x, *y, *vx, *vy, *tmp; /* tmp: the sort's gather buffer */
    uint32_t *rank, *cell, *order; /* cell: also the gather buffer of rank */
    uint32_t *last, *prev; /* ranks of the last two collision partners (GR_DSMC_RANK: none) */
    int64_t *ids;          /* ids by rank (sorted) */
    uint32_t *start;       /* first particle of each cell of the shifted grid; then the gone */
    struct gr_dsmc_cellv *cv; /* the Enskog mode's per-cell bounds of this step (dsmc_esmc.c) */
    uint32_t *hist;        /* the threaded sort's histograms, hist_threads x (cells + 1) */
    int hist_threads;
    uint64_t key;          /* the collisions' counter-based stream (Philox) */
    gr_rng *floor_rng;
    gr_particles *view;    /* grains in id order for output, made when asked */
    uint64_t step, pairs, walls, cand, lost, stand_ins;
    unsigned bad;          /* GR_DSMC_BAD_* at create */
    uint64_t dense_steps;  /* steps with a region packed above gas_eta_max */
    double dense[5];       /* the densest such region: packing fraction, x0, y0, x1, y1 */
    double lim_val[GR_DSMC_NLIMITS], lim_max[GR_DSMC_NLIMITS]; /* what broke each limit: measured, limit */
    double t;
    double wall_mom, wall_time, wall_len;
    double virial;         /* sum of sigma J over collisions (collisional transfer) */
    gr_stress_acc *stress; /* the stress window (dsmc_stress.c), NULL until asked */
} gr_dsmc;

/* dsmc_params.c */
extern const gr_param gr_dsmc_param_table[];
void gr_dsmc_params_from(const gr_param_values *pv, gr_dsmc_params *p);

/* dsmc_stream.c: the free flight of all particles over one step of
 * length h from time t, with gravity, walls and floor as for hard disks,
 * periodic wrap, exit through open sides. */
void gr_dsmc_stream_all(gr_dsmc *d, double t, double h);

/* dsmc_dense.c: every GR_DSMC_DENSE_EVERY steps, the packing of bins of
 * about 32 grains against gas_eta_max (a measurement: the dynamics does
 * not depend on it). */
void gr_dsmc_dense_check(gr_dsmc *d);
/* The live particles counted in bins of about 32 of them, bx x by (at
 * most 256 a side), row-major; NULL when out of memory. Also the measure
 * of the density the grains see at create (dsmc_state.c). */
double *gr_dsmc_bins(const gr_dsmc *d, int *bx, int *by, size_t *live);

/* dsmc_cells.c: the grid of collision cells, shifted by a random offset
 * every step. */
void gr_dsmc_grid(gr_dsmc *d);
/* Index along one axis of coordinate x with offset o, cell width w. */
static inline int gr_dsmc_axis_of(double x, double o, double w, int n, int g)
{
    int k = (int)floor((x + o) / w);
    if (g == n) /* periodic */
        return k >= n ? k - n : k < 0 ? k + n : k;
    return k < 0 ? 0 : k >= g ? g - 1 : k;
}
/* The cell of this step's grid that holds (x, y). */
static inline uint32_t gr_dsmc_cell_of(const gr_dsmc *d, double x, double y)
{
    int cx = gr_dsmc_axis_of(x, d->ox, d->cw, d->nx, d->gx), cy = gr_dsmc_axis_of(y, d->oy, d->ch, d->ny, d->gy);
    return (uint32_t)(cy * d->gx + cx);
}
/* This step's offset and the counting sort of the particles by cell. */
int gr_dsmc_sort(gr_dsmc *d, gr_err *err);
/* The area of cell c of this step's grid (cells along a wall are cut). */
double gr_dsmc_cell_area(const gr_dsmc *d, size_t c);
static inline size_t gr_dsmc_ncells(const gr_dsmc *d) { return (size_t)d->gx * (size_t)d->gy; }

/* dsmc_partner.c: the stand-in for a recent partner. */
/* i and j are each other's partner in one of the last two collisions of
 * either. */
static inline int gr_dsmc_recent(const gr_dsmc *d, size_t i, size_t j)
{
    uint32_t ri = d->rank[i] & GR_DSMC_RANK, rj = d->rank[j] & GR_DSMC_RANK;
    return d->last[i] == rj || d->prev[i] == rj || d->last[j] == ri || d->prev[j] == ri;
}
/* The pool of a pair alone in its cell: the smallest square of cells
 * around it, R0 or more cells from it (lo..hi per axis, wrapped across
 * periodic sides), that holds a third particle, or the whole grid. */
typedef struct {
    int lo[2], hi[2];
} gr_dsmc_pool;
gr_dsmc_pool gr_dsmc_pool_of(const gr_dsmc *d, size_t c, int R0);
/* A bound of |v_k - v_l| for k = i or j, l anywhere in the pool. */
double gr_dsmc_pool_bound(const gr_dsmc *d, const gr_dsmc_pool *p, size_t i, size_t j);
/* The particle that meets i or j in place of the other: a uniform draw u
 * in [0, 1) picks another particle of the cell (start a, m particles) or,
 * when the pair is alone in it (m = 2), of the pool; (size_t)-1 when
 * there is none. */
size_t gr_dsmc_stand_in(const gr_dsmc *d, double u, size_t a, size_t m, const gr_dsmc_pool *p, size_t i, size_t j);

/* What a block of cells adds to the counters and the virial: summed per
 * block in cell order, then over the blocks in order, so that the sums
 * do not depend on the threads. */
typedef struct {
    uint64_t pairs, cand, stand_ins;
    double virial;
} gr_dsmc_tally;

/* dsmc_esmc.c: the Enskog mode's collisions (Enskog simulation Monte
 * Carlo). A cell's candidates touch the particles of the cells up to
 * gr_dsmc_esmc_reach cells from it (where a partner touching one of them
 * can sit). */
typedef struct gr_dsmc_cellv {
    double mx, my, r; /* mean velocity, largest distance of a velocity from it */
    double a;         /* area */
    double ha, ba;    /* area of the 3 cells of its row around it, of the 3 x 3 */
    double n;         /* number density (real grains) of the 3 x 3 cells around */
    uint32_t hc, cnt; /* particles of the 3 cells of its row around it, of the 3 x 3 */
} gr_dsmc_cellv;
int gr_dsmc_esmc_reach(const gr_dsmc *d);
/* This step's bounds of every cell (d->cv), on T threads. */
void gr_dsmc_esmc_prepare(gr_dsmc *d, int T);
/* The candidates of cell c: they touch the particles of the cells within
 * the reach + 1 of it. */
void gr_dsmc_esmc_cell(gr_dsmc *d, size_t c, gr_dsmc_tally *y);

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

/* The stress window's share of a collision (dsmc_collide.c, dsmc_esmc.c),
 * after the velocities changed: the momentum the collision moves across
 * the pair, W times, half to each partner's cell. Nothing carries it
 * (point particles), so the stress counts the hard disks' sigma n (x) J
 * that the collision stands for, the term the virial (`virial`) sums.
 * k: the change of normal velocity, J = m k. Inline, so that the
 * collision files call no other file for it. */
static inline void gr_dsmc_stress_pair(gr_dsmc *d, size_t i, size_t j, double nx, double ny, double k)
{
    if (!d->stress)
        return;
    double lx = d->sigma * nx, ly = d->sigma * ny, Jx = d->W * d->mass * k * nx, Jy = d->W * d->mass * k * ny;
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

/* The calling thread's number in an OpenMP team (0 without OpenMP). */
#ifdef _OPENMP
#include <omp.h>
static inline int gr_dsmc_thread(void) { return omp_get_thread_num(); }
#else
static inline int gr_dsmc_thread(void) { return 0; }
#endif

/* Henderson's pair correlation at contact for hard disks. */
static inline double gr_dsmc_chi(double eta) { return (1.0 - 7.0 * eta / 16.0) / ((1.0 - eta) * (1.0 - eta)); }

#endif
