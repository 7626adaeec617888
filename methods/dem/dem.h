/* Soft-particle DEM backend (chapter 2 of the thesis): internal interface
 * shared by the backend's files and its tests. Not part of method.h. */
#ifndef GR_DEM_H
#define GR_DEM_H

#include <stddef.h>
#include <math.h>
#include <stdatomic.h>
#include <stdint.h>

#include "ckpt.h"
#include "contacts.h"
#include "err.h"
#include "observe.h"
#include "particles.h"
#include "scene.h"

struct gr_rng;

typedef enum { GR_DEM_VERLET = 0, GR_DEM_GEAR, GR_DEM_EULER, GR_DEM_CVODE } gr_dem_integrator;
typedef enum { GR_DEM_NB_VERLET = 0, GR_DEM_NB_CELLS, GR_DEM_NB_BRUTE } gr_dem_neighbour;

/* Parameters of the [dem] section (docs/methods/dem.md). */
typedef struct {
    double dt;            /* time step; <= 0 before gr_dem_params_read: t_c / 50 */
    double dt_fraction;   /* refused above dt_fraction * t_c */
    double v_impact;      /* impact speed for the Hertz t_c; <= 0: from the scene */
    int integrator;       /* gr_dem_integrator */
    int neighbour;        /* gr_dem_neighbour */
    double skin;          /* Verlet list skin, in length units */
    long threads;
    double max_overlap;   /* in units of the smaller diameter of the pair */
    double energy_jump;   /* allowed relative kinetic energy rise per step */
    long sort_every;      /* cells: spatial sort period in steps */
    double cvode_rtol, cvode_atol;
} gr_dem_params;

/* Field arrays, double-buffered so a failed step leaves the last good
 * state untouched (parity cur is the state at time t). */
enum {
    F_X, F_Y, F_VX, F_VY, F_W, F_FX, F_FY, F_TQ,
    /* Gear: angle and scaled derivatives b_k = dt^k/k! d^k q/dt^k, k = 2..5 */
    F_TH, F_B2X, F_B2Y, F_B2T, F_B3X, F_B3Y, F_B3T, F_B4X, F_B4Y, F_B4T, F_B5X, F_B5Y, F_B5T,
    F_NFIELDS
};
#define F_NBASIC (F_TQ + 1)

/* A wall segment of infinite mass (user walls, silo walls, domain sides). */
typedef struct {
    double x0, y0, x1, y1;
    double open_time;
    int vibrating;
} gr_dem_seg;

/* Contact history (tangential spring): fixed slots per particle, owned by
 * the grain of smaller tag; a slot is live when its stamp is the previous
 * step. The *_old fields undo a failed step. */
typedef struct {
    int cap;                 /* slots per particle */
    int32_t *partner, *partner_old; /* tag, or ntag + segment; -1 empty */
    double *z, *z_old;
    uint64_t *stamp, *stamp_old;
} gr_dem_hist;

/* Cells: CSR of particle indices by cell, row-major (row = y). */
typedef struct {
    int nx, ny;
    double x0, y0, cx, cy, icx, icy;
    int px, py;              /* periodic */
    int32_t *start;          /* nx*ny+1 */
    int32_t *idx;            /* particle indices sorted by cell */
    int32_t *cell;           /* cell of each particle */
    size_t cap;
    int32_t *cell_seg_start, *cell_seg; /* segments near each cell */
} gr_dem_cells;

/* Groups of cell rows processed in colours, so that threads never write
 * the same grain and the summation order does not depend on the thread
 * count. A strip writes to itself and the next one (pairs i < j after the
 * sort by rows, or a cell's forward neighbours), so strips two apart never
 * collide; periodic in y, the last strip also writes to the first, which
 * needs three colours. */
typedef struct {
    int n;
    int32_t *row0;           /* n+1 row boundaries */
    int32_t *i0;             /* n+1 particle index boundaries (sorted modes) */
} gr_dem_strips;

typedef struct gr_dem {
    gr_scene sc;             /* shallow copy: pointers stay the caller's */
    gr_dem_params par;
    gr_normal_law normal;
    gr_tang_law tang;
    double kn, gn, kt, gt, mu;
    double gw;               /* normal damping at walls (dem_damping.c) */
    int clip, rot, hist_on;
    double g;
    double Lx, Ly;           /* periods, 0 if none */
    double dmin, dmax, rmax;

    size_t n, cap;           /* live grains in the arrays */
    size_t ntag;             /* all grains ever (tags 0..ntag-1 in id order) */
    int nmobile;
    int cur;
    /* [2]: the next step's drift done ahead (gr_dem_eval_fuse_kick),
     * fields F_X .. F_TQ only; swapped with the new buffer when used */
    double *f[F_NFIELDS][3];
    double *rad, *im, *iI, *gf, *mass, *inertia;
    int32_t *tag;
    uint32_t *flags;
    int32_t *species;
    double *xref, *yref;     /* positions at the last list build */
    double *ext_fx, *ext_fy; /* external forces (tests), NULL if none */

    gr_particles *gone;      /* tag-indexed record of grains that left */
    int64_t *tag_id;         /* original id per tag */

    gr_dem_seg *seg;
    int nseg;

    gr_dem_cells cells;
    gr_dem_strips strips;
    /* Verlet list (half: j > i), CSR */
    int32_t *nb_start, *nb_j;
    int32_t *nb_i;           /* the grain of each pair (the batched loop's flat pass) */
    size_t nb_cap;
    int32_t *sg_start, *sg_j; /* candidate segments per particle */
    size_t sg_cap;
    int need_build;
    uint64_t builds;
    uint64_t list_gen;       /* list builds in this object (not checkpointed): caches key on it */

    gr_dem_hist hist;

    uint64_t step;           /* steps done */
    double t;
    double t0;               /* time when step was 0 */
    double ekin_last;        /* kinetic + elastic energy of the last good step */
    double eel_eval;         /* elastic energy of the last force evaluation */
    double e_floor;          /* energy below which jumps are not checked */
    double e_ref;            /* mechanical energy when the growth check began (NAN: not yet) */
    uint64_t outflow;
    int gates_open;
    double wall_impulse;     /* normal impulse on segments since last observe */
    double wall_time;
    double max_ovl;          /* largest overlap of the last force evaluation */
    double *seg_force;       /* per segment: fx, fy, normal force (3 each) */
    struct gr_rng *rng;      /* reinsertion: the caller's (the instance's stream) */
    struct gr_rng *own_rng;  /* or, made without a caller's, its own */
    gr_particles *scratch;
    void *cv;                /* CVODE reference integrator, or NULL */
    uint64_t since_sort;
    int f_zeroed;            /* the predictor already zeroed the new forces */
    double *blk;             /* per-block partial results: two per block of the capacity */
    /* grains the Verlet drift put outside the exit box (gr_dem_exit_box)
     * this step, when exits_known: spares the step's end a pass over all */
    _Atomic long exits;
    int exits_known;
    /* the step whose drift f[.][2] holds (0: none), and the grains it
     * put outside the exit box */
    uint64_t pre_E;
    _Atomic long exits_pre;
    struct gr_dem_eval *ev;  /* force evaluation in progress (dem_force.c) */
    struct gr_dem_team *team; /* the list rebuild's per-thread scratch (dem_neigh.c) */
} gr_dem;

/* The baseline build is x86-64 (SSE2); the hot loops (pair loop, drift) get an AVX2 clone
 * chosen at load time (GCC's target_clones) on CPUs that have it. C11 mode
 * contracts no multiply-add (-ffp-contract=off), and AVX2 alone brings no
 * FMA, so both clones compute the same bits. -DDEM_NO_CLONES builds the
 * baseline alone. */
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(DEM_NO_CLONES)
#define DEM_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define DEM_CLONES
#endif
/* GCC keeps a loop with floating-point compares (a select, a count) from
 * vectorising while it must preserve their exception flags; nothing here
 * reads them, and the values do not change. */
#if defined(__GNUC__) && !defined(__clang__)
#define DEM_NOTRAP __attribute__((optimize("no-trapping-math")))
#else
#define DEM_NOTRAP
#endif
/* Short copies and zeroings stay loops: GCC makes them calls to memcpy or
 * memset, each costing more than the loop at these sizes. */
#if defined(__GNUC__) && !defined(__clang__)
#define DEM_NODIST __attribute__((optimize("no-tree-loop-distribute-patterns")))
#else
#define DEM_NODIST
#endif

/* Grains per block of the per-grain loops (fixed: sums do not depend on
 * the number of threads). */
#define DEM_BLOCK 512

/* v into the two largest so far, m[0] >= m[1]. */
static inline void gr_dem_top2_add(double v, double m[2])
{
    if (v > m[0])
        m[1] = m[0], m[0] = v;
    else if (v > m[1])
        m[1] = v;
}

/* The two largest of v[0..n) (squared displacements), and their square
 * roots summed: the Verlet-list test, the same whatever grouping produced
 * v (maxima). */
static inline void gr_dem_top2(const double *v, size_t n, double m[2])
{
    m[0] = m[1] = 0;
    for (size_t k = 0; k < n; k++)
        gr_dem_top2_add(v[k], m);
}

static inline double gr_dem_top2_sum(const double *v, size_t n)
{
    double m[2];
    gr_dem_top2(v, n, m);
    return sqrt(m[0]) + sqrt(m[1]);
}

/* Parameters: defaults, then the scene's [dem] section; checks the time
 * step against the contact time (GR_EINPUT naming the key). */
void gr_dem_params_default(gr_dem_params *p);
int gr_dem_params_read(const gr_scene *sc, gr_dem_params *p, gr_err *err);
/* Contact time of the stiffest pair (eq. 2.2 or 2.5) and the speed used. */
double gr_dem_contact_time(const gr_scene *sc, const gr_particles *init, double v_impact);
double gr_dem_default_v_impact(const gr_scene *sc, const gr_particles *init);
/* dem_damping.c: the pair and wall damping a scene asks for (gamma_n, or
 * derived from [material] restitution and wall_restitution). */
int gr_dem_damping(const gr_scene *sc, const gr_particles *init, double *gn, double *gw, gr_err *err);
/* Velocity Verlet's stability bound in a dense (triangular) packing of the
 * scene's contacts; gr_dem_check_dt refuses a Verlet dt above it. */
double gr_dem_dense_dt(const gr_scene *sc, const gr_particles *init, double v_impact);
int gr_dem_check_dt(const gr_scene *sc, const gr_particles *init, gr_dem_params *p, gr_err *err);

/* reinsert: the stream of reinsertion spots (GR_STREAM_DEM_REINSERT),
 * owned by the caller; needed only by a silo that reinserts. */
int gr_dem_create(const gr_scene *sc, const gr_particles *init, const gr_dem_params *par, struct gr_rng *reinsert,
                  gr_dem **out, gr_err *err);
void gr_dem_free(gr_dem *d);
int gr_dem_advance(gr_dem *d, double t_end, uint64_t max_steps, gr_err *err);
int gr_dem_snapshot(gr_dem *d, gr_particles *out, gr_err *err);
int gr_dem_observe(gr_dem *d, gr_obs *o, gr_err *err);
/* Start a new wall-pressure window (observe averages since the last reset). */
void gr_dem_reset_window(gr_dem *d);
int gr_dem_save(const gr_dem *d, gr_ckpt *ck, gr_err *err);
int gr_dem_load(gr_dem *d, gr_ckpt *ck, gr_err *err);

/* Forces on the current state (velocities as they are, springs not
 * stretched) with a given neighbour mode, in internal order; the state is
 * left unchanged. Tests compare the modes with it. */
int gr_dem_forces(gr_dem *d, int mode, double *fx, double *fy, double *tq, gr_err *err);
/* Kinetic (translation + rotation) and, if eel, elastic contact energy
 * (all pairs: small systems only). Ignores a vibrating floor's offset. */
void gr_dem_energy(gr_dem *d, double *ekin, double *eel);
/* Index of tag, or -1 if gone. */
long gr_dem_index(const gr_dem *d, long tag);
/* Tests: an external force on a grain, and locking its rotation. */
int gr_dem_set_external(gr_dem *d, long tag, double fx, double fy, gr_err *err);
void gr_dem_lock_rotation(gr_dem *d, long tag);
/* Bytes held by the state (arrays, lists, history, records). */
double gr_dem_memory(const gr_dem *d);
/* Force exerted by the grains on segment s during the last evaluation. */
void gr_dem_segment_force(const gr_dem *d, int s, double *fx, double *fy);

/* Internals shared by the backend's files, by file from the bottom
 * layer up: a file calls only files of the groups above its own here
 * (tests/layers.py checks it; docs/methods/dem.md, "Files and layers"). */

/* Threads of the parallel loops ([dem] threads, at least 1). */
static inline int gr_dem_threads(const gr_dem *d) { return (int)(d->par.threads > 0 ? d->par.threads : 1); }
static inline int gr_dem_colours(const gr_dem *d) { return d->cells.py ? 3 : 2; }

/* dem_cells.c: cells, binning, strips; the distance from point p to
 * segment [a, b], and how far a vibrating segment moves either way. */
int gr_dem_cells_setup(gr_dem *d, double cutoff, gr_err *err);
int gr_dem_bin(gr_dem *d, const double *x, const double *y, gr_err *err);
void gr_dem_make_strips(gr_dem *d);
double gr_dem_seg_dist(double ax, double ay, double bx, double by, double px, double py);
double gr_dem_seg_margin(const gr_dem *d);

/* dem_grains.c: per-grain arrays (also gr_dem_snapshot, gr_dem_index). */
int gr_dem_grow(gr_dem *d, size_t cap, gr_err *err);
/* Drop the grains with gone[i] != 0 (recorded in d->gone), keeping order. */
int gr_dem_compact(gr_dem *d, const unsigned char *gone, gr_err *err);
/* The external force arrays, zero, if not there yet. */
int gr_dem_external_arrays(gr_dem *d, gr_err *err);

/* dem_integ.c: the integrators' passes over grains, old buffer p, new q. */
/* Drift and first kick of grains [i0, i1) (two largest squared moves in
 * top2 when track); second kick, returning their kinetic energy, and in
 * *v2max (if not NULL) the largest squared speed of the next drift. */
void gr_dem_drift(gr_dem *d, int p, int q, int track, size_t i0, size_t i1, double top2[2], _Atomic long *exits);
/* The box outside which a mobile grain leaves (open sides, the silo's
 * exit line; infinite bounds where none): box = xlo, xhi, ylo, yhi.
 * Returns 0 when every bound is infinite. */
int gr_dem_exit_box(const gr_dem *d, double box[4]);
double gr_dem_kick(gr_dem *d, int p, int q, size_t i0, size_t i1, double *v2max);
/* The kick of [i0, i1) (old buffer p, new q) and their drift from q into
 * r in one pass: the two calls' results (gr_dem_drift's with track). */
double gr_dem_kick_drift(gr_dem *d, int p, int q, int r, size_t i0, size_t i1, double *v2max, double top2[2],
                         _Atomic long *exits);
/* The same over block b of DEM_BLOCK grains, results in d->blk. */
void gr_dem_predict_block(gr_dem *d, int p, int q, int track, size_t b);
void gr_dem_kick_block(gr_dem *d, int p, int q, size_t b);
/* From the blocks' results: the two largest moves summed, kinetic energy. */
double gr_dem_moved_blocks(const gr_dem *d);
double gr_dem_kinetic_blocks(const gr_dem *d, size_t nb);
/* All blocks, on the threads when there are several: drift (returns the
 * moves summed when track, else 0) and kick (returns kinetic energy). */
double gr_dem_predict_verlet(gr_dem *d, int p, int q, int track);
double gr_dem_correct_verlet(gr_dem *d, int p, int q);
double gr_dem_kinetic(gr_dem *d, int q);
void gr_dem_predict_euler(gr_dem *d, int p, int q);
void gr_dem_predict_gear(gr_dem *d, int p, int q);
void gr_dem_correct_gear(gr_dem *d, int q);

/* dem_balance.c (dem_eval.h): runs of strips per thread. */

/* dem_network.c: the contact network at the current state (the law at
 * this state's positions and velocities, springs as the last step left
 * them), rows sorted by ids; reads the state only. */
int gr_dem_contacts(const gr_dem *d, gr_contacts *out, gr_err *err);

/* dem_neigh.c: spatial sort, Verlet lists. */
int gr_dem_sort(gr_dem *d, gr_err *err);
int gr_dem_build_list(gr_dem *d, const double *x, const double *y, gr_err *err);
/* Sort and build the list on the current positions, for a step that then
 * drifts every grain (the other buffer's positions and velocities are left
 * unsorted: the drift writes them). _team: called by every thread of the
 * enclosing parallel region (or by one thread outside any), which share
 * the work, meeting at m, and all return the same status; the list is
 * complete once they have met once more (the caller's meeting).
 * gr_dem_rebuild: by one thread (outside a parallel region, on the
 * scene's threads). The same list as gr_dem_sort and gr_dem_build_list. */
struct gr_dem_meet;
int gr_dem_rebuild_team(gr_dem *d, struct gr_dem_meet *m, gr_err *err);
int gr_dem_rebuild(gr_dem *d, gr_err *err);
void gr_dem_team_free(struct gr_dem_team *tm);
/* Bytes the rebuild's per-thread scratch holds (gr_dem_memory). */
double gr_dem_team_bytes(const struct gr_dem_team *tm);

/* dem_force.c: the force evaluation. */
/* Forces on the positions and velocities of parity q at time
 * t_eval; E numbers the evaluation for the contact history, integ is the
 * spring's time step (0: do not stretch). Fills seg_force. */
int gr_dem_eval_at(gr_dem *d, int q, double t_eval, uint64_t E, double integ, int mode,
                   double *seg_out, gr_err *err);
/* The same in three parts, for a step that runs in one parallel region:
 * begin (one thread), every colour in turn (all threads of the region, or
 * one thread outside any), end (one thread: sums, overlap check). */
int gr_dem_eval_begin(gr_dem *d, int q, double t_eval, uint64_t E, double integ, int mode, gr_err *err);
int gr_dem_eval_ncolours(const gr_dem *d);
void gr_dem_eval_colour(gr_dem *d, int col);
/* All colours: on the threads of the scene when called outside a parallel
 * region with more than one. */
void gr_dem_eval_run(gr_dem *d);
/* Cut each colour's strips into one run per thread (one thread, before
 * the colours run on the threads of a region: gr_dem_eval_run does it). */
void gr_dem_eval_split(gr_dem *d);
/* One strip's pushes (Verlet lists), and the kicks that fall after it. */
void gr_dem_eval_strip(gr_dem *d, int s);
int gr_dem_eval_end(gr_dem *d, double *seg_out, gr_err *err);
void gr_dem_eval_free(struct gr_dem_eval *ev);

/* dem_flow.c: the fused kick and the one-barrier step. */
/* With Verlet lists and grains in strip order, have the colours also give
 * the second kick of velocity Verlet (gr_dem_kick, old buffer p) to each
 * strip once its last push is in; returns 1 if so. Kinetic energy of the
 * kicked state, summed strip by strip in order: gr_dem_eval_kinetic. */
int gr_dem_eval_fuse_kick(gr_dem *d, int p);
double gr_dem_eval_kinetic(const gr_dem *d);
/* After the one-barrier step: the sum of the two largest displacements
 * since the list build, from its per-strip drifts (the same value as from
 * blocks: a maximum). */
double gr_dem_eval_moved(const gr_dem *d);
/* The drift done ahead (velocity Verlet, Verlet lists, kick fused): after
 * gr_dem_eval_fuse_kick, _pre(on) has the kicks also drift each strip for
 * the next step into buffer 2 (returns 1 if so); after the evaluation the
 * step then sets d->pre_E to that step.
 * At that step's start, before its evaluation, _use takes the drift if it
 * is still good (nothing rebuilt, compacted, sorted or reinserted since),
 * swapping buffer 2 in as the new buffer, with *moved and the exit count
 * as the drift would give them; returns 0 when the step must drift. The
 * same operations as the drift at its usual place: the same bits. */
int gr_dem_eval_pre(gr_dem *d, int on);
int gr_dem_pre_use(gr_dem *d, uint64_t E, double *moved);
/* The one-barrier step (two colours, kick fused, two or more threads):
 * _begin (one thread, after the evaluation's begin and the fusing) says
 * whether it applies and cuts the strips; then every thread of the region
 * calls gr_dem_eval_flow (scratch: stride >= strips.n ints per thread), which drifts,
 * pushes and kicks its run of strips, waiting only on its neighbours';
 * the caller's barrier ends the step. */
int gr_dem_eval_flow_begin(gr_dem *d);
void gr_dem_eval_flow(gr_dem *d, int p, int q, int *scratch, size_t stride);
/* The first strip of each of T threads' runs in the last evaluation, if it
 * was a one-barrier step on T threads and the strips are as they were
 * (cut[T] = strips.n): the rebuild hands each thread the grains it will
 * step. 0 otherwise. */
int gr_dem_eval_flow_cut(const gr_dem *d, int T, int *cut);
/* dem_force.c: the fused kick of strip r, whatever its kicker. */
void gr_dem_eval_kick_strip(gr_dem *d, int r);
/* Largest squared half-kick speed v + (dt/2) a of the next drift, from the
 * fused kick: with the displacements so far it bounds the next step's. */
double gr_dem_eval_vmax2(const gr_dem *d);

/* dem_cvode.c: CVODE reference integrator. */
int gr_dem_cv_create(gr_dem *d, gr_err *err);
int gr_dem_cv_advance(gr_dem *d, double t_end, uint64_t max_steps, gr_err *err);
void gr_dem_cv_free(gr_dem *d);

/* dem_commit.c: the end of a step. Undo the contact history written by
 * evaluation E; the energy checks, then the new state (buffer q) becomes
 * the current one and the grains that left are handled; the gates open. */
void gr_dem_hist_undo_at(gr_dem *d, uint64_t E);
int gr_dem_commit(gr_dem *d, int q, uint64_t E, double tn, double ek, gr_err *err);
int gr_dem_open_gates(gr_dem *d, gr_err *err);

/* dem_step.c: a step (also gr_dem_step, gr_dem_advance, gr_dem_forces). */
int gr_dem_step(gr_dem *d, gr_err *err);

/* dem_state.c: creation and freeing (also gr_dem_create, gr_dem_free,
 * gr_dem_energy, gr_dem_observe and the test hooks). */
int gr_dem_prepare(gr_dem *d, gr_err *err);

#endif
