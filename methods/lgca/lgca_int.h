/* The lattice-gas backend (docs/methods/lgca.md): a granular FHP lattice
 * gas on a triangular lattice, seven channels per node stored as bit
 * planes, 64 nodes per machine word.
 *
 * Lattice coordinates: node (i, j), i along a lattice axis that points up
 * (+y), j the lane across it (+x). Node (i, j) sits at
 *   x = (j + 1/2) h,  y = (i + 1/4 + (j odd) / 2) a,  h = a sqrt(3) / 2,
 * so gravity (-y) lies along a lattice direction. Channel k < 6 moves along
 * c_k = (sin 60k, cos 60k) in (x, y): 0 up, 1 up-right, 2 down-right, 3
 * down, 4 down-left, 5 up-left; channel 6 is the rest particle. */
#ifndef GR_LGCA_INT_H
#define GR_LGCA_INT_H

#include <stddef.h>
#include <stdint.h>

#include "err.h"
#include "fields.h"
#include "observe.h"
#include "params.h"
#include "particles.h"
#include "rng.h"
#include "scene.h"
#include "stress.h"

#define LGCA_CH 7
#define LGCA_REST 6

/* The unit velocity of moving channel k < 6 in (x, y) (lattice speeds). */
static inline void lgca_unit_velocity(int k, double *vx, double *vy)
{
    static const double sx[6] = {0, 0.86602540378443865, 0.86602540378443865, 0, -0.86602540378443865,
                                 -0.86602540378443865};
    static const double sy[6] = {1, 0.5, -0.5, -1, -0.5, 0.5};
    *vx = sx[k], *vy = sy[k];
}

enum { LGCA_RULES_FHP3 = 0, LGCA_RULES_GRANULAR = 1, LGCA_NRULES = 2 };

/* Which particle gravity turns first at a drawn node (Peng and Herrmann's
 * lattice has a horizontal axis, so theirs does not carry over): the rest
 * particle, then up-right, then up-left (REST); up-right, up-left, then the
 * rest particle (MOVERS); the rest particle, then the side the step's
 * parity says (ALTERNATE: no preferred side). */
enum { LGCA_GRAV_REST = 0, LGCA_GRAV_MOVERS = 1, LGCA_GRAV_ALTERNATE = 2 };

typedef struct {
    double dt;   /* time per step (tau) */
    double p;    /* dissipation probability (granular rules) */
    double g;    /* gravity probability per node and step; NaN: from the scene */
    double b;    /* wall roughness: bounce-back probability */
    double stop; /* a head-on pair meeting a rest particle stops (granular) */
    int rules;   /* LGCA_RULES_* */
    int gravity; /* LGCA_GRAV_* */
    int threads;
} lgca_params;

extern const gr_param lgca_param_table[];
void lgca_params_from(const gr_param_values *pv, lgca_params *p);

/* ---- collision rules (lgca_table.c): the readable reference ----
 * out[s | ch << 7 | pb << 8]: the state after the collision of state s with
 * chirality bit ch and dissipation bit pb (granular rules only). */
#define LGCA_TABLE_SIZE 512
void lgca_table_build(int rules, uint8_t out[LGCA_TABLE_SIZE]);
/* Momentum of a state in integer units: qx = sum of sign(sin 60k) (units of
 * sqrt(3)/2 lattice speeds along x), qy = sum of 2 cos 60k (units of half a
 * lattice speed along y). Exact, for conservation checks. */
void lgca_state_momentum(unsigned s, int *qx, int *qy);
/* Channel k after the mirror of kind m (axis at 30 m degrees from +x);
 * m = 6: bounce-back. */
static inline int lgca_mirror(int m, int k)
{
    if (k == LGCA_REST)
        return k;
    return m == 6 ? (k + 3) % 6 : ((3 - m - k) % 6 + 12) % 6;
}

/* ---- the generated bit-parallel collision (lgca_kernel.c, made by
 * lgca_gen.c from the table above) ---- */
/* d: the bits that change (apply as s ^= d & fluid). */
void lgca_delta_fhp3(const uint64_t s[LGCA_CH], uint64_t ch, uint64_t d[LGCA_CH]);
void lgca_delta_granular(const uint64_t s[LGCA_CH], uint64_t ch, uint64_t pb, uint64_t d[LGCA_CH]);
/* The collision of nl consecutive lanes of nw words (a lane: 7 planes of
 * nw words) at their fluid nodes (fluid, ch, pb: nw words a lane). */
void lgca_delta_fhp3_lanes(uint64_t *lanes, size_t nl, size_t nw, const uint64_t *fluid0, const uint64_t *ch0);
void lgca_delta_granular_lanes(uint64_t *lanes, size_t nl, size_t nw, const uint64_t *fluid0, const uint64_t *ch0,
                               const uint64_t *pb0);

/* ---- random bits (lgca_rand.c): Philox4x32-10 keyed by the run's key,
 * counted by word, purpose and step ---- */
enum { LGCA_RND_CHIRAL = 0, LGCA_RND_P = 2, LGCA_RND_G = 18, LGCA_RND_WALL = 34, LGCA_RND_REINSERT = 35,
       LGCA_RND_STOP = 36 /* and 37 */ };
uint64_t lgca_rand_word(const uint32_t key[2], uint64_t word, unsigned purpose, uint64_t step);
uint32_t lgca_rand_u32(const uint32_t key[2], uint64_t node, unsigned purpose, uint64_t step);
/* The same bits as lgca_rand_word for words word0 .. word0 + n - 1 into
 * out, batched so that the Philox rounds vectorise. */
void lgca_rand_words(const uint32_t key[2], uint64_t word0, size_t n, unsigned purpose, uint64_t step,
                     uint64_t *out);
/* lgca_dense.c. Lanes lane0 .. lane0 + nl - 1 (nl <= LGCA_CHUNK_WORDS) of
 * nw words each: out (nl nw words) has a 1 with probability thr / 2^16
 * (thr <= 65536) at each node set in need, 0 elsewhere; a function of the
 * key, the lane, its need, purpose and step (purposes purpose .. purpose +
 * 7). scratch: LGCA_DENSE_SCRATCH nl nw words. */
#define LGCA_DENSE_SCRATCH 16
/* BMI2's pdep, portable: the low bits of src at the set bits of mask. */
static inline __attribute__((always_inline)) uint64_t lgca_pdep_soft(uint64_t src, uint64_t mask)
{
    uint64_t r = 0;
    for (; mask; mask &= mask - 1, src >>= 1)
        r |= (uint64_t)-(int64_t)(src & 1u) & (mask & -mask);
    return r;
}
void lgca_rand_biased_lanes(const uint32_t key[2], uint64_t lane0, size_t nl, size_t nw, unsigned purpose,
                            uint64_t step, uint32_t thr, const uint64_t *need, uint64_t *out, uint64_t *scratch);
/* The baseline build is x86-64 (SSE2); hot loops get an AVX2 clone chosen
 * at load time (GCC's target_clones) on CPUs that have it. -DLGCA_NO_CLONES
 * builds the baseline alone, so that its tests run on an AVX2 machine. */
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(LGCA_NO_CLONES)
#define LGCA_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define LGCA_CLONES
#endif

/* The random words of a few lanes are drawn together, so that short lanes
 * fill the batches of Philox calls. */
#define LGCA_CHUNK_WORDS 256
/* fluid, chirality, biased bits, need, and lgca_rand_biased_lanes' */
#define LGCA_SCRATCH (4 + LGCA_DENSE_SCRATCH)

/* A wall node: where, its mirror kind, whether it is a gate. */
typedef struct {
    uint32_t i, j;
    uint32_t mirror;   /* 0..5 mirror axis at 30 m degrees; 6 bounce-back (corners) */
    uint64_t open_step; /* a gate: fluid from this step on; UINT64_MAX: never */
} lgca_wall;

typedef struct lgca {
    const gr_scene *sc;
    lgca_params par;
    int ni, nj, nw;         /* nodes per lane, lanes, words per lane */
    double a, h, mass;      /* spacing, lane spacing, particle mass */
    int per_i, per_j;       /* periodic along the axis (y) and across (x) */
    int open[4];            /* GR_LEFT.. side open (particles leaving vanish) */
    uint64_t **lane;        /* [j]: lane j, 7 planes of nw words ([c * nw + w]) */
    uint64_t **seg;         /* where the lanes live: one allocation per thread's block (lgca_geom.c) */
    int nseg, *seg_j;       /* segment k holds lanes seg_j[k] .. seg_j[k + 1] - 1, in order */
    uint64_t *solid;        /* [j * nw + w] wall nodes */
    uint64_t *valid;        /* [w] nodes that exist in a lane */
    lgca_wall *walls;
    size_t nwalls;
    int has_gates;
    uint32_t thr_p, thr_g;  /* probabilities in units of 2^-16 */
    uint64_t thr_b;         /* in units of 2^-32 */
    uint64_t thr_stop;      /* in units of 2^-32 */
    uint64_t *stop_mask;    /* [j * nw + w] nodes where a rest collision may happen */
    uint32_t key[2];
    uint64_t step;
    int exits;              /* a silo: nodes below exit_below empty out */
    int exit_n[2];          /* rows i < exit_n[j & 1] lie below exit_below */
    int band_i0[2], band_i1[2]; /* reinsertion band rows [i0, i1) per lane parity */
    int band_j0, band_j1;   /* and lanes */
    int reinsert;
    uint64_t outflow, reinserted, lost;
    int nthreads;
    int chunk;              /* lanes collided together (LGCA_CHUNK_WORDS words) */
    uint64_t *scratch;      /* per thread: LGCA_SCRATCH chunk nw words (fluid, random bits, masks) */
    uint64_t *edge;         /* per step parity and thread: a slot of 4 planes of a block's edge lanes */
    uint64_t *sweep;        /* per thread: 4 planes, the sweep's copies of a chunk's last lane (lgca_step.c) */
    int prefetch;           /* a thread's lanes outgrow L2: the collision prefetches the next chunk's */
    gr_stress_acc *stress;  /* the open stress window (lgca_stress.c), or NULL */
} lgca;

/* Words per slot of L->edge: 4 planes, rounded up to whole pairs of cache
 * lines (lgca_geom.c's zalloc_lines says why). */
static inline size_t lgca_edge_slot(const lgca *L)
{
    return (4 * (size_t)L->nw + 15) & ~(size_t)15;
}

/* Words per thread of L->sweep: 4 planes too, the size of an edge slot. */
static inline size_t lgca_sweep_words(const lgca *L)
{
    return lgca_edge_slot(L);
}

/* lgca_geom.c: lattice size, walls, the initial state. */
/* init: the scene's grains, rasterised onto nodes; rng fills the channels
 * of an occupation initial state. */
int lgca_create(const gr_scene *sc, const lgca_params *par, const uint32_t key[2],
                const gr_particles *init, gr_rng *rng, lgca **out, gr_err *err);
void lgca_free(lgca *L);
static inline void lgca_node_xy(const lgca *L, int i, int j, double *x, double *y)
{
    *x = (j + 0.5) * L->h;
    *y = (i + 0.25 + 0.5 * (j & 1)) * L->a;
}
static inline int lgca_get(const lgca *L, int i, int j, int c)
{
    return (int)(L->lane[j][(size_t)c * (size_t)L->nw + (size_t)(i >> 6)] >> (i & 63) & 1u);
}
static inline void lgca_put(lgca *L, int i, int j, int c, int v)
{
    uint64_t *w = &L->lane[j][(size_t)c * (size_t)L->nw + (size_t)(i >> 6)];
    uint64_t m = (uint64_t)1 << (i & 63);
    *w = v ? *w | m : *w & ~m;
}
static inline int lgca_is_solid(const lgca *L, int i, int j)
{
    return (int)(L->solid[(size_t)j * (size_t)L->nw + (size_t)(i >> 6)] >> (i & 63) & 1u);
}
/* lgca_init.c. The neighbour of (i, j) along channel k, or 0 when it is off
 * the lattice (non-periodic side). */
int lgca_neighbour(const lgca *L, int i, int j, int k, int *ni, int *nj);
/* Fill the lattice from the scene's grains or its occupations. */
int lgca_init_state(lgca *L, const gr_particles *init, gr_rng *rng, gr_err *err);

/* lgca_exit.c: particles below the silo's exit height leave (counted);
 * with reinsertion each goes back, in its channel, to the highest free node
 * of the band in a lane drawn at random (or the next lane with room). */
void lgca_exits(lgca *L);

/* lgca_stop.c: Peng and Herrmann's rest collision, on bit planes or bytes
 * through an accessor of node states. */
typedef struct {
    unsigned (*get)(const void *ctx, int i, int j);
    void (*set)(void *ctx, int i, int j, unsigned s);
    void *ctx;
} lgca_access;
void lgca_stop_node(const lgca *L, int i, int j, uint64_t step, const lgca_access *a);
void lgca_stop_pass(lgca *L, uint64_t *mask);

/* lgca_step.c: gravity's three moves (from, to channel) in the order
 * LGCA_GRAV_* `order` gives at `step`. */
void lgca_gravity_moves(int order, uint64_t step, unsigned char mv[3][2]);
/* lgca_step.c: n steps (collision, gravity, walls, propagation, exits). */
int lgca_steps(lgca *L, uint64_t n, gr_err *err);
/* lgca_ref.c: the same step on one byte per node through the table, for
 * the tests (bytes[j * ni + i] in, out). */
int lgca_ref_step(const lgca *L, uint8_t *bytes, uint64_t step, gr_err *err);
void lgca_to_bytes(const lgca *L, uint8_t *bytes);

/* lgca_observe.c */
void lgca_observe(const lgca *L, gr_obs *o);
int lgca_fields(const lgca *L, gr_field *f, double w, gr_err *err);
void lgca_populations(const lgca *L, uint64_t *moving, uint64_t *resting);

/* lgca_stress.c: the kinetic stress window (methods/method.h's stress);
 * sample adds the state after a step while a window is open. */
void lgca_stress_sample(lgca *L);
int lgca_stress(lgca *L, int nx, int ny, double global[4], double *cells, gr_err *err);
int lgca_stress_save(const lgca *L, gr_ckpt *ck, gr_err *err);
int lgca_stress_load(lgca *L, gr_ckpt *ck, gr_err *err);

#endif
