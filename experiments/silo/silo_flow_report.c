/* grano silo-flow: the report. Flow rate, its fluctuations and the packing
 * above the orifice against D; the Beverloo, power-law, density-law and
 * modified-law fits; silo-flow.h5, tables, and thesis figs. 4.1-4.6. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "h5md.h"
#include "parts.h"
#include "plot.h"
#include "silo_flow.h"
#include "stats.h"
#include "table.h"

#define NB 30
#define UMAX 5.0
enum { FIT_BEV, FIT_SIG_ALL, FIT_SIG_SMALL, FIT_SIG_LARGE, FIT_DENS, FIT_MOD, NFITS };
enum { C_D, C_W, C_WERR, C_PERBLOCK, C_SIGW, C_PHI, C_PHIERR, C_BULK, C_NBLK, C_KAPPA, NCOL };
static const char *const flow_cols = "D,W,W_err,grains_per_block,sigma_w,packing,packing_err,bulk_packing,blocks,kappa_w";

/* A number gnuplot reads back: NaN for failed fits. */
static const char *gp_num(char *buf, double v)
{
    if (isfinite(v))
        snprintf(buf, 32, "%.10g", v);
    else
        snprintf(buf, 32, "NaN");
    return buf;
}


/* One row of the fits table: p0 e0 p1 e1 p2 e2 chi2/dof n ok; errors scaled
 * by sqrt(chi2/dof) when that exceeds 1 (block errors ignore correlations). */
static void fit_row(const gr_fit *f, int ok, double *row)
{
    for (int k = 0; k < 9; k++)
        row[k] = NAN;
    row[8] = ok;
    if (!ok)
        return;
    double s = f->weighted && f->chi2_dof > 1 ? sqrt(f->chi2_dof) : 1.0;
    for (size_t k = 0; k < f->np && k < 3; k++)
        row[2 * k] = f->p[k], row[2 * k + 1] = f->err[k] * s;
    row[6] = f->chi2_dof, row[7] = (double)f->n;
}

static size_t nearest(const sf_ctx *c, double D)
{
    size_t b = 0;
    for (size_t o = 1; o < c->norif; o++)
        if (fabs(c->orifice[o] - D) < fabs(c->orifice[b] - D))
            b = o;
    return b;
}

/* Thesis fig. 4.1: the flow rate against D, linear with the Beverloo fit
 * and logarithmic with the slopes 3/2 and 5/2 through the widest orifice. */
static int fig4_1(const sf_ctx *c, const double *tab, const double *fits, double rho, gr_err *err)
{
    size_t n = c->norif;
    char png[1200];
    double bt = (double)c->block * c->base.dt;
    snprintf(png, sizeof png, "%s/fig4_1_flow_rate.png", c->dir);
    FILE *gp = gr_plot_open(png, 1100, 480, err);
    if (!gp)
        return err->code;
    fprintf(gp, "$t << EOD\n");
    for (size_t o = 0; o < n; o++)
        fprintf(gp, "%g %g %g\n", tab[o * NCOL + C_D], tab[o * NCOL + C_W], tab[o * NCOL + C_WERR]);
    fprintf(gp, "EOD\n");
    const double *fb = fits + FIT_BEV * 9, *fm = fits + FIT_MOD * 9;
    double Dmax = tab[(n - 1) * NCOL + C_D], Wmax = tab[(n - 1) * NCOL + C_W];
    for (size_t o = 0; o < n; o++)
        if (tab[o * NCOL + C_D] > Dmax)
            Dmax = tab[o * NCOL + C_D], Wmax = tab[o * NCOL + C_W];
    char b1[32], b2[32], b3[32], b4[32];
    fprintf(gp, "rho = %s\nC = %s\nk = %s\nB(D) = D > k ? C*rho*(D-k)**1.5 : 0\n", gp_num(b1, rho),
            gp_num(b2, fb[0]), gp_num(b3, fb[2]));
    fprintf(gp, "Cm = %s\nam = %s\nbm = %s\nM(D) = Cm*rho*(1-am*exp(-bm*D))*D**1.5\n", gp_num(b1, fm[0]),
            gp_num(b2, fm[2]), gp_num(b3, fm[4]));
    (void)b4;
    fprintf(gp, "set multiplot layout 1,2 title 'Flow rate against orifice width (thesis fig. 4.1); a block of %ld steps is %g {/Symbol t}'\n",
            c->block, bt);
    fprintf(gp, "set xlabel 'D / d'\nset ylabel 'W / (grains {/Symbol t}^{-1})'\nset key top left\nset xrange [0:*]\nset yrange [0:*]\n");
    fprintf(gp, "plot $t using 1:2:3 with yerrorbars pt 7 lc rgb 'black' title 'grano', B(x) lw 2 lc rgb 'red' title sprintf('Beverloo 2D: C = %%.3f, k = %%.2f', C, k)\n");
    fprintf(gp, "set logscale xy\nset xrange [*:*]\nset yrange [*:*]\n");
    fprintf(gp, "plot $t using 1:2:3 with yerrorbars pt 7 lc rgb 'black' title 'grano', %g*(x/%g)**1.5 lw 2 lc rgb 'red' title 'slope 1.5', %g*(x/%g)**2.5 lw 2 lc rgb 'blue' title 'slope 2.5'\n",
            Wmax, Dmax, Wmax, Dmax);
    fprintf(gp, "unset multiplot\n");
    return gr_plot_close(gp, png, err);
}

/* Thesis fig. 4.2: the reduced flow of three orifices block by block, and
 * its spread against D with the power-law fits (all, small, large D). */
static int fig4_2(const sf_ctx *c, const double *tab, const double *fits, const double *wser, gr_err *err)
{
    size_t n = c->norif;
    char png[1200];
    snprintf(png, sizeof png, "%s/fig4_2_flow_fluctuations.png", c->dir);
    FILE *gp = gr_plot_open(png, 1100, 480, err);
    if (!gp)
        return err->code;
    const double want[3] = {3.56, 6.24, 16.04};
    const char *col[3] = {"black", "red", "blue"};
    fprintf(gp, "$w << EOD\n");
    for (int b = 0; b < c->nblocks; b++) {
        fprintf(gp, "%ld", c->discard + (long)(b + 1) * c->block);
        for (int k = 0; k < 3; k++)
            fprintf(gp, " %g", wser[(size_t)b * n + nearest(c, want[k])]);
        fprintf(gp, "\n");
    }
    fprintf(gp, "EOD\n$s << EOD\n");
    for (size_t o = 0; o < n; o++)
        fprintf(gp, "%g %g\n", tab[o * NCOL + C_D], tab[o * NCOL + C_SIGW]);
    fprintf(gp, "EOD\n");
    fprintf(gp, "set multiplot layout 1,2 title 'Reduced flow w = W/<W> (thesis fig. 4.2)'\n");
    fprintf(gp, "set xlabel 'steps after opening'\nset ylabel 'reduced flow w = W/<W> (dimensionless)'\n"
                "set key top right\nplot ");
    for (int k = 0; k < 3; k++)
        fprintf(gp, "%s$w using 1:%d with lines lw 1.5 lc rgb '%s' title 'D = %g d'", k ? ", " : "", k + 2, col[k],
                c->orifice[nearest(c, want[k])]);
    const double *fa = fits + FIT_SIG_ALL * 9, *fsm = fits + FIT_SIG_SMALL * 9, *fl = fits + FIT_SIG_LARGE * 9;
    fprintf(gp, "\nset logscale xy\nset xlabel 'D / d'\nset ylabel '{/Symbol s}_w, standard deviation of w (dimensionless)'\n"
                "set key bottom left\n");
    fprintf(gp, "plot $s using 1:2 with points pt 7 lc rgb 'black' title 'grano'");
    if (fa[8] > 0)
        fprintf(gp, ", %g*x**%g lw 2 lc rgb 'blue' title 'all: (D/d)^{%.2f}'", fa[0], fa[2], fa[2]);
    if (fsm[8] > 0)
        fprintf(gp, ", (x<=%g ? %g*x**%g : 1/0) dt 2 lc rgb 'dark-green' title 'D <= %g: (D/d)^{%.2f}'", c->split, fsm[0], fsm[2], c->split, fsm[2]);
    if (fl[8] > 0)
        fprintf(gp, ", (x>%g ? %g*x**%g : 1/0) dt 2 lc rgb 'orange' title 'D > %g: (D/d)^{%.2f}'", c->split, fl[0], fl[2], c->split, fl[2]);
    fprintf(gp, ", %g*(x/%g)**-2 lw 2 lc rgb 'red' title '(D/d)^{-2}'\n", tab[C_SIGW], tab[C_D]);
    fprintf(gp, "unset multiplot\n");
    return gr_plot_close(gp, png, err);
}

/* Thesis fig. 4.3: the pdf of the reduced flow fluctuations, small and
 * large orifices, against eq. 4.4 and a Gaussian. */
static int fig4_3(const sf_ctx *c, const double *pdf, gr_err *err)
{
    char png[1200];
    snprintf(png, sizeof png, "%s/fig4_3_fluctuation_pdf.png", c->dir);
    FILE *gp;
    if (!(gp = gr_plot_open(png, 700, 500, err)))
        return err->code;
    fprintf(gp, "$p << EOD\n");
    for (int b = 0; b < NB; b++)
        fprintf(gp, "%g %g %g\n", pdf[b * 5], pdf[b * 5 + 1], pdf[b * 5 + 3]);
    fprintf(gp, "EOD\nset logscale y\nset format y '10^{%%L}'\nset yrange [1e-4:2]\nset xrange [-%g:%g]\n", UMAX, UMAX);
    fprintf(gp, "set title 'Reduced flow fluctuations {/Symbol D}w / {/Symbol s}_w (thesis fig. 4.3)'\nset xlabel '{/Symbol D}w / {/Symbol s}_w'\nset ylabel 'probability density P'\nset key bottom center\n");
    fprintf(gp, "plot $p using 1:($2>0?$2:1/0) with points pt 6 ps 1.2 lc rgb 'black' title 'D <= %g d', $p using 1:($3>0?$3:1/0) with points pt 4 ps 1.2 lc rgb 'black' title 'D > %g d', (2/pi)/(1+x*x)**2 lw 2 lc rgb 'red' title 'eq. 4.4', exp(-x*x/2)/sqrt(2*pi) lw 2 lc rgb 'blue' title 'Gaussian'\n",
            c->split, c->split);
    return gr_plot_close(gp, png, err);
}

/* Thesis fig. 4.5: the packing fraction above the orifice against D. The
 * thesis calls it the density rho and fits rho_0 (1 - a e^{-bD}) (eq. 4.7),
 * but its caption defines that density as the packing fraction (area
 * covered by grains over the area measured): the same quantity, named phi
 * here, and its fit phi_0 (1 - a e^{-bD}) is the thesis's rho_0 etc. */
static int fig4_5(const sf_ctx *c, const double *tab, const double *fits, gr_err *err)
{
    size_t n = c->norif;
    char png[1200];
    snprintf(png, sizeof png, "%s/fig4_5_packing.png", c->dir);
    FILE *gp;
    if (!(gp = gr_plot_open(png, 700, 500, err)))
        return err->code;
    const double *fd = fits + FIT_DENS * 9;
    fprintf(gp, "$t << EOD\n");
    for (size_t o = 0; o < n; o++)
        fprintf(gp, "%g %g %g\n", tab[o * NCOL + C_D], tab[o * NCOL + C_PHI], tab[o * NCOL + C_PHIERR]);
    fprintf(gp, "EOD\nset title 'Packing fraction in the D x D square %g d above the base (thesis fig. 4.5)'\n", c->lift);
    fprintf(gp, "set xlabel 'D / d'\nset ylabel 'packing fraction {/Symbol f} (the thesis'' {/Symbol r})'\n"
                "set key bottom right\n");
    fprintf(gp, "plot $t using 1:2:3 with yerrorbars pt 5 lc rgb 'black' title 'grano'");
    if (fd[8] > 0)
        fprintf(gp, ", %g*(1-%g*exp(-%g*x)) lw 2 lc rgb 'red' title '{/Symbol f}_0(1 - a e^{-bD}) (eq. 4.7): {/Symbol f}_0 = %.3f, a = %.2f, b = %.2f%s'",
                fd[0], fd[2], fd[4], fd[0], fd[2], fd[4], fd[8] == 2 ? " (b at a bound)" : "");
    fprintf(gp, "\n");
    return gr_plot_close(gp, png, err);
}

/* Thesis fig. 4.6: the flow with the modified law against Beverloo's,
 * linear and logarithmic. */
static int fig4_6(const sf_ctx *c, const double *tab, const double *fits, double rho, gr_err *err)
{
    size_t n = c->norif;
    char png[1200];
    const double *fb = fits + FIT_BEV * 9, *fm = fits + FIT_MOD * 9;
    char b1[32], b2[32], b3[32];
    snprintf(png, sizeof png, "%s/fig4_6_modified_flow_law.png", c->dir);
    FILE *gp;
    if (!(gp = gr_plot_open(png, 1100, 480, err)))
        return err->code;
    fprintf(gp, "$t << EOD\n");
    for (size_t o = 0; o < n; o++)
        fprintf(gp, "%g %g %g\n", tab[o * NCOL + C_D], tab[o * NCOL + C_W], tab[o * NCOL + C_WERR]);
    fprintf(gp, "EOD\nrho = %s\nC = %s\nk = %s\nB(D) = D > k ? C*rho*(D-k)**1.5 : 1/0\n", gp_num(b1, rho),
            gp_num(b2, fb[0]), gp_num(b3, fb[2]));
    fprintf(gp, "Cm = %s\nam = %s\nbm = %s\nM(D) = Cm*rho*(1-am*exp(-bm*D))*D**1.5\n", gp_num(b1, fm[0]),
            gp_num(b2, fm[2]), gp_num(b3, fm[4]));
    fprintf(gp, "set multiplot layout 1,2 title 'Flow with the modified law W = C {/Symbol r}(1 - a e^{-bD}) g^{1/2} D^{3/2} (thesis eqs. 4.14-4.15, fig. 4.6)'\n");
    fprintf(gp, "set xlabel 'D / d'\nset ylabel 'W / (grains {/Symbol t}^{-1})'\nset key top left\n");
    for (int lg = 0; lg < 2; lg++) {
        if (lg)
            fprintf(gp, "set logscale xy\n");
        fprintf(gp, "plot $t using 1:2:3 with yerrorbars pt 7 lc rgb 'black' title 'grano', M(x) lw 2 lc rgb 'red' title sprintf('modified: C = %%.3f, a = %%.2f, b = %%.2f', Cm, am, bm), B(x) dt 2 lc rgb 'blue' title 'Beverloo'\n");
    }
    fprintf(gp, "unset multiplot\n");
    return gr_plot_close(gp, png, err);
}

static int figures(const sf_ctx *c, const double *tab, const double *fits, const double *wser,
                   const double *pdf, double rho, gr_err *err)
{
    /* every figure below divides by or takes logs of the flow */
    for (size_t o = 0; o < c->norif; o++)
        if (!(tab[o * NCOL + C_W] > 0))
            return gr_fail(err, GR_ERUN,
                           "no grain left through the %g d orifice in the %d measured blocks: the flow "
                           "figures need outflow (the results and tables are written); measure longer "
                           "(--discard, --blocks, --block-steps)",
                           tab[o * NCOL + C_D], c->nblocks);
    int rc = fig4_1(c, tab, fits, rho, err);
    if (!rc)
        rc = fig4_2(c, tab, fits, wser, err);
    if (!rc)
        rc = fig4_3(c, pdf, err);
    if (!rc)
        rc = fig4_5(c, tab, fits, err);
    if (!rc)
        rc = fig4_6(c, tab, fits, rho, err);
    return rc;
}

static int fit_sigma(const double *D, const double *s, size_t n, double lo, double hi, gr_fit *f)
{
    double x[SF_MAX_ORIF], y[SF_MAX_ORIF];
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if (D[i] > lo && D[i] <= hi && s[i] > 0)
            x[m] = D[i], y[m] = s[i], m++;
    gr_err e = {0};
    return m >= 3 && gr_fit_loglog(x, y, NULL, m, f, &e) == GR_OK;
}

/* What the report gathers from the parts on its way to the tables. */
typedef struct {
    const sf_ctx *c;
    char *const *parts;
    gr_h5md *h;
    double sc_width;     /* the domain's width, for the snapshot */
    size_t n, nb, nr;    /* orifices, blocks, realisations */
    double *tab;         /* per orifice: flow_cols */
    double *wser;        /* w per block and orifice, realisation 0 */
    double *dev[2];      /* dw / sigma_w for D <= split and D > split */
    size_t ndev[2];
    double *cnt, *phi;   /* counts and packing of one orifice's blocks */
    double *cost;        /* D, realisation, then the part's cost record */
    double bulk_sum;
    size_t bulk_n;
    double rho;
    double fits[NFITS * 9], pdf[NB * 5], pstat[2][4];
    char fitmsg[1024];
} sf_rep;

/* silo-flow.h5 with the scene of the first orifice. */
static int open_result(sf_rep *r, gr_err *err)
{
    const sf_ctx *c = r->c;
    silo_cfg cfg = c->base;
    cfg.orifice = c->orifice[0];
    cfg.seed = c->seed;
    cfg.reinsert = 1;
    gr_scene *sc = silo_scene(&cfg, 0, err);
    if (!sc)
        return err->code;
    char path[1300];
    snprintf(path, sizeof path, "%s/silo-flow.h5", c->dir);
    gr_h5md_opts ho = {.method = c->base.method->name, .seed = c->seed, .force = 1, .no_xdmf = 1};
    r->h = gr_h5md_create(path, sc, &ho, err);
    r->sc_width = sc->width;
    gr_scene_free(sc);
    return r->h ? GR_OK : err->code;
}

/* Orifice o's parts: its blocks into cnt and phi, each realisation's
 * series to the result file, the costs. */
static int read_parts(sf_rep *r, size_t o, gr_err *err)
{
    const sf_ctx *c = r->c;
    size_t nb = r->nb, nr = r->nr;
    int rc = GR_OK;
    for (size_t q = 0; q < nr && !rc; q++) {
        gr_ckpt *ck = gr_ckpt_open(r->parts[o * nr + q], err);
        if (!ck)
            return err->code;
        if (!(rc = gr_ckpt_get_f64(ck, "counts", r->cnt + q * nb, nb, err)))
            rc = gr_ckpt_get_f64(ck, "packing", r->phi + q * nb, nb, err);
        double meta[4] = {(double)(c->seed + q), exp_get_scalar(ck, "t_settle"), exp_get_scalar(ck, "top0"),
                          exp_get_scalar(ck, "bulk_packing")};
        if (isfinite(meta[3]))
            r->bulk_sum += meta[3], r->bulk_n++;
        r->tab[o * NCOL + C_BULK] += meta[3] / (double)nr;
        char nm[128];
        snprintf(nm, sizeof nm, "D%g/r%02zu/counts", c->orifice[o], q);
        if (!rc) rc = exp_put_result(r->h, nm, nb, 0, NULL, "grains that left in each block", r->cnt + q * nb, err);
        snprintf(nm, sizeof nm, "D%g/r%02zu/packing", c->orifice[o], q);
        if (!rc) rc = exp_put_result(r->h, nm, nb, 0, NULL, "mean packing fraction of the D x D square in each block", r->phi + q * nb, err);
        snprintf(nm, sizeof nm, "D%g/r%02zu/meta", c->orifice[o], q);
        if (!rc) rc = exp_put_result(r->h, nm, 4, 0, NULL, "seed, settling time, settled top height, bulk packing fraction", meta, err);
        double *cr = r->cost + (o * nr + q) * 7;
        cr[0] = c->orifice[o], cr[1] = (double)q;
        exp_get_cost(ck, cr + 2);
        gr_err ig = {0};
        gr_ckpt_close(ck, &ig);
    }
    return rc;
}

/* Orifice o's row of the table from its blocks: flow rate, packing, and
 * the reduced flow w = W / <W> per realisation (eq. 4.2) with sigma_w over
 * every block (eq. 4.3) and the deviations for the histograms. */
static int orifice_stats(sf_rep *r, size_t o, gr_err *err)
{
    const sf_ctx *c = r->c;
    size_t nb = r->nb, nr = r->nr, n = r->n, m = nb * nr;
    double bt = (double)c->block * c->base.dt;
    double *t = r->tab + o * NCOL, mean, sem;
    gr_block_average(r->cnt, m, 1, NULL, &mean, &sem);
    t[C_D] = c->orifice[o];
    t[C_PERBLOCK] = mean;
    t[C_W] = mean / bt, t[C_WERR] = sem / bt;
    gr_block_average(r->phi, m, 1, NULL, &t[C_PHI], &t[C_PHIERR]);
    t[C_NBLK] = (double)m;
    double s2 = 0, *wv = malloc(m * sizeof *wv);
    if (!wv)
        return gr_fail(err, GR_ERUN, "out of memory");
    for (size_t q = 0; q < nr; q++) {
        const double *cq = r->cnt + q * nb;
        double mr = 0;
        for (size_t b = 0; b < nb; b++)
            mr += cq[b] / (double)nb;
        for (size_t b = 0; b < nb; b++) {
            double w = mr > 0 ? cq[b] / mr : NAN;
            wv[q * nb + b] = w - 1;
            if (q == 0)
                r->wser[b * n + o] = w;
            s2 += (w - 1) * (w - 1) / (double)m;
        }
    }
    t[C_SIGW] = sqrt(s2);
    t[C_KAPPA] = gr_kappa_zero(wv, m);
    int big = c->orifice[o] > c->split;
    for (size_t i = 0; i < m && t[C_SIGW] > 0; i++)
        if (isfinite(wv[i]))
            r->dev[big][r->ndev[big]++] = wv[i] / t[C_SIGW];
    free(wv);
    return GR_OK;
}

/* Eq. 4.7 with its decay rate confined to where the law means what the
 * thesis says: the plateau rho0 is reached (to a tenth of the dip) within
 * the largest orifice, b >= ln 10 / D_max, and the dip is still seen at the
 * smallest, b <= ln 100 / D_min. Outside, rho0 would be an extrapolation or
 * a would be unpinned; the fit then stops at the bound and says so
 * (weighted by the block errors). Returns whether it converged. */
static int fit_density(sf_rep *r, const double *D, const double *P, const double *Pe, gr_fit *f)
{
    size_t n = r->n;
    double dmin = INFINITY, dmax = 0;
    for (size_t o = 0; o < n; o++)
        dmin = fmin(dmin, D[o]), dmax = fmax(dmax, D[o]);
    int edge = 0;
    gr_err e = {0};
    int ok = gr_fit_density_law_bounded(D, P, Pe, n, log(10.0) / dmax, log(100.0) / dmin, f, &edge, &e) == GR_OK;
    if (!ok)
        snprintf(r->fitmsg, sizeof r->fitmsg, "  density-law fit failed: %.300s\n", e.msg);
    else if (edge)
        snprintf(r->fitmsg, sizeof r->fitmsg,
                 "  density law: the best decay rate is the %s bound b = %.3g of [ln 10 / D_max, ln 100 / D_min]: the packing does not follow a saturating exponential in D\n",
                 f->p[2] > log(10.0) / dmax * 1.0001 ? "upper" : "lower", f->p[2]);
    fit_row(f, ok, r->fits + FIT_DENS * 9);
    if (ok && edge)
        r->fits[FIT_DENS * 9 + 8] = 2;
    return ok;
}

/* The flow laws against D: Beverloo, sigma_w power laws, the density law
 * and the modified law started from them. */
static void fit_laws(sf_rep *r)
{
    size_t n = r->n;
    const double *tab = r->tab;
    double D[SF_MAX_ORIF], W[SF_MAX_ORIF], We[SF_MAX_ORIF], S[SF_MAX_ORIF], P[SF_MAX_ORIF], Pe[SF_MAX_ORIF];
    for (size_t o = 0; o < n; o++) {
        D[o] = tab[o * NCOL + C_D], W[o] = tab[o * NCOL + C_W], S[o] = tab[o * NCOL + C_SIGW];
        We[o] = tab[o * NCOL + C_WERR] > 0 ? tab[o * NCOL + C_WERR] : 1e-3;
        P[o] = tab[o * NCOL + C_PHI], Pe[o] = tab[o * NCOL + C_PHIERR] > 0 ? tab[o * NCOL + C_PHIERR] : 1e-4;
    }
    gr_beverloo_par bp = {r->rho, 1.0, 1.5};
    gr_fit f;
    gr_err e = {0};
    int ok = gr_fit_beverloo(&bp, D, W, We, n, NULL, &f, &e) == GR_OK;
    fit_row(&f, ok, r->fits + FIT_BEV * 9);
    double Cb = ok ? f.p[0] : 0.5, split = r->c->split;
    ok = fit_sigma(D, S, n, 0, INFINITY, &f), fit_row(&f, ok, r->fits + FIT_SIG_ALL * 9);
    ok = fit_sigma(D, S, n, 0, split, &f), fit_row(&f, ok, r->fits + FIT_SIG_SMALL * 9);
    ok = fit_sigma(D, S, n, split, INFINITY, &f), fit_row(&f, ok, r->fits + FIT_SIG_LARGE * 9);
    ok = fit_density(r, D, P, Pe, &f);
    double a0 = ok && f.p[1] > 0 ? f.p[1] : 0.3, b0 = ok && f.p[2] > 0 ? f.p[2] : 0.3;
    double p0[3] = {Cb, a0, b0};
    ok = gr_fit_beverloo_mod(&bp, D, W, We, n, p0, &f, &e) == GR_OK;
    if (!ok)
        snprintf(r->fitmsg + strlen(r->fitmsg), sizeof r->fitmsg - strlen(r->fitmsg),
                 "  modified-law fit failed: %.300s\n", e.msg);
    fit_row(&f, ok, r->fits + FIT_MOD * 9);
}

/* Histograms of the fluctuations against eq. 4.4 and a Gaussian. */
static int fluctuation_pdfs(sf_rep *r, gr_err *err)
{
    for (int g = 0; g < 2; g++) {
        gr_hist *hh = gr_hist_create(NB, -UMAX, UMAX, err);
        if (!hh)
            return err->code;
        gr_hist_add_array(hh, r->dev[g], r->ndev[g]);
        double cen[NB], den[NB], er[NB];
        gr_hist_density(hh, cen, den, er);
        for (int b = 0; b < NB; b++)
            r->pdf[b * 5] = cen[b], r->pdf[b * 5 + 1 + 2 * g] = den[b], r->pdf[b * 5 + 2 + 2 * g] = er[b];
        gr_hist_free(hh);
        double *ps = r->pstat[g];
        ps[0] = (double)r->ndev[g];
        ps[1] = ps[2] = NAN;
        gr_err e = {0};
        if (r->ndev[g] >= 2) {
            gr_ks_distance(r->dev[g], r->ndev[g], gr_cdf_eq34_cb, NULL, &ps[1], &e);
            gr_ks_distance(r->dev[g], r->ndev[g], gr_cdf_gauss_cb, NULL, &ps[2], &e);
        }
        ps[3] = r->ndev[g] ? gr_kappa_zero(r->dev[g], r->ndev[g]) : NAN;
    }
    return GR_OK;
}

static int write_results(const sf_rep *r, gr_err *err)
{
    size_t n = r->n, nb = r->nb, nr = r->nr;
    gr_h5md *h = r->h;
    const char *fcols = "p0,p0_err,p1,p1_err,p2,p2_err,chi2_dof,n,converged (2: density-law b at a bound of its range)";
    int rc = exp_put_result(h, "flow", n, NCOL, flow_cols, "per orifice: flow rate (grains/tau), fluctuations, packing", r->tab, err);
    if (!rc) rc = exp_put_result(h, "fits", NFITS, 9, fcols,
                      "rows: beverloo {C,k}; sigma_w A D^p all, D<=split, D>split {A,p}; density law {rho0,a,b}; modified law {C,a,b}", r->fits, err);
    if (!rc) rc = exp_put_result(h, "rho_bulk", 1, 0, NULL, "bulk number density used in the flow laws (grains/d^2)", &r->rho, err);
    if (!rc) rc = exp_put_result(h, "pdf_fluctuations", NB, 5, "u,p_small,err_small,p_large,err_large", "density of dw/sigma_w", r->pdf, err);
    if (!rc) rc = exp_put_result(h, "pdf_fluctuation_stats", 2, 4, "n,ks_eq44,ks_gauss,kappa", "rows: D <= split, D > split", &r->pstat[0][0], err);
    if (!rc) rc = exp_put_result(h, "cost", n * nr, 7, "D,realisation,wall_fill,cpu_fill,wall_run,cpu_run,steps_run",
                      "seconds per unit of work: filling and settling, then the run after opening", r->cost, err);
    if (!rc) rc = exp_put_result(h, "reduced_flow_r00", nb, n, NULL, "w per block (rows) and orifice (columns), realisation 0", r->wser, err);
    return rc;
}

static int write_tables(const sf_rep *r, gr_err *err)
{
    const char *dir = r->c->dir;
    char hdr[600], path[1300];
    snprintf(hdr, sizeof hdr, "%s", flow_cols);
    for (char *q = hdr; *q; q++)
        *q = *q == ',' ? ' ' : *q;
    snprintf(path, sizeof path, "%s/flow.dat", dir);
    int rc = exp_write_dat(path, hdr, r->tab, r->n, NCOL, err);
    snprintf(path, sizeof path, "%s/fits.dat", dir);
    if (!rc) rc = exp_write_dat(path, "rows: beverloo(C,k) sigma_all(A,p) sigma_small(A,p) sigma_large(A,p) density(rho0,a,b) modified(C,a,b); p0 p0_err p1 p1_err p2 p2_err chi2_dof n converged (2: density-law b at a bound of its range)", r->fits, NFITS, 9, err);
    snprintf(path, sizeof path, "%s/pdf_fluctuations.dat", dir);
    if (!rc) rc = exp_write_dat(path, "u p_small err_small p_large err_large", r->pdf, NB, 5, err);
    snprintf(path, sizeof path, "%s/reduced_flow.dat", dir);
    if (!rc) rc = exp_write_dat(path, "w per block (rows) for each orifice (columns, in --orifices order), realisation 0", r->wser, r->nb, r->n, err);
    return rc;
}

/* silo_snapshot.png: the end of realisation 0 at the orifice nearest 6.24. */
static int snapshot_figure(const sf_rep *r, gr_err *err)
{
    const sf_ctx *c = r->c;
    gr_particles *p = gr_particles_create(0, err);
    size_t o = nearest(c, 6.24);
    gr_ckpt *ck = p ? gr_ckpt_open(r->parts[o * r->nr], err) : NULL;
    int rc;
    if (!ck || exp_get_particles(ck, "final", p, err))
        rc = err->code ? err->code : GR_ERUN;
    else {
        char title[128], path[1300];
        snprintf(path, sizeof path, "%s/silo_snapshot.png", c->dir);
        snprintf(title, sizeof title, "silo-flow, D = %g d, with reinsertion", c->orifice[o]);
        rc = gr_plot_snapshot(path, p, r->sc_width, c->base.base + c->base.height + 2,
                              (double)(c->discard + c->block * c->nblocks) * c->base.dt, title, err);
    }
    gr_err ig = {0};
    if (ck)
        gr_ckpt_close(ck, &ig);
    gr_particles_free(p);
    return rc;
}

static void summarise(sf_rep *r, char *summary, size_t nsum)
{
    const sf_ctx *c = r->c;
    size_t nu = r->n * r->nr;
    double cs[4] = {0, 0, 0, 0};
    for (size_t u = 0; u < nu; u++)
        for (int k = 0; k < 4; k++)
            cs[k] += r->cost[u * 7 + 2 + k] / (double)nu;
    size_t used = strlen(r->fitmsg);
    snprintf(r->fitmsg + used, sizeof r->fitmsg - used,
             "  per unit: filling %.0f s wall (%.0f s CPU), run %.0f s wall (%.0f s CPU) for %ld steps\n",
             cs[0], cs[1], cs[2], cs[3], c->discard + c->block * (long)c->nblocks);
    if (!summary || !nsum)
        return;
    const double *fb = r->fits + FIT_BEV * 9, *fa = r->fits + FIT_SIG_ALL * 9, *fd = r->fits + FIT_DENS * 9,
                 *fm = r->fits + FIT_MOD * 9, *fs = r->fits + FIT_SIG_SMALL * 9;
    snprintf(summary, nsum,
             "  Beverloo (rho = %.3f /d^2): C = %.3f +- %.3f, k = %.2f +- %.2f (chi2/dof %.3g)\n"
             "  sigma_w ~ D^%.2f +- %.2f (all), D^%.2f +- %.2f (D <= %g)\n"
             "  packing rho0 = %.3f +- %.3f, a = %.2f +- %.2f, b = %.2f +- %.2f\n"
             "  modified law C = %.3f +- %.3f, a = %.2f +- %.2f, b = %.2f +- %.2f (chi2/dof %.3g)\n"
             "  fluctuations: KS distance to eq. 4.4 / Gaussian %.3f / %.3f (D <= %g), %.3f / %.3f (D > %g)\n%s",
             r->rho, fb[0], fb[1], fb[2], fb[3], fb[6], fa[2], fa[3], fs[2], fs[3], c->split, fd[0], fd[1], fd[2],
             fd[3], fd[4], fd[5], fm[0], fm[1], fm[2], fm[3], fm[4], fm[5], fm[6], r->pstat[0][1], r->pstat[0][2],
             c->split, r->pstat[1][1], r->pstat[1][2], c->split, r->fitmsg);
}

/* Every orifice's parts, the fits, then the tables and figures. */
static int gather(sf_rep *r, gr_err *err)
{
    const sf_ctx *c = r->c;
    double par[10] = {(double)c->base.n, c->base.width, c->base.height, c->base.dt, (double)c->nreal,
                      (double)c->discard, (double)c->block, (double)c->nblocks, c->lift, (double)c->seed};
    int rc = exp_put_result(r->h, "config", 10, 0, NULL, "grains, width, height, dt, realisations, discarded steps, block steps, blocks, square lift, seed", par, err);
    if (!rc)
        rc = exp_put_result(r->h, "orifices", r->n, 0, NULL, "orifice widths D / d", c->orifice, err);
    for (size_t o = 0; o < r->n && !rc; o++)
        rc = read_parts(r, o, err) || orifice_stats(r, o, err);
    if (rc)
        return err->code ? err->code : GR_ERUN;
    r->rho = r->bulk_n ? r->bulk_sum / (double)r->bulk_n * 4.0 / M_PI : NAN; /* number density */
    fit_laws(r);
    rc = fluctuation_pdfs(r, err) || write_results(r, err) || write_tables(r, err) ||
         figures(c, r->tab, r->fits, r->wser, r->pdf, r->rho, err) || snapshot_figure(r, err);
    return rc ? (err->code ? err->code : GR_ERUN) : GR_OK;
}

int sf_report(const sf_ctx *c, char *const *parts, char *summary, size_t nsum, gr_err *err)
{
    sf_rep r = {.c = c, .parts = parts, .n = c->norif, .nb = (size_t)c->nblocks, .nr = (size_t)c->nreal};
    if (open_result(&r, err))
        return err->code;
    size_t n = r.n, nb = r.nb, nr = r.nr;
    r.tab = calloc(n * NCOL, sizeof *r.tab);
    r.wser = calloc(nb * n, sizeof *r.wser);
    r.dev[0] = malloc(n * nb * nr * sizeof(double));
    r.dev[1] = malloc(n * nb * nr * sizeof(double));
    r.cnt = malloc(nb * nr * sizeof *r.cnt);
    r.phi = malloc(nb * nr * sizeof *r.phi);
    r.cost = calloc(n * nr * 7, sizeof *r.cost);
    int rc = r.tab && r.wser && r.dev[0] && r.dev[1] && r.cnt && r.phi && r.cost
                 ? gather(&r, err)
                 : gr_fail(err, GR_ERUN, "out of memory");
    summarise(&r, summary, nsum);
    if (rc)
        gr_h5md_free(r.h);
    else
        rc = gr_h5md_close(r.h, err);
    free(r.tab), free(r.wser), free(r.dev[0]), free(r.dev[1]), free(r.cnt), free(r.phi), free(r.cost);
    return rc;
}
