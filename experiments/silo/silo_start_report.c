/* grano silo-start: the report. Averages the discharges of each orifice,
 * fits the mean-square-displacement exponents, compares the displacement
 * distributions with eq. 3.4 and a Gaussian, and writes silo-start.h5, the
 * tables and the figures of thesis figs. 3.1-3.6. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fields.h"
#include "h5md.h"
#include "parts.h"
#include "plot.h"
#include "silo_start.h"
#include "stats.h"
#include "table.h"

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

/* Writes realisation k's raw data to the file and adds its cost to the mean. */
static int write_part(const ss_ctx *c, int k, gr_ckpt *ck, const ss_part *p, ss_res *r,
                      gr_h5md *h, gr_err *err)
{
    size_t ns = r->ns;
    char nm[128];
    double *raw = malloc(ns * 7 * sizeof *raw);
    for (size_t s = 0; raw && s < ns; s++)
        for (int i = 0; i < 7; i++)
            raw[s * 7 + (size_t)i] = p->a[i][s];
    snprintf(nm, sizeof nm, "D%g/r%02d/msd_sums", r->D, k);
    int rc = raw ? exp_put_result(h, nm, ns, 7, "lag,n,sum_dx2,sum_dx4,sum_dy2,sum_dy4,sum_fall",
                       "per-slot sums of this discharge", raw, err)
                 : gr_fail(err, GR_ERUN, "out of memory");
    free(raw);
    snprintf(nm, sizeof nm, "D%g/r%02d/series", r->D, k);
    if (!rc && p->nser >= 3)
        rc = exp_put_result(h, nm, p->nser / 3, 3, "step,top,outflow", "highest grain and outflow after opening", p->ser, err);
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
    snprintf(nm, sizeof nm, "D%g/r%02d/cost", r->D, k);
    if (!rc)
        rc = exp_put_result(h, nm, 5, 0, NULL, "wall and CPU seconds of the branch, of the run, and its steps", cost, err);
    snprintf(nm, sizeof nm, "D%g/r%02d/branch", r->D, k);
    if (!rc)
        rc = exp_put_result(h, nm, 4, 0, NULL,
                            "the branch from the realisation's filling: its settling time (tau), the lift (d), the filling's CPU seconds, kinetic energy per grain at opening (m g d)",
                            branch, err);
    double meta[4] = {(double)(c->seed + (uint64_t)k), exp_get_scalar(ck, "t_settle"),
                      exp_get_scalar(ck, "top0"), exp_get_scalar(ck, "steps")};
    snprintf(nm, sizeof nm, "D%g/r%02d/meta", r->D, k);
    if (!rc)
        rc = exp_put_result(h, nm, 4, 0, NULL, "seed, settling time, top height, steps run", meta, err);
    return rc;
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
static int gather(const ss_ctx *c, size_t o, char *const *parts, ss_res *r, gr_h5md *h,
                  gr_err *err)
{
    size_t ns = c->nslots, nt = c->ntimes;
    r->D = c->orifice[o];
    r->ns = ns;
    if (!(r->msd = gr_msd_create(ns, err)))
        return err->code;
    ss_field_sums f = {0};
    int rc = GR_OK;
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
            rc = write_part(c, k, ck, &p, r, h, err);
        part_free(&p);
        gr_err ig = {0};
        gr_ckpt_close(ck, &ig);
    }
    if (!rc)
        rc = mean_velocity(&f, nt, r, err);
    free(f.num), free(f.py), free(f.mass);
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

/* silo-start.h5 with the scene of the first orifice, and the run's
 * configuration. */
static gr_h5md *open_result(const ss_ctx *c, gr_err *err)
{
    silo_cfg cfg = c->base;
    cfg.orifice = c->orifice[0];
    cfg.seed = c->seed;
    gr_scene *sc = silo_scene(&cfg, 0, err);
    if (!sc)
        return NULL;
    char path[1300];
    snprintf(path, sizeof path, "%s/silo-start.h5", c->dir);
    gr_h5md_opts ho = {.method = c->base.method->name, .seed = c->seed, .force = 1, .no_xdmf = 1};
    gr_h5md *h = gr_h5md_create(path, sc, &ho, err);
    gr_scene_free(sc);
    if (!h)
        return NULL;
    double par[12] = {(double)c->base.n, c->base.width, c->base.height, c->base.dt, (double)c->nreal,
                      (double)c->fs, c->window, c->cell, c->fall_stop, (double)c->max_steps,
                      (double)c->min_steps, (double)c->seed};
    if (exp_put_result(h, "config", 12, 0, NULL,
                       "grains, width, height, dt, realisations, frame steps, window, cell, fall to stop, max steps, min steps, seed", par, err) ||
        exp_put_result(h, "orifices", c->norif, 0, NULL, "orifice widths D / d", c->orifice, err)) {
        gr_h5md_free(h);
        return NULL;
    }
    return h;
}

/* Orifice o from its parts: the MSD and its kurtosis per lag, the two
 * displacement distributions, the MSD fits. */
static int analyse(const ss_ctx *c, size_t o, char *const *parts, ss_res *r, gr_h5md *h, gr_err *err)
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
static int write_msd(const ss_ctx *c, const ss_res *r, gr_h5md *h, double fit[2][6], gr_err *err)
{
    char nm[128], dat[1400];
    double tab[SS_MAX_SLOTS][10];
    for (size_t s = 0; s < r->ns; s++) {
        double row[10] = {r->lag[s], r->lag[s] / c->base.dt, r->msd->n[s], r->fall[s], r->mx[s],
                          r->my[s], r->ex[s], r->ey[s], r->kx[s], r->ky[s]};
        memcpy(tab[s], row, sizeof row);
    }
    const char *mcols = "lag_time,lag_steps,n,fall,msd_x,msd_y,err_x,err_y,kappa_x,kappa_y";
    snprintf(nm, sizeof nm, "D%g/msd", r->D);
    int rc = exp_put_result(h, nm, r->ns, 10, mcols, "mean square displacement and kurtosis per lag, all discharges", &tab[0][0], err);
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
    snprintf(nm, sizeof nm, "D%g/msd_fit", r->D);
    if (!rc)
        rc = exp_put_result(h, nm, 2, 6, "exponent,exponent_err,prefactor,prefactor_err,t_lo,t_hi",
                 "log-log fit <d^2> = A t^p, rows x then y", &fit[0][0], err);
    return rc;
}

/* The displacement distributions and their statistics, and the velocity
 * fields with their grid and times. */
static int write_pdfs_fields(const ss_ctx *c, const ss_res *r, gr_h5md *h, gr_err *err)
{
    char nm[128], dat[1400];
    int rc = GR_OK;
    for (int w = 0; w < 2 && !rc; w++) {
        snprintf(nm, sizeof nm, "D%g/pdf_%s", r->D, w ? "long" : "short");
        rc = exp_put_result(h, nm, NB, 5, "u,p_x,err_x,p_y,err_y",
                 w ? "normalised displacement density, lag of a 2 d fall" : "normalised displacement density, lag of a 0.01 d fall",
                 &r->pdf[w][0][0], err);
        snprintf(dat, sizeof dat, "%s/pdf_%s_D%g.dat", c->dir, w ? "long" : "short", r->D);
        if (!rc)
            rc = exp_write_dat(dat, "u p_x err_x p_y err_y", &r->pdf[w][0][0], NB, 5, err);
    }
    snprintf(nm, sizeof nm, "D%g/pdf_stats", r->D);
    if (!rc)
        rc = exp_put_result(h, nm, 2, 10, "lag_time,fall,sd_x,sd_y,ks_eq34_x,ks_gauss_x,ks_eq34_y,ks_gauss_y,kappa_x,kappa_y",
                 "rows: short lag, long lag", &r->stats[0][0], err);
    size_t nc = (size_t)(r->grid[0] * r->grid[1]);
    snprintf(nm, sizeof nm, "D%g/velocity_y", r->D);
    if (!rc)
        rc = exp_put_result(h, nm, c->ntimes, nc, NULL, "mean vertical velocity per cell (row-major, y rows) at field_steps", r->vy, err);
    snprintf(nm, sizeof nm, "D%g/field_grid", r->D);
    if (!rc)
        rc = exp_put_result(h, nm, 6, 0, NULL, "nx, ny, x0, y0, cell width, cell height", r->grid, err);
    double ts[SS_MAX_TIMES];
    for (size_t j = 0; j < c->ntimes; j++)
        ts[j] = (double)c->times[j];
    snprintf(nm, sizeof nm, "D%g/field_steps", r->D);
    if (!rc)
        rc = exp_put_result(h, nm, c->ntimes, 0, NULL, "steps after opening of each velocity field", ts, err);
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

static int write_summary(const ss_ctx *c, gr_h5md *h, const double *summ, gr_err *err)
{
    const char *scols = "D,realisations,lag_short,fall_short,sd_x,sd_y,exp_x,exp_x_err,exp_y,exp_y_err,kappa_x_short,kappa_y_short,fall_long,kappa_x_long,kappa_y_long,ks_eq34_x,ks_gauss_x,ks_eq34_y,ks_gauss_y,lag_long";
    if (exp_put_result(h, "summary", c->norif, 20, scols, "one row per orifice", summ, err))
        return err->code;
    char path[1300], hdr[600];
    snprintf(path, sizeof path, "%s/summary.dat", c->dir);
    snprintf(hdr, sizeof hdr, "%s", scols);
    for (char *q = hdr; *q; q++)
        if (*q == ',')
            *q = ' ';
    return exp_write_dat(path, hdr, summ, c->norif, 20, err);
}

/* Figs. 3.1-3.6 and the stationarity table (which the figure computes). */
static int figures(const ss_ctx *c, char *const *parts, ss_res *res, double *stab, gr_h5md *h, gr_err *err)
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
    if (!rc)
        rc = exp_put_result(h, "stationarity", nr * c->ntimes, 3, "step,discharges,relative_change",
                 "velocity field change since the previous field time, rows by orifice then time", stab, err);
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
    gr_h5md *h = open_result(c, err);
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
    rc = rc || write_summary(c, h, &summ[0][0], err) || figures(c, parts, res, stab, h, err);
    if (rc) {
        gr_h5md_free(h);
        rc = err->code ? err->code : GR_ERUN;
    } else
        rc = gr_h5md_close(h, err);
    for (size_t o = 0; res && o < nr; o++)
        orif_free(&res[o]);
    free(res), free(stab);
    return rc;
}
