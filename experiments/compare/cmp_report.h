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
    double error, error_sem; /* |mean - ref| / |ref| and sem / |ref| */
    char msg[240];         /* the first failure */
} cmp_point;

/* The points of case c in plan order (room for pl->nunits), its reference
 * and aux reference (NaN when the case has no runs). */
int cmp_collect(const cmp_plan *pl, char *const *parts, const cmp_case *c, cmp_point *pts, size_t *npts,
                double *ref, double *aux_ref, gr_err *err);
/* The checks (printed); returns how many failed. */
int cmp_check(const cmp_case *c, const cmp_point *pts, size_t n);

#endif
