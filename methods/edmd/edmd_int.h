/* Internal state of the event-driven backend, shared by its files. */
#ifndef GR_EDMD_INT_H
#define GR_EDMD_INT_H

#include <math.h>
#include <stdint.h>

#include "edmd.h"
#include "rng.h"
#include "stress.h"

#define EDMD_INF INFINITY
/* The depth (in d) a grain that stays in contact below the resolution of
 * the contact function may reach before its next contact (roots.c): a
 * tenth of what inside.c tolerates. */
#define EDMD_SLACK 1e-10
/* Trees with at least this many leaves (and their grains) outgrow the
 * caches: prefetching pays from there on. */
#define EDMD_PREFETCH_P 32768

/* A prefetch the compiler keeps: GCC drops __builtin_prefetch from loops
 * it can prove finite and otherwise free of side effects (seen at -O3 in
 * the look-ahead, whose every cell-head prefetch vanished). */
static inline void edmd_pf(const void *a)
{
#if defined(__x86_64__) || defined(__i386__)
    __asm__ volatile("prefetcht0 %0" : : "m"(*(const char *)a));
#else
    __builtin_prefetch(a);
    __asm__ volatile("" : : "r"(a));
#endif
}

/* Event kinds; `partner` holds the other particle, the crossing direction
 * or the wall id. */
enum { EV_PAIR = 0, EV_CROSS = 1, EV_WALL = 2 };
/* Crossing directions. */
enum { DIR_LEFT = 0, DIR_RIGHT = 1, DIR_DOWN = 2, DIR_UP = 3 };
/* Wall ids: the four sides (GR_LEFT...) and the moving floor. */
enum { W_FLOOR = 4, W_COUNT = 5 };
/* Exits (a grain leaving through an open side or below the silo) are wall
 * events W_EXIT; segment k of the scene is wall W_SEG + k. */
enum { W_EXIT = 5, W_SEG = 8 };

typedef struct {
    double t;
    int32_t partner; /* >= 0: the other grain; < 0: -1 - (direction or wall << 2 | kind) */
    uint32_t pncol;  /* partner's collision counter when predicted */
} edmd_ev;
static inline int edmd_ev_kind(const edmd_ev *e) { return e->partner >= 0 ? EV_PAIR : (-1 - e->partner) & 3; }
static inline int edmd_ev_sub(const edmd_ev *e) { return e->partner >= 0 ? e->partner : (-1 - e->partner) >> 2; }

/* The hot part of a particle: one cache line. Position and velocity are
 * those at time t, the particle's last state change (lazy advancement). */
typedef struct {
    double x, y, vx, vy, t, r;
    int32_t cell;    /* event cell, -1 when not in a cell (naive) */
    int16_t nev;     /* events in its slab */
    int16_t asleep;  /* collapse = sleep: at rest, fixed, no events of its own */
    int32_t cnext;   /* next particle in its cell */
    uint32_t ncol;   /* state changes so far (collision counter) */
} edmd_p;

/* An inner node of the tree: the earliest event below it. */
typedef struct {
    double t;
    int32_t i, pad;
} edmd_node;

/* Calendar queue (calendar.c): an entry is a grain and the time of its
 * earliest event when queued; a ring bucket is one 64-byte line. */
typedef struct {
    double t;
    int32_t i;
    int32_t pad; /* look-ahead stages done (front only) */
} edmd_qe;
#define EDMD_SLOT_N 4
typedef struct {
    double t[EDMD_SLOT_N];
    int32_t i[EDMD_SLOT_N];
    int32_t n, more; /* entries here; 1 + the next chunk, 0 = none */
    int32_t pad[2];
} edmd_slot;
typedef struct {
    double t;
    int64_t b;
    int32_t i;
} edmd_pend;
#define EDMD_PEND 16
/* Live entries per bucket near the present, and grains per ring bucket. */
#define EDMD_CAL_FILL 2.0
#define EDMD_CAL_SLOTDIV 1

/* The event queue: which grain holds the earliest of all the slabs'
 * slot 0 events. Two implementations pop the same events in the same
 * order (ties go to the lower index): the complete binary tree (tree.c,
 * edmd_queue_tree) and Paul's calendar (calendar.c, edmd_queue_calendar),
 * chosen at creation; the engine calls them through this table only. */
typedef struct {
    int (*init)(gr_edmd *s);               /* its room, once the slabs are there */
    int (*build)(gr_edmd *s);              /* anew from every slab's slot 0 */
    int (*update)(gr_edmd *s, int32_t i);  /* grain i's slot 0 may have changed */
    int32_t (*top)(gr_edmd *s, double *t); /* the next event's grain and time (INF: none);
                                              -2: out of memory */
    void (*pop)(gr_edmd *s);               /* the top event is being handled */
    void (*prefetch)(const gr_edmd *s, int32_t i); /* an update of grain i is coming */
    void (*free)(gr_edmd *s);
    int looks_ahead;                       /* requests the coming events' lines itself */
} edmd_queue;
extern const edmd_queue edmd_queue_tree, edmd_queue_calendar;

/* Per-cell field accumulators: time integrals of mass-weighted moments and
 * sums of collisional transfers over the averaging window. */
typedef struct {
    double n, m, mvx, mvy, mvxx, mvxy, mvyy, mv2vx, mv2vy;
    double cxx, cxy, cyy, cqx, cqy, diss;
} edmd_cellacc;
#define EDMD_CELLACC_N 15

struct gr_edmd {
    gr_edmd_params prm;
    gr_edmd_collapse collapse_asked; /* prm.collapse is it only while collisions dissipate */
    int sleep_on;            /* collapse = sleep under gravity: slow supported grains sleep */
    int32_t *wake_stack;     /* sleep: the sleepers a wake frees of a support, n of them at most */
    double t_gate;           /* sleep: the next gate opening, when every sleeper wakes */
    size_t n;
    edmd_p *p;
    double *w, *m, *inertia, *tlast, *tacc;
    double m_one;            /* the common mass when all are equal, else 0 */
    int64_t *id;
    int32_t *species;
    size_t *order;           /* internal indices in id order */

    /* scene */
    double W, H, ybot, g;    /* domain [0,W] x [ybot,H]; ybot < 0 for a floor that dips */
    int periodic_x, periodic_y;
    int hard[4];             /* side is a hard wall */
    double alpha, alpha_w, beta, mu;
    int rough;               /* rotation and tangential impulses */
    gr_floor_motion floor;   /* GR_FLOOR_FIXED: the bottom is an ordinary side */
    double fA, fomega, fV0;  /* amplitude, angular frequency, HF speed A omega */
    double rmax;
    /* segments (silo walls, gates) and exits */
    int nseg;
    gr_segment *seg;
    double *seg_len;
    int32_t *cseg_start, *cseg; /* per cell, the segments within reach (CSR) */
    double y_exit;           /* grains whose centre falls below leave; -INF: none */
    int open[4];             /* open sides: grains crossing them leave */
    int reinsert;
    gr_scene *sc_silo;       /* the silo part of the scene, for gr_reinsert_spot */
    uint8_t *gone;           /* per grain: left and not reinserted */
    uint64_t outflow;
    gr_particles *scratch;   /* snapshot for reinsertion */

    /* cells */
    int nx, ny;
    double cw, ch;
    int32_t *chead;
    uint8_t *wmask;          /* per cell: walls a grain in it can touch */
    int any_wall;            /* some cell has a wall in reach */
    int32_t *corder;         /* cells in Morton order, for spatial sorting */
    uint64_t sort_period;    /* collisions between re-sorts, 0 = never */
    uint64_t last_sort;      /* collision count at the last sort */
    /* the re-sort's room, kept from one sort to the next: freeing and
     * allocating it anew cost more than the sort itself at large N (the
     * kernel zeroes every fresh page) */
    edmd_p *sort_p;          /* grains in the new order; swapped with p */
    edmd_ev *sort_ev;        /* slabs in the new order; swapped with ev */
    size_t sort_ev_n;        /* events sort_ev holds */
    int32_t *sort_perm, *sort_inv;
    void *sort_buf;          /* n doubles */

    /* events */
    edmd_ev *ev;             /* n slabs of ecap events */
    int32_t ecap;
    const edmd_queue *q;     /* the event queue */
    edmd_ev *lf;             /* tree: leaves, a copy of each grain's slot 0 */
    edmd_node *node;         /* complete binary tree: inner nodes 1..P-1, node[1] the root */
    int32_t P;               /* tree leaves (power of K >= n); both queues' size class */
    int tshift;              /* log2 of the tree's branching K (1: binary) */
    edmd_slot *cal;          /* calendar: ring of cal_nb buckets */
    size_t cal_nb;
    double cal_inv_w;        /* 1 / bucket width */
    int64_t cal_b;           /* last bucket loaded into the front */
    size_t cal_count;        /* entries in the ring */
    size_t cal_loaded, cal_skipped, cal_steps; /* entries loaded and superseded, buckets, since the last check */
    int cal_retune;          /* rebuild with width cal_w_next (0: estimate) at the next pop */
    double cal_w_next;
    edmd_slot *chunk;        /* spill lines of full buckets */
    int32_t ch_n, ch_cap, ch_free;
    edmd_qe *fr;             /* front: loaded entries, sorted, fr[fr_head] first */
    int32_t fr_head, fr_n, fr_cap;
    edmd_pend pd[EDMD_PEND]; /* entries on their way to the ring */
    int pd_n;
    edmd_qe *ov;             /* more than a year ahead */
    size_t ov_n, ov_cap;

    double t;                /* current time */
    double t_prev_coll;
    uint64_t stuck;
    gr_edmd_counters cnt;
    uint64_t steps;
    gr_rng *rng;
    gr_rng *own_rng; /* rng when the caller gave none */

    /* global exact averages (measure.c) */
    double m_t;              /* bookkeeping time */
    double m_K, m_Krot, m_U, m_Smvy, m_Sm;
    double a_t0, a_K, a_Krot, a_U;
    double a_mom[4], a_virial, a_inj, a_diss;
    uint64_t a_pair0, a_wall0;
    double e_inj, e_diss;    /* since creation */
    double obs_t0, obs_mom;  /* wall momentum since the last window reset */
    edmd_cellacc *cacc;
    gr_stress_acc *stress;   /* the stress window (gr_edmd_stress), NULL until asked */

    gr_edmd_event_fn hook;
    void *hook_user;
};

/* Kinematics of free flight. */
static inline double edmd_x_at(const edmd_p *p, double t) { return p->x + p->vx * (t - p->t); }
static inline double edmd_y_at(const edmd_p *p, double t, double g)
{
    double s = t - p->t;
    return p->y + s * (p->vy - 0.5 * g * s);
}
static inline double edmd_vy_at(const edmd_p *p, double t, double g) { return p->vy - g * (t - p->t); }
/* The gravity a grain feels: none while it sleeps (it stays where it fell
 * asleep, at rest). Only the cold paths (snapshots, measurements, checks)
 * meet sleepers; the event loop never advances one. */
static inline double edmd_g_of(const edmd_p *p, double g) { return p->asleep ? 0.0 : g; }
/* Bring a particle's reference state to time t. */
static inline void edmd_advance_p(edmd_p *p, double t, double g)
{
    double s = t - p->t;
    p->x += p->vx * s;
    p->y += s * (p->vy - 0.5 * g * s);
    p->vy -= g * s;
    p->t = t;
}
static inline double edmd_min_image(double d, double L)
{
    if (L > 0.0 && fabs(d) > 0.5 * L)
        d -= L * nearbyint(d / L);
    return d;
}
/* Height y + vy s - g s^2/2: first s >= 0 at which it rises to a level dy
 * above, or falls to a level dy below (dy >= 0; a negative dy from
 * rounding means "already there"). */
static inline double edmd_rise_time(double dy, double vy, double g)
{
    if (vy <= 0.0)
        return EDMD_INF;
    if (dy <= 0.0)
        return 0.0;
    if (g == 0.0)
        return dy / vy;
    double disc = vy * vy - 2.0 * g * dy;
    if (disc < 0.0)
        return EDMD_INF;
    return 2.0 * dy / (vy + sqrt(disc));
}
static inline double edmd_fall_time(double dy, double vy, double g)
{
    if (g == 0.0) {
        if (vy >= 0.0)
            return EDMD_INF;
        return dy > 0.0 ? dy / -vy : 0.0;
    }
    double disc = vy * vy + 2.0 * g * dy;
    double sq = disc > 0.0 ? sqrt(disc) : 0.0;
    if (vy > 0.0)
        return (vy + sq) / g;
    if (dy <= 0.0)
        return 0.0;
    return 2.0 * dy / (sq - vy);
}

/* Grain i's event slab. Slot 0 holds its earliest event (time INF when
 * the slab is empty): the queue reads it from the slab's first line, which
 * the event needs anyway, rather than from a separate leaf array. */
static inline edmd_ev *edmd_slab(const gr_edmd *s, int32_t i) { return s->ev + (size_t)i * (size_t)s->ecap; }

/* Large systems whose queue does not look ahead: the engine and the
 * prediction request an event's lines themselves. */
static inline int edmd_engine_prefetches(const gr_edmd *s)
{
    return s->P >= EDMD_PREFETCH_P && !s->q->looks_ahead;
}

static inline int edmd_wrap_cell(const gr_edmd *s, int ix, int iy)
{
    if (ix < 0 || ix >= s->nx) {
        if (!s->periodic_x)
            return -1;
        ix = (ix + s->nx) % s->nx;
    }
    if (iy < 0 || iy >= s->ny) {
        if (!s->periodic_y)
            return -1;
        iy = (iy + s->ny) % s->ny;
    }
    return ix + s->nx * iy;
}

/* The 3x3 block of cells around grain i (no repeats in narrow periodic
 * boxes), in the order the pair loops visit them. */
static inline int edmd_block_cells(const gr_edmd *s, int32_t i, int cells[9])
{
    int c = s->p[i].cell, ix = c % s->nx, iy = c / s->nx;
    int ns = 0;
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++) {
            int cc = edmd_wrap_cell(s, ix + dx, iy + dy);
            if (cc < 0)
                continue;
            int dup = 0;
            for (int k = 0; k < ns; k++)
                dup |= cells[k] == cc;
            if (!dup)
                cells[ns++] = cc;
        }
    return ns;
}

/* Files, bottom-up (docs/methods/edmd.md, "Files and layers"). */

/* alloc.c */
void *edmd_big_alloc(size_t bytes);
edmd_ev *edmd_ev_alloc(size_t count);

/* cells.c */
int edmd_cell_of(const gr_edmd *s, double x, double y);
void edmd_cell_remove(gr_edmd *s, int32_t i);
void edmd_cell_insert(gr_edmd *s, int32_t i, int c);

/* roots.c */
double edmd_point_time(const gr_edmd *s, const edmd_p *p, double ex, double ey, double a, double b);
double edmd_floor_sine_time(const gr_edmd *s, const edmd_p *p, double a, double horizon);
/* GR_ERUN when a grain is below the floor or into a hard wall at t (inside.c) */
int edmd_check_inside(const gr_edmd *s, double t, gr_err *err);
/* Where a grain can meet a floor moving in [-A, A] with the given period:
 * [*a, *b] from *a, cut at the horizon; 0 if nowhere. */
int edmd_floor_band(const edmd_p *p, double g, double A, double period, double horizon, double *a,
                    double *b);

/* lookahead.c: front positions (0: the next event) of the look-ahead's
 * four stages: grain and slab; cell heads and partner; first grains and
 * the partner's heads; the partner's first grains. The calendar keeps its
 * front EDMD_CAL_AHEAD deep. */
#define EDMD_LA_1 9
#define EDMD_LA_2 7
#define EDMD_LA_3 5
#define EDMD_LA_4 3
#define EDMD_CAL_AHEAD 12
void edmd_lookahead(gr_edmd *s);

/* slab.c: per-grain event lists (slabs); edmd_events_init also sets up
 * the queue */
int edmd_events_init(gr_edmd *s, gr_err *err);
int edmd_ev_push(gr_edmd *s, int32_t i, double t, int kind, int32_t partner, uint32_t pncol);
void edmd_list_clear(gr_edmd *s, int32_t i);
void edmd_list_remove(gr_edmd *s, int32_t i, int32_t e);

/* segment.c */
int edmd_segments_setup(gr_edmd *s, const gr_scene *sc, gr_err *err);
double edmd_segment_time(const gr_edmd *s, int32_t i, int k, double t_from, double horizon);
/* unit normal from segment k to a grain at (x, y), and its distance */
double edmd_segment_normal(const gr_edmd *s, int k, double x, double y, double *nx, double *ny);

/* rest.c (collapse = sleep): 1 if grain i's static and slow contacts hold
 * it up against gravity; 1 if grain i moves slower than v_sleep; the
 * sleepers that may rest on grain j (touching it, beside or above), at
 * most cap of them into out; the first time after t a gate opens (INF:
 * none, or no sleep model) */
int edmd_held(const gr_edmd *s, int32_t i);
int edmd_slow(const gr_edmd *s, int32_t i);
size_t edmd_rests_on(const gr_edmd *s, int32_t j, int32_t *out, size_t cap);
double edmd_next_gate(const gr_edmd *s, double t);

/* predict.c */
double edmd_pair_time(const gr_edmd *s, const edmd_p *a, const edmd_p *b);
double edmd_wall_time(gr_edmd *s, int32_t i, int wall, double t_from, double horizon);
double edmd_cross_time(const gr_edmd *s, int32_t i, int *dir);
int edmd_wall_relevant(const gr_edmd *s, int cell, int wall);
int edmd_predict_all(gr_edmd *s, int32_t i);
int edmd_predict_cross(gr_edmd *s, int32_t i, int dir);
/* Grain i fell asleep: its moving neighbours predict their contacts with it. */
int edmd_sleep_neighbours(gr_edmd *s, int32_t i);
static inline int edmd_any_asleep(const gr_edmd *s) { return s->cnt.sleeps != s->cnt.wakes; }
void edmd_prefetch_block(const gr_edmd *s, int32_t i);

/* measure.c */
void edmd_measure_init(gr_edmd *s);
void edmd_measure_advance(gr_edmd *s, double t);
void edmd_field_flush(gr_edmd *s, int32_t i, double t);
void edmd_measure_pair(gr_edmd *s, int32_t i, int32_t j, double dvx_i, double dvy_i,
                       double dE_i, double dE_j, double dx, double dy);
double edmd_kinetic(const gr_edmd *s, int32_t i, double t);
/* Something is accumulated per grain and cell (fields or the stress
 * window): the events then flush the grains they touch. */
static inline int edmd_measuring_cells(const gr_edmd *s) { return s->cacc || s->stress; }
/* Every grain's moments up to time t. */
void edmd_field_flush_all(gr_edmd *s, double t);

/* snapshot.c: gr_edmd_snapshot */

/* collide.c: the collision rules; a grain leaves (reinserted at the top of
 * the silo or gone) */
void edmd_collide_pair(gr_edmd *s, int32_t i, int32_t j, double t);
void edmd_collide_wall(gr_edmd *s, int32_t i, int wall, double t);
/* Moving grain i meets sleeping grain j: j wakes, or i bounces off it. */
void edmd_collide_sleeper(gr_edmd *s, int32_t i, int32_t j, double t);
/* Sleeping grain j wakes at rest where it slept, falling again. */
void edmd_wake(gr_edmd *s, int32_t j, double t);
int edmd_exit(gr_edmd *s, int32_t i, double t, gr_err *err);

/* sort.c: renumber grains along a Morton curve over the cells */
int edmd_sort_setup(gr_edmd *s, gr_err *err);
int edmd_sort(gr_edmd *s, gr_err *err);

/* engine.c */
int edmd_advance_tree(gr_edmd *s, double t_end, uint64_t max_coll, gr_err *err);
int edmd_advance_naive(gr_edmd *s, double t_end, uint64_t max_coll, gr_err *err);
int edmd_schedule_all(gr_edmd *s, gr_err *err);

/* checkpoint.c: gr_edmd_save, gr_edmd_load; state.c: creation, the rest
 * of the public API */

#endif
