/* grano silo-start: the report. Averages the discharges of each orifice,
 * fits the mean-square-displacement exponents, compares the displacement
 * distributions with eq. 3.4 and a Gaussian, and writes silo-start.h5 (typed
 * tables), the text tables and, when gnuplot is on PATH, the figures of
 * thesis figs. 3.1-3.6. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fields.h"
#include "h5tab.h"
#include "parts.h"
#include "plot.h"
#include "silo_start.h"
#include "stats.h"
#include "table.h"

#define SS_DCOL 13 /* columns of a discharges table */

static void orif_free(ss_res *o)
{
    gr_msd_free(o->msd);
    for (int a = 0; a < 2; a++)
        free(o->pool[a][0]), free(o->pool[a][1]);
    free(o->vy), free(o->wsum);
}

/* The arrays one part (one discharge) left in its checkpoint. */
typedef struct {
    double *a[7]; /* per slot: lag, n, sx2, sx4, sy2, sy4, fall_sum */
    double *fn, *fp, *fm, *fw, *ser, *grid;
    size_t n, fnn, nser, ng, nw;
} ss_part;

/* The velocity field's sums over the parts of one orifice. */
typedef struct {
    double *num, *py, *mass;
    size_t nc;
} ss_field_sums;

static int read_part(gr_ckpt *ck, const char *path, size_t ns, size_t nt, ss_part *p,
                     gr_err *err)
{
    int rc = GR_OK;
    const char *names[] = {"lag", "n", "sx2", "sx4", "sy2", "sy4", "fall_sum"};
    for (int i = 0; i < 7 && !rc; i++)
        rc = exp_get_array(ck, names[i], &p->a[i], &p->n, err);
    if (!rc) rc = exp_get_array(ck, "field_num", &p->fn, &p->fnn, err);
    if (!rc) rc = exp_get_array(ck, "field_py", &p->fp, &p->fnn, err);
    if (!rc) rc = exp_get_array(ck, "field_mass", &p->fm, &p->fnn, err);
    if (!rc) rc = exp_get_array(ck, "field_wsum", &p->fw, &p->nw, err);
    if (!rc) rc = exp_get_array(ck, "field_grid", &p->grid, &p->ng, err);
    if (!rc) rc = exp_get_array(ck, "series", &p->ser, &p->nser, err);
    if (!rc && (p->n != ns || p->nw != nt))
        rc = gr_fail(err, GR_EINPUT, "%s: part does not match the options", path);
    return rc;
}

static void part_free(ss_part *p)
{
    for (int i = 0; i < 7; i++)
        free(p->a[i]);
    free(p->fn), free(p->fp), free(p->fm), free(p->fw), free(p->grid), free(p->ser);
}

/* Adds part p to the sums; the first part sets the field's size and grid. */
static int add_part(const ss_part *p, size_t nt, ss_res *r, ss_field_sums *f, gr_err *err)
{
    if (!f->num) {
        f->nc = p->fnn / nt;
        memcpy(r->grid, p->grid, sizeof r->grid);
        f->num = calloc(p->fnn, sizeof *f->num), f->py = calloc(p->fnn, sizeof *f->py),
        f->mass = calloc(p->fnn, sizeof *f->mass);
        r->wsum = calloc(nt, sizeof *r->wsum);
        if (!f->num || !f->py || !f->mass || !r->wsum)
            return gr_fail(err, GR_ERUN, "out of memory");
    }
    for (size_t i = 0; i < nt * f->nc; i++)
        f->num[i] += p->fn[i], f->py[i] += p->fp[i], f->mass[i] += p->fm[i];
    for (size_t j = 0; j < nt; j++)
        r->wsum[j] += p->fw[j];
    double *const *a = p->a;
    for (size_t s = 0; s < r->ns; s++) {
        if (a[1][s] <= 0)
            continue;
        if (isnan(r->msd->lag[s]))
            r->msd->lag[s] = a[0][s];
        r->msd->n[s] += a[1][s], r->msd->sx2[s] += a[2][s], r->msd->sx4[s] += a[3][s];
        r->msd->sy2[s] += a[4][s], r->msd->sy4[s] += a[5][s];
        r->fall[s] += a[6][s];
    }
    return GR_OK;
}

/* Writes realisation k's raw data to the file, its row of the orifice's
 * discharges table into disc, and adds its cost to the mean. */
static int write_part(const ss_ctx *c, int k, gr_ckpt *ck, const ss_part *p, ss_res *r,
                      exp_tab_file *h, double *disc, gr_err *err)
{
    size_t ns = r->ns;
    char nm[128];
    snprintf(nm, sizeof nm, "D%g/r%02d/msd_sums", r->D, k);
    const exp_col sums[] = {
        {"lag", "tau", "lag time", EXP_F64, p->a[0], 0},
        {"n", "1", "displacements summed", EXP_INT, p->a[1], 0},
        {"sum_dx2", "d+2", "sum of dx^2", EXP_F64, p->a[2], 0},
        {"sum_dx4", "d+4", "sum of dx^4", EXP_F64, p->a[3], 0},
        {"sum_dy2", "d+2", "sum of dy^2", EXP_F64, p->a[4], 0},
        {"sum_dy4", "d+4", "sum of dy^4", EXP_F64, p->a[5], 0},
        {"sum_fall", "d", "sum of the surface's fall over the lag", EXP_F64, p->a[6], 0},
    };
    int rc = exp_tab_write(h, nm, "per-slot sums of this discharge", ns, sums, sizeof sums / sizeof sums[0], err);
    snprintf(nm, sizeof nm, "D%g/r%02d/series", r->D, k);
    const exp_col ser[] = {
        {"step", "1", "steps after opening", EXP_INT, p->ser, 3},
        {"top", "d", "highest grain", EXP_F64, p->ser + 1, 3},
        {"outflow", "1", "grains out so far", EXP_INT, p->ser + 2, 3},
    };
    if (!rc && p->nser >= 3)
        rc = exp_tab_write(h, nm, "highest grain and outflow after opening", p->nser / 3, ser, 3, err);
    double cost[5], branch[4];
    exp_get_cost(ck, cost);
    gr_err ig = {0};
    if (gr_ckpt_get_f64(ck, "branch", branch, 4, &ig))
        for (int q = 0; q < 4; q++)
            branch[q] = NAN;
    for (int q = 0; q < 5; q++)
        r->cost[q] += cost[q] / (double)c->nreal;
    for (int q = 0; q < 4; q++)
        r->branch[q] += branch[q] / (double)c->nreal;
    double row[SS_DCOL] = {(double)k, (double)(c->seed + (uint64_t)k), exp_get_scalar(ck, "t_settle"),
                           exp_get_scalar(ck, "top0"), exp_get_scalar(ck, "steps"), cost[0], cost[1], cost[2],
                           cost[3], branch[0], branch[1], branch[2], branch[3]};
    memcpy(disc, row, sizeof row);
    return rc;
}

/* The orifice's discharges, one row per realisation. */
static int write_discharges(const ss_ctx *c, const ss_res *r, exp_tab_file *h, const double *d, gr_err *err)
{
    const exp_col cols[] = {
        {"realisation", "1", "realisation (its filling)", EXP_INT, d, SS_DCOL},
        {"seed", "1", "its seed", EXP_INT, d + 1, SS_DCOL},
        {"settle_time", "tau", "time the filling took to settle", EXP_F64, d + 2, SS_DCOL},
        {"top_height", "d", "highest grain at opening", EXP_F64, d + 3, SS_DCOL},
        {"steps", "1", "steps run after opening", EXP_INT, d + 4, SS_DCOL},
        {"wall_branch", "s", "wall seconds of the branch from the filling", EXP_F64, d + 5, SS_DCOL},
        {"cpu_branch", "s", "CPU seconds of the branch", EXP_F64, d + 6, SS_DCOL},
        {"wall_run", "s", "wall seconds of the discharge", EXP_F64, d + 7, SS_DCOL},
        {"cpu_run", "s", "CPU seconds of the discharge", EXP_F64, d + 8, SS_DCOL},
        {"branch_settle_time", "tau", "settling time of the branch", EXP_F64, d + 9, SS_DCOL},
        {"lift", "d", "the branch's lift", EXP_F64, d + 10, SS_DCOL},
        {"cpu_fill", "s", "CPU seconds of the filling", EXP_F64, d + 11, SS_DCOL},
        {"ekin_open", "m d+2 tau-2", "kinetic energy per grain at opening", EXP_F64, d + 12, SS_DCOL},
    };
    char nm[64];
    snprintf(nm, sizeof nm, "D%g/discharges", r->D);
    return exp_tab_write(h, nm, "one row per realisation's discharge", (size_t)c->nreal, cols,
                         sizeof cols / sizeof cols[0], err);
}

static int mean_velocity(const ss_field_sums *f, size_t nt, ss_res *r, gr_err *err)
{
    r->vy = malloc((nt * f->nc + 1) * sizeof *r->vy);
    if (!r->vy)
        return gr_fail(err, GR_ERUN, "out of memory");
    for (size_t i = 0; i < nt * f->nc; i++)
        r->vy[i] = f->mass[i] > 0 ? f->py[i] / f->mass[i] : NAN;
    return GR_OK;
}

/* Sums of every part of orifice o; per-realisation raw data go to the file. */
static int gather(const ss_ctx *c, size_t o, char *const *parts, ss_res *r, exp_tab_file *h,
                  gr_err *err)
{
    size_t ns = c->nslots, nt = c->ntimes;
    r->D = c->orifice[o];
    r->ns = ns;
    if (!(r->msd = gr_msd_create(ns, err)))
        return err->code;
    ss_field_sums f = {0};
    double *disc = malloc((size_t)c->nreal * SS_DCOL * sizeof *disc);
    int rc = disc ? GR_OK : gr_fail(err, GR_ERUN, "out of memory");
    for (int k = 0; k < c->nreal && !rc; k++) {
        const char *path = parts[o * (size_t)c->nreal + (size_t)k];
        gr_ckpt *ck = gr_ckpt_open(path, err);
        if (!ck)
            return err->code;
        ss_part p = {0};
        rc = read_part(ck, path, ns, nt, &p, err);
        if (!rc)
            rc = add_part(&p, nt, r, &f, err);
        if (!rc)
            rc = write_part(c, k, ck, &p, r, h, disc + (size_t)k * SS_DCOL, err);
        part_free(&p);
        gr_err ig = {0};
        gr_ckpt_close(ck, &ig);
    }
    if (!rc)
        rc = write_discharges(c, r, h, disc, err) || mean_velocity(&f, nt, r, err);
    free(f.num), free(f.py), free(f.mass), free(disc);
    return rc;
}

static int nearest_slot(const ss_res *r, double fall)
{
    int best = -1;
    double bd = INFINITY;
    for (size_t s = 0; s < r->ns; s++) {
        if (!(r->msd->n[s] > 0) || !(r->fall[s] > 0))
            continue;
        double d = fabs(log(r->fall[s] / fall));
        if (d < bd)
            bd = d, best = (int)s;
    }
    return best;
}

/* Pool the samples of the chosen slots, scale them to unit standard
 * deviation, histogram them and compare with eq. 3.4 and a Gaussian. */
static int distributions(const ss_ctx *c, size_t o, char *const *parts, ss_res *r, gr_err *err)
{
    for (int w = 0; w < 2; w++) {
        int s = r->sel[w];
        for (int k = 0; k < 10; k++)
            r->stats[w][k] = NAN;
        if (s < 0)
            continue;
        size_t cap = (size_t)c->nreal * c->sample_cap, m = 0;
        r->pool[w][0] = malloc(cap * sizeof(double));
        r->pool[w][1] = malloc(cap * sizeof(double));
        if (!r->pool[w][0] || !r->pool[w][1])
            return gr_fail(err, GR_ERUN, "out of memory");
        for (int k = 0; k < c->nreal; k++) {
            gr_ckpt *ck = gr_ckpt_open(parts[o * (size_t)c->nreal + (size_t)k], err);
            if (!ck)
                return err->code;
            char nm[64];
            for (int comp = 0; comp < 2; comp++) {
                double *v;
                size_t n;
                snprintf(nm, sizeof nm, "samples_%c_%d", comp ? 'y' : 'x', s);
                if (exp_get_array(ck, nm, &v, &n, err)) {
                    gr_ckpt_discard(ck);
                    return err->code;
                }
                memcpy(r->pool[w][comp] + m, v, (n < cap - m ? n : cap - m) * sizeof *v);
                if (comp)
                    m += n < cap - m ? n : cap - m;
                free(v);
            }
            gr_err ig = {0};
            gr_ckpt_close(ck, &ig);
        }
        r->npool[w] = m;
        double *st = r->stats[w];
        st[0] = r->msd->lag[s], st[1] = r->fall[s];
        if (m < 10)
            continue;
        for (int comp = 0; comp < 2; comp++) {
            double *v = r->pool[w][comp], sd, dks, dg;
            st[8 + comp] = gr_kappa_zero(v, m);
            if (gr_standardize(v, m, 0, v, NULL, &sd, err))
                return err->code;
            st[2 + comp] = sd;
            if (gr_ks_distance(v, m, gr_cdf_eq34_cb, NULL, &dks, err) ||
                gr_ks_distance(v, m, gr_cdf_gauss_cb, NULL, &dg, err))
                return err->code;
            st[4 + 2 * comp] = dks, st[5 + 2 * comp] = dg;
            gr_hist *hh = gr_hist_create(NB, -UMAX, UMAX, err);
            if (!hh)
                return err->code;
            gr_hist_add_array(hh, v, m);
            double cen[NB], den[NB], er[NB];
            gr_hist_density(hh, cen, den, er);
            for (int b = 0; b < NB; b++)
                r->pdf[w][b][0] = cen[b], r->pdf[w][b][1 + 2 * comp] = den[b], r->pdf[w][b][2 + 2 * comp] = er[b];
            gr_hist_free(hh);
        }
    }
    return GR_OK;
}

static void fit_msd(ss_res *r)
{
    double lo = r->sel[0] >= 0 ? r->fall[r->sel[0]] * 0.999 : 0, hi = 1.0;
    double x[SS_MAX_SLOTS], y[2][SS_MAX_SLOTS];
    size_t n = 0;
    for (int pass = 0; pass < 2 && n < 3; pass++) {
        n = 0;
        for (size_t s = 0; s < r->ns; s++) {
            if (!(r->msd->n[s] > 0) || !(r->mx[s] > 0) || !(r->my[s] > 0))
                continue;
            if (pass == 0 && (r->fall[s] < lo || r->fall[s] > hi))
                continue;
            x[n] = r->lag[s], y[0][n] = r->mx[s], y[1][n] = r->my[s];
            n++;
        }
    }
    r->fit_range[0] = n ? x[0] : NAN, r->fit_range[1] = n ? x[n - 1] : NAN;
    for (int comp = 0; comp < 2; comp++) {
        gr_err e = {0};
        r->fit_ok[comp] = n >= 3 && gr_fit_loglog(x, y[comp], NULL, n, &r->fit[comp], &e) == GR_OK;
    }
}

/* silo-start.h5, a file of typed tables, with the run's settings. */
static exp_tab_file *open_result(const ss_ctx *c, gr_err *err)
{
    char path[1300];
    snprintf(path, sizeof path, "%s/silo-start.h5", c->dir);
    exp_tab_file *h = exp_tab_create(path, "grano silo-start: the start of the discharge (thesis chapter 3)", err);
    if (!h)
        return NULL;
    const char *method = c->base.method->name;
    char mat_text[SILO_PARAMS + 160];
    silo_material(&c->base, mat_text, sizeof mat_text);
    const char *mat = mat_text;
    double outlet = c->base.hopper ? c->base.outlet : 0.0;
    double v[12] = {(double)c->base.n, c->base.width, c->base.height, c->base.dt, (double)c->nreal,
                    (double)c->fs, c->window, c->cell, c->fall_stop, (double)c->max_steps,
                    (double)c->min_steps, (double)c->seed};
    const exp_col cols[] = {
        {"method", "", "the method that ran", EXP_STR, &method, 0},
        {"material", "", "the [material] section the grains ran with (--material)", EXP_STR, &mat, 0},
        {"hopper_outlet", "1", "the filling hopper's outlet, a fraction of the width (0: no hopper)", EXP_F64,
         &outlet, 0},
        {"grains", "1", "grains in the silo", EXP_INT, v, 0},
        {"width", "d", "silo width", EXP_F64, v + 1, 0},
        {"height", "d", "silo height", EXP_F64, v + 2, 0},
        {"dt", "tau", "time step", EXP_F64, v + 3, 0},
        {"realisations", "1", "discharges per orifice (one filling each, shared by the orifices)", EXP_INT,
         v + 4, 0},
        {"frame_steps", "1", "steps between frames of the displacement record", EXP_INT, v + 5, 0},
        {"window", "d", "side of the displacement window", EXP_F64, v + 6, 0},
        {"cell", "d", "velocity field cells", EXP_F64, v + 7, 0},
        {"fall_stop", "d", "a discharge stops once the surface has fallen this far", EXP_F64, v + 8, 0},
        {"max_steps", "1", "most steps of a discharge", EXP_INT, v + 9, 0},
        {"min_steps", "1", "fewest steps of a discharge", EXP_INT, v + 10, 0},
        {"seed", "1", "seed of realisation 0 (realisation k: seed + k)", EXP_INT, v + 11, 0},
    };
    const exp_col ocol = {"D", "d", "orifice width", EXP_F64, c->orifice, 0};
    if (exp_tab_write(h, "config", "the run's settings", 1, cols, sizeof cols / sizeof cols[0], err) ||
        exp_tab_write(h, "orifices", "the orifice widths, in --orifices order", c->norif, &ocol, 1, err)) {
        exp_tab_free(h);
        return NULL;
    }
    return h;
}

/* Orifice o from its parts: the MSD and its kurtosis per lag, the two
 * displacement distributions, the MSD fits. */
static int analyse(const ss_ctx *c, size_t o, char *const *parts, ss_res *r, exp_tab_file *h, gr_err *err)
{
    if (gather(c, o, parts, r, h, err))
        return err->code;
    gr_msd_result(r->msd, r->mx, r->my, r->ex, r->ey, r->kx, r->ky);
    for (size_t s = 0; s < r->ns; s++) {
        r->lag[s] = r->msd->lag[s];
        r->fall[s] = r->msd->n[s] > 0 ? r->fall[s] / r->msd->n[s] : NAN;
    }
    r->sel[0] = nearest_slot(r, 0.01);
    r->sel[1] = nearest_slot(r, c->fall_stop);
    if (distributions(c, o, parts, r, err))
        return err->code;
    fit_msd(r);
    return GR_OK;
}

/* The MSD table (file and .dat) and its fits: exponent, error, prefactor,
 * error and range for x then y, into fit. */
static int write_msd(const ss_ctx *c, const ss_res *r, exp_tab_file *h, double fit[2][6], gr_err *err)
{
    char nm[128], dat[1400];
    double tab[SS_MAX_SLOTS][10];
    for (size_t s = 0; s < r->ns; s++) {
        double row[10] = {r->lag[s], r->lag[s] / c->base.dt, r->msd->n[s], r->fall[s], r->mx[s],
                          r->my[s], r->ex[s], r->ey[s], r->kx[s], r->ky[s]};
        memcpy(tab[s], row, sizeof row);
    }
    const double *t = &tab[0][0];
    const exp_col mcols[] = {
        {"lag_time", "tau", "lag", EXP_F64, t, 10},
        {"lag_steps", "1", "lag in steps", EXP_INT, t + 1, 10},
        {"n", "1", "displacements averaged (all discharges)", EXP_INT, t + 2, 10},
        {"fall", "d", "mean fall of the surface over the lag", EXP_F64, t + 3, 10},
        {"msd_x", "d+2", "mean square horizontal displacement", EXP_F64, t + 4, 10},
        {"msd_y", "d+2", "mean square vertical displacement (local mean flow subtracted)", EXP_F64, t + 5, 10},
        {"err_x", "d+2", "error bar of msd_x", EXP_F64, t + 6, 10},
        {"err_y", "d+2", "error bar of msd_y", EXP_F64, t + 7, 10},
        {"kappa_x", "1", "excess kurtosis of dx", EXP_F64, t + 8, 10},
        {"kappa_y", "1", "excess kurtosis of dy", EXP_F64, t + 9, 10},
    };
    snprintf(nm, sizeof nm, "D%g/msd", r->D);
    int rc = exp_tab_write(h, nm, "mean square displacement and kurtosis per lag, all discharges", r->ns, mcols,
                           sizeof mcols / sizeof mcols[0], err);
    snprintf(dat, sizeof dat, "%s/msd_D%g.dat", c->dir, r->D);
    if (!rc)
        rc = exp_write_dat(dat, "lag_time lag_steps n fall msd_x msd_y err_x err_y kappa_x kappa_y", &tab[0][0], r->ns, 10, err);
    for (int comp = 0; comp < 2; comp++) {
        const gr_fit *f = &r->fit[comp];
        double row[6] = {r->fit_ok[comp] ? f->p[1] : NAN, r->fit_ok[comp] ? f->err[1] : NAN,
                         r->fit_ok[comp] ? f->p[0] : NAN, r->fit_ok[comp] ? f->err[0] : NAN,
                         r->fit_range[0], r->fit_range[1]};
        memcpy(fit[comp], row, sizeof row);
    }
    static const char *const axis[2] = {"x", "y"};
    const double *q = &fit[0][0];
    const exp_col fcols[] = {
        {"axis", "", "displacement component", EXP_STR, axis, 0},
        {"exponent", "1", "p of <d^2> = A t^p", EXP_F64, q, 6},
        {"exponent_err", "1", "its error", EXP_F64, q + 1, 6},
        {"prefactor", "d+2 tau-p", "A", EXP_F64, q + 2, 6},
        {"prefactor_err", "d+2 tau-p", "its error", EXP_F64, q + 3, 6},
        {"t_lo", "tau", "first lag fitted", EXP_F64, q + 4, 6},
        {"t_hi", "tau", "last lag fitted", EXP_F64, q + 5, 6},
    };
    snprintf(nm, sizeof nm, "D%g/msd_fit", r->D);
    if (!rc)
        rc = exp_tab_write(h, nm, "log-log fit <d^2> = A t^p", 2, fcols, sizeof fcols / sizeof fcols[0], err);
    return rc;
}

/* Relative change of the velocity field since the previous field time
 * (every discharge still running at both), rows by orifice then time:
 * step, discharges, change (NaN at the first time and where a discharge
 * had ended). */
static void stationarity(const ss_ctx *c, const ss_res *res, size_t nr, double *table)
{
    size_t nc = (size_t)(res[0].grid[0] * res[0].grid[1]);
    for (size_t o = 0; o < nr; o++) {
        const ss_res *r = &res[o];
        long prev = -1;
        for (size_t j = 0; j < c->ntimes; j++) {
            double *row = table + (o * c->ntimes + j) * 3;
            row[0] = (double)c->times[j], row[1] = r->wsum[j] / 5.0, row[2] = NAN;
            if (r->wsum[j] < 5.0 * c->nreal - 0.5)
                continue; /* not every discharge lasted that long */
            if (prev >= 0) {
                double num = 0, den = 0;
                for (size_t i = 0; i < nc; i++) {
                    double a = r->vy[j * nc + i], b = r->vy[(size_t)prev * nc + i];
                    if (isfinite(a) && isfinite(b))
                        num += (a - b) * (a - b), den += a * a;
                }
                row[2] = den > 0 ? sqrt(num / den) : NAN;
            }
            prev = (long)j;
        }
    }
}

/* The displacement distributions and their statistics, and the velocity
 * field with its grid and times. */
static int write_pdfs_fields(const ss_ctx *c, const ss_res *r, exp_tab_file *h, gr_err *err)
{
    char nm[128], dat[1400];
    int rc = GR_OK;
    for (int w = 0; w < 2 && !rc; w++) {
        const double *p = &r->pdf[w][0][0];
        const exp_col pc[] = {
            {"u", "1", "displacement / its standard deviation, bin centre", EXP_F64, p, 5},
            {"p_x", "1", "probability density, horizontal", EXP_F64, p + 1, 5},
            {"err_x", "1", "its error bar", EXP_F64, p + 2, 5},
            {"p_y", "1", "probability density, vertical", EXP_F64, p + 3, 5},
            {"err_y", "1", "its error bar", EXP_F64, p + 4, 5},
        };
        snprintf(nm, sizeof nm, "D%g/pdf_%s", r->D, w ? "long" : "short");
        rc = exp_tab_write(h, nm,
                           w ? "normalised displacement density, lag of a 2 d fall"
                             : "normalised displacement density, lag of a 0.01 d fall",
                           NB, pc, sizeof pc / sizeof pc[0], err);
        snprintf(dat, sizeof dat, "%s/pdf_%s_D%g.dat", c->dir, w ? "long" : "short", r->D);
        if (!rc)
            rc = exp_write_dat(dat, "u p_x err_x p_y err_y", p, NB, 5, err);
    }
    static const char *const lag[2] = {"short", "long"};
    const double *st = &r->stats[0][0];
    const exp_col sc[] = {
        {"lag", "", "short (a 0.01 d fall) or long (a 2 d fall)", EXP_STR, lag, 0},
        {"lag_time", "tau", "the lag", EXP_F64, st, 10},
        {"fall", "d", "mean fall of the surface over it", EXP_F64, st + 1, 10},
        {"sd_x", "d", "standard deviation of dx", EXP_F64, st + 2, 10},
        {"sd_y", "d", "standard deviation of dy", EXP_F64, st + 3, 10},
        {"ks_eq34_x", "1", "KS distance of dx to eq. 3.4", EXP_F64, st + 4, 10},
        {"ks_gauss_x", "1", "KS distance of dx to the Gaussian", EXP_F64, st + 5, 10},
        {"ks_eq34_y", "1", "KS distance of dy to eq. 3.4", EXP_F64, st + 6, 10},
        {"ks_gauss_y", "1", "KS distance of dy to the Gaussian", EXP_F64, st + 7, 10},
        {"kappa_x", "1", "excess kurtosis of dx", EXP_F64, st + 8, 10},
        {"kappa_y", "1", "excess kurtosis of dy", EXP_F64, st + 9, 10},
    };
    snprintf(nm, sizeof nm, "D%g/pdf_stats", r->D);
    if (!rc)
        rc = exp_tab_write(h, nm, "the displacement distributions against eq. 3.4 and a Gaussian", 2, sc,
                           sizeof sc / sizeof sc[0], err);
    size_t dims[3] = {c->ntimes, (size_t)r->grid[1], (size_t)r->grid[0]};
    snprintf(nm, sizeof nm, "D%g/velocity_y", r->D);
    if (!rc)
        rc = exp_tab_array(h, nm, 3, dims, r->vy, "d tau-1",
                           "mean vertical velocity per cell [field time][y][x] (NaN: no grain), at field_steps' "
                           "steps, on field_grid's cells", err);
    const double *g = r->grid;
    const exp_col gc[] = {
        {"nx", "1", "cells across", EXP_INT, g, 0},        {"ny", "1", "cells up", EXP_INT, g + 1, 0},
        {"x0", "d", "left edge", EXP_F64, g + 2, 0},        {"y0", "d", "lower edge", EXP_F64, g + 3, 0},
        {"cell_width", "d", "cell width", EXP_F64, g + 4, 0}, {"cell_height", "d", "cell height", EXP_F64, g + 5, 0},
    };
    snprintf(nm, sizeof nm, "D%g/field_grid", r->D);
    if (!rc)
        rc = exp_tab_write(h, nm, "the velocity field's grid", 1, gc, sizeof gc / sizeof gc[0], err);
    double ts[SS_MAX_TIMES];
    for (size_t j = 0; j < c->ntimes; j++)
        ts[j] = (double)c->times[j];
    const exp_col tc = {"step", "1", "steps after opening of each velocity field", EXP_INT, ts, 0};
    snprintf(nm, sizeof nm, "D%g/field_steps", r->D);
    if (!rc)
        rc = exp_tab_write(h, nm, "the times of the velocity fields", c->ntimes, &tc, 1, err);
    return rc;
}

/* Orifice r's row of the summary table, and its lines of the printed
 * summary appended at *off. */
static void summary_row(const ss_ctx *c, const ss_res *r, double fit[2][6], double *s, char *summary, size_t nsum,
                        size_t *off)
{
    double row[20] = {r->D, (double)c->nreal, r->stats[0][0], r->stats[0][1], r->stats[0][2], r->stats[0][3],
                      fit[0][0], fit[0][1], fit[1][0], fit[1][1], r->stats[0][8], r->stats[0][9],
                      r->stats[1][1], r->stats[1][8], r->stats[1][9], r->stats[0][4], r->stats[0][5],
                      r->stats[0][6], r->stats[0][7], r->stats[1][0]};
    memcpy(s, row, sizeof row);
    if (summary && *off < nsum)
        *off += (size_t)snprintf(summary + *off, nsum - *off,
                                 "  D = %g d: MSD exponents x %.3f +- %.3f, y %.3f +- %.3f; kappa (x, y) %.2f, %.2f at a %.3g d fall, %.2f, %.2f at %.3g d\n"
                                 "    per discharge: the filling %.0f s CPU (one per realisation, shared by the orifices), branch %.1f s CPU\n"
                                 "    (lift %.3f d, settled %.2f tau, kinetic energy %.2g m g d per grain at opening), run %.0f s wall (%.0f s CPU) for %.0f steps\n",
                                 r->D, fit[0][0], fit[0][1], fit[1][0], fit[1][1], s[10], s[11], s[3], s[13], s[14], s[12],
                                 r->branch[2], r->cost[1], r->branch[1], r->branch[0], r->branch[3], r->cost[2], r->cost[3], r->cost[4]);
}

static int write_summary(const ss_ctx *c, exp_tab_file *h, const double *summ, gr_err *err)
{
    const char *scols = "D,realisations,lag_short,fall_short,sd_x,sd_y,exp_x,exp_x_err,exp_y,exp_y_err,kappa_x_short,kappa_y_short,fall_long,kappa_x_long,kappa_y_long,ks_eq34_x,ks_gauss_x,ks_eq34_y,ks_gauss_y,lag_long";
    const double *v = summ;
    const exp_col cols[20] = {
        {"D", "d", "orifice width", EXP_F64, v, 20},
        {"realisations", "1", "discharges", EXP_INT, v + 1, 20},
        {"lag_short", "tau", "the short lag (a 0.01 d fall)", EXP_F64, v + 2, 20},
        {"fall_short", "d", "the fall over it", EXP_F64, v + 3, 20},
        {"sd_x", "d", "standard deviation of dx at the short lag", EXP_F64, v + 4, 20},
        {"sd_y", "d", "standard deviation of dy at the short lag", EXP_F64, v + 5, 20},
        {"exp_x", "1", "MSD exponent, horizontal", EXP_F64, v + 6, 20},
        {"exp_x_err", "1", "its error", EXP_F64, v + 7, 20},
        {"exp_y", "1", "MSD exponent, vertical", EXP_F64, v + 8, 20},
        {"exp_y_err", "1", "its error", EXP_F64, v + 9, 20},
        {"kappa_x_short", "1", "excess kurtosis of dx, short lag", EXP_F64, v + 10, 20},
        {"kappa_y_short", "1", "excess kurtosis of dy, short lag", EXP_F64, v + 11, 20},
        {"fall_long", "d", "the fall over the long lag", EXP_F64, v + 12, 20},
        {"kappa_x_long", "1", "excess kurtosis of dx, long lag", EXP_F64, v + 13, 20},
        {"kappa_y_long", "1", "excess kurtosis of dy, long lag", EXP_F64, v + 14, 20},
        {"ks_eq34_x", "1", "KS distance of dx to eq. 3.4, short lag", EXP_F64, v + 15, 20},
        {"ks_gauss_x", "1", "KS distance of dx to the Gaussian, short lag", EXP_F64, v + 16, 20},
        {"ks_eq34_y", "1", "KS distance of dy to eq. 3.4, short lag", EXP_F64, v + 17, 20},
        {"ks_gauss_y", "1", "KS distance of dy to the Gaussian, short lag", EXP_F64, v + 18, 20},
        {"lag_long", "tau", "the long lag (a 2 d fall)", EXP_F64, v + 19, 20},
    };
    if (exp_tab_write(h, "summary", "one row per orifice", c->norif, cols, 20, err))
        return err->code;
    char path[1300], hdr[600];
    snprintf(path, sizeof path, "%s/summary.dat", c->dir);
    snprintf(hdr, sizeof hdr, "%s", scols);
    for (char *q = hdr; *q; q++)
        if (*q == ',')
            *q = ' ';
    return exp_write_dat(path, hdr, summ, c->norif, 20, err);
}

/* The field's approach to stationarity, every orifice's rows. */
static int write_stationarity(const ss_ctx *c, const double *stab, gr_err *err, exp_tab_file *h)
{
    size_t nr = c->norif, n = nr * c->ntimes;
    double *D = malloc(n * sizeof *D);
    if (!D)
        return gr_fail(err, GR_ERUN, "out of memory");
    for (size_t k = 0; k < n; k++)
        D[k] = c->orifice[k / c->ntimes];
    const exp_col cols[] = {
        {"D", "d", "orifice width", EXP_F64, D, 0},
        {"step", "1", "steps after opening", EXP_INT, stab, 3},
        {"discharges", "1", "discharges still running", EXP_F64, stab + 1, 3},
        {"relative_change", "1", "|v_j - v_j-1| / |v_j| (NaN: first time, or a discharge had ended)", EXP_F64,
         stab + 2, 3},
    };
    int rc = exp_tab_write(h, "stationarity", "velocity field change since the previous field time", n, cols,
                           sizeof cols / sizeof cols[0], err);
    free(D);
    return rc;
}

/* Figs. 3.1-3.6. */
static int figures(const ss_ctx *c, char *const *parts, ss_res *res, const double *stab, gr_err *err)
{
    size_t nr = c->norif, big = 0;
    char path[1300];
    for (size_t o = 1; o < nr; o++)
        if (c->orifice[o] > c->orifice[big])
            big = o;
    int rc = GR_OK;
    for (size_t o = 0; o < nr && !rc; o++) {
        if (o == big)
            snprintf(path, sizeof path, "%s/fig3_2_velocity_profiles.png", c->dir);
        else
            snprintf(path, sizeof path, "%s/fig3_2_velocity_profiles_D%g.png", c->dir, c->orifice[o]);
        rc = ss_fig_velocity(path, c, &res[o], ss_fig32_steps, 6, err);
    }
    snprintf(path, sizeof path, "%s/fig3_2_stationarity.png", c->dir);
    if (!rc)
        rc = ss_fig_stationarity(path, c, res, nr, stab, err);
    snprintf(path, sizeof path, "%s/fig3_3_displacement_pdf.png", c->dir);
    if (!rc)
        rc = ss_fig_pdf(path, res, nr, 0, 1, "Displacements over a 0.01 d fall (thesis fig. 3.3)", err);
    snprintf(path, sizeof path, "%s/fig3_4_msd.png", c->dir);
    if (!rc)
        rc = ss_fig_msd(path, res, nr, err);
    snprintf(path, sizeof path, "%s/fig3_5_displacement_pdf_long.png", c->dir);
    if (!rc)
        rc = ss_fig_pdf(path, res, nr, 1, 0, "Displacements at long times: a 2 d fall (thesis fig. 3.5)", err);
    snprintf(path, sizeof path, "%s/fig3_6_kurtosis.png", c->dir);
    if (!rc)
        rc = ss_fig_kurtosis(path, res, nr, err);
    if (!rc)
        rc = ss_pictures(c, parts, big, err);
    return rc;
}

int ss_report(const ss_ctx *c, char *const *parts, char *summary, size_t nsum, gr_err *err)
{
    exp_tab_file *h = open_result(c, err);
    if (!h)
        return err->code;
    size_t nr = c->norif, off = 0;
    ss_res *res = calloc(nr, sizeof *res);
    double *stab = malloc(nr * c->ntimes * 3 * sizeof *stab);
    double summ[SS_MAX_ORIF][20];
    int rc = res && stab ? GR_OK : gr_fail(err, GR_ERUN, "out of memory");
    if (summary && nsum)
        summary[0] = 0;
    for (size_t o = 0; o < nr && !rc; o++) {
        double fit[2][6];
        rc = analyse(c, o, parts, &res[o], h, err) || write_msd(c, &res[o], h, fit, err) ||
             write_pdfs_fields(c, &res[o], h, err);
        if (!rc)
            summary_row(c, &res[o], fit, summ[o], summary, nsum, &off);
    }
    if (!rc)
        stationarity(c, res, nr, stab);
    rc = rc || write_summary(c, h, &summ[0][0], err) || write_stationarity(c, stab, err, h);
    /* the data whole and closed before any figure */
    if (!rc) {
        rc = exp_tab_close(h, err);
        h = NULL;
    }
    if (!rc && gr_plot_have_gnuplot())
        rc = figures(c, parts, res, stab, err);
    exp_tab_free(h);
    if (rc)
        rc = err->code ? err->code : GR_ERUN;
    for (size_t o = 0; res && o < nr; o++)
        orif_free(&res[o]);
    free(res), free(stab);
    return rc;
}
