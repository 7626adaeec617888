/* Event-driven hard disks (edmd): the public API beyond the method table,
 * for the course programs, benchmarks and tests (counters, exact time
 * averages, hydrodynamic fields on the event cells, the bare engine). */
#ifndef GR_EDMD_H
#define GR_EDMD_H

#include <stdint.h>

#include "method.h"

extern const gr_method_type gr_edmd_method;

typedef enum { GR_EDMD_TREE = 0, GR_EDMD_NAIVE } gr_edmd_algorithm;
typedef enum {
    GR_EDMD_COLLAPSE_NONE = 0,
    GR_EDMD_COLLAPSE_TC,
    GR_EDMD_COLLAPSE_THRESHOLD,
    GR_EDMD_COLLAPSE_SLEEP /* tc, and slow supported grains sleep (docs/methods/edmd.md) */
} gr_edmd_collapse;

/* The [edmd] section of a scene (docs/methods/edmd.md). */
typedef struct {
    gr_edmd_algorithm algorithm; /* tree (O(log N) per event) or naive (v1.0, O(N^2)) */
    double cell;                 /* minimum cell side; 0 = largest diameter */
    gr_edmd_collapse collapse;   /* guard against inelastic collapse */
    double tc;                   /* TC model: elastic if a partner collided less than tc ago */
    double v_threshold;          /* threshold model: elastic below this normal speed */
    double v_sleep;              /* sleep model: a supported grain slower than this sleeps */
    double v_wake;               /* sleep model: an impact faster than this wakes a sleeper */
    int fields;                  /* accumulate hydrodynamic fields on the cells */
    double sort_every;           /* collisions per grain between spatial re-sorts; 0 never, < 0 auto */
    int tree_arity;              /* 2: the slides' complete binary tree; 4: every other level elided */
    int calendar;                /* event queue: 1 Paul's calendar, 0 the tree (same events) */
} gr_edmd_params;

void gr_edmd_params_default(gr_edmd_params *p);
/* Read [edmd] of sc (defaults for absent keys). */
int gr_edmd_params_read(const gr_scene *sc, gr_edmd_params *p, gr_err *err);

typedef struct gr_edmd gr_edmd;

/* Create from a scene, its particles and explicit parameters (the method
 * table's create reads them from the scene). */
/* rng: the stream of floor phases and reinsertion spots (GR_STREAM_EDMD),
 * the caller's and saved by it; NULL: one of its own, saved here. */
int gr_edmd_create(const gr_scene *sc, const gr_particles *init, const gr_edmd_params *prm, struct gr_rng *rng,
                   gr_edmd **out, gr_err *err);
void gr_edmd_free(gr_edmd *s);
/* Advance to t_end or until max_collisions state-changing events (pair,
 * wall and floor collisions; 0 = no limit). */
int gr_edmd_advance(gr_edmd *s, double t_end, uint64_t max_collisions, gr_err *err);
double gr_edmd_time(const gr_edmd *s);
/* Change the restitution from now on (e.g. quench an equilibrated elastic
 * gas); alpha_wall NaN = alpha. Pending events stay valid: restitution only
 * enters the collision rules. */
void gr_edmd_set_restitution(gr_edmd *s, double alpha, double alpha_wall);

typedef struct {
    uint64_t pair;      /* disk-disk collisions (CPP) */
    uint64_t wall;      /* hard-wall collisions (CPD), floor included */
    uint64_t floor;     /* of which with the (vibrating) floor */
    uint64_t crossing;  /* virtual-wall crossings (CPV) */
    uint64_t stale;     /* predicted events dropped by the collision counters */
    uint64_t elastic_guard; /* collisions made elastic by the collapse guard */
    uint64_t sleeps, wakes; /* grains put to sleep, woken (collapse = sleep) */
} gr_edmd_counters;
void gr_edmd_get_counters(const gr_edmd *s, gr_edmd_counters *c);

/* Exact time averages since the last gr_edmd_reset_averages (or creation). */
typedef struct {
    double t0, t1;           /* averaging window */
    double ekin;             /* <K> translational + rotational */
    double ekin_rot;         /* <K_rot> */
    double epot;             /* <U> = <sum m g y> */
    double pressure[4];      /* per side (GR_LEFT...): momentum given to the side / (length time) */
    double pressure_walls;   /* all hard sides together */
    double virial_pressure;  /* bulk pressure from the collisional virial and <K> (periodic boxes) */
    double collision_rate;   /* pair collisions per unit time */
    double dissipation_rate; /* energy lost in collisions per unit time */
    double injection_rate;   /* energy given by the floor and moving walls per unit time */
    double e_injected, e_dissipated; /* totals over the window */
    uint64_t pair, wall;     /* collisions in the window */
} gr_edmd_averages;
void gr_edmd_reset_averages(gr_edmd *s);
void gr_edmd_get_averages(gr_edmd *s, gr_edmd_averages *a);

/* Hydrodynamic fields on the event cells, exact time averages over the
 * window of the averages (needs params.fields). Arrays are nx*ny, row major
 * (index ix + nx*iy); pxx.. is the pressure tensor (kinetic + collisional). */
typedef struct {
    int nx, ny;
    double x0, y0, cx, cy;
    double *density;        /* number per unit area */
    double *ux, *uy;        /* mean velocity */
    double *temperature;    /* m <|c|^2> / 2 per grain */
    double *qx, *qy;        /* heat flux (kinetic + collisional) */
    double *pxx, *pxy, *pyy;
    double *dissipation;    /* energy lost per unit time and area */
} gr_edmd_fields;
/* Fill f (arrays allocated here; free with gr_edmd_fields_free). */
int gr_edmd_get_fields(gr_edmd *s, gr_edmd_fields *f, gr_err *err);
void gr_edmd_fields_free(gr_edmd_fields *f);

/* The stress tensor averaged over the window since the previous call, on
 * nx x ny cells tiling the scene's domain (the method table's stress,
 * methods/method.h): kinetic (each grain's moments integrated between its
 * events, in the cell of the flight's midpoint) plus collisional (l (x) J of
 * every pair collision, shared between the cells of the two centres in
 * proportion to their radii, and r n (x) J of every wall collision, in the
 * grain's cell). The first call starts the window and gives NaN. */
int gr_edmd_stress(gr_edmd *s, int nx, int ny, double global[4], double *cells, gr_err *err);

/* Bookkeeping totals since creation: energy injected by the floor and
 * walls, lost in pair and wall collisions (exact sums over events). */
void gr_edmd_energy_budget(const gr_edmd *s, double *injected, double *dissipated);

/* One callback per state-changing event (tests and the course): kind 0
 * pair (i<j ids), 1 wall/floor (j = -1 - wall id). */
typedef void (*gr_edmd_event_fn)(void *user, int kind, long i, long j, double t);
void gr_edmd_set_event_hook(gr_edmd *s, gr_edmd_event_fn fn, void *user);

/* Snapshot of the current state (id order, at the current time). */
int gr_edmd_snapshot(gr_edmd *s, gr_particles *out, gr_err *err);
int gr_edmd_save(const gr_edmd *s, gr_ckpt *ck, gr_err *err);
int gr_edmd_load(gr_edmd *s, gr_ckpt *ck, gr_err *err);

#endif
