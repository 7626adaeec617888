/* Shared by `grano silo-start` and `grano silo-flow` (thesis chapters 3
 * and 4): the thesis silo built from a scene text for a given size,
 * orifice and seed; filling through a hopper and settling until the
 * kinetic energy has decayed; opening. Everything is deterministic from
 * seeds. The sweep over units of work is lib/sweep.h. */
#ifndef GR_SILO_COMMON_H
#define GR_SILO_COMMON_H

#include <stddef.h>
#include <stdint.h>

#include "err.h"
#include "method.h"
#include "particles.h"
#include "scene.h"

/* room for the --param lines of the method's section */
#define SILO_PARAMS 512

/* One silo. Lengths in grain diameters, times in tau = sqrt(d/g). */
typedef struct {
    long n;              /* mobile grains */
    double width, height; /* container inner size */
    double base;         /* y of the base's inner surface */
    double orifice;      /* D */
    int hopper;          /* fill through a hopper from a lattice above it;
                            0: lattice inside the container (quick modes) */
    double outlet;       /* the hopper's outlet, a fraction of the width */
    int reinsert;        /* grains that leave come back at the top */
    uint64_t seed;       /* lattice velocities and every stream after them */
    const gr_method_type *method; /* dem unless --method says otherwise */
    double dt;           /* dem's time step; for another method the time one
                            "step" of the experiments stands for */
    double ke_tol;       /* settled when kinetic energy per grain < ke_tol (m g d) */
    double fill_max;     /* give up settling at this simulated time */
    double band_lo, band_hi; /* reinsertion band; 0: the scene default */
    char params[SILO_PARAMS]; /* "key = value\n" lines for the method's own
                                 section (--param), replacing its defaults */
    char material[SILO_PARAMS]; /* the same for [material] (--material) */
} silo_cfg;

/* The hopper's outlet as a fraction of the width: the thesis gives no
 * size (fig. 3.1 shows a hopper over the container) and the packing the
 * discharges see does not depend on it (docs/experiments.md, "Filling"),
 * while the time of a filling does. */
#define SILO_OUTLET 0.6
/* a macro's value as a string (the usage texts) */
#define SILO_STR_(x) #x
#define SILO_STR(x) SILO_STR_(x)

/* The thesis silo (section 3.1) at full size, orifice D. */
void silo_cfg_thesis(silo_cfg *c, double D);
/* The small silo of the quick modes: n grains, a narrower container,
 * filled from a lattice inside it. */
void silo_cfg_quick(silo_cfg *c, double D);

/* The silo's [material] section: for dem Hertz with viscous damping and
 * regularised Coulomb friction (the thesis's eqs. 3.1-3.3 and constants),
 * for cd rigid disks with mu 0.5 and e = 0; the --material lines replace
 * the keys they name. */
void silo_material(const silo_cfg *c, char *mat, size_t nmat);

/* Scene text for the silo; the orifice opens at open_time (INFINITY:
 * closed). Returns the parsed scene or NULL. */
gr_scene *silo_scene(const silo_cfg *c, double open_time, gr_err *err);

/* The method named `name` (--method) into c->method; GR_EINPUT naming the
 * nearest method, or the first missing feature or operation, when it
 * cannot run the silo of c opened at its orifice. */
int silo_choose_method(silo_cfg *c, const char *name, gr_err *err);

/* A settled silo: every grain (walls, gate grains closing the orifice and
 * the mobile ones) after the filling. */
typedef struct {
    gr_particles *p;
    double t_settle;     /* simulated time of the filling and settling */
    double top;          /* height of the highest mobile grain */
    double ekin;         /* kinetic energy per grain at the end */
    gr_particles *filling; /* a picture of the filling (thesis fig. 3.1), may be NULL */
    double t_filling;
    double lift;         /* silo_rebase: how far the packing was lifted */
    double *trace;       /* silo_fill: per check, SILO_TRACE values: time
                            (tau), CPU s, grains inside, kinetic energy per
                            grain (m g d); where a filling's time goes */
    size_t ntrace;
} silo_settled;
#define SILO_TRACE 4

/* How often a filling or a branch checks whether it has settled (tau):
 * it stops at the first check that passes, half a check late on average,
 * and a check (a snapshot and a sort of the energies) costs 0.3 % of the
 * steps between two. */
#define SILO_CHECK 0.1

/* Fill and settle: run with the orifice closed until every grain is inside
 * the container and the kinetic energy per grain is below ke_tol (checked
 * every SILO_CHECK). progress (may be NULL) receives the fraction done. */
int silo_fill(const silo_cfg *c, silo_settled *out, volatile double *progress, gr_err *err);
void silo_settled_free(silo_settled *s);

/* A settled silo branched to the orifice of c (settle once, branch many):
 * the mobile grains of s, at rest, on the walls and closed gates of c. The
 * base grains sit from the orifice's edges outwards, so another orifice
 * moves them under the bottom layer: the packing is lifted by the least
 * height that clears them (at most about 0.14 d) and settles again onto
 * the new base, until its kinetic energy is below ke_tol again or for
 * SILO_BRANCH_MAX tau at most (a frictional pile creeps with 1e-4 to 1e-3
 * m g d per grain for tens of tau, docs/experiments.md, so a branch must
 * not wait on it as long as a filling may); out->ekin says where it
 * stopped. */
#define SILO_BRANCH_MAX 5.0
int silo_rebase(const silo_cfg *c, const silo_settled *s, silo_settled *out, volatile double *progress,
                gr_err *err);

/* An instance on the settled grains whose orifice opens at its first step
 * (its clock restarts at 0, so times are times after opening). Grains that
 * leave are reinserted (when c->reinsert) in a band from 1 d to 5 d above
 * the settled packing's highest grain, so that they land on its surface
 * and the height stays constant. */
int silo_open(const silo_cfg *c, const silo_settled *s, gr_scene **sc, gr_sim **state,
              gr_err *err);

/* Advance exactly `steps` steps of dem, or steps * c->dt in time with
 * another method (for cd a whole number of its steps when steps is a
 * multiple of 20, which every chunk of the silo commands is). */
int silo_advance(const silo_cfg *c, gr_sim *sim, uint64_t steps, gr_err *err);

/* Append the --param and --material lines (if any) to a unit's key in buf, so that a
 * part made with other parameters is not reused. */
void silo_key_params(const silo_cfg *c, char *buf, size_t n);

/* dem's speed on the flowing silo, one thread, on an idle core
 * (particle-steps per CPU second, wall grains included; docs/experiments.md
 * "Measured cost"); the cost of a thesis-size filling and of a branch to
 * another orifice in steps at that speed (measured means): the estimates
 * printed before a full run. */
#define SILO_DEM_RATE 4.1e7
#define SILO_FILL_STEPS 3.0e5
#define SILO_BRANCH_STEPS 1.9e4
/* a branch to the filling's own orifice: its packing is lifted only off
 * the contact overlaps (0.014-0.024 d) and settles in 0.66 tau (mean) */
#define SILO_REBRANCH_STEPS 5.3e3
/* CPU seconds of `steps` steps of the silo c with dem; NAN for another
 * method (no estimate). */
double silo_cpu_estimate(const silo_cfg *c, double steps);

/* Highest mobile grain of a snapshot (-INFINITY if none). */
double silo_top(const gr_particles *p);
/* Height of the free surface: the mean height of the k highest mobile
 * grains (one layer for k = the silo width), robust to a loose grain perched
 * on top. */
double silo_surface(const gr_particles *p, size_t k, double *buf);
/* Mean packing fraction of the mobile grains over a rectangle (exact disk
 * areas). */
double silo_packing(const gr_particles *p, double x0, double y0, double x1, double y1);

#endif
