/* grano compare's outputs: compare.h5 (a typed table per case), compare.txt,
 * a speed-against-error figure per case and a summary figure, each with its
 * gnuplot script beside it. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmp.h"
#include "table.h"
#include "cmp_report.h"
#include "cmp_reach.h"
#include "h5tab.h"
#include "plot.h"

/* Errors below this are drawn at it on the log axis (exact methods). */
static const double floor_err = 1e-16;

/* Which row, if any, is the case's reference. */
static void text_case(FILE *f, const cmp_case *c, const cmp_point *pts, size_t n, const cmp_refs *ref)
{
    const char *rl = cmp_ref_label(c);
    fprintf(f, "\n== %s: %s: reference %.8g +- %.2g (%s)", c->name, c->quantity, ref->value, ref->sem,
            rl ? rl : "analytic");
    if (rl && isfinite(ref->analytic))
        fprintf(f, ", analytic %.8g", ref->analytic);
    fprintf(f, "; %s: reference %.6g", c->aux, ref->aux);
    if (c->tol > 0)
        fprintf(f, "; tolerance %.3g", c->tol);
    fprintf(f, "\n");
    fprintf(f, "%-9s %-14s %-9s %5s %9s %11s %-24s %-20s %12s %s\n", "method", "knob", "value", "runs", "wall/s",
            "steps", "measured +- error bar", "relative error", c->aux, "");
    for (size_t i = 0; i < n; i++) {
        const cmp_point *p = &pts[i];
        char meas[64], er[64];
        snprintf(meas, sizeof meas, "%.7g +- %.2g", p->mean, p->sem);
        snprintf(er, sizeof er, "%.3g +- %.2g", p->error, p->error_sem);
        int limit = p->row->role == CMP_LIMIT;
        int told = !(p->row->role == CMP_REFERENCE || p->outcome == CMP_OUT_NONE || p->nok < p->n);
        fprintf(f, "%-9s %-14s %-9s %2d/%-2d %9.3g %11.4g %-24s %-20s %12.5g %s%s%s\n", p->row->label,
                p->row->knob ? p->row->knob : "-", p->value[0] ? p->value : "-", p->nok, p->n,
                p->nok ? p->wall : p->fail_wall, p->steps, meas, er, p->aux,
                p->nok < p->n ? (limit ? "(failed: the method's limit)" : "FAILED")
                : p->row->role == CMP_REFERENCE ? "(reference)"
                : p->row->role == CMP_MODEL && p->error > 2 * p->error_sem ? "(its own model's answer)"
                : p->row->role == CMP_OWN ? "(against its own model)"
                : p->error > 2 * p->error_sem ? "" : "(within the error bar)",
                told ? " tolerance: " : "", told ? cmp_outcome_name(p->outcome) : "");
        if (limit && (i == 0 || pts[i - 1].row != p->row))
            fprintf(f, "          limit: %s\n", p->row->why ? p->row->why : "");
        if (p->row->role == CMP_OWN)
            fprintf(f, "          against its own model, not the case's reference: %s %.7g; %s %.6g\n",
                    p->row->own_label ? p->row->own_label : "", p->ref, c->aux, p->aux_ref);
        if (p->msg[0])
            fprintf(f, "          %s\n", p->msg);
        if (p->diag[0])
            fprintf(f, "          validity limits broken: %s\n", p->diag);
    }
}

/* The case's table: cases/<name>, a column per quantity, one row per
 * (method line, knob value), the knob value as the user wrote it. */
static int h_case(exp_tab_file *h, const cmp_case *c, const cmp_point *pts, size_t n, const cmp_refs *ref,
                   gr_err *err)
{
    size_t m = n ? n : 1;
    const char **str = malloc(9 * m * sizeof *str);
    double *num = malloc(15 * m * sizeof *num);
    if (!str || !num) {
        free(str), free(num);
        return gr_fail(err, GR_ERUN, "out of memory");
    }
    for (size_t i = 0; i < n; i++) {
        const cmp_point *p = &pts[i];
        const char *s[9] = {p->row->method, p->row->label, p->row->knob ? p->row->knob : "", p->value,
                            cmp_role_name(p->row->role),
                            p->row->role == CMP_REFERENCE ? "reference" : cmp_outcome_name(p->outcome),
                            p->msg, p->diag, p->row->role == CMP_OWN && p->row->own_label ? p->row->own_label : ""};
        double v[15] = {p->n, p->nok, p->wall, p->steps, p->mean, p->sem, p->ref, p->ref_sem, p->error,
                        p->error_sem, p->aux, p->aux_ref, ref->analytic, p->fail_wall, cmp_row_tol(c, p->row)};
        for (int k = 0; k < 9; k++)
            str[k * m + i] = s[k];
        for (int k = 0; k < 15; k++)
            num[k * m + i] = v[k];
    }
    const char *rl = cmp_ref_label(c);
    char dq[160], dref[200], daux[160], dauxref[200], dan[200], desc[400];
    snprintf(dq, sizeof dq, "%s, mean over the finished runs", c->quantity);
    snprintf(dref, sizeof dref, "%s of the reference (%s; an own row's: its own, named in against)", c->quantity,
             rl ? rl : "the analytic value");
    snprintf(daux, sizeof daux, "%s, mean over the finished runs", c->aux);
    snprintf(dauxref, sizeof dauxref, "%s of the reference (%s; an own row's: its own)", c->aux,
             rl ? rl : "the analytic value");
    snprintf(dan, sizeof dan, "analytic or published %s (NaN: none)", c->quantity);
    snprintf(desc, sizeof desc, "%s against %s: one row per (method line, knob value), seeds pooled", c->quantity,
             rl ? rl : "the analytic value");
    const exp_col cols[] = {
        {"method", "", "registered method that ran", EXP_STR, str, 0},
        {"variant", "", "the method line (its label in compare.txt and the figures)", EXP_STR, str + m, 0},
        {"knob", "", "scene keys the knob sets ('+' joins two keys set together; empty: none)", EXP_STR,
         str + 2 * m, 0},
        {"knob_value", "", "the knob's value as written in the case (':' between the values of two keys)",
         EXP_STR, str + 3 * m, 0},
        {"role", "", "sweep, reference, bias, model, limit or own (docs/comparison.md)", EXP_STR, str + 4 * m, 0},
        {"outcome", "", "against the case's tolerance: within, beyond or unclear (error +- 2 error bars), "
                        "failed, some runs failed, reference, no tolerance", EXP_STR, str + 5 * m, 0},
        {"message", "", "the first failed run's message, where it stopped (empty: none failed)", EXP_STR,
         str + 6 * m, 0},
        {"diagnostics", "", "validity limits the first run broke: name, count, the key that changes it",
         EXP_STR, str + 7 * m, 0},
        {"against", "", "an own row's reference, its model's own answer (empty: the case's reference)", EXP_STR,
         str + 8 * m, 0},
        {"runs", "1", "independent runs (seeds)", EXP_INT, num, 0},
        {"finished", "1", "runs that finished with finite numbers", EXP_INT, num + m, 0},
        {"wall_s", "s", "wall time per run", EXP_F64, num + 2 * m, 0},
        {"steps", "1", "steps (or events) per run, mean over the finished runs", EXP_F64, num + 3 * m, 0},
        {"value", c->unit, dq, EXP_F64, num + 4 * m, 0},
        {"value_sem", c->unit, "error bar of value (seed scatter, or the run's block average)", EXP_F64,
         num + 5 * m, 0},
        {"reference", c->unit, dref, EXP_F64, num + 6 * m, 0},
        {"reference_sem", c->unit, "error bar of reference (0 when analytic)", EXP_F64, num + 7 * m, 0},
        {"rel_error", "1", "|value - reference| / |reference|", EXP_F64, num + 8 * m, 0},
        {"rel_error_sem", "1", "error bar of rel_error", EXP_F64, num + 9 * m, 0},
        {"aux", c->aux_unit, daux, EXP_F64, num + 10 * m, 0},
        {"aux_reference", c->aux_unit, dauxref, EXP_F64, num + 11 * m, 0},
        {"analytic", c->unit, dan, EXP_F64, num + 12 * m, 0},
        {"failed_wall_s", "s", "wall time per failed run, to its failure (NaN: none failed)", EXP_F64,
         num + 13 * m, 0},
        {"tolerance", "1", "the relative error the row is held to (the case's; an own row's may be its own)",
         EXP_F64, num + 14 * m, 0},
    };
    char name[128];
    snprintf(name, sizeof name, "cases/%s", c->name);
    int rc = exp_tab_write(h, name, desc, n, cols, sizeof cols / sizeof cols[0], err);
    char tol[32];
    snprintf(tol, sizeof tol, "%.6g", c->tol);
    rc = rc || exp_tab_attr(h, name, "quantity", c->quantity, err) || exp_tab_attr(h, name, "aux", c->aux, err) ||
         exp_tab_attr(h, name, "tolerance", tol, err) ||
         exp_tab_attr(h, name, "reference", rl ? rl : "analytic", err) ||
         exp_tab_attr(h, name, "scene", c->scene, err);
    free(str), free(num);
    return rc;
}

/* s for a double-quoted string of gnuplot's enhanced text: _ and ^ kept
 * as themselves, not sub- and superscripts (Z_Luding(eta_bulk)). */
static const char *enh(const char *s, char *out, size_t n)
{
    size_t k = 0;
    for (; *s && k + 4 < n; s++) {
        if (*s == '_' || *s == '^')
            out[k++] = '\\', out[k++] = '\\';
        out[k++] = *s;
    }
    out[k] = 0;
    return out;
}

/* Error (x) against wall time (y), log-log, a line per row with the knob
 * value written at each point and the error bar of the error; the
 * reference row, when the case has one, is not drawn (its error is zero by
 * definition): its error bar is, as a dashed line (no method can be shown
 * closer to it than that). An error bar larger than the error is drawn
 * down to a tenth of it: the error is then consistent with zero. */
static int plot_case(const char *dir, const cmp_case *c, const cmp_point *pts, size_t n, const cmp_refs *ref,
                     gr_err *err)
{
    char png[2048], q[512];
    snprintf(png, sizeof png, "%s/%s.png", dir, c->name);
    FILE *gp = gr_plot_open(png, 900, 620, err);
    if (!gp)
        return err->code;
    int nrow = 0, has[CMP_MAXROWS] = {0};
    /* the axes fitted to what is drawn: the points, their error bars, the
     * reference's error bar (the wall time of a quick run can span less
     * than a decade, which gnuplot's log autoscale would widen to ten) */
    double x0 = INFINITY, x1 = 0, y0 = INFINITY, y1 = 0;
    for (int r = 0; c->rows[r].method; r++) {
        fprintf(gp, "$r%d << EOD\n", r);
        for (size_t i = 0; i < n; i++)
            if (pts[i].row == &c->rows[r] && pts[i].nok > 0 && c->rows[r].role != CMP_REFERENCE) {
                double e = fmax(pts[i].error, floor_err), lo = fmax(e - pts[i].error_sem, e / 10);
                fprintf(gp, "%.6g %.6g %.6g %.6g \"%s\"\n", e, pts[i].wall, lo, e + pts[i].error_sem,
                        pts[i].value[0] ? pts[i].value : "");
                x0 = fmin(x0, lo), x1 = fmax(x1, e + pts[i].error_sem);
                y0 = fmin(y0, pts[i].wall), y1 = fmax(y1, pts[i].wall);
                has[r] = 1;
            }
        fprintf(gp, "EOD\n");
        nrow++;
    }
    const char *rl = cmp_ref_label(c);
    if (rl && ref->sem > 0)
        x0 = fmin(x0, ref->sem / fabs(ref->value)), x1 = fmax(x1, ref->sem / fabs(ref->value));
    gr_plot_log_axis(gp, "x", x0, x1);
    gr_plot_log_axis(gp, "y", y0, y1);
    /* the legend below the plot, not beside it: it took half the width */
    fprintf(gp, "set title \"%s: %s against %s\"\nset logscale xy\n"
                "set xlabel \"relative error of %s (below 10^{-16} drawn at 10^{-16}); beside each point the "
                "knob's value\"\n"
                "set ylabel 'wall time per run / s'\nset key below center horizontal\nset grid\n",
            c->name, enh(c->quantity, q, sizeof q), rl ? rl : "the analytic value", q);
    /* errors inside the reference's own error bar cannot be told apart:
     * that band shaded */
    if (rl && ref->sem > 0)
        fprintf(gp, "set object 1 rect from graph 0, graph 0 to first %.6g, graph 1 behind fc rgb '#ebebeb' "
                    "fs solid 1.0 noborder\n"
                    "set label \"within %s's error bar\" at %.6g, graph 0.04 right offset -0.5,0 tc rgb 'gray30'\n",
                ref->sem / fabs(ref->value), rl, ref->sem / fabs(ref->value));
    fprintf(gp, "plot ");
    for (int r = 0, first = 1; r < nrow; r++)
        if (has[r]) {
            fprintf(gp, "%s$r%d u 1:2 w lp lw 2 pt 7 lc %d t '%s%s%s%s', $r%d u 1:2:3:4 w xerrorbars lc %d notitle, "
                        "$r%d u 1:2:5 w labels offset 0.8,0.8 font ',9' notitle",
                    first ? "" : ", ", r, r + 1, c->rows[r].label, c->rows[r].knob ? " by " : "",
                    c->rows[r].knob ? c->rows[r].knob : "",
                    c->rows[r].role == CMP_LIMIT ? " (its limit)"
                    : c->rows[r].role == CMP_OWN ? " (against its own model)" : "", r,
                    r + 1, r);
            first = 0;
        }
    fprintf(gp, "\n");
    return gr_plot_close(gp, png, err);
}

/* The summary: per case, the error and wall time of each row's finest
 * setting (the last of its values), a point style per registered method. */
static int plot_summary(const char *dir, const cmp_case *cs, const cmp_point *const *all, const size_t *nall,
                        gr_err *err)
{
    char png[2048];
    snprintf(png, sizeof png, "%s/summary.png", dir);
    FILE *gp = gr_plot_open(png, 1100, 520, err);
    if (!gp)
        return err->code;
    const gr_method_type *const *methods = gr_method_all();
    int nm = 0;
    while (methods[nm])
        nm++;
    int *count = calloc((size_t)nm + 1, sizeof *count);
    if (!count) {
        gr_plot_close(gp, png, err);
        return gr_fail(err, GR_ERUN, "out of memory");
    }
    /* each panel's log axis fitted to the points it draws */
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {0, 0};
    for (int m = 0; m < nm; m++) {
        fprintf(gp, "$m%d << EOD\n", m);
        for (int k = 0; cs[k].name; k++)
            for (size_t i = 0; i < nall[k]; i++) {
                const cmp_point *p = &all[k][i];
                int last = i + 1 == nall[k] || all[k][i + 1].row != p->row;
                if (last && p->nok > 0 && !strcmp(p->row->method, methods[m]->name) &&
                    (p->row->role == CMP_SWEEP || p->row->role == CMP_MODEL) &&
                    !strchr(p->row->label, '-')) {
                    double e = fmax(p->error, floor_err);
                    fprintf(gp, "%d %.6g %.6g\n", k, e, p->wall);
                    lo[0] = fmin(lo[0], e), hi[0] = fmax(hi[0], e);
                    lo[1] = fmin(lo[1], p->wall), hi[1] = fmax(hi[1], p->wall);
                    count[m]++;
                }
            }
        fprintf(gp, "EOD\n");
    }
    fprintf(gp, "set multiplot layout 1,2 title \"grano compare: each method at its finest setting, against "
                "each case's reference (compare.txt names it)\"\n");
    fprintf(gp, "set xtics (");
    for (int k = 0; cs[k].name; k++)
        fprintf(gp, "%s'%s' %d", k ? ", " : "", cs[k].name, k);
    int ncases = 0;
    while (cs[ncases].name)
        ncases++;
    fprintf(gp, ") rotate by 30 right\nset xrange [-0.5:%g]\nset grid\nset key below center horizontal\n",
            ncases - 0.5);
    int any = 0;
    for (int m = 0; m < nm; m++)
        any += count[m];
    for (int panel = 0; panel < 2; panel++) {
        if (!any) { /* only rows against their own models, or none finished */
            fprintf(gp, "set ylabel '%s'\nset label 1 'no method line against a case reference' at graph 0.5, "
                        "graph 0.5 center\nset yrange [0:1]\nunset ytics\nplot -1 notitle\n",
                    panel ? "wall time per run / s" : "relative error");
            continue;
        }
        gr_plot_log_axis(gp, "y", lo[panel], hi[panel]);
        fprintf(gp, "set ylabel '%s'\nplot ", panel ? "wall time per run / s" : "relative error");
        for (int m = 0, first = 1; m < nm; m++)
            if (count[m]) {
                fprintf(gp, "%s$m%d u ($1+%.2f):%d w p pt %d ps 1.5 t '%s'", first ? "" : ", ", m,
                        0.08 * (m - (nm - 1) / 2.0), panel ? 3 : 2, 5 + 2 * m, methods[m]->name);
                first = 0;
            }
        fprintf(gp, "\n");
    }
    fprintf(gp, "unset multiplot\n");
    free(count);
    return gr_plot_close(gp, png, err);
}

/* The case's points (none when it has no runs), its table lines and
 * checks, its tables in the file. */
static int one_case(const cmp_plan *pl, char *const *parts, const cmp_case *c, FILE *txt, exp_tab_file *h,
                    cmp_point **pts, size_t *n, cmp_refs *ref, cmp_reach_row *rr, size_t *nrr, int *bad,
                    gr_err *err)
{
    *pts = malloc((pl->nunits ? pl->nunits : 1) * sizeof **pts);
    if (!*pts)
        return gr_fail(err, GR_ERUN, "out of memory");
    if (cmp_collect(pl, parts, c, *pts, n, ref, err))
        return err->code;
    if (!*n)
        return GR_OK;
    text_case(stdout, c, *pts, *n, ref);
    text_case(txt, c, *pts, *n, ref);
    *nrr = cmp_reach(*pts, *n, rr);
    cmp_reach_text(stdout, rr, *nrr);
    cmp_reach_text(txt, rr, *nrr);
    int failed = cmp_check(c, *pts, *n, ref, pl->quick);
    if (failed && c->advisory)
        printf("  (a scene of your own: the %d check%s above %s reported, not enforced)\n", failed,
               failed > 1 ? "s" : "", failed > 1 ? "are" : "is");
    *bad += c->advisory ? 0 : failed;
    if (h_case(h, c, *pts, *n, ref, err) || cmp_reach_h5(h, c->name, rr, *nrr, err) ||
        cmp_profiles(pl, parts, c, txt, h, err))
        return err->code;
    return GR_OK;
}

/* DIR/guide.md: the guide as a markdown table, for the docs. */
static int write_guide(const cmp_plan *pl, const cmp_case *cs, const cmp_reach_row (*rr)[CMP_MAXROWS],
                       const size_t *nrr, gr_err *err)
{
    char path[2048];
    snprintf(path, sizeof path, "%s/guide.md", pl->out);
    FILE *f = exp_dat_open(path, err);
    if (!f)
        return err->code;
    fprintf(f, "The cheapest method line to reach each relative error, wall seconds per run (grano compare%s; "
               "per case, the cost along each line's knob: compare.txt)\n\n",
            pl->quick ? " --quick" : "");
    cmp_reach_guide(f, 1, cs, rr, nrr);
    return exp_dat_close(f, path, err);
}

/* compare.txt and compare.h5, written whole before any figure: a study
 * whose figures cannot be drawn still leaves its data. */
static int tables(const cmp_plan *pl, char *const *parts, const cmp_case *cs, int ncases, cmp_point **all,
                  size_t *nall, cmp_refs *refs, int *bad, gr_err *err)
{
    char path[2048], tpath[2048];
    snprintf(tpath, sizeof tpath, "%s/compare.txt", pl->out);
    FILE *txt = exp_dat_open(tpath, err);
    if (!txt)
        return err->code;
    fprintf(txt, "# grano compare%s: relative error = |measured - reference| / |reference|; error bars\n"
                 "# from independent seeds (several) or block averages (one run)\n%s",
            pl->quick ? " --quick" : "", pl->notes);
    snprintf(path, sizeof path, "%s/compare.h5", pl->out);
    exp_tab_file *h = exp_tab_create(path, "grano compare: a table per case", err);
    int rc = h ? exp_tab_attr(h, "/", "mode", pl->quick ? "quick" : "full", err) : err->code;
    cmp_reach_row(*rr)[CMP_MAXROWS] = calloc((size_t)ncases, sizeof *rr);
    size_t *nrr = calloc((size_t)ncases, sizeof *nrr);
    if (!rc && (!rr || !nrr))
        rc = gr_fail(err, GR_ERUN, "out of memory");
    for (int k = 0; k < ncases && !rc; k++)
        rc = one_case(pl, parts, &cs[k], txt, h, &all[k], &nall[k], &refs[k], rr[k], &nrr[k], bad, err);
    if (!rc) {
        const cmp_reach_row(*cr)[CMP_MAXROWS] = (const cmp_reach_row(*)[CMP_MAXROWS])rr;
        cmp_reach_guide(stdout, 0, cs, cr, nrr);
        cmp_reach_guide(txt, 0, cs, cr, nrr);
        rc = write_guide(pl, cs, cr, nrr, err);
    }
    free(rr), free(nrr);
    if (h)
        rc = rc ? (exp_tab_free(h), rc) : exp_tab_close(h, err);
    if (rc) {
        char part[2100];
        fclose(txt);
        snprintf(part, sizeof part, "%s.part", tpath);
        remove(part);
        return rc;
    }
    return exp_dat_close(txt, tpath, err);
}

int cmp_report(const cmp_plan *pl, char *const *parts, int *drawn, gr_err *err)
{
    const cmp_case *cs = cmp_plan_cases(pl);
    int ncases = 0, bad = 0, rc = GR_OK;
    while (cs[ncases].name)
        ncases++;
    cmp_point **all = calloc((size_t)ncases, sizeof *all);
    size_t *nall = calloc((size_t)ncases, sizeof *nall);
    cmp_refs *refs = calloc((size_t)ncases, sizeof *refs);
    rc = all && nall && refs ? tables(pl, parts, cs, ncases, all, nall, refs, &bad, err)
                             : gr_fail(err, GR_ERUN, "out of memory");
    *drawn = !rc && gr_plot_have_gnuplot();
    for (int k = 0; k < ncases && *drawn && !rc; k++)
        if (nall[k])
            rc = plot_case(pl->out, &cs[k], all[k], nall[k], &refs[k], err);
    if (*drawn && !rc)
        rc = plot_summary(pl->out, cs, (const cmp_point *const *)all, nall, err);
    for (int k = 0; all && k < ncases; k++)
        free(all[k]);
    free(all), free(nall), free(refs);
    if (!rc && bad)
        rc = gr_fail(err, GR_ERUN, "%d check%s failed (above)", bad, bad > 1 ? "s" : "");
    return rc ? (err->code ? err->code : GR_ERUN) : GR_OK;
}
