/* grano compare: the same scenes on every method, each at several settings
 * of its accuracy knob, cost against error (docs/comparison.md).
 *
 * A case is a scene file of experiments/scenes/compare/, a measurement made
 * through the method interface, a reference, and a table of rows: one row
 * per method line (the method, the knob, its values). Adding a method to a
 * case is adding a row. */
#ifndef GR_CMP_H
#define GR_CMP_H

#include <stddef.h>
#include <stdio.h>

#include "err.h"
#include "h5tab.h"
#include "method.h"
#include "particles.h"
#include "scene.h"
#include "watch.h"

#define CMP_MAXV 8      /* knob values per row */
#define CMP_MAXROWS 8   /* rows per case */

/* What a measurement gives: the quantity, its statistical error from
 * within the run (NaN when the run gives none), a second quantity (aux),
 * and the steps or events done. */
#define CMP_NBINS 24 /* profile bins, 1 d high from the floor's mean height */
#define CMP_DIAG 400 /* the validity limits a run broke, as text */
typedef struct {
    double value, sem, aux;
    double own, own_aux;          /* a CMP_OWN row's own answers for this run (else NaN) */
    double steps;
    char diag[CMP_DIAG];          /* "name count/steps (key), ..." or "" */
    exp_watch *watch;             /* the run's cost watch (cmp_advance), or NULL */
    int nprof;                    /* 4 * CMP_NBINS when the case measures profiles, else 0 */
    double prof[4 * CMP_NBINS];   /* number density, its error bar, temperature, its error bar */
} cmp_meas;

typedef struct cmp_case cmp_case;
/* Measure on a fresh instance of the scene. */
typedef int (*cmp_measure_fn)(const cmp_case *c, gr_sim *s, const gr_scene *sc, cmp_meas *out, gr_err *err);
/* The analytic or published value (and aux's in *aux_ref) for the scene,
 * or NULL. Errors are against the case's CMP_REFERENCE row when it has
 * one, else against this; edmd's tolerance is always against this. */
typedef double (*cmp_ref_fn)(const gr_scene *sc, double *aux_ref);
/* The initial grains (NULL: the scene's [init]). */
typedef int (*cmp_prepare_fn)(const gr_scene *sc, gr_particles *p, gr_err *err);

/* One line of a case's plot: a method swept over one knob. */
typedef struct {
    const char *method;  /* registered backend */
    const char *label;   /* line label ("dem", "dem-gear") */
    const char *knob;    /* "section.key" set for each value; NULL: no knob */
    const char *full;    /* comma-separated values of the full comparison */
    const char *quick;   /* those of --quick */
    const char *fixed;   /* further "section.key=value" settings, ';'-separated, or NULL */
    int role;            /* CMP_SWEEP, CMP_REFERENCE, CMP_BIAS, CMP_MODEL, CMP_LIMIT or CMP_OWN */
    const char *scene;   /* the row's own variant of the case's scene (same geometry, the
                            method's own model of what it cannot represent), or NULL */
    const char *why;     /* CMP_LIMIT: what the method lacks that the case needs (the
                            tables print it beside the row's outcome) */
    /* CMP_OWN: the row's own measurement of the case's quantity (NULL: the
     * case's; when set, on the scene's [init], not the case's prepare),
     * which also gives its model's own answer for the state the run
     * realised (cmp_meas.own); what that answer is (the tables print it);
     * the tolerance against it (0: the case's) */
    cmp_measure_fn measure;
    const char *own_label;
    double tol;
} cmp_row;
enum {
    CMP_SWEEP = 0,     /* its error must not grow as the knob is tightened (--quick checks) */
    CMP_REFERENCE = 1, /* its result is the case's reference (a long or exact run) */
    CMP_BIAS = 2,      /* shows a bias that grows along the knob: reported, not checked */
    CMP_MODEL = 3,     /* converges to its own model's answer, not the reference's: its
                          value must settle as the knob is tightened (checked), its error
                          against the reference is reported */
    CMP_LIMIT = 4,     /* the method models the scene's features but not the physics the
                          case measures: its outcome (a failed run with its diagnostic, or
                          an error beyond the case's tolerance) is the row's result, and
                          a value that clearly reaches the tolerance fails the check (the
                          row is then no limit: it must become a sweep) */
    CMP_OWN = 5        /* the method's model states the case's quantity differently from
                          the grains (a lattice gas): its errors are against its model's
                          own answer for each run (cmp_meas.own) and checked as a sweep's;
                          the guide and grano advise leave it out */
};

struct cmp_case {
    const char *name;
    const char *scene;     /* file name under the scenes folder */
    const char *quantity;  /* what value is, for tables and axes */
    const char *aux;       /* what aux is */
    const char *unit, *aux_unit; /* their units (H5MD's unit strings: "1", "d", "tau", "m d2 tau-2") */
    const char *quick_set; /* settings of --quick ("section.key=value;..."), or NULL */
    int seeds_full, seeds_quick; /* independent realisations */
    double tol_edmd;       /* edmd's relative deviation from the analytic value must stay
                              below this (--quick test); 0: none */
    double tol;            /* the error a user of the case accepts, against its reference:
                              a sweep row's finest setting must reach it within its error
                              bar, a limit row's must not clearly reach it (bias and model
                              rows are reported against it, not checked) */
    int advisory;          /* a user's scene (grano compare SCENE.ini): its checks are printed
                              as notes and do not fail the comparison */
    cmp_measure_fn measure;
    cmp_ref_fn reference;
    cmp_prepare_fn prepare;   /* NULL: the scene's [init] */
    cmp_row rows[CMP_MAXROWS]; /* ended by a NULL method */
};

/* The cases, NULL-name ended (cmp_cases.c). */
const cmp_case *cmp_cases(void);

/* The measurements (cmp_measure.c). */
int cmp_measure_collision(const cmp_case *c, gr_sim *s, const gr_scene *sc, cmp_meas *out, gr_err *err);
double cmp_ref_collision(const gr_scene *sc, double *aux_ref);
int cmp_prepare_collision(const gr_scene *sc, gr_particles *p, gr_err *err);
int cmp_measure_cooling(const cmp_case *c, gr_sim *s, const gr_scene *sc, cmp_meas *out, gr_err *err);
double cmp_ref_cooling(const gr_scene *sc, double *aux_ref);
int cmp_prepare_cooling(const gr_scene *sc, gr_particles *p, gr_err *err);
int cmp_measure_column(const cmp_case *c, gr_sim *s, const gr_scene *sc, cmp_meas *out, gr_err *err);
double cmp_ref_column(const gr_scene *sc, double *aux_ref);
int cmp_measure_eos(const cmp_case *c, gr_sim *s, const gr_scene *sc, cmp_meas *out, gr_err *err);
double cmp_ref_eos(const gr_scene *sc, double *aux_ref);
double cmp_ref_silo(const gr_scene *sc, double *aux_ref);
int cmp_measure_silo(const cmp_case *c, gr_sim *s, const gr_scene *sc, cmp_meas *out, gr_err *err);
int cmp_measure_silo_widths(const cmp_case *c, gr_sim *s, const gr_scene *sc, cmp_meas *out, gr_err *err);
double cmp_ref_silo_widths(const gr_scene *sc, double *aux_ref);
int cmp_measure_bed(const cmp_case *c, gr_sim *s, const gr_scene *sc, cmp_meas *out, gr_err *err);
/* The lattice gas's own rows (cmp_lattice.c): each run's own answer in out->own. */
int cmp_measure_lattice_column(const cmp_case *c, gr_sim *s, const gr_scene *sc, cmp_meas *out, gr_err *err);
int cmp_measure_lattice_cooling(const cmp_case *c, gr_sim *s, const gr_scene *sc, cmp_meas *out, gr_err *err);

/* Advance the unit's instance to t as grano run does: watched for a time
 * that stalls or a cost that grows past [run] max_cost_growth (an
 * inelastic collapse stops with the diagnostic instead of running for
 * ever), when m has a watch (cmp_unit.c). */
int cmp_advance(gr_sim *s, const gr_scene *sc, const cmp_meas *m, double t, gr_err *err);

/* The runs of a comparison: one per (case, row, knob value, seed). */
typedef struct {
    const cmp_case *c;
    const cmp_row *row;
    char value[32];   /* knob value as text ("" when no knob) */
    int seed;         /* 1, 2, ... */
} cmp_unit;

typedef struct {
    const cmp_case *cases; /* NULL-name ended; NULL: the built-in cases (cmp_cases) */
    int quick, jobs, force, progress;
    const char *out;     /* results folder */
    const char *scenes;  /* folder of the case scenes */
    cmp_unit *units;
    size_t nunits;
    char notes[4096];    /* "case: method: not modelled: <feature>" lines */
} cmp_plan;

/* Whether name is in the comma-separated list (NULL: every name is). */
int cmp_listed(const char *list, const char *name);
/* The plan's cases: pl->cases, or the built-in ones. */
const cmp_case *cmp_plan_cases(const cmp_plan *pl);
/* A user's scene's measurement: the case's quantity is an observable's
 * name, block-averaged over 10 instants of the run's second half; aux: its
 * value at the end (cmp_own.c). */
int cmp_measure_observable(const cmp_case *c, gr_sim *s, const gr_scene *sc, cmp_meas *out, gr_err *err);

/* Every unit of the chosen cases and methods (comma-separated lists, NULL:
 * all), with notes on the methods left out (cmp_plan.c). */
int cmp_plan_build(cmp_plan *pl, const char *cases, const char *methods, gr_err *err);

/* The scene of a unit: file (the row's own or the case's), quick settings,
 * the row's fixed settings, knob value and seed, parsed (cmp_unit.c). */
gr_scene *cmp_unit_scene(const cmp_plan *pl, const cmp_unit *u, gr_err *err);
/* Scene sc again with "section.key=value;..." applied to its text. */
gr_scene *cmp_scene_with(const gr_scene *sc, const char *settings, gr_err *err);
/* The sweep runner's unit function: runs unit `unit` of the plan (ctx)
 * and writes its part. */
int cmp_run_unit(size_t unit, const char *part, const char *key, void *ctx, volatile double *progress,
                 gr_err *err);
void cmp_unit_label(size_t unit, void *ctx, char *label, size_t n);
void cmp_unit_key(size_t unit, void *ctx, char *key, size_t n);

/* The profiles' table lines and HDF5 tables of case c, when its runs gave
 * profiles: each (row, value)'s against the CMP_REFERENCE row's
 * (cmp_profile.c). */
int cmp_profiles(const cmp_plan *pl, char *const *parts, const cmp_case *c, FILE *txt, exp_tab_file *h,
                 gr_err *err);
/* The names of a row's role ("sweep", "reference", "bias", "model"). */
const char *cmp_role_name(int role);
/* The label of case c's CMP_REFERENCE row; NULL when its reference is
 * the analytic value. */
const char *cmp_ref_label(const cmp_case *c);

/* Tables, figures and checks from the parts (cmp_output.c): returns
 * GR_ERUN when a --quick check fails (after writing everything). *drawn:
 * whether the figures were drawn (not without gnuplot on PATH; the tables
 * are written all the same). */
int cmp_report(const cmp_plan *pl, char *const *parts, int *drawn, gr_err *err);

#endif
