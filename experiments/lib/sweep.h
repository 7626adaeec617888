/* The sweep runner: independent units of work (realisations, orifice sizes)
 * spread over local cores with fork(), one part file per unit, so that an
 * interrupted sweep resumes without redoing finished parts. */
#ifndef GR_EXP_SWEEP_H
#define GR_EXP_SWEEP_H

#include <stddef.h>

#include "err.h"

/* A unit of work writes its part file (through a gr_ckpt, which appears
 * only once complete). key identifies the unit's parameters: a part whose
 * key differs is redone. */
typedef int (*exp_unit_fn)(size_t unit, const char *part_path, const char *key, void *ctx,
                           volatile double *progress, gr_err *err);

typedef struct {
    size_t nunits;
    int jobs;            /* concurrent processes */
    const char *dir;     /* where the parts go */
    const char *prefix;  /* part file names: <dir>/<prefix>-<unit label>.part */
    int progress;        /* progress line on a terminal */
    const char *what;    /* progress label */
    int force;           /* redo every unit, whatever parts exist */
    /* optional: called when the first unit run here has finished, and a
     * quarter, a half and three quarters of them, with the wall seconds
     * since the sweep began, the units finished and still to finish, and
     * the jobs (an estimate calibrated on this machine) */
    void (*paced)(void *paced_ctx, double elapsed, size_t finished, size_t left, int jobs);
    void *paced_ctx;
} exp_sweep;

/* label(unit) -> file-name label; key(unit) -> parameter key string. */
typedef void (*exp_label_fn)(size_t unit, void *ctx, char *label, size_t n);

/* Run every unit whose part is missing or stale, up to jobs at once; on
 * return paths[unit] names each part. Returns GR_ERUN naming the first
 * failed unit (the others still run). *done_before counts parts reused. */
int exp_sweep_run(const exp_sweep *sw, exp_unit_fn fn, exp_label_fn label, exp_label_fn key,
                  void *ctx, char **paths, size_t *done_before, gr_err *err);

/* The whole sweep of a command: run (or reuse) every unit, then
 * report(ctx, parts, summary, nsum, err) from all the parts. *seconds is
 * the wall time of the units, *reused the parts found done. */
typedef int (*exp_report_fn)(const void *ctx, char *const *parts, char *summary, size_t nsum,
                             gr_err *err);
int exp_sweep_and_report(const exp_sweep *sw, exp_unit_fn fn, exp_label_fn label, exp_label_fn key,
                         exp_report_fn report, void *ctx, char *summary, size_t nsum,
                         double *seconds, size_t *reused, gr_err *err);

#endif
