/* The answer a user comes for: per case, the cost each method line needs
 * to reach a relative error of 1, 5 and 10 %, interpolated along its
 * knob; and across cases the cheapest method for each (the guide).
 * Calls nothing of compare's but its types. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmp_reach.h"

const double cmp_reach_targets[CMP_NTARGETS] = {0.01, 0.05, 0.10};

static const double tiny = 1e-16; /* errors below are drawn and interpolated there */

/* The wall time at which errors e[0..m) (coarse to fine) first fall to
 * E: interpolated log-log between the last point above E and the first at
 * or below it; the first point's own cost when it is already there; NaN
 * when no point reaches E. */
static double cost_at(const double *e, const double *w, int m, double E)
{
    for (int i = 0; i < m; i++) {
        if (!(e[i] <= E))
            continue;
        if (i == 0)
            return w[0];
        double a = log(fmax(e[i - 1], tiny)), b = log(fmax(e[i], tiny)), t = (log(E) - a) / (b - a);
        return exp(log(w[i - 1]) + t * (log(w[i]) - log(w[i - 1])));
    }
    return NAN;
}

/* One method line's points (pts[first..first+m), coarse to fine). */
static void reach_row(const cmp_point *p, int m, cmp_reach_row *r)
{
    double e[CMP_MAXVALUES], lo[CMP_MAXVALUES], hi[CMP_MAXVALUES], w[CMP_MAXVALUES];
    int k = 0;
    for (int i = 0; i < m && k < CMP_MAXVALUES; i++)
        if (p[i].nok > 0 && isfinite(p[i].error) && p[i].wall > 0) {
            double s = isfinite(p[i].error_sem) ? p[i].error_sem : 0;
            e[k] = p[i].error, lo[k] = fmax(p[i].error - s, 0), hi[k] = p[i].error + s, w[k] = p[i].wall;
            k++;
        }
    r->row = p[0].row;
    for (int t = 0; t < CMP_NTARGETS; t++) {
        double E = cmp_reach_targets[t];
        r->cost[t] = cost_at(e, w, k, E);
        r->first[t] = k > 0 && e[0] <= E;
        r->cost_lo[t] = cost_at(lo, w, k, E);
        r->cost_hi[t] = cost_at(hi, w, k, E);
    }
}

size_t cmp_reach(const cmp_point *pts, size_t n, cmp_reach_row *out)
{
    size_t nr = 0;
    for (size_t i = 0; i < n;) {
        size_t j = i;
        while (j < n && pts[j].row == pts[i].row)
            j++;
        if (pts[i].row->role != CMP_REFERENCE && nr < CMP_MAXROWS)
            reach_row(pts + i, (int)(j - i), &out[nr++]);
        i = j;
    }
    return nr;
}

/* "0.0123 (0.011-0.014)", "<=0.012" when the coarsest setting already
 * reaches it, or "not reached". */
static void cell(char *s, size_t n, const cmp_reach_row *r, int t)
{
    const char *le = r->first[t] ? "<=" : "";
    if (!isfinite(r->cost[t]))
        snprintf(s, n, "not reached");
    else if (isfinite(r->cost_hi[t]))
        snprintf(s, n, "%s%.3g (%.3g-%.3g)", le, r->cost[t], r->cost_lo[t], r->cost_hi[t]);
    else
        snprintf(s, n, "%s%.3g (%.3g-not)", le, r->cost[t], r->cost_lo[t]);
}

void cmp_reach_text(FILE *f, const cmp_reach_row *r, size_t nr)
{
    fprintf(f, "  cost to reach a relative error of 1 %%, 5 %%, 10 %%: wall s per run along the knob (range: the "
               "error bars)\n");
    for (size_t i = 0; i < nr; i++) {
        char a[3][64];
        for (int t = 0; t < CMP_NTARGETS; t++)
            cell(a[t], sizeof a[t], &r[i], t);
        fprintf(f, "  %-12s %-26s %-26s %-26s%s\n", r[i].row->label, a[0], a[1], a[2],
                r[i].row->role == CMP_OWN ? " (against its own model)" : "");
    }
}

int cmp_reach_h5(exp_tab_file *h, const char *cname, const cmp_reach_row *r, size_t nr, gr_err *err)
{
    size_t m = nr ? nr * CMP_NTARGETS : 1, k = 0;
    const char **str = malloc(2 * m * sizeof *str);
    double *num = malloc(4 * m * sizeof *num);
    if (!str || !num) {
        free(str), free(num);
        return gr_fail(err, GR_ERUN, "out of memory");
    }
    for (size_t i = 0; i < nr; i++)
        for (int t = 0; t < CMP_NTARGETS; t++, k++) {
            str[k] = r[i].row->method, str[m + k] = r[i].row->label;
            num[k] = cmp_reach_targets[t], num[m + k] = r[i].cost[t];
            num[2 * m + k] = r[i].cost_lo[t], num[3 * m + k] = r[i].cost_hi[t];
        }
    const exp_col cols[] = {
        {"method", "", "registered method", EXP_STR, str, 0},
        {"variant", "", "the method line (its label in compare.txt)", EXP_STR, str + m, 0},
        {"target", "1", "relative error to reach", EXP_F64, num, 0},
        {"wall_s", "s", "wall time per run at which the error falls to target, interpolated log-log along the "
                        "knob (NaN: not reached)", EXP_F64, num + m, 0},
        {"wall_s_lo", "s", "the same with every error lowered by its error bar", EXP_F64, num + 2 * m, 0},
        {"wall_s_hi", "s", "the same with every error raised by its error bar (NaN: not reached)", EXP_F64,
         num + 3 * m, 0},
    };
    char name[128];
    snprintf(name, sizeof name, "reach/%s", cname);
    int rc = exp_tab_write(h, name, "the cost each method line needs to reach 1, 5 and 10 % error", k, cols,
                           sizeof cols / sizeof cols[0], err);
    free(str), free(num);
    return rc;
}

/* The cheapest line of case k at target t that is the case's own answer
 * (sweep rows: bias and model rows answer another question). */
static const cmp_reach_row *cheapest(const cmp_reach_row *r, size_t nr, int t)
{
    const cmp_reach_row *b = NULL;
    for (size_t i = 0; i < nr; i++)
        if (r[i].row->role == CMP_SWEEP && isfinite(r[i].cost[t]) && (!b || r[i].cost[t] < b->cost[t]))
            b = &r[i];
    return b;
}

void cmp_reach_guide(FILE *f, int markdown, const cmp_case *cs, const cmp_reach_row (*r)[CMP_MAXROWS],
                     const size_t *nr)
{
    if (markdown)
        fprintf(f, "| case | reference | 1 %% error | 5 %% error | 10 %% error |\n| --- | --- | --- | --- | --- |\n");
    else
        fprintf(f, "\n== guide: the cheapest method line to reach each relative error (wall s per run)\n");
    for (int k = 0; cs[k].name; k++) {
        if (!nr[k])
            continue;
        fprintf(f, markdown ? "| %s | %s |" : "%-14s %-10s", cs[k].name,
                cmp_ref_label(&cs[k]) ? cmp_ref_label(&cs[k]) : "analytic");
        for (int t = 0; t < CMP_NTARGETS; t++) {
            const cmp_reach_row *b = cheapest(r[k], nr[k], t);
            char s[96];
            if (b)
                snprintf(s, sizeof s, "%s %s%.3g s", b->row->label, b->first[t] ? "<=" : "", b->cost[t]);
            else
                snprintf(s, sizeof s, "none reached");
            fprintf(f, markdown ? " %s |" : " %-26s", s);
        }
        fprintf(f, "\n");
    }
}
