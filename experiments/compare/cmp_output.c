/* grano compare's outputs: compare.h5 (a table per case), compare.txt, a
 * speed-against-error figure per case and a summary figure, each with its
 * gnuplot script beside it. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmp.h"
#include "cmp_report.h"
#include "h5md.h"
#include "plot.h"
#include "table.h"

#define NCOL 14
static const char *const columns = "row,knob_value,runs,finished,wall_s,steps,value,value_sem,reference,rel_error,"
                                   "rel_error_sem,aux,aux_reference,analytic";

/* Errors below this are drawn at it on the log axis (exact methods). */
static const double floor_err = 1e-16;

/* Which row, if any, is the case's reference. */
static const char *ref_label(const cmp_case *c)
{
    for (const cmp_row *r = c->rows; r->method; r++)
        if (r->role == CMP_REFERENCE)
            return r->label;
    return NULL;
}

static void text_case(FILE *f, const cmp_case *c, const cmp_point *pts, size_t n, const cmp_refs *ref)
{
    const char *rl = ref_label(c);
    fprintf(f, "\n== %s: %s: reference %.8g +- %.2g (%s)", c->name, c->quantity, ref->value, ref->sem,
            rl ? rl : "analytic");
    if (rl && isfinite(ref->analytic))
        fprintf(f, ", analytic %.8g", ref->analytic);
    fprintf(f, "; %s: reference %.6g\n", c->aux, ref->aux);
    fprintf(f, "%-9s %-14s %-9s %5s %9s %11s %-24s %-20s %12s %s\n", "method", "knob", "value", "runs", "wall/s",
            "steps", "measured +- error bar", "relative error", c->aux, "");
    for (size_t i = 0; i < n; i++) {
        const cmp_point *p = &pts[i];
        char meas[64], er[64];
        snprintf(meas, sizeof meas, "%.7g +- %.2g", p->mean, p->sem);
        snprintf(er, sizeof er, "%.3g +- %.2g", p->error, p->error_sem);
        fprintf(f, "%-9s %-14s %-9s %2d/%-2d %9.3g %11.4g %-24s %-20s %12.5g %s\n", p->row->label,
                p->row->knob ? p->row->knob : "-", p->value[0] ? p->value : "-", p->nok, p->n, p->wall, p->steps,
                meas, er, p->aux,
                p->nok < p->n ? "FAILED"
                : p->row->role == CMP_REFERENCE ? "(reference)"
                : p->row->role == CMP_MODEL && p->error > 2 * p->error_sem ? "(its own model's answer)"
                : p->error > 2 * p->error_sem ? "" : "(within the error bar)");
        if (p->msg[0])
            fprintf(f, "          %s\n", p->msg);
    }
}

static int h5_case(gr_h5md *h, const cmp_case *c, const cmp_point *pts, size_t n, const cmp_refs *ref, gr_err *err)
{
    double *v = malloc((n ? n : 1) * NCOL * sizeof *v);
    if (!v)
        return gr_fail(err, GR_ERUN, "out of memory");
    char desc[1024];
    int k = snprintf(desc, sizeof desc, "%s against its reference; aux = %s; rows:", c->quantity, c->aux);
    for (int r = 0; c->rows[r].method && k < (int)sizeof desc; r++)
        k += snprintf(desc + k, sizeof desc - (size_t)k, " %d=%s(%s)", r, c->rows[r].label,
                      c->rows[r].knob ? c->rows[r].knob : "no knob");
    for (size_t i = 0; i < n; i++) {
        const cmp_point *p = &pts[i];
        double row[NCOL] = {(double)(p->row - c->rows), p->value[0] ? atof(p->value) : NAN, p->n, p->nok,
                            p->wall, p->steps, p->mean, p->sem, ref->value, p->error, p->error_sem, p->aux,
                            ref->aux, ref->analytic};
        memcpy(v + i * NCOL, row, sizeof row);
    }
    char name[128];
    snprintf(name, sizeof name, "compare/%s", c->name);
    int rc = exp_put_result(h, name, n, NCOL, columns, desc, v, err);
    free(v);
    return rc;
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
    char png[2048];
    snprintf(png, sizeof png, "%s/%s.png", dir, c->name);
    FILE *gp = gr_plot_open(png, 900, 620, err);
    if (!gp)
        return err->code;
    int nrow = 0, has[CMP_MAXROWS] = {0};
    for (int r = 0; c->rows[r].method; r++) {
        fprintf(gp, "$r%d << EOD\n", r);
        for (size_t i = 0; i < n; i++)
            if (pts[i].row == &c->rows[r] && pts[i].nok > 0 && c->rows[r].role != CMP_REFERENCE) {
                double e = fmax(pts[i].error, floor_err);
                fprintf(gp, "%.6g %.6g %.6g %.6g \"%s\"\n", e, pts[i].wall, fmax(e - pts[i].error_sem, e / 10),
                        e + pts[i].error_sem, pts[i].value[0] ? pts[i].value : "");
                has[r] = 1;
            }
        fprintf(gp, "EOD\n");
        nrow++;
    }
    const char *rl = ref_label(c);
    fprintf(gp, "set title \"%s: %s against %s\"\nset logscale xy\nset format x '10^{%%T}'\n"
                "set xlabel \"relative error of %s (below 1e-16 drawn at 1e-16)\"\n"
                "set ylabel 'wall time per run / s'\nset key outside right\nset grid\n",
            c->name, c->quantity, rl ? rl : "the analytic value", c->quantity);
    if (rl && ref->sem > 0)
        fprintf(gp, "set arrow from %.6g, graph 0 to %.6g, graph 1 nohead dt 2 lc rgb 'gray40'\n"
                    "set label \"%s's error bar\" at %.6g, graph 0.95 right offset -0.5,0 tc rgb 'gray40'\n",
                ref->sem / fabs(ref->value), ref->sem / fabs(ref->value), rl, ref->sem / fabs(ref->value));
    fprintf(gp, "plot ");
    for (int r = 0, first = 1; r < nrow; r++)
        if (has[r]) {
            fprintf(gp, "%s$r%d u 1:2 w lp lw 2 pt 7 lc %d t '%s%s%s', $r%d u 1:2:3:4 w xerrorbars lc %d notitle, "
                        "$r%d u 1:2:5 w labels offset 0.8,0.8 font ',9' notitle",
                    first ? "" : ", ", r, r + 1, c->rows[r].label, c->rows[r].knob ? " by " : "",
                    c->rows[r].knob ? c->rows[r].knob : "", r, r + 1, r);
            first = 0;
        }
    fprintf(gp, "\n");
    return gr_plot_close(gp, png, err);
}

/* The summary: per case, the error and wall time of each row's finest
 * setting (the last of its values). */
static int plot_summary(const char *dir, const cmp_case *cs, const cmp_point *const *all, const size_t *nall,
                        gr_err *err)
{
    char png[2048];
    snprintf(png, sizeof png, "%s/summary.png", dir);
    FILE *gp = gr_plot_open(png, 1100, 520, err);
    if (!gp)
        return err->code;
    static const char *const methods[] = {"dem", "edmd", "cd", "dsmc", "lgca", NULL};
    int count[8] = {0};
    for (int m = 0; methods[m]; m++) {
        fprintf(gp, "$m%d << EOD\n", m);
        for (int k = 0; cs[k].name; k++)
            for (size_t i = 0; i < nall[k]; i++) {
                const cmp_point *p = &all[k][i];
                int last = i + 1 == nall[k] || all[k][i + 1].row != p->row;
                if (last && p->nok > 0 && !strcmp(p->row->method, methods[m]) &&
                    (p->row->role == CMP_SWEEP || p->row->role == CMP_MODEL) &&
                    !strchr(p->row->label, '-')) {
                    fprintf(gp, "%d %.6g %.6g\n", k, fmax(p->error, floor_err), p->wall);
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
    fprintf(gp, ") rotate by 30 right\nset xrange [-0.5:%g]\nset logscale y\nset grid\nset key top left\n",
            ncases - 0.5);
    for (int panel = 0; panel < 2; panel++) {
        fprintf(gp, "set ylabel '%s'\nplot ", panel ? "wall time per run / s" : "relative error");
        for (int m = 0, first = 1; methods[m]; m++)
            if (count[m]) {
                fprintf(gp, "%s$m%d u ($1+%.2f):%d w p pt %d ps 1.5 t '%s'", first ? "" : ", ", m,
                        0.08 * (m - 2), panel ? 3 : 2, 5 + 2 * m, methods[m]);
                first = 0;
            }
        fprintf(gp, "\n");
    }
    fprintf(gp, "unset multiplot\n");
    return gr_plot_close(gp, png, err);
}

/* The case's points (NULL when it has none), its table lines and checks. */
static int one_case(const cmp_plan *pl, char *const *parts, const cmp_case *c, FILE *txt, gr_h5md *h,
                    cmp_point **pts, size_t *n, int *bad, gr_err *err)
{
    cmp_refs ref;
    *pts = malloc((pl->nunits ? pl->nunits : 1) * sizeof **pts);
    if (!*pts)
        return gr_fail(err, GR_ERUN, "out of memory");
    if (cmp_collect(pl, parts, c, *pts, n, &ref, err))
        return err->code;
    if (!*n)
        return GR_OK;
    text_case(stdout, c, *pts, *n, &ref);
    text_case(txt, c, *pts, *n, &ref);
    *bad += cmp_check(c, *pts, *n, &ref);
    if (h5_case(h, c, *pts, *n, &ref, err) || cmp_profiles(pl, parts, c, txt, h, err) ||
        plot_case(pl->out, c, *pts, *n, &ref, err))
        return err->code;
    return GR_OK;
}

int cmp_report(const cmp_plan *pl, char *const *parts, gr_err *err)
{
    const cmp_case *cs = cmp_cases();
    int ncases = 0, bad = 0, rc = GR_OK;
    while (cs[ncases].name)
        ncases++;
    cmp_point **all = calloc((size_t)ncases, sizeof *all);
    size_t *nall = calloc((size_t)ncases, sizeof *nall);
    char path[2048];
    snprintf(path, sizeof path, "%s/compare.txt", pl->out);
    FILE *txt = all && nall ? fopen(path, "w") : NULL;
    if (!txt)
        rc = gr_fail(err, GR_ERUN, "%s: cannot write", path);
    gr_h5md *h = NULL;
    if (!rc) {
        fprintf(txt, "# grano compare%s: relative error = |measured - reference| / |reference|; error bars\n"
                     "# from independent seeds (several) or block averages (one run)\n%s",
                pl->quick ? " --quick" : "", pl->notes);
        snprintf(path, sizeof path, "%s/compare.h5", pl->out);
        gr_scene *sc = pl->nunits ? cmp_unit_scene(pl, &pl->units[0], err) : NULL;
        gr_h5md_opts ho = {.method = "compare", .seed = 1, .force = 1, .no_xdmf = 1};
        h = sc ? gr_h5md_create(path, sc, &ho, err) : NULL;
        gr_scene_free(sc);
        rc = h ? GR_OK : (err->code ? err->code : gr_fail(err, GR_ERUN, "no runs to report"));
    }
    for (int k = 0; k < ncases && !rc; k++)
        rc = one_case(pl, parts, &cs[k], txt, h, &all[k], &nall[k], &bad, err);
    if (!rc)
        rc = plot_summary(pl->out, cs, (const cmp_point *const *)all, nall, err);
    if (h)
        rc = gr_h5md_close(h, err) || rc;
    if (txt && fclose(txt) && !rc)
        rc = gr_fail(err, GR_ERUN, "%s/compare.txt: write failed", pl->out);
    for (int k = 0; all && k < ncases; k++)
        free(all[k]);
    free(all), free(nall);
    if (!rc && bad)
        rc = gr_fail(err, GR_ERUN, "%d check%s failed (above)", bad, bad > 1 ? "s" : "");
    return rc ? (err->code ? err->code : GR_ERUN) : GR_OK;
}
