/* Shared by `grano silo-start` and `grano silo-flow` (thesis chapters 3
 * and 4): the thesis silo built from a scene text for a given size,
 * orifice and seed; filling through a hopper and settling until the
 * kinetic energy has decayed; opening; and a runner that spreads
 * independent units of work (realisations, orifice sizes) over local cores
 * with fork(), one part file per unit, so that an interrupted sweep resumes
 * without redoing finished parts. Everything is deterministic from seeds. */
#ifndef GR_SILO_COMMON_H
#define GR_SILO_COMMON_H

#include <stddef.h>
#include <stdint.h>

#include "ckpt.h"
#include "err.h"
#include "h5md.h"
#include "method.h"
#include "particles.h"
#include "scene.h"

/* One silo. Lengths in grain diameters, times in tau = sqrt(d/g). */
typedef struct {
    long n;              /* mobile grains */
    double width, height; /* container inner size */
    double base;         /* y of the base's inner surface */
    double orifice;      /* D */
    int hopper;          /* fill through a hopper from a lattice above it;
                            0: lattice inside the container (quick modes) */
    int reinsert;        /* grains that leave come back at the top */
    uint64_t seed;       /* lattice velocities and every stream after them */
    double dt;           /* DEM time step */
    double ke_tol;       /* settled when kinetic energy per grain < ke_tol (m g d) */
    double fill_max;     /* give up settling at this simulated time */
    double band_lo, band_hi; /* reinsertion band; 0: the scene default */
} silo_cfg;

/* The thesis silo (section 3.1) at full size, orifice D. */
void silo_cfg_thesis(silo_cfg *c, double D);
/* The small silo of the quick modes: n grains, a narrower container,
 * filled from a lattice inside it. */
void silo_cfg_quick(silo_cfg *c, double D);

/* Scene text for the silo; the orifice opens at open_time (INFINITY:
 * closed). Returns the parsed scene or NULL. */
gr_scene *silo_scene(const silo_cfg *c, double open_time, gr_err *err);

/* A settled silo: every grain (walls, gate grains closing the orifice and
 * the mobile ones) after the filling. */
typedef struct {
    gr_particles *p;
    double t_settle;     /* simulated time of the filling and settling */
    double top;          /* height of the highest mobile grain */
    double ekin;         /* kinetic energy per grain at the end */
    gr_particles *filling; /* a picture of the filling (thesis fig. 3.1), may be NULL */
    double t_filling;
} silo_settled;

/* Fill and settle: run with the orifice closed until every grain is inside
 * the container and the kinetic energy per grain is below ke_tol (checked
 * every 0.5 tau). progress (may be NULL) receives the fraction done. */
int silo_fill(const silo_cfg *c, silo_settled *out, volatile double *progress, gr_err *err);
void silo_settled_free(silo_settled *s);

/* A DEM state from the settled grains whose orifice opens at its first step
 * (its clock restarts at 0, so times are times after opening). Grains that
 * leave are reinserted (when c->reinsert) in a band from 1 d to 5 d above
 * the settled packing's highest grain, so that they land on its surface
 * and the height stays constant. */
int silo_open(const silo_cfg *c, const silo_settled *s, gr_scene **sc, gr_sim **state,
              gr_err *err);

/* Advance exactly `steps` steps. */
int silo_advance(gr_sim *sim, uint64_t steps, gr_err *err);

/* Highest mobile grain of a snapshot (-INFINITY if none). */
double silo_top(const gr_particles *p);
/* Height of the free surface: the mean height of the k highest mobile
 * grains (one layer for k = the silo width), robust to a loose grain perched
 * on top. */
double silo_surface(const gr_particles *p, size_t k, double *buf);
/* Mean packing fraction of the mobile grains over a rectangle (exact disk
 * areas). */
double silo_packing(const gr_particles *p, double x0, double y0, double x1, double y1);

/* ------------------------------------------------------------- the runner */

/* A unit of work writes its part file (through a gr_ckpt, which appears
 * only once complete). key identifies the unit's parameters: a part whose
 * key differs is redone. */
typedef int (*silo_unit_fn)(size_t unit, const char *part_path, const char *key, void *ctx,
                            volatile double *progress, gr_err *err);

typedef struct {
    size_t nunits;
    int jobs;            /* concurrent processes */
    const char *dir;     /* where the parts go */
    const char *prefix;  /* part file names: <dir>/<prefix>-<unit label>.part */
    int progress;        /* progress line on a terminal */
    const char *what;    /* progress label */
    int force;           /* redo every unit, whatever parts exist */
} silo_sweep;

/* label(unit) -> file-name label; key(unit) -> parameter key string. */
typedef void (*silo_label_fn)(size_t unit, void *ctx, char *label, size_t n);

/* Run every unit whose part is missing or stale, up to jobs at once; on
 * return paths[unit] names each part. Returns GR_ERUN naming the first
 * failed unit (the others still run). *done_before counts parts reused. */
int silo_sweep_run(const silo_sweep *sw, silo_unit_fn fn, silo_label_fn label,
                   silo_label_fn key, void *ctx, char **paths, size_t *done_before,
                   gr_err *err);

/* The whole sweep of a command: run (or reuse) every unit, then
 * report(ctx, parts, summary, nsum, err) from all the parts. *seconds is
 * the wall time of the units, *reused the parts found done. */
typedef int (*silo_report_fn)(const void *ctx, char *const *parts, char *summary, size_t nsum,
                              gr_err *err);
int silo_sweep_and_report(const silo_sweep *sw, silo_unit_fn fn, silo_label_fn label,
                          silo_label_fn key, silo_report_fn report, void *ctx, char *summary,
                          size_t nsum, double *seconds, size_t *reused, gr_err *err);

/* A result table: to the HDF5 file (columns named by cols_csv, comma
 * separated, or NULL) and as a plain .dat with a '# header' line. */
int silo_put_result(gr_h5md *h, const char *name, size_t rows, size_t cols, const char *cols_csv,
                    const char *desc, const double *v, gr_err *err);
int silo_write_dat(const char *path, const char *header, const double *v, size_t rows, size_t cols,
                   gr_err *err);

/* Part file helpers. */
int silo_part_key_matches(const char *path, const char *key);
int silo_put_particles(gr_ckpt *ck, const char *name, const gr_particles *p, gr_err *err);
int silo_get_particles(gr_ckpt *ck, const char *name, gr_particles *p, gr_err *err);
int silo_put_scalar(gr_ckpt *ck, const char *name, double v, gr_err *err);
double silo_get_scalar(gr_ckpt *ck, const char *name);
/* A whole f64 array of unknown length (malloc'd). */
int silo_get_array(gr_ckpt *ck, const char *name, double **v, size_t *n, gr_err *err);

/* The "cost" record of a part: wall and CPU seconds of the filling, of the
 * run after opening, and the steps of that run (NaN when absent). */
void silo_get_cost(gr_ckpt *ck, double cost[5]);

/* Make a directory and its parents. */
int silo_mkdirs(const char *dir, gr_err *err);

/* Parse a comma-separated list of positive numbers (at most cap). */
int silo_parse_list(const char *s, double *v, size_t cap, size_t *n);

#endif
