/* grano compare's profiles (the vibrated bed's density and temperature in
 * height bins): each (row, value)'s, pooled over seeds, against the
 * CMP_REFERENCE row's, as relative L2 norms over the bins with error bars,
 * and the density's max norm; a text block and two HDF5 tables.
 *
 *   e_n = |n - n_ref|_2 / |n_ref|_2,
 *   e_T = sqrt(sum n_ref (T - T_ref)^2 / sum n_ref T_ref^2)
 * (the temperature weighted by the reference density: a nearly empty bin
 * has a noisy temperature and no weight), over the bins where both
 * temperatures are known. The error bar of a norm is the first-order
 * propagation of the bins' error bars (seed scatter with several seeds,
 * block averages with one). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cmp.h"
#include "parts.h"

#define NP (4 * CMP_NBINS)

typedef struct {
    const cmp_row *row;
    char value[32];
    double p[NP];
} prof_point;

static int read_profile(const char *path, double *v, int *ok, gr_err *err)
{
    gr_ckpt *ck = gr_ckpt_open(path, err);
    if (!ck)
        return err->code;
    size_t len = 0;
    gr_err e = {0};
    *ok = !gr_ckpt_len(ck, "profile", &len, &e) && len == NP && !gr_ckpt_get_f64(ck, "profile", v, NP, err);
    gr_ckpt_close(ck, &e);
    return GR_OK;
}

/* Pool the seeds of units first.. (same row and value): mean per bin; error
 * bar from the seeds' scatter when there are several, else the run's. */
static int pool(const cmp_plan *pl, char *const *parts, size_t first, prof_point *pt, int *any, gr_err *err)
{
    double s1[NP] = {0}, s2[NP] = {0}, run[NP] = {0}, v[NP];
    int m[NP] = {0}, ok = 0;
    for (size_t k = first; k < pl->nunits && pl->units[k].c == pl->units[first].c &&
                           pl->units[k].row == pl->units[first].row &&
                           !strcmp(pl->units[k].value, pl->units[first].value);
         k++) {
        if (read_profile(parts[k], v, &ok, err))
            return err->code;
        for (int j = 0; ok && j < NP; j += 2)
            if (isfinite(v[j]))
                s1[j] += v[j], s2[j] += v[j] * v[j], run[j] = v[j + 1], m[j]++;
        *any |= ok;
    }
    for (int j = 0; j < NP; j += 2) {
        pt->p[j] = m[j] ? s1[j] / m[j] : NAN;
        pt->p[j + 1] = m[j] >= 2 ? sqrt(fmax(s2[j] / m[j] - pt->p[j] * pt->p[j], 0) / (m[j] - 1)) : run[j];
    }
    return GR_OK;
}

/* e (k = 0: density, 2: temperature) of a against r, its error bar, and
 * the density's max norm over the largest reference density. */
static void norms(const double *a, const double *r, int k, double *e, double *es, double *emax)
{
    double num = 0, den = 0, var = 0, nmax = 0, dmax = 0;
    for (int b = 0; b < CMP_NBINS; b++) {
        const double *x = a + 4 * b, *y = r + 4 * b;
        double w = k ? y[0] : 1, d = x[k] - y[k];
        if (!isfinite(d) || !isfinite(x[k + 1]) || !isfinite(y[k + 1]))
            continue;
        num += w * d * d, den += w * y[k] * y[k];
        var += w * w * d * d * (x[k + 1] * x[k + 1] + y[k + 1] * y[k + 1]);
        nmax = fmax(nmax, fabs(y[0])), dmax = fmax(dmax, fabs(x[0] - y[0]));
    }
    *e = den > 0 ? sqrt(num / den) : NAN;
    *es = num > 0 ? sqrt(var / num / den) : 0;
    *emax = nmax > 0 ? dmax / nmax : NAN;
}

#define NCOL 5 /* density_l2, its error bar, density_max, temperature_l2, its error bar */
#define DCOL 5 /* height, density, its error bar, temperature, its error bar */

/* The profile tables of case c: profiles/<case>/errors, one row per (row,
 * value), and profiles/<case>/bins, one row per (row, value, bin). */
static int tables(const cmp_case *c, const prof_point *pts, size_t n, const double *t, const double *d,
                  exp_tab_file *h, gr_err *err)
{
    size_t nb = n * CMP_NBINS;
    const char **s = malloc(4 * nb * sizeof *s);
    if (!s)
        return gr_fail(err, GR_ERUN, "out of memory");
    for (size_t i = 0; i < nb; i++) {
        const prof_point *p = &pts[i / CMP_NBINS];
        s[i] = p->row->method, s[nb + i] = p->row->label, s[2 * nb + i] = p->row->knob ? p->row->knob : "",
        s[3 * nb + i] = p->value;
    }
    /* per point: every CMP_NBINS-th of the per-bin strings */
    const exp_col ecols[] = {
        {"method", "", "registered method that ran", EXP_STR, s, CMP_NBINS},
        {"variant", "", "the method line", EXP_STR, s + nb, CMP_NBINS},
        {"knob", "", "scene keys the knob sets (empty: none)", EXP_STR, s + 2 * nb, CMP_NBINS},
        {"knob_value", "", "the knob's value as written in the case", EXP_STR, s + 3 * nb, CMP_NBINS},
        {"density_l2", "1", "relative L2 error of the density profile", EXP_F64, t, NCOL},
        {"density_l2_sem", "1", "its error bar", EXP_F64, t + 1, NCOL},
        {"density_max", "1", "largest density deviation over the largest reference density", EXP_F64, t + 2,
         NCOL},
        {"temperature_l2", "1", "relative L2 error of the temperature, weighted by the reference density",
         EXP_F64, t + 3, NCOL},
        {"temperature_l2_sem", "1", "its error bar", EXP_F64, t + 4, NCOL},
    };
    const exp_col bcols[] = {
        {"method", "", "registered method that ran", EXP_STR, s, 0},
        {"variant", "", "the method line", EXP_STR, s + nb, 0},
        {"knob", "", "scene keys the knob sets (empty: none)", EXP_STR, s + 2 * nb, 0},
        {"knob_value", "", "the knob's value as written in the case", EXP_STR, s + 3 * nb, 0},
        {"height", "d", "bin centre above the floor's mean height", EXP_F64, d, DCOL},
        {"density", "d-2", "number density, mean over seeds", EXP_F64, d + 1, DCOL},
        {"density_sem", "d-2", "its error bar", EXP_F64, d + 2, DCOL},
        {"temperature", "m d+2 tau-2", "granular temperature (NaN: no grain reached the bin)", EXP_F64, d + 3,
         DCOL},
        {"temperature_sem", "m d+2 tau-2", "its error bar", EXP_F64, d + 4, DCOL},
    };
    char name[128];
    snprintf(name, sizeof name, "profiles/%s/errors", c->name);
    int rc = exp_tab_write(h, name, "profile errors against the reference row, per (method line, knob value)", n,
                           ecols, sizeof ecols / sizeof ecols[0], err);
    snprintf(name, sizeof name, "profiles/%s/bins", c->name);
    rc = rc || exp_tab_write(h, name, "profiles per (method line, knob value, bin of 1 d), pooled over seeds", nb,
                             bcols, sizeof bcols / sizeof bcols[0], err);
    free(s);
    return rc;
}

static int write_out(const cmp_case *c, const prof_point *pts, size_t n, const prof_point *ref, FILE *txt,
                     exp_tab_file *h, gr_err *err)
{
    double *t = malloc(n * NCOL * sizeof *t), *d = malloc(n * CMP_NBINS * DCOL * sizeof *d);
    int rc = t && d ? GR_OK : gr_fail(err, GR_ERUN, "out of memory");
    char line[256];
    snprintf(line, sizeof line, "-- %s: profiles (%d bins of 1 d) against %s's: relative L2 error +- error bar; "
             "density max norm\n", c->name, CMP_NBINS, ref->row->label);
    fputs(line, txt), fputs(line, stdout);
    for (size_t i = 0; i < n && !rc; i++) {
        double en, ens, emax, eT, eTs, dummy;
        norms(pts[i].p, ref->p, 0, &en, &ens, &emax);
        norms(pts[i].p, ref->p, 2, &eT, &eTs, &dummy);
        snprintf(line, sizeof line, "%-12s %-9s density %.3g +- %.2g (max %.3g)  temperature %.3g +- %.2g\n",
                 pts[i].row->label, pts[i].value[0] ? pts[i].value : "-", en, ens, emax, eT, eTs);
        fputs(line, txt), fputs(line, stdout);
        double row[NCOL] = {en, ens, emax, eT, eTs};
        memcpy(t + i * NCOL, row, sizeof row);
        for (int b = 0; b < CMP_NBINS; b++) {
            double *o = d + (i * CMP_NBINS + (size_t)b) * DCOL;
            o[0] = b + 0.5;
            memcpy(o + 1, pts[i].p + 4 * b, 4 * sizeof *o);
        }
    }
    rc = rc || tables(c, pts, n, t, d, h, err);
    free(t), free(d);
    return rc;
}

int cmp_profiles(const cmp_plan *pl, char *const *parts, const cmp_case *c, FILE *txt, exp_tab_file *h,
                 gr_err *err)
{
    prof_point *pts = malloc((pl->nunits ? pl->nunits : 1) * sizeof *pts);
    if (!pts)
        return gr_fail(err, GR_ERUN, "out of memory");
    size_t n = 0;
    int any = 0, rc = GR_OK;
    const prof_point *ref = NULL;
    for (size_t u = 0; u < pl->nunits && !rc; u++) {
        const cmp_unit *x = &pl->units[u];
        if (x->c != c || (u > 0 && pl->units[u - 1].c == c && pl->units[u - 1].row == x->row &&
                          !strcmp(pl->units[u - 1].value, x->value)))
            continue;
        pts[n].row = x->row;
        snprintf(pts[n].value, sizeof pts[n].value, "%s", x->value);
        rc = pool(pl, parts, u, &pts[n], &any, err);
        n++;
    }
    for (size_t i = 0; i < n; i++)
        if (pts[i].row->role == CMP_REFERENCE)
            ref = &pts[i];
    if (!rc && any && ref)
        rc = write_out(c, pts, n, ref, txt, h, err);
    free(pts);
    return rc;
}
