/* The cost each method line needs to reach 1, 5 and 10 % relative error,
 * interpolated along its knob, and the guide across cases (cmp_reach.c,
 * used by cmp_output.c). */
#ifndef GR_CMP_REACH_H
#define GR_CMP_REACH_H

#include <stdio.h>

#include "cmp_report.h"
#include "h5tab.h"

enum { CMP_NTARGETS = 3, CMP_MAXVALUES = 16 };
extern const double cmp_reach_targets[CMP_NTARGETS];

/* One method line: the wall time per run at which its error falls to
 * each target (NaN: not reached), and the same with every error lowered
 * (lo) or raised (hi) by its error bar. */
typedef struct {
    const cmp_row *row;
    double cost[CMP_NTARGETS], cost_lo[CMP_NTARGETS], cost_hi[CMP_NTARGETS];
    int first[CMP_NTARGETS]; /* reached at the coarsest setting: its cost bounds the cost from above */
} cmp_reach_row;

/* The lines of a case's points (plan order, room for CMP_MAXROWS),
 * the reference line left out; returns how many. */
size_t cmp_reach(const cmp_point *pts, size_t n, cmp_reach_row *out);
void cmp_reach_text(FILE *f, const cmp_reach_row *r, size_t nr);
int cmp_reach_h5(exp_tab_file *h, const char *cname, const cmp_reach_row *r, size_t nr, gr_err *err);
/* Per case, the cheapest sweep line at each target: as text, or as a
 * markdown table (markdown = 1). r[k], nr[k]: case k's lines. */
void cmp_reach_guide(FILE *f, int markdown, const cmp_case *cs, const cmp_reach_row (*r)[CMP_MAXROWS],
                     const size_t *nr);

#endif
