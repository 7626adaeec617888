/* A time step: the neighbour-list rebuild rule, the drift, the force
 * evaluation, then the commit (dem_commit.c); the loop over steps
 * (gr_dem_advance), for velocity Verlet on several threads many steps in
 * one parallel region. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dem.h"
#include "dem_sync.h"
#include "geom.h"

#ifdef _OPENMP
#include <omp.h>
#endif

/* Rebuild the list or re-sort the cells when the step's rule says so. */
static int maybe_rebuild(gr_dem *d, int p, int q, int mode, double moved, gr_err *err)
{
    if (mode == GR_DEM_NB_VERLET && (d->need_build || moved > d->par.skin)) {
        /* sort and build on the new positions; both buffers move along */
        d->cur = q;
        int rc = gr_dem_sort(d, err) || gr_dem_build_list(d, d->f[F_X][q], d->f[F_Y][q], err);
        d->cur = p;
        return rc ? err->code : GR_OK;
    }
    if (mode == GR_DEM_NB_CELLS && (d->need_build || ++d->since_sort >= (uint64_t)d->par.sort_every)) {
        d->cur = q;
        int rc = gr_dem_sort(d, err);
        d->cur = p;
        if (rc)
            return err->code;
        d->need_build = 0;
    }
    return GR_OK;
}

/* Velocity Verlet with Verlet lists (and no external force) rebuilds its
 * list at the start of a step, before the drift, when the step before found
 * that this drift could take the two largest displacements past the skin
 * (their sum so far plus twice the largest drift, v + (dt/2) a times dt,
 * which that step's kick knows). Nothing in the step then waits for all
 * grains midway, which the one-barrier threaded step needs; gr_dem_step
 * keeps the same rule, so the bits do not depend on the thread count. */
static int early(const gr_dem *d)
{
    return d->par.integrator == GR_DEM_VERLET && d->par.neighbour == GR_DEM_NB_VERLET && !d->ext_fx;
}

/* After a committed early-mode step: whether the next one starts with a
 * rebuild (an unfused step knows no drift bound: it always does). */
static void plan_rebuild(gr_dem *d, int fused, double moved)
{
    if (!fused || moved + 2.0 * d->par.dt * sqrt(gr_dem_eval_vmax2(d)) > d->par.skin)
        d->need_build = 1;
}

/* A step; next: another follows in this advance (the kicks then drift
 * ahead for it). */
static int step(gr_dem *d, int next, gr_err *err)
{
    if (!d->gates_open && d->t >= d->sc.silo.open_time && gr_dem_open_gates(d, err))
        return err->code;
    int p = d->cur, q = 1 - p;
    double dt = d->par.dt;
    uint64_t E = d->step + 1;
    double tn = d->t0 + (double)E * dt;
    int mode = d->par.neighbour;
    double moved = 0;
    const int ahead = early(d);
    d->exits_known = 0; /* the Verlet drift counts the grains that leave */
    if (ahead) {
        if (d->need_build && gr_dem_rebuild(d, err))
            return err->code;
        if (!gr_dem_pre_use(d, E, &moved))
            moved = gr_dem_predict_verlet(d, p, q, 1);
    } else {
        switch (d->par.integrator) {
        case GR_DEM_GEAR: gr_dem_predict_gear(d, p, q); break;
        case GR_DEM_EULER: gr_dem_predict_euler(d, p, q); break;
        default:
            moved = gr_dem_predict_verlet(d, p, q, mode == GR_DEM_NB_VERLET && !d->need_build);
            break;
        }
        if (mode == GR_DEM_NB_VERLET && d->par.integrator != GR_DEM_VERLET && !d->need_build) {
            for (size_t i = 0; i < d->n; i++) {
                double dx = gr_min_image(d->f[F_X][q][i] - d->xref[i], d->Lx);
                double dy = gr_min_image(d->f[F_Y][q][i] - d->yref[i], d->Ly);
                /* twice the largest displacement bounds the sum of the two
                 * largest; Verlet's fused loop has the exact rule */
                moved = fmax(moved, 2 * sqrt(dx * dx + dy * dy));
            }
        }
        if (maybe_rebuild(d, p, q, mode, moved, err))
            return err->code;
    }
    d->f_zeroed = d->par.integrator == GR_DEM_VERLET;
    if (gr_dem_eval_begin(d, q, tn, E, dt, mode, err))
        return err->code;
    int fused = d->par.integrator == GR_DEM_VERLET && gr_dem_eval_fuse_kick(d, p);
    int pre = gr_dem_eval_pre(d, ahead && fused && next);
    gr_dem_eval_run(d);
    if (gr_dem_eval_end(d, d->seg_force, err)) {
        gr_dem_hist_undo_at(d, E);
        return err->code;
    }
    if (pre)
        d->pre_E = E + 1; /* unless the commit moves grains */
    double ek;
    if (fused) {
        ek = gr_dem_eval_kinetic(d);
    } else if (d->par.integrator == GR_DEM_VERLET) {
        ek = gr_dem_correct_verlet(d, p, q);
    } else {
        if (d->par.integrator == GR_DEM_GEAR)
            gr_dem_correct_gear(d, q);
        ek = gr_dem_kinetic(d, q);
    }
    if (gr_dem_commit(d, q, E, tn, ek, err))
        return err->code;
    if (ahead)
        plan_rebuild(d, fused, moved);
    return GR_OK;
}

int gr_dem_step(gr_dem *d, gr_err *err)
{
    d->pre_E = 0; /* the caller may change the state between steps */
    return step(d, 0, err);
}

/* Whether another step follows the one now starting (steps done before it,
 * and its time t1) in an advance to t_end or max_steps. */
static int another(const gr_dem *d, uint64_t done, double t1, double t_end, uint64_t max_steps)
{
    return (max_steps == 0 || done + 1 < max_steps) && t1 < t_end - 1e-6 * d->par.dt;
}

/* What the threaded Verlet loop carries from one step to the next. */
typedef struct {
    int stop, rebuild, p, q, track, fused, early, flow;
    int pre, ahead; /* this step's drift was done ahead; this one drifts ahead */
    uint64_t done, E;
    double tn, moved_pre;
    size_t nb;
} vt_step;

/* The start of a step, run by one thread: stop test, gates, buffers, and
 * (with Verlet lists) the force evaluation's set-up (vt_setup), which needs
 * neither the new positions nor a barrier of its own. When the step starts
 * with a list rebuild, v->rebuild says so and the set-up waits for it. */
static int vt_setup(gr_dem *d, vt_step *v, double t_end, uint64_t max_steps, gr_err *err);
static int vt_start(gr_dem *d, vt_step *v, double t_end, uint64_t max_steps, gr_err *err)
{
    const double eps = 1e-6 * d->par.dt;
    v->fused = v->flow = v->pre = v->ahead = v->rebuild = 0;
    v->stop = !(d->t < t_end - eps && (max_steps == 0 || v->done < max_steps));
    if (v->stop)
        return GR_OK;
    if (!d->gates_open && d->t >= d->sc.silo.open_time && gr_dem_open_gates(d, err))
        return v->stop = 1, err->code;
    v->p = d->cur, v->q = 1 - v->p;
    v->E = d->step + 1;
    v->tn = d->t0 + (double)v->E * d->par.dt;
    v->early = early(d);
    if (v->early && d->need_build)
        return v->rebuild = 1, GR_OK;
    return vt_setup(d, v, t_end, max_steps, err);
}

static int vt_setup(gr_dem *d, vt_step *v, double t_end, uint64_t max_steps, gr_err *err)
{
    v->rebuild = 0;
    /* every grain drifts in this step (per block or per strip), counting exits */
    atomic_store_explicit(&d->exits, 0, memory_order_relaxed);
    d->exits_known = 1;
    v->track = d->par.neighbour == GR_DEM_NB_VERLET && !d->need_build;
    v->nb = (d->n + DEM_BLOCK - 1) / DEM_BLOCK;
    v->pre = v->early && v->track && gr_dem_pre_use(d, v->E, &v->moved_pre);
    if (v->track) {
        d->f_zeroed = 1; /* the drift zeroes the new forces */
        if (gr_dem_eval_begin(d, v->q, v->tn, v->E, d->par.dt, d->par.neighbour, err))
            return v->stop = 1, err->code;
        v->fused = gr_dem_eval_fuse_kick(d, v->p);
        v->flow = v->early && v->fused && gr_dem_eval_flow_begin(d);
        v->ahead = gr_dem_eval_pre(d, v->early && v->fused && another(d, v->done, v->tn, t_end, max_steps));
        if (!v->flow)
            gr_dem_eval_split(d);
    }
    return GR_OK;
}

/* A step's drift over blocks, its colours of strips and (linked cells)
 * its kick over blocks, run by every thread of the region, with a barrier
 * after each; linked cells, or a list rebuild outside the look-ahead rule,
 * add a serial section after the drift. Returns 1 when that section
 * failed (*rc, *stop set). */
static int vt_colours(gr_dem *d, vt_step *v, int *rc, int *stop, gr_err *err)
{
    const int p = v->p, q = v->q, mode = d->par.neighbour;
    const size_t nb = v->nb;
    if (!v->pre) {
#pragma omp for schedule(static)
        for (size_t b = 0; b < nb; b++)
            gr_dem_predict_block(d, p, q, v->track, b);
    }
    /* every thread reads the same maxima: the same decision */
    double moved = !v->track ? 0.0 : v->pre ? v->moved_pre : gr_dem_moved_blocks(d);
    if (!v->track || (!v->early && moved > d->par.skin)) {
#pragma omp single
        {
            d->f_zeroed = 1;
            if (maybe_rebuild(d, p, q, mode, moved, err) ||
                gr_dem_eval_begin(d, q, v->tn, v->E, d->par.dt, mode, err))
                *rc = err->code, *stop = 1;
            else
                v->fused = gr_dem_eval_fuse_kick(d, p), gr_dem_eval_split(d);
        }
        if (*stop)
            return 1;
    }
    /* read before the colours' barriers: past them, the end of the step
     * may already be setting up the next */
    const int fused = v->fused, ncol = gr_dem_eval_ncolours(d);
    for (int col = 0; col < ncol; col++)
        gr_dem_eval_colour(d, col);
    /* the kick writes only the new buffer: harmless if the step is
     * refused; with Verlet lists the colours did it */
    if (!fused) {
#pragma omp for schedule(static)
        for (size_t b = 0; b < nb; b++)
            gr_dem_kick_block(d, p, q, b);
    }
    return 0;
}

/* The serial end of a step (one thread): sums and checks, the commit, and
 * the start of the next step. */
static void vt_end(gr_dem *d, vt_step *v, int *rc, double t_end, uint64_t max_steps, gr_err *err)
{
    double ek = v->fused ? gr_dem_eval_kinetic(d) : gr_dem_kinetic_blocks(d, v->nb);
    if (gr_dem_eval_end(d, d->seg_force, err)) {
        gr_dem_hist_undo_at(d, v->E);
        *rc = err->code, v->stop = 1;
    } else if ((d->pre_E = v->ahead ? v->E + 1 : 0), gr_dem_commit(d, v->q, v->E, v->tn, ek, err)) {
        *rc = err->code, v->stop = 1;
    } else {
        /* the drift's maxima: done ahead, per strip in the one-barrier
         * step, per block otherwise (no kick over blocks has overwritten
         * them when the kick was fused) */
        double moved = v->pre ? v->moved_pre : v->flow ? gr_dem_eval_moved(d) : gr_dem_moved_blocks(d);
        if (v->early)
            plan_rebuild(d, v->fused, !v->fused ? 0.0 : moved);
        v->done++;
        *rc = vt_start(d, v, t_end, max_steps, err);
    }
}

/* Velocity Verlet on several threads, many steps in one parallel region.
 * With Verlet lists and two colours a step is the one-barrier step of
 * dem_flow.c, at whose end the last thread to finish its strips runs the
 * serial end while the others wait (one meeting per step); else that of
 * vt_colours, then the serial end in a single. The serial end also starts
 * the next step; a list rebuild runs on all threads, then the last to
 * finish its share sets the step up. The work and every sum are split
 * exactly as in gr_dem_step, so the runs are the same bits. */
static int advance_verlet_threads(gr_dem *d, double t_end, uint64_t max_steps, gr_err *err)
{
    const int nth = gr_dem_threads(d);
    int rc = GR_OK, stop_b = 0;
    vt_step v = {0};
    gr_dem_meet_t mt;
    gr_dem_meet_init(&mt);
    size_t per = (size_t)d->strips.n + 1;
    int *order = malloc((size_t)nth * per * sizeof *order);
    if (!order)
        return gr_fail(err, GR_ERUN, "out of memory");
#pragma omp parallel num_threads(nth)
    {
        const int T = omp_get_num_threads();
        if (gr_dem_meet(&mt, T))
            rc = vt_start(d, &v, t_end, max_steps, err), gr_dem_meet_release(&mt);
        while (!v.stop) {
            if (v.rebuild) {
                int r = gr_dem_rebuild_team(d, &mt, err);
                if (gr_dem_meet(&mt, T)) {
                    if (r)
                        rc = r, v.stop = 1;
                    else
                        rc = vt_setup(d, &v, t_end, max_steps, err);
                    gr_dem_meet_release(&mt);
                }
                if (v.stop)
                    break;
            }
            if (v.flow) {
                gr_dem_eval_flow(d, v.p, v.q, order, per);
                if (gr_dem_meet(&mt, T))
                    vt_end(d, &v, &rc, t_end, max_steps, err), gr_dem_meet_release(&mt);
                continue;
            }
            if (vt_colours(d, &v, &rc, &stop_b, err))
                break;
#pragma omp single
            vt_end(d, &v, &rc, t_end, max_steps, err);
        }
    }
    free(order);
    return rc;
}

int gr_dem_advance(gr_dem *d, double t_end, uint64_t max_steps, gr_err *err)
{
    d->pre_E = 0; /* the caller may have changed the state since the last advance */
    if (d->par.integrator == GR_DEM_CVODE)
        return gr_dem_cv_advance(d, t_end, max_steps, err);
    if (d->par.integrator == GR_DEM_VERLET && gr_dem_threads(d) > 1 && d->par.neighbour != GR_DEM_NB_BRUTE)
        return advance_verlet_threads(d, t_end, max_steps, err);
    uint64_t done = 0;
    double eps = 1e-6 * d->par.dt;
    while (d->t < t_end - eps && (max_steps == 0 || done < max_steps)) {
        if (step(d, another(d, done, d->t0 + (double)(d->step + 1) * d->par.dt, t_end, max_steps), err))
            return err->code;
        done++;
    }
    return GR_OK;
}

int gr_dem_forces(gr_dem *d, int mode, double *fx, double *fy, double *tq, gr_err *err)
{
    int p = d->cur, q = 1 - p;
    size_t n = d->n;
    memcpy(d->f[F_X][q], d->f[F_X][p], n * sizeof(double));
    memcpy(d->f[F_Y][q], d->f[F_Y][p], n * sizeof(double));
    memcpy(d->f[F_VX][q], d->f[F_VX][p], n * sizeof(double));
    memcpy(d->f[F_VY][q], d->f[F_VY][p], n * sizeof(double));
    if (d->rot)
        memcpy(d->f[F_W][q], d->f[F_W][p], n * sizeof(double));
    uint64_t E = d->step + 1;
    double *segf = calloc((size_t)d->nseg * 3 + 3, sizeof *segf);
    if (!segf)
        return gr_fail(err, GR_ERUN, "out of memory");
    double ovl = d->max_ovl;
    int rc = gr_dem_eval_at(d, q, d->t, E, 0.0, mode, segf, err);
    gr_dem_hist_undo_at(d, E);
    d->max_ovl = ovl;
    free(segf);
    if (rc)
        return rc;
    memcpy(fx, d->f[F_FX][q], n * sizeof(double));
    memcpy(fy, d->f[F_FY][q], n * sizeof(double));
    if (tq)
        for (size_t i = 0; i < n; i++)
            tq[i] = d->rot ? d->f[F_TQ][q][i] : 0.0;
    return GR_OK;
}
