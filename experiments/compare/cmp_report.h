/* The results of one case, pooled (cmp_report.c), for the tables and
 * figures (cmp_output.c). */
#ifndef GR_CMP_REPORT_H
#define GR_CMP_REPORT_H

#include "cmp.h"

/* A (row, knob value): its runs over seeds pooled. */
typedef struct {
    const cmp_row *row;
    char value[32];
    int n, nok;            /* runs, finished runs */
    double mean, sem;      /* the measured quantity and its error bar */
    double aux;            /* the second quantity (mean over seeds) */
    double wall, steps;    /* per run */
    double ref, ref_sem, aux_ref; /* what the error is against: the case's reference, or a
                                     CMP_OWN row's own answers (mean over its runs) */
    double own_ratio, own_ratio_sem; /* a CMP_OWN row: value / own answer, mean over runs */
    double error, error_sem; /* |mean - ref| / |ref| and sem / |ref| */
    char msg[640];         /* the first failure */
    char diag[CMP_DIAG];   /* the first run's broken validity limits ("" if none) */
    double fail_wall;      /* mean wall time of the failed runs to their failure */
    int outcome;           /* against the case's tolerance (CMP_OUT_*) */
} cmp_point;

/* A point's outcome against its case's tolerance: every run failed, some
 * failed, the error clearly within the tolerance (error + 2 error bars),
 * clearly beyond it (error - 2 error bars), or the error bar straddles it. */
enum { CMP_OUT_FAILED, CMP_OUT_SOME_FAILED, CMP_OUT_WITHIN, CMP_OUT_BEYOND, CMP_OUT_UNCLEAR, CMP_OUT_NONE };
/* Its name in the tables ("failed", "some runs failed", "within", "beyond",
 * "unclear", "no tolerance"). */
const char *cmp_outcome_name(int outcome);

/* A case's references: the value errors are taken against (the
 * CMP_REFERENCE row's result, or the analytic value), its error bar, and
 * the analytic value (NaN when the case has none); the same for aux. */
typedef struct {
    double value, sem, analytic;
    double aux, aux_analytic;
} cmp_refs;

/* The tolerance row r's errors are held to: its own, else the case's. */
double cmp_row_tol(const cmp_case *c, const cmp_row *r);
/* The points of case c in plan order (room for pl->nunits) and its
 * references (NaN when the case has no runs). */
int cmp_collect(const cmp_plan *pl, char *const *parts, const cmp_case *c, cmp_point *pts, size_t *npts,
                cmp_refs *ref, gr_err *err);
/* The checks (printed); returns how many failed. quick: the plan is
 * --quick's (the tolerance is checked where a row ends as in the full). */
int cmp_check(const cmp_case *c, const cmp_point *pts, size_t n, const cmp_refs *ref, int quick);

#endif
