/* Contact dynamics backend (Moreau-Jean): internal interface shared by the
 * backend's files and its tests. Not part of method.h. */
#ifndef GR_CD_INT_H
#define GR_CD_INT_H

#include <stddef.h>
#include <stdint.h>

#include "ckpt.h"
#include "contacts.h"
#include "err.h"
#include "grid.h"
#include "observe.h"
#include "params.h"
#include "particles.h"
#include "rng.h"
#include "scene.h"

typedef enum { GR_CD_SEQUENTIAL = 0, GR_CD_SHUFFLED, GR_CD_RANDOM, GR_CD_SYMMETRIC, GR_CD_HEIGHT } gr_cd_order;

/* A contact's sorting key for the height order. */
typedef struct {
    double y;
    size_t k;
} gr_cd_key;

/* The [cd] section (docs/methods/cd.md). */
typedef struct {
    double dt, theta, tol, gap;
    double relax;   /* over-relaxation factor of the local updates */
    long max_iter, check_every;
    int order;      /* gr_cd_order */
    int accel;      /* Nesterov's momentum on the sweeps */
    int strict;     /* non-convergence at max_iter is an error */
    int warm;       /* warm start from the previous step's impulses */
} gr_cd_params;

/* A wall segment of infinite mass; a vibrating one follows the floor. */
typedef struct {
    double x0, y0, x1, y1, open_time;
    int vibrating;
} gr_cd_wall;

/* A contact of grain i with grain j (j < n) or wall j - n: identity (i, j),
 * unit normal from j to i, gap at the start of the step, the diagonal of
 * its 2x2 Delassus block (W_nt = 0 for disks), its restitutions, the
 * relative velocity at the start of the step and the impulses. */
typedef struct {
    int64_t i, j;
    double nx, ny, g;
    double wn, wt;
    double en, et;
    double un0, ut0;
    double vwx, vwy;   /* wall velocity over the step (walls only) */
    double rn, rt;
    double dmin;       /* smaller diameter of the pair, for overlaps */
    int status;        /* last local solution: gr_cd_status */
    int closed;        /* Jean's rule in the last sweep: 1 closed, 0 open, -1 not yet */
    int flips;         /* changes of that decision in this step's sweeps */
    int flipped;       /* the last visit changed that decision */
} gr_cd_contact;

/* The four cases of the single-contact problem. */
typedef enum { GR_CD_OPEN = 0, GR_CD_STICK, GR_CD_SLIDE_FWD, GR_CD_SLIDE_BWD } gr_cd_status;

typedef struct {
    gr_cd_contact *c;
    size_t n, cap;
} gr_cd_list;

/* Results of the sweeps of one step. */
typedef struct {
    long sweeps;
    int converged;
    double residual;
    size_t active, sliding;
    size_t forced_open; /* contacts left open by the flip rule */
} gr_cd_solve_info;

typedef struct gr_cd {
    gr_scene sc;             /* shallow copy: pointers stay the caller's */
    gr_cd_params par;
    double mu, en, et, enw, etw; /* grain-grain and wall restitutions */
    double g, Lx, Ly, dmax;
    size_t n;                /* every grain ever, index = rank of its id */
    gr_particles *p;         /* state at time t (flags GONE for grains that left) */
    double *im, *iI;         /* inverse mass and inertia, 0 for fixed grains */
    double *vx, *vy, *w;     /* new velocities during a step */
    double *x1, *y1;         /* new positions during a step */
    unsigned char *skip;     /* grains out of detection (gone) */
    gr_cd_wall *wall;
    int nwall;
    gr_grid *grid;
    gr_cd_list cur, prev;    /* this step's contacts, the last committed step's */
    size_t *perm, perm_cap;  /* visiting order of a sweep */
    gr_cd_key *key;          /* height order: contacts by height (perm_cap of them) */
    double *racc;            /* momentum: per contact, the last sweep's impulses and its start */
    gr_rng *order_rng, *reinsert_rng;
    int gates_open;
    uint64_t step, sweeps, nonconv, outflow, lost;
    uint64_t forced;         /* steps that left a contact open by the flip rule (not saved) */
    double t, last_residual, max_ovl;
    size_t last_active, last_sliding;
    double wall_impulse, wall_time;
    gr_particles *scratch;
} gr_cd;

/* Relative velocity of the contact point of i with respect to j (or the
 * wall) on the new velocities: normal and tangential (t = n rotated by +90
 * degrees) components. */
static inline void gr_cd_rel(const gr_cd *d, const gr_cd_contact *c, double *un, double *ut)
{
    const double *r = d->p->radius;
    size_t i = (size_t)c->i, j = (size_t)c->j;
    double dvx = d->vx[i], dvy = d->vy[i], spin = d->w[i] * r[i];
    if (j < d->n) {
        dvx -= d->vx[j], dvy -= d->vy[j];
        spin += d->w[j] * r[j];
    } else {
        dvx -= c->vwx, dvy -= c->vwy;
    }
    *un = dvx * c->nx + dvy * c->ny;
    *ut = -dvx * c->ny + dvy * c->nx - spin;
}

/* cd_params.c: the table and its values. */
extern const gr_param gr_cd_param_table[];
void gr_cd_params_from(const gr_param_values *pv, gr_cd_params *p);

/* cd_contacts.c: the contacts of the current positions, within margin of
 * touching, at time t (wall velocities over [t, t + dt]); then the
 * previous step's impulses matched by identity (warm start). */
int gr_cd_detect(gr_cd *d, double margin, gr_err *err);
void gr_cd_warm_start(gr_cd *d);

/* cd_solve.c: the non-linear Gauss-Seidel sweeps on the new velocities
 * (which hold the free velocities plus the warm-start impulses). */
int gr_cd_solve(gr_cd *d, gr_cd_solve_info *info, gr_err *err);
/* cd_order.c: d->perm[0..n) for sweep s (from 1); d->perm and d->key hold n. */
void gr_cd_visit_order(gr_cd *d, size_t n, long s);
/* Apply impulse (dn, dt) of contact c to the new velocities. */
void gr_cd_apply(gr_cd *d, const gr_cd_contact *c, double dn, double dtn);

/* cd_export.c: the current step's local problem u = W r + q, dense and
 * row-major (tests/oracle/fc2d.h), for the oracle test and the bench:
 * contacts k[0..nc) of cur (with closed_only, those whose predicted gap
 * closes on the current velocities: the others carry no impulse), r their
 * impulses, u their local velocities (+ e u- with restitution e), q = u - W r. */
typedef struct {
    int nc;
    size_t *k;
    double *W, *q, *mu, *r, *u;
} gr_cd_local;
int gr_cd_local_export(const gr_cd *d, int closed_only, gr_cd_local *lp, gr_err *err);
void gr_cd_local_free(gr_cd_local *lp);

/* cd_step.c: gr_cd_begin is a step's start (gates, free velocities into
 * the new-velocity arrays, contacts with zero impulses), which gr_cd_step
 * goes on from; alone, for the oracle test and the bench. */
int gr_cd_begin(gr_cd *d, gr_err *err);
int gr_cd_step(gr_cd *d, gr_err *err);
int gr_cd_advance(gr_cd *d, double t_end, uint64_t max_steps, gr_err *err);

/* cd_state.c */
int gr_cd_create(const gr_scene *sc, const gr_particles *init, const gr_cd_params *par,
                 gr_rng *order_rng, gr_rng *reinsert_rng, gr_cd **out, gr_err *err);
void gr_cd_free(gr_cd *d);
int gr_cd_snapshot(gr_cd *d, gr_particles *out, gr_err *err);
int gr_cd_observe(gr_cd *d, gr_obs *o, gr_err *err);
void gr_cd_reset_window(gr_cd *d);

/* cd_ckpt.c */
int gr_cd_save(const gr_cd *d, gr_ckpt *ck, gr_err *err);
int gr_cd_load(gr_cd *d, gr_ckpt *ck, gr_err *err);

/* cd_network.c: the last step's contacts that carry a force, as forces on
 * grain i along n (from j to i) and t (n rotated by +90 degrees). */
int gr_cd_contacts(const gr_cd *d, gr_contacts *out, gr_err *err);

#endif
