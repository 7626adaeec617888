/* grano silo-flow: the report. Flow rate, its fluctuations and the packing
 * above the orifice against D; the Beverloo, power-law, density-law and
 * modified-law fits; silo-flow.h5 (typed tables), text tables, and thesis
 * figs. 4.1-4.6 (drawn when gnuplot is on PATH). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "h5tab.h"
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
    exp_tab_file *h;
    double sc_width;     /* the domain's width, for the snapshot */
    size_t n, nb, nr;    /* orifices, blocks, realisations */
    double *tab;         /* per orifice: flow_cols */
    double *wser;        /* w per block and orifice, realisation 0 */
    double *dev[2];      /* dw / sigma_w for D <= split and D > split */
    size_t ndev[2];
    double *cnt, *phi;   /* counts and packing per (orifice, realisation, block) */
    double *w;           /* the reduced flow of each of those blocks */
    double *meta;        /* per (orifice, realisation): seed, settling time, top, bulk packing */
    double *cost;        /* D, realisation, then the part's cost record */
    double bulk_sum;
    size_t bulk_n;
    double rho;
    double fits[NFITS * 9], pdf[NB * 5], pstat[2][4];
    char fitmsg[1024];
} sf_rep;

/* silo-flow.h5, a file of typed tables, and the domain's width. */
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
    r->sc_width = sc->width;
    gr_scene_free(sc);
    char path[1300];
    snprintf(path, sizeof path, "%s/silo-flow.h5", c->dir);
    r->h = exp_tab_create(path, "grano silo-flow: flow rate against orifice width (thesis chapter 4)", err);
    return r->h ? GR_OK : err->code;
}

/* Orifice o's parts: its blocks, each realisation's settled silo and the
 * costs. */
static int read_parts(sf_rep *r, size_t o, gr_err *err)
{
    const sf_ctx *c = r->c;
    size_t nb = r->nb, nr = r->nr;
    int rc = GR_OK;
    for (size_t q = 0; q < nr && !rc; q++) {
        size_t u = o * nr + q;
        gr_ckpt *ck = gr_ckpt_open(r->parts[u], err);
        if (!ck)
            return err->code;
        if (!(rc = gr_ckpt_get_f64(ck, "counts", r->cnt + u * nb, nb, err)))
            rc = gr_ckpt_get_f64(ck, "packing", r->phi + u * nb, nb, err);
        double *meta = r->meta + u * 4;
        meta[0] = (double)(c->seed + q), meta[1] = exp_get_scalar(ck, "t_settle");
        meta[2] = exp_get_scalar(ck, "top0"), meta[3] = exp_get_scalar(ck, "bulk_packing");
        if (isfinite(meta[3]))
            r->bulk_sum += meta[3], r->bulk_n++;
        r->tab[o * NCOL + C_BULK] += meta[3] / (double)nr;
        double *cr = r->cost + u * 7;
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
    const double *cnt = r->cnt + o * m, *phi = r->phi + o * m;
    gr_block_average(cnt, m, 1, NULL, &mean, &sem);
    t[C_D] = c->orifice[o];
    t[C_PERBLOCK] = mean;
    t[C_W] = mean / bt, t[C_WERR] = sem / bt;
    gr_block_average(phi, m, 1, NULL, &t[C_PHI], &t[C_PHIERR]);
    t[C_NBLK] = (double)m;
    double s2 = 0, *wv = malloc(m * sizeof *wv);
    if (!wv)
        return gr_fail(err, GR_ERUN, "out of memory");
    for (size_t q = 0; q < nr; q++) {
        const double *cq = cnt + q * nb;
        double mr = 0;
        for (size_t b = 0; b < nb; b++)
            mr += cq[b] / (double)nb;
        for (size_t b = 0; b < nb; b++) {
            double w = mr > 0 ? cq[b] / mr : NAN;
            wv[q * nb + b] = w - 1;
            r->w[o * m + q * nb + b] = w;
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

/* The run's settings, one row. */
static int write_config(const sf_rep *r, gr_err *err)
{
    const sf_ctx *c = r->c;
    const char *method = c->base.method->name;
    char mat_text[SILO_PARAMS + 160];
    silo_material(&c->base, mat_text, sizeof mat_text);
    const char *mat = mat_text;
    double outlet = c->base.hopper ? c->base.outlet : 0.0;
    double v[13] = {(double)c->base.n, c->base.width, c->base.height, c->base.dt, (double)c->nreal,
                    (double)c->discard, (double)c->block, (double)c->nblocks, (double)c->block * c->base.dt,
                    c->lift, c->split, (double)c->seed, r->rho};
    const exp_col cols[] = {
        {"method", "", "the method that ran", EXP_STR, &method, 0},
        {"material", "", "the [material] section the grains ran with (--material)", EXP_STR, &mat, 0},
        {"hopper_outlet", "1", "the filling hopper's outlet, a fraction of the width (0: no hopper)", EXP_F64,
         &outlet, 0},
        {"grains", "1", "grains in the silo", EXP_INT, v, 0},
        {"width", "d", "silo width", EXP_F64, v + 1, 0},
        {"height", "d", "silo height", EXP_F64, v + 2, 0},
        {"dt", "tau", "time step", EXP_F64, v + 3, 0},
        {"realisations", "1", "independent fillings, each branched to every orifice", EXP_INT, v + 4, 0},
        {"discard_steps", "1", "steps discarded after the orifice opens", EXP_INT, v + 5, 0},
        {"block_steps", "1", "steps per measuring block", EXP_INT, v + 6, 0},
        {"blocks", "1", "measuring blocks per run", EXP_INT, v + 7, 0},
        {"block_time", "tau", "time per block", EXP_F64, v + 8, 0},
        {"square_lift", "d", "base of the D x D packing square above the silo's base", EXP_F64, v + 9, 0},
        {"split", "d", "small orifices D <= split, large D > split (figs. 4.2-4.3)", EXP_F64, v + 10, 0},
        {"seed", "1", "seed of realisation 0 (realisation q: seed + q)", EXP_INT, v + 11, 0},
        {"rho_bulk", "d-2", "bulk number density used in the flow laws", EXP_F64, v + 12, 0},
    };
    return exp_tab_write(r->h, "config", "the run's settings", 1, cols, sizeof cols / sizeof cols[0], err);
}

/* Per orifice and realisation: the settled silo and the costs; per block:
 * the grains that left, the packing and the reduced flow. */
static int write_runs(const sf_rep *r, gr_err *err)
{
    size_t n = r->n, nb = r->nb, nr = r->nr, nu = n * nr, nbl = nu * nb;
    double *x = malloc(nbl * 3 * sizeof *x);
    if (!x)
        return gr_fail(err, GR_ERUN, "out of memory");
    for (size_t k = 0; k < nbl; k++) {
        x[k] = r->c->orifice[k / (nr * nb)], x[nbl + k] = (double)(k / nb % nr);
        x[2 * nbl + k] = (double)(r->c->discard + (long)(k % nb + 1) * r->c->block);
    }
    const double *cost = r->cost, *meta = r->meta;
    const exp_col rcols[] = {
        {"D", "d", "orifice width", EXP_F64, cost, 7},
        {"realisation", "1", "realisation (its filling)", EXP_INT, cost + 1, 7},
        {"seed", "1", "its seed", EXP_INT, meta, 4},
        {"settle_time", "tau", "time the filling took to settle", EXP_F64, meta + 1, 4},
        {"top_height", "d", "highest grain of the settled silo", EXP_F64, meta + 2, 4},
        {"bulk_packing", "1", "packing fraction of the settled bulk", EXP_F64, meta + 3, 4},
        {"wall_fill", "s", "wall seconds of the filling and settling", EXP_F64, cost + 2, 7},
        {"cpu_fill", "s", "CPU seconds of the filling and settling", EXP_F64, cost + 3, 7},
        {"wall_run", "s", "wall seconds of the run after opening", EXP_F64, cost + 4, 7},
        {"cpu_run", "s", "CPU seconds of the run after opening", EXP_F64, cost + 5, 7},
        {"steps_run", "1", "steps of the run after opening", EXP_INT, cost + 6, 7},
    };
    const exp_col bcols[] = {
        {"D", "d", "orifice width", EXP_F64, x, 0},
        {"realisation", "1", "realisation", EXP_INT, x + nbl, 0},
        {"end_step", "1", "steps after opening at the block's end", EXP_INT, x + 2 * nbl, 0},
        {"grains", "1", "grains that left in the block", EXP_INT, r->cnt, 0},
        {"packing", "1", "mean packing fraction of the D x D square in the block", EXP_F64, r->phi, 0},
        {"reduced_flow", "1", "w = grains / their mean over the realisation's blocks (eq. 4.2)", EXP_F64, r->w, 0},
    };
    int rc = exp_tab_write(r->h, "realisations", "one row per (orifice, realisation)", nu, rcols,
                           sizeof rcols / sizeof rcols[0], err) ||
             exp_tab_write(r->h, "blocks", "one row per (orifice, realisation, block)", nbl, bcols,
                           sizeof bcols / sizeof bcols[0], err);
    free(x);
    return rc ? err->code : GR_OK;
}

static int write_results(const sf_rep *r, gr_err *err)
{
    const double *t = r->tab, *f = r->fits;
    const exp_col flow[] = {
        {"D", "d", "orifice width", EXP_F64, t + C_D, NCOL},
        {"W", "tau-1", "flow rate (grains per tau)", EXP_F64, t + C_W, NCOL},
        {"W_err", "tau-1", "its error bar (block average)", EXP_F64, t + C_WERR, NCOL},
        {"grains_per_block", "1", "mean grains out per block", EXP_F64, t + C_PERBLOCK, NCOL},
        {"sigma_w", "1", "standard deviation of the reduced flow w (eq. 4.3)", EXP_F64, t + C_SIGW, NCOL},
        {"packing", "1", "packing fraction of the D x D square above the orifice", EXP_F64, t + C_PHI, NCOL},
        {"packing_err", "1", "its error bar", EXP_F64, t + C_PHIERR, NCOL},
        {"bulk_packing", "1", "packing fraction of the settled bulk, mean over realisations", EXP_F64,
         t + C_BULK, NCOL},
        {"blocks", "1", "blocks measured (all realisations)", EXP_INT, t + C_NBLK, NCOL},
        {"kappa_w", "1", "excess kurtosis of w", EXP_F64, t + C_KAPPA, NCOL},
    };
    static const char *const law[NFITS] = {"beverloo", "sigma_w_all", "sigma_w_small", "sigma_w_large",
                                           "density_law", "modified_law"};
    static const char *const par[NFITS] = {"C,k", "A,p", "A,p", "A,p", "phi0,a,b", "C,a,b"};
    static const char *const pu[NFITS] = {"1,d", "1,1", "1,1", "1,1", "1,1,d-1", "1,1,d-1"};
    const char *vary = "per row: units";
    const exp_col fits[] = {
        {"law", "", "W = C rho g^1/2 (D - k)^3/2; sigma_w = A D^p (all, D <= split, D > split); packing "
                    "phi0 (1 - a e^-bD); W = C rho (1 - a e^-bD) g^1/2 D^3/2", EXP_STR, law, 0},
        {"parameters", "", "names of p0, p1, p2", EXP_STR, par, 0},
        {"units", "", "units of p0, p1, p2", EXP_STR, pu, 0},
        {"p0", vary, "first parameter", EXP_F64, f, 9},
        {"p0_err", vary, "its error (scaled by sqrt(chi2/dof) when above 1)", EXP_F64, f + 1, 9},
        {"p1", vary, "second parameter", EXP_F64, f + 2, 9},
        {"p1_err", vary, "its error", EXP_F64, f + 3, 9},
        {"p2", vary, "third parameter (NaN: none)", EXP_F64, f + 4, 9},
        {"p2_err", vary, "its error", EXP_F64, f + 5, 9},
        {"chi2_dof", "1", "chi^2 per degree of freedom", EXP_F64, f + 6, 9},
        {"n", "1", "points fitted", EXP_INT, f + 7, 9},
        {"converged", "1", "1 converged, 0 failed, 2 density law: b at a bound of its range", EXP_INT, f + 8, 9},
    };
    const double *p = r->pdf, *ps = &r->pstat[0][0];
    char lo[64], hi[64];
    snprintf(lo, sizeof lo, "D <= %g", r->c->split);
    snprintf(hi, sizeof hi, "D > %g", r->c->split);
    const char *grp[2] = {lo, hi};
    const exp_col pdf[] = {
        {"u", "1", "dw / sigma_w, bin centre", EXP_F64, p, 5},
        {"p_small", "1", "probability density, D <= split", EXP_F64, p + 1, 5},
        {"err_small", "1", "its error bar", EXP_F64, p + 2, 5},
        {"p_large", "1", "probability density, D > split", EXP_F64, p + 3, 5},
        {"err_large", "1", "its error bar", EXP_F64, p + 4, 5},
    };
    const exp_col pst[] = {
        {"orifices", "", "which orifices (d)", EXP_STR, grp, 0},
        {"n", "1", "blocks pooled", EXP_INT, ps, 4},
        {"ks_eq44", "1", "KS distance to eq. 4.4", EXP_F64, ps + 1, 4},
        {"ks_gauss", "1", "KS distance to the Gaussian", EXP_F64, ps + 2, 4},
        {"kappa", "1", "excess kurtosis", EXP_F64, ps + 3, 4},
    };
    int rc = write_config(r, err) ||
             exp_tab_write(r->h, "flow", "per orifice: flow rate, its fluctuations, packing", r->n, flow,
                           sizeof flow / sizeof flow[0], err) ||
             exp_tab_write(r->h, "fits", "the flow laws against D", NFITS, fits, sizeof fits / sizeof fits[0],
                           err) ||
             exp_tab_write(r->h, "pdf_fluctuations", "density of dw / sigma_w", NB, pdf,
                           sizeof pdf / sizeof pdf[0], err) ||
             exp_tab_write(r->h, "pdf_fluctuation_stats", "the fluctuations against eq. 4.4 and a Gaussian", 2,
                           pst, sizeof pst / sizeof pst[0], err) ||
             write_runs(r, err);
    return rc ? err->code : GR_OK;
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

/* Every orifice's parts, the fits, the tables (silo-flow.h5 closed), then
 * the figures when gnuplot is there to draw them. */
static int gather(sf_rep *r, gr_err *err)
{
    const sf_ctx *c = r->c;
    int rc = GR_OK;
    for (size_t o = 0; o < r->n && !rc; o++)
        rc = read_parts(r, o, err) || orifice_stats(r, o, err);
    if (rc)
        return err->code ? err->code : GR_ERUN;
    r->rho = r->bulk_n ? r->bulk_sum / (double)r->bulk_n * 4.0 / M_PI : NAN; /* number density */
    fit_laws(r);
    rc = fluctuation_pdfs(r, err) || write_results(r, err) || write_tables(r, err);
    if (!rc) {
        rc = exp_tab_close(r->h, err);
        r->h = NULL;
    }
    if (!rc && gr_plot_have_gnuplot())
        rc = figures(c, r->tab, r->fits, r->wser, r->pdf, r->rho, err) || snapshot_figure(r, err);
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
    r.cnt = malloc(n * nb * nr * sizeof *r.cnt);
    r.phi = malloc(n * nb * nr * sizeof *r.phi);
    r.w = malloc(n * nb * nr * sizeof *r.w);
    r.meta = calloc(n * nr * 4, sizeof *r.meta);
    r.cost = calloc(n * nr * 7, sizeof *r.cost);
    int rc = r.tab && r.wser && r.dev[0] && r.dev[1] && r.cnt && r.phi && r.w && r.meta && r.cost
                 ? gather(&r, err)
                 : gr_fail(err, GR_ERUN, "out of memory");
    summarise(&r, summary, nsum);
    exp_tab_free(r.h);
    free(r.tab), free(r.wser), free(r.dev[0]), free(r.dev[1]), free(r.cnt), free(r.phi), free(r.w), free(r.meta),
        free(r.cost);
    return rc;
}
