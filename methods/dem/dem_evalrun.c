/* The force evaluation's set-up and end: per-strip scratch, the context
 * of one evaluation, the colours run on the threads, the sums and the
 * overlap check. Above the pair loops of dem_force.c. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dem.h"
#include "dem_eval.h"
#include "geom.h"

#ifdef _OPENMP
#include <omp.h>
#endif

void gr_dem_eval_free(struct gr_dem_eval *ev)
{
    if (!ev)
        return;
    free(ev->st), free(ev->sel), free(ev->kin), free(ev->sseg), free(ev->soff), free(ev->svy);
    free(ev->son), free(ev->sway), free(ev->split), free(ev->kicker), free(ev->tred), free(ev->sstr);
    free(ev);
}

static int eval_scratch(gr_dem *d, int ns, int nseg, size_t nsf, int nth, gr_err *err)
{
    struct gr_dem_eval *ev = d->ev;
    if (!ev) {
        size_t sz = (sizeof *ev + 63) & ~(size_t)63;
        if (!(ev = d->ev = aligned_alloc(64, sz)))
            return gr_fail(err, GR_ERUN, "out of memory in the force evaluation");
        memset(ev, 0, sz);
    }
    if ((size_t)ns > ev->cap_ns) {
        free(ev->st), free(ev->sel), free(ev->kin), free(ev->sway), free(ev->kicker), free(ev->sstr);
        ev->sstr = malloc((size_t)ns);
        ev->st = aligned_alloc(128, (size_t)ns * sizeof *ev->st);
        ev->sel = malloc((size_t)ns * sizeof *ev->sel);
        ev->kin = malloc((size_t)ns * sizeof *ev->kin);
        ev->kicker = calloc((size_t)ns, sizeof *ev->kicker);
        ev->sway = calloc((size_t)ns, 1);
        if (ev->st) {
            memset(ev->st, 0, (size_t)ns * sizeof *ev->st);
            for (int k = 0; k < ns; k++) {
                atomic_init(&ev->st[k].dflag, ev->epoch);
                atomic_init(&ev->st[k].cflag, ev->epoch);
            }
        }
        ev->cap_ns = (size_t)ns;
    } else if (ns != ev->ns) {
        for (int k = 0; k < ns; k++)
            ev->st[k].stime = 0.0;
    }
    size_t nsp = (size_t)4 * ((size_t)nth + 1); /* three colours, then the one cut */
    if (nsp > ev->cap_split) {
        free(ev->split);
        ev->split = calloc(nsp, sizeof *ev->split);
        ev->cap_split = nsp;
    }
    if (nth > ev->cap_tred) {
        free(ev->tred);
        ev->tred = aligned_alloc(128, (size_t)nth * sizeof *ev->tred);
        ev->cap_tred = nth;
    }
    if ((size_t)nseg + 1 > ev->cap_seg) {
        free(ev->soff), free(ev->svy), free(ev->son);
        ev->soff = malloc(((size_t)nseg + 1) * sizeof *ev->soff);
        ev->svy = malloc(((size_t)nseg + 1) * sizeof *ev->svy);
        ev->son = malloc((size_t)nseg + 1);
        ev->cap_seg = (size_t)nseg + 1;
    }
    if (nsf > ev->cap_sseg) {
        free(ev->sseg);
        ev->sseg = aligned_alloc(64, nsf * sizeof *ev->sseg);
        ev->cap_sseg = nsf;
    }
    if (!ev->st || !ev->sel || !ev->kin || !ev->soff || !ev->svy || !ev->son || !ev->sseg || !ev->sway ||
        !ev->split || !ev->kicker || !ev->tred || !ev->sstr) {
        gr_dem_eval_free(ev);
        d->ev = NULL;
        return gr_fail(err, GR_ERUN, "out of memory in the force evaluation");
    }
    return GR_OK;
}

/* Whether strip s may push on a segment: with Verlet lists, if its grains
 * have candidate segments (the flowing silo's strips have none); any strip
 * otherwise. A strip that cannot holds zeros in sseg, which add nothing
 * (+0.0: the sums never hold -0.0), so it is neither cleared nor summed. */
static int seg_strip(const gr_dem *d, int mode, int s)
{
    if (mode != GR_DEM_NB_VERLET || d->nseg == 0)
        return d->nseg > 0;
    const int32_t *i0 = d->strips.i0;
    return d->sg_start[i0[s]] != d->sg_start[i0[s + 1]];
}

/* dst = src, storing only the words that differ: a line left alone stays
 * in the other cores' caches. */
static void store_changed(void *dst, const void *src, size_t bytes)
{
    unsigned char *a = dst;
    const unsigned char *b = src;
    size_t k = 0;
    for (; k + 8 <= bytes; k += 8) {
        uint64_t u, v;
        memcpy(&u, a + k, 8), memcpy(&v, b + k, 8);
        if (u != v)
            memcpy(a + k, &v, 8);
    }
    for (; k < bytes; k++)
        if (a[k] != b[k])
            a[k] = b[k];
}

int gr_dem_eval_begin(gr_dem *d, int q, double t_eval, uint64_t E, double integ, int mode, gr_err *err)
{
    if (mode == GR_DEM_NB_CELLS) {
        if (gr_dem_bin(d, d->f[F_X][q], d->f[F_Y][q], err))
            return err->code;
    }
    int ns = mode == GR_DEM_NB_BRUTE ? 1 : d->strips.n;
    int nseg = d->nseg;
    /* whole cache lines per strip: strips of a colour run at once */
    size_t sstride = ((size_t)(nseg > 0 ? nseg : 1) * 3 + 7) & ~(size_t)7;
    size_t nsf = (size_t)ns * sstride;
    int nth = (int)(d->par.threads > 0 ? d->par.threads : 1);
    if (eval_scratch(d, ns, nseg, nsf, nth, err))
        return err->code;
    struct gr_dem_eval *ev = d->ev;
    /* every strip stores its overlap and energy (dem_pair.h, acc_store);
     * with lists, only a strip with candidate segments pushes on walls */
    /* sstr changes only with the list (Verlet) or not at all */
    if (ev->sstr_key != d->list_gen + 1 || ev->sstr_mode != mode || ev->sstr_ns != ns || ev->sstr_nseg != nseg) {
        for (int s = 0; s < ns; s++)
            ev->sstr[s] = (unsigned char)seg_strip(d, mode, s);
        ev->sstr_key = d->list_gen + 1, ev->sstr_mode = mode, ev->sstr_ns = ns, ev->sstr_nseg = nseg;
    }
    for (int s = 0; s < ns; s++)
        if (ev->sstr[s])
            memset(ev->sseg + (size_t)s * sstride, 0, sstride * sizeof *ev->sseg);
    ev->tred_on = 0;
    ev->cut_keep = ev->flow_E + 1 == E && (ev->flow_E & 15) != 0 && ev->flow_gen == d->list_gen && ev->ns == ns && ev->c.nth == nth;
    ev->flow_E = 0; /* set again by gr_dem_eval_flow_begin */
    for (int k = 0; k < nseg; k++) {
        ev->son[k] = t_eval < d->seg[k].open_time;
        ev->soff[k] = ev->svy[k] = 0.0;
        if (d->seg[k].vibrating) {
            ev->soff[k] = gr_floor_offset(&d->sc.floor, t_eval);
            ev->svy[k] = gr_floor_velocity(&d->sc.floor, t_eval);
        }
    }
    size_t n = d->n;
    if (!d->f_zeroed) {
        memset(d->f[F_FX][q], 0, n * sizeof(double));
        memset(d->f[F_FY][q], 0, n * sizeof(double));
        if (d->rot)
            memset(d->f[F_TQ][q], 0, n * sizeof(double));
    }
    d->f_zeroed = 0;
    ev->mode = mode;
    ev->ns = ns;
    ev->nseg = nseg;
    ev->t_eval = t_eval;
    ev->E = E;
    dem_ctx c = {
        .d = d,
        .x = d->f[F_X][q], .y = d->f[F_Y][q],
        .fx = d->f[F_FX][q], .fy = d->f[F_FY][q], .tq = d->f[F_TQ][q],
        .ux = d->f[F_VX][q], .uy = d->f[F_VY][q], .uw = d->f[F_W][q], .rad = d->rad,
        .tag = d->tag, .flags = d->flags,
        .law = {d->kn, d->gn, d->kt, d->gt, d->mu, d->par.dt, d->clip},
        .law_w = {d->kn, d->gw, d->kt, d->gt, d->mu, d->par.dt, d->clip},
        .E = E, .integ = integ, .Lx = d->Lx, .Ly = d->Ly,
        .seg_off = ev->soff, .seg_vy = ev->svy, .seg_on = ev->son,
        .st = ev->st, .sseg = ev->sseg, .sstride = sstride, .ncol = ns > 1 ? gr_dem_colours(d) : 1,
        .sway = ev->sway, .split = ev->split, .nth = nth, .kicker = ev->kicker,
    };
    store_changed(&ev->c, &c, sizeof c);
    return GR_OK;
}

void gr_dem_eval_split(gr_dem *d) { gr_dem_split_strips(d, d->ev, d->ev->c.nth); }

int gr_dem_eval_ncolours(const gr_dem *d) { return d->ev ? d->ev->c.ncol : 1; }


/* The evaluation's error, if any: a grain out of history slots, or the
 * largest overlap past the bound (pair bi, bj; bj = -1 - s a segment). */
static int eval_error(const gr_dem *d, const dem_ctx *c, double best, long bi, long bj, gr_err *err)
{
    const struct gr_dem_eval *ev = d->ev;
    if (c->hist_full)
        return gr_fail(err, GR_ERUN, "t = %.9g: grain id %lld has more than %d contacts at once; the packing is unphysically compressed",
                       ev->t_eval, (long long)d->tag_id[d->tag[c->full_i]], d->hist.cap);
    if (!(best > d->par.max_overlap))
        return GR_OK;
    char other[96];
    if (bj >= 0)
        snprintf(other, sizeof other, "grain id %lld", (long long)d->tag_id[d->tag[bj]]);
    else
        snprintf(other, sizeof other, "wall segment %ld", -1 - bj);
    if (ev->E == 0)
        return gr_fail(err, GR_EINPUT,
                       "initial state: grain id %lld overlaps %s by %.4g of its diameter (bound max_overlap = %g); place the grains apart",
                       (long long)d->tag_id[d->tag[bi]], other, best, d->par.max_overlap);
    return gr_fail(err, GR_ERUN,
                   "unstable at t = %.9g: grain id %lld overlaps %s by %.4g of its diameter (bound max_overlap = %g); lower dt or check the scene",
                   ev->t_eval, (long long)d->tag_id[d->tag[bi]], other, best, d->par.max_overlap);
}

/* Per segment, the strips' forces summed in strip order (from +0.0, over
 * the strips that may push on a segment, found at the set-up). */
static void segment_sums(const struct gr_dem_eval *ev, double *seg_out)
{
    for (int k = 0; k < 3 * ev->nseg; k++)
        seg_out[k] = 0.0;
    for (int s = 0; s < ev->ns; s++) {
        if (!ev->sstr[s])
            continue;
        const double *sf = ev->sseg + (size_t)s * ev->c.sstride;
        for (int k = 0; k < 3 * ev->nseg; k++)
            seg_out[k] += sf[k];
    }
}

int gr_dem_eval_end(gr_dem *d, double *seg_out, gr_err *err)
{
    struct gr_dem_eval *ev = d->ev;
    dem_ctx *c = &ev->c;
    size_t n = d->n;
    if (d->ext_fx) {
        for (size_t i = 0; i < n; i++) {
            c->fx[i] += d->ext_fx[i];
            c->fy[i] += d->ext_fy[i];
        }
    }
    double best = 0.0, eel = 0.0;
    long bi = -1, bj = -1;
    if (ev->tred_on) {
        /* the threads' runs of strips in order: the same first maximum */
        const gr_dem_tred *r = ev->tred;
        eel = r[0].eel0;
        for (int s = ev->split[3 * (c->nth + 1) + 1]; s < ev->ns; s++)
            eel += ev->sel[s]; /* packed by the threads (dem_flow.c) */
        for (int t = 0; t < c->nth; t++)
            if (r[t].best > best)
                best = r[t].best, bi = r[t].bi, bj = r[t].bj;
    } else {
        for (int s = 0; s < ev->ns; s++) {
            const dem_strip *r = ev->st + s;
            eel += r->sel;
            if (r->smax > best) {
                best = r->smax;
                bi = r->si;
                bj = r->sj;
            }
        }
    }
    if (seg_out)
        segment_sums(ev, seg_out);
    d->max_ovl = best;
    d->eel_eval = eel;
    return eval_error(d, c, best, bi, bj, err);
}

void gr_dem_eval_run(gr_dem *d)
{
    int nth = (int)(d->par.threads > 0 ? d->par.threads : 1), ncol = gr_dem_eval_ncolours(d);
    if (nth > 1 && d->ev->ns > 1 && !omp_in_parallel()) {
        gr_dem_eval_split(d);
#pragma omp parallel num_threads(nth)
        for (int col = 0; col < ncol; col++)
            gr_dem_eval_colour(d, col);
    } else if (omp_in_parallel()) {
        /* a thread of a caller's team (several instances advanced at once):
         * the colours' barriers and single constructs must bind to a team
         * of this instance, not to the caller's */
#pragma omp parallel num_threads(1)
        for (int col = 0; col < ncol; col++)
            gr_dem_eval_colour(d, col);
    } else {
        for (int col = 0; col < ncol; col++)
            gr_dem_eval_colour(d, col);
    }
}

int gr_dem_eval_at(gr_dem *d, int q, double t_eval, uint64_t E, double integ, int mode,
                   double *seg_out, gr_err *err)
{
    if (gr_dem_eval_begin(d, q, t_eval, E, integ, mode, err))
        return err->code;
    gr_dem_eval_run(d);
    return gr_dem_eval_end(d, seg_out, err);
}
