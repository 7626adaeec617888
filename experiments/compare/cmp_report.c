/* grano compare's results: the runs of each (row, knob value) pooled over
 * seeds, the error against the case's reference with its error bar, the
 * HDF5 and text tables, the figures, and the checks of --quick. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmp.h"
#include "cmp_report.h"
#include "parts.h"
#include "table.h"

/* Text entry `name` of an open part into out (n bytes), "" if absent. */
static void get_text(gr_ckpt *ck, const char *name, char *out, size_t n)
{
    size_t len;
    gr_err e = {0};
    out[0] = 0;
    if (!gr_ckpt_len(ck, name, &len, &e) && len < n)
        gr_ckpt_get_bytes(ck, name, out, len, &e);
}

/* One part's result: ok, value, sem, aux, steps, wall, and an own row's
 * answers (NaN when none); its failure's message and its broken validity
 * limits. */
static int read_part(const char *path, double v[8], char *msg, size_t n, char *diag, size_t nd, gr_err *err)
{
    gr_ckpt *ck = gr_ckpt_open(path, err);
    if (!ck)
        return err->code;
    int rc = gr_ckpt_get_f64(ck, "result", v, 6, err);
    gr_err e = {0};
    size_t len;
    v[6] = v[7] = NAN;
    if (!rc && !gr_ckpt_len(ck, "own", &len, &e) && len == 2)
        rc = gr_ckpt_get_f64(ck, "own", v + 6, 2, err);
    get_text(ck, "message", msg, n);
    get_text(ck, "diag", diag, nd);
    gr_ckpt_close(ck, &e);
    return rc;
}

const char *cmp_outcome_name(int outcome)
{
    static const char *const names[] = {"failed", "some runs failed", "within", "beyond", "unclear",
                                        "no tolerance"};
    return outcome >= 0 && outcome <= CMP_OUT_NONE ? names[outcome] : "?";
}

/* The point's outcome against tolerance tol (0: none). */
static int outcome(const cmp_point *p, double tol)
{
    if (!p->nok)
        return CMP_OUT_FAILED;
    if (p->nok < p->n)
        return CMP_OUT_SOME_FAILED;
    if (!(tol > 0))
        return CMP_OUT_NONE;
    if (p->error + 2 * p->error_sem <= tol)
        return CMP_OUT_WITHIN;
    return p->error - 2 * p->error_sem > tol ? CMP_OUT_BEYOND : CMP_OUT_UNCLEAR;
}

/* The error bar of the mean of m samples from their sum and sum of
 * squares (their scatter); 0 below two. */
static double scatter_sem(double sum, double sum2, int m)
{
    if (m < 2)
        return 0;
    double mean = sum / m;
    return sqrt(fmax(sum2 / m - mean * mean, 0) / (m - 1));
}

/* Pool the seeds of point *pt (units first..first+nseeds-1). */
static int pool(const cmp_plan *pl, char *const *parts, size_t first, cmp_point *pt, gr_err *err)
{
    double sum = 0, sum2 = 0, semw = 0, rsum = 0, rsum2 = 0;
    int nsem = 0, nfail = 0, nown = 0;
    pt->wall = pt->steps = pt->aux = pt->ref = pt->aux_ref = 0;
    for (size_t k = first; k < pl->nunits && pl->units[k].c == pl->units[first].c &&
                           pl->units[k].row == pl->units[first].row &&
                           !strcmp(pl->units[k].value, pl->units[first].value);
         k++) {
        double v[8];
        char msg[1100], diag[CMP_DIAG];
        if (read_part(parts[k], v, msg, sizeof msg, diag, sizeof diag, err))
            return err->code;
        pt->n++;
        if (!pt->diag[0])
            snprintf(pt->diag, sizeof pt->diag, "%s", diag);
        if (!(v[0] > 0)) {
            if (!pt->msg[0])
                snprintf(pt->msg, sizeof pt->msg, "seed %d: %.600s", pl->units[k].seed, msg);
            pt->fail_wall += v[5], nfail++;
            continue;
        }
        pt->nok++;
        sum += v[1], sum2 += v[1] * v[1];
        if (isfinite(v[2]))
            semw += v[2] * v[2], nsem++;
        pt->aux += v[3], pt->steps += v[4], pt->wall += v[5];
        if (isfinite(v[6])) { /* an own row: each run against its own answer */
            double r = v[1] / v[6];
            rsum += r, rsum2 += r * r, pt->ref += v[6], pt->aux_ref += v[7], nown++;
        }
    }
    int m = pt->nok;
    pt->ref = nown ? pt->ref / nown : NAN, pt->aux_ref = nown ? pt->aux_ref / nown : NAN;
    pt->own_ratio = nown ? rsum / nown : NAN;
    pt->own_ratio_sem = scatter_sem(rsum, rsum2, nown);
    pt->fail_wall = nfail ? pt->fail_wall / nfail : NAN;
    pt->mean = m ? sum / m : NAN;
    pt->aux = m ? pt->aux / m : NAN;
    pt->wall = m ? pt->wall / m : NAN;
    pt->steps = m ? pt->steps / m : NAN;
    /* independent seeds give the error bar; one run, its own (block) one */
    if (m >= 2)
        pt->sem = scatter_sem(sum, sum2, m);
    else
        pt->sem = nsem ? sqrt(semw / nsem) : 0;
    return GR_OK;
}

/* The references of case c from its points (pooled) and its analytic
 * function. */
static int references(const cmp_plan *pl, const cmp_case *c, size_t first_unit, const cmp_point *pts, size_t n,
                      cmp_refs *ref, gr_err *err)
{
    *ref = (cmp_refs){NAN, 0, NAN, NAN, NAN};
    if (c->reference) {
        /* the case's own scene (the first row's settings), not a row's variant */
        cmp_unit probe = pl->units[first_unit];
        probe.row = &c->rows[0];
        snprintf(probe.value, sizeof probe.value, "%s", "");
        gr_scene *sc = cmp_unit_scene(pl, &probe, err);
        if (!sc)
            return err->code;
        ref->analytic = c->reference(sc, &ref->aux_analytic);
        gr_scene_free(sc);
    }
    ref->value = ref->analytic, ref->aux = ref->aux_analytic;
    for (size_t i = 0; i < n; i++)
        if (pts[i].row->role == CMP_REFERENCE)
            ref->value = pts[i].mean, ref->sem = pts[i].sem, ref->aux = pts[i].aux;
    return GR_OK;
}

double cmp_row_tol(const cmp_case *c, const cmp_row *r)
{
    return r->tol > 0 ? r->tol : c->tol;
}

int cmp_collect(const cmp_plan *pl, char *const *parts, const cmp_case *c, cmp_point *pts, size_t *npts,
                cmp_refs *ref, gr_err *err)
{
    *npts = 0;
    size_t first_unit = pl->nunits;
    for (size_t u = 0; u < pl->nunits; u++) {
        const cmp_unit *x = &pl->units[u];
        if (x->c != c || (u > 0 && pl->units[u - 1].c == c && pl->units[u - 1].row == x->row &&
                          !strcmp(pl->units[u - 1].value, x->value)))
            continue;
        if (first_unit == pl->nunits)
            first_unit = u;
        cmp_point *pt = &pts[(*npts)++];
        memset(pt, 0, sizeof *pt);
        pt->row = x->row;
        snprintf(pt->value, sizeof pt->value, "%s", x->value);
        if (pool(pl, parts, u, pt, err))
            return err->code;
    }
    *ref = (cmp_refs){NAN, 0, NAN, NAN, NAN};
    if (first_unit == pl->nunits)
        return GR_OK;
    if (references(pl, c, first_unit, pts, *npts, ref, err))
        return err->code;
    for (size_t i = 0; i < *npts; i++) {
        cmp_point *pt = &pts[i];
        int is_ref = pt->row->role == CMP_REFERENCE;
        if (pt->row->role == CMP_OWN) {
            /* each run against its own answer: the ratios' scatter is the error bar */
            pt->ref_sem = 0;
            pt->error = fabs(pt->own_ratio - 1), pt->error_sem = pt->own_ratio_sem;
            if (pt->nok == 1)
                pt->error_sem = pt->sem / fabs(pt->ref);
        } else {
            pt->ref = ref->value, pt->ref_sem = ref->sem, pt->aux_ref = ref->aux;
            pt->error = is_ref ? 0 : fabs(pt->mean - pt->ref) / fabs(pt->ref);
            /* against a measured reference the two error bars add */
            pt->error_sem = is_ref ? 0 : hypot(pt->sem, pt->ref_sem) / fabs(pt->ref);
        }
        pt->outcome = outcome(pt, is_ref ? 0 : cmp_row_tol(c, pt->row));
    }
    return GR_OK;
}

/* A model row's value settles as its knob is tightened: the change from q
 * to r is not larger than that from p to q, beyond 10 % and the error bars
 * (it converges to the model's own answer, whatever the reference's). */
static int settles(const cmp_case *c, const cmp_point *p, const cmp_point *q, const cmp_point *r)
{
    double d1 = fabs(q->mean - p->mean), d2 = fabs(r->mean - q->mean);
    double slack = 2 * sqrt(p->sem * p->sem + 2 * q->sem * q->sem + r->sem * r->sem) + 1e-9;
    if (d2 <= 1.1 * d1 + slack)
        return 0;
    printf("  CHECK FAILED %s %s: the value moved by %.3g (%s to %s), more than the %.3g before, beyond the "
           "error bars\n", c->name, p->row->label, d2, q->value, r->value, d1);
    return 1;
}

/* Whether the last value of a row's quick list is that of its full one:
 * a quick run checks the tolerance only at the setting the full run ends
 * on (a row's coarse settings may miss it by design). */
static int ends_as_full(const cmp_row *r)
{
    const char *a = strrchr(r->quick, ','), *b = strrchr(r->full, ',');
    return !strcmp(a ? a + 1 : r->quick, b ? b + 1 : r->full);
}

/* The tolerance checks of point p, the last of its row when finest: a
 * sweep row's finest setting reaches the case's tolerance (its error minus
 * two error bars within it); a limit row's settings do not clearly reach
 * it (a run failed, or its error plus two error bars beyond it), and a
 * limit row whose runs all finish without a number fails. */
static int tolerance(const cmp_case *c, const cmp_point *p, int finest, int quick)
{
    int role = p->row->role;
    double tol = cmp_row_tol(c, p->row);
    if ((role == CMP_SWEEP || role == CMP_OWN) && finest && tol > 0 && p->outcome == CMP_OUT_BEYOND &&
        (!quick || ends_as_full(p->row))) {
        printf("  CHECK FAILED %s %s %s: error %.3g +- %.2g, beyond the %s tolerance %.3g\n", c->name,
               p->row->label, p->value, p->error, p->error_sem, role == CMP_OWN ? "row's" : "case's", tol);
        return 1;
    }
    if (role == CMP_LIMIT && p->outcome == CMP_OUT_WITHIN) {
        printf("  CHECK FAILED %s %s %s: error %.3g +- %.2g reaches the tolerance %.3g: the row is no limit "
               "(make it a sweep)\n", c->name, p->row->label, p->value, p->error, p->error_sem, c->tol);
        return 1;
    }
    return 0;
}

/* The checks of docs/comparison.md: each swept row's error does not grow as
 * its knob is tightened (values are listed coarse to fine) beyond the error
 * bars, which is how it falls until the statistical floor, and its finest
 * setting reaches the case's tolerance (an own row: the same against its
 * own reference and tolerance); a model row's value settles (its
 * error against the reference is its model's); a limit row does not reach
 * the tolerance, and its failures are its result; edmd within the case's
 * tolerance of the analytic value; every other run finished with finite
 * numbers. Failures are printed; returns how many. */
int cmp_check(const cmp_case *c, const cmp_point *pts, size_t n, const cmp_refs *ref, int quick)
{
    int bad = 0;
    for (size_t i = 0; i < n; i++) {
        const cmp_point *p = &pts[i];
        int limit = p->row->role == CMP_LIMIT;
        if (!limit && (p->nok < p->n || !isfinite(p->mean) || !isfinite(p->aux) || !isfinite(p->error_sem))) {
            printf("  CHECK FAILED %s %s %s: %s\n", c->name, p->row->label, p->value,
                   p->msg[0] ? p->msg : "a non-finite number");
            bad++;
        }
        if (limit && p->nok && !isfinite(p->mean)) {
            printf("  CHECK FAILED %s %s %s: finished without a number, and said nothing\n", c->name,
                   p->row->label, p->value);
            bad++;
        }
        double dev = fabs(p->mean - ref->analytic) / fabs(ref->analytic);
        if (!limit && !strcmp(p->row->method, "edmd") && c->tol_edmd > 0 && !(dev <= c->tol_edmd)) {
            printf("  CHECK FAILED %s edmd: %.3g from the analytic value, beyond the tolerance %.3g\n", c->name,
                   dev, c->tol_edmd);
            bad++;
        }
        int finest = i + 1 == n || pts[i + 1].row != p->row;
        bad += tolerance(c, p, finest, quick);
        if (p->row->role == CMP_MODEL && i + 2 < n && pts[i + 2].row == p->row)
            bad += settles(c, p, p + 1, p + 2);
        if ((p->row->role == CMP_SWEEP || p->row->role == CMP_OWN) && i + 1 < n && pts[i + 1].row == p->row) {
            const cmp_point *q = &pts[i + 1];
            double slack = 2 * hypot(p->error_sem, q->error_sem) + 1e-9;
            if (!(q->error <= 1.1 * p->error + slack)) {
                printf("  CHECK FAILED %s %s: error rose from %.3g (%s) to %.3g (%s), beyond the error bars\n",
                       c->name, p->row->label, p->error, p->value, q->error, q->value);
                bad++;
            }
        }
    }
    return bad;
}
