/* Time stepping: velocity Verlet (2.17-2.21), Gear's 6-value predictor-
 * corrector and explicit Euler, written into the other buffer so that a
 * step that fails its checks leaves the last good state in place; the
 * neighbour-list rebuild rule; gates, grains leaving and reinsertion. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dem.h"
#include "init.h"
#include "rng.h"

void gr_dem_hist_undo_at(gr_dem *d, uint64_t E)
{
    if (!d->hist_on)
        return;
    gr_dem_hist *h = &d->hist;
    size_t ns = d->n * (size_t)h->cap;
    for (size_t s = 0; s < ns; s++) {
        if (h->stamp[s] == E) {
            h->partner[s] = h->partner_old[s];
            h->z[s] = h->z_old[s];
            h->stamp[s] = h->stamp_old[s];
        }
    }
}

static inline double wrap(double x, double L)
{
    if (L > 0) {
        if (x >= L)
            x -= L;
        else if (x < 0)
            x += L;
    }
    return x;
}

/* Per-particle loops run over fixed blocks, threads taking whole blocks;
 * block results are combined in block order, so sums do not depend on the
 * number of threads. */

/* gr_dem_grow keeps d->blk at two results per block of the capacity */
static int nthreads(const gr_dem *d) { return (int)(d->par.threads > 0 ? d->par.threads : 1); }

/* Drift and first kick of grains [i0, i1); their two largest squared
 * displacements since the list build go to top2[0], top2[1] when
 * track != 0. */
void gr_dem_drift(gr_dem *d, int p, int q, int track, size_t i0, size_t i1, double top2[2])
{
    double dt = d->par.dt, h = 0.5 * dt;
    const double *restrict x = d->f[F_X][p], *restrict y = d->f[F_Y][p];
    const double *restrict vx = d->f[F_VX][p], *restrict vy = d->f[F_VY][p];
    const double *restrict fx = d->f[F_FX][p], *restrict fy = d->f[F_FY][p];
    double *restrict xn = d->f[F_X][q], *restrict yn = d->f[F_Y][q];
    double *restrict vxn = d->f[F_VX][q], *restrict vyn = d->f[F_VY][q];
    const double *restrict im = d->im;
    const double *restrict xr = d->xref, *restrict yr = d->yref;
    double *restrict fxn = d->f[F_FX][q], *restrict fyn = d->f[F_FY][q], *restrict tqn = d->f[F_TQ][q];
    double g = d->g;
    const double *restrict w = d->f[F_W][p], *restrict tq = d->f[F_TQ][p];
    double *restrict wn = d->f[F_W][q];
    const double *restrict iI = d->iI;
    double Lx = d->Lx, Ly = d->Ly;
    int rot = d->rot;
    double m1 = 0, m2 = 0;
    for (size_t i = i0; i < i1; i++) {
        /* fixed grains (im = 0) feel no gravity */
        double ax = fx[i] * im[i], ay = fy[i] * im[i] - g * (im[i] != 0);
        double hx = vx[i] + h * ax, hy = vy[i] + h * ay;
        double nx = wrap(x[i] + dt * hx, Lx), ny = wrap(y[i] + dt * hy, Ly);
        /* the new forces start from zero here, saving a pass */
        fxn[i] = 0.0;
        fyn[i] = 0.0;
        xn[i] = nx;
        yn[i] = ny;
        /* the new buffer holds v(t+dt) predicted to second order,
         * v(t+dt/2) + (dt/2) a(t), which the damping sees (the half-step
         * velocity would make the dissipation first order); the second
         * kick corrects it with a(t+dt) - a(t) */
        vxn[i] = hx + h * ax;
        vyn[i] = hy + h * ay;
        if (rot) {
            wn[i] = w[i] + dt * tq[i] * iI[i];
            tqn[i] = 0.0;
        }
        if (track) {
            double dx = gr_dem_image(nx - xr[i], Lx), dy = gr_dem_image(ny - yr[i], Ly);
            double s2 = dx * dx + dy * dy;
            if (s2 > m2) {
                if (s2 > m1) {
                    m2 = m1;
                    m1 = s2;
                } else {
                    m2 = s2;
                }
            }
        }
    }
    top2[0] = m1;
    top2[1] = m2;
}

static void predict_block(gr_dem *d, int p, int q, int track, size_t b)
{
    size_t i0 = b * DEM_BLOCK, i1 = i0 + DEM_BLOCK < d->n ? i0 + DEM_BLOCK : d->n;
    gr_dem_drift(d, p, q, track, i0, i1, d->blk + 2 * b);
}

/* Sum of the two largest displacements from the per-block maxima that
 * predict_block left (the same whatever the thread count: a maximum). */
static double moved_from_blocks(const gr_dem *d)
{
    return gr_dem_top2_sum(d->blk, 2 * ((d->n + DEM_BLOCK - 1) / DEM_BLOCK));
}

/* Returns the sum of the two largest displacements since the list build
 * when track != 0 (section 2.4.1), else 0. */
static double predict_verlet(gr_dem *d, int p, int q, int track)
{
    size_t nb = (d->n + DEM_BLOCK - 1) / DEM_BLOCK;
    int nth = nthreads(d);
    if (nth > 1 && nb > 1) {
#pragma omp parallel for schedule(static) num_threads(nth)
        for (size_t b = 0; b < nb; b++)
            predict_block(d, p, q, track, b);
    } else {
        for (size_t b = 0; b < nb; b++)
            predict_block(d, p, q, track, b);
    }
    return track ? moved_from_blocks(d) : 0.0;
}

/* Second kick of grains [i0, i1): v(t+dt) = u + (dt/2) (a(t+dt) - a(t)),
 * where u is the predicted velocity (gravity cancels); returns their
 * kinetic energy (m v^2 / 2 as v^2 / (2 im): no mass array to stream). */
double gr_dem_kick(gr_dem *d, int p, int q, size_t i0, size_t i1, double *v2max)
{
    double h = 0.5 * d->par.dt;
    double *restrict vx = d->f[F_VX][q], *restrict vy = d->f[F_VY][q];
    const double *restrict fx = d->f[F_FX][q], *restrict fy = d->f[F_FY][q];
    const double *restrict fxo = d->f[F_FX][p], *restrict fyo = d->f[F_FY][p];
    const double *restrict im = d->im;
    double *restrict w = d->f[F_W][q];
    const double *restrict tq = d->f[F_TQ][q], *restrict tqo = d->f[F_TQ][p], *restrict iI = d->iI;
    int rot = d->rot;
    double ek = 0, g = d->g, vm = 0;
    for (size_t i = i0; i < i1; i++) {
        double a = vx[i] + h * (fx[i] - fxo[i]) * im[i], c = vy[i] + h * (fy[i] - fyo[i]) * im[i];
        vx[i] = a;
        vy[i] = c;
        if (v2max) {
            double hx = a + h * fx[i] * im[i], hy = c + h * (fy[i] * im[i] - g * (im[i] != 0));
            double v2 = hx * hx + hy * hy;
            vm = v2 > vm ? v2 : vm; /* not fmax: a libm call in this loop */
        }
        if (im[i] != 0)
            ek += 0.5 * (a * a + c * c) / im[i];
        if (rot) {
            double ww = w[i] + h * (tq[i] - tqo[i]) * iI[i];
            w[i] = ww;
            if (iI[i] != 0)
                ek += 0.5 * ww * ww / iI[i];
        }
    }
    if (v2max)
        *v2max = vm;
    return ek;
}

static void correct_block(gr_dem *d, int p, int q, size_t b)
{
    size_t i0 = b * DEM_BLOCK, i1 = i0 + DEM_BLOCK < d->n ? i0 + DEM_BLOCK : d->n;
    d->blk[b] = gr_dem_kick(d, p, q, i0, i1, NULL);
}

/* Kinetic energy from the kick's per-block sums, in block order (the same
 * bits whatever the thread count). */
static double kinetic_from_blocks(const gr_dem *d, size_t nb)
{
    double ek = 0;
    for (size_t b = 0; b < nb; b++)
        ek += d->blk[b];
    return ek;
}

/* Second kick; returns the kinetic energy of the new state. */
static double correct_verlet(gr_dem *d, int p, int q)
{
    size_t nb = (d->n + DEM_BLOCK - 1) / DEM_BLOCK;
    int nth = nthreads(d);
    if (nth > 1 && nb > 1) {
#pragma omp parallel for schedule(static) num_threads(nth)
        for (size_t b = 0; b < nb; b++)
            correct_block(d, p, q, b);
    } else {
        for (size_t b = 0; b < nb; b++)
            correct_block(d, p, q, b);
    }
    return kinetic_from_blocks(d, nb);
}

static double kinetic(gr_dem *d, int q)
{
    double ek = 0;
    for (size_t i = 0; i < d->n; i++) {
        double vx = d->f[F_VX][q][i], vy = d->f[F_VY][q][i];
        ek += (d->im[i] != 0) * 0.5 * d->mass[i] * (vx * vx + vy * vy);
        if (d->rot)
            ek += (d->iI[i] != 0) * 0.5 * d->inertia[i] * d->f[F_W][q][i] * d->f[F_W][q][i];
    }
    return ek;
}

static void predict_euler(gr_dem *d, int p, int q)
{
    double dt = d->par.dt;
    for (size_t i = 0; i < d->n; i++) {
        double ax = d->f[F_FX][p][i] * d->im[i], ay = d->f[F_FY][p][i] * d->im[i] - d->gf[i];
        d->f[F_X][q][i] = wrap(d->f[F_X][p][i] + dt * d->f[F_VX][p][i], d->Lx);
        d->f[F_Y][q][i] = wrap(d->f[F_Y][p][i] + dt * d->f[F_VY][p][i], d->Ly);
        d->f[F_VX][q][i] = d->f[F_VX][p][i] + dt * ax;
        d->f[F_VY][q][i] = d->f[F_VY][p][i] + dt * ay;
        if (d->rot)
            d->f[F_W][q][i] = d->f[F_W][p][i] + dt * d->f[F_TQ][p][i] * d->iI[i];
    }
}

/* Gear, 6 values (Allen & Tildesley, app. E), scaled derivatives b_k;
 * c0 = 3/16 because the forces depend on velocities. */
static const double gear_c[6] = {3.0 / 16.0, 251.0 / 360.0, 1.0, 11.0 / 18.0, 1.0 / 6.0, 1.0 / 60.0};

static void predict_gear(gr_dem *d, int p, int q)
{
    double dt = d->par.dt;
    static const int q0[3] = {F_X, F_Y, F_TH}, qv[3] = {F_VX, F_VY, F_W};
    static const int qb[3][4] = {{F_B2X, F_B3X, F_B4X, F_B5X}, {F_B2Y, F_B3Y, F_B4Y, F_B5Y},
                                 {F_B2T, F_B3T, F_B4T, F_B5T}};
    int ndof = d->rot ? 3 : 2;
    for (int c = 0; c < ndof; c++) {
        double *r0 = d->f[q0[c]][p], *v = d->f[qv[c]][p];
        double *b2 = d->f[qb[c][0]][p], *b3 = d->f[qb[c][1]][p], *b4 = d->f[qb[c][2]][p], *b5 = d->f[qb[c][3]][p];
        double *R0 = d->f[q0[c]][q], *V = d->f[qv[c]][q];
        double *B2 = d->f[qb[c][0]][q], *B3 = d->f[qb[c][1]][q], *B4 = d->f[qb[c][2]][q], *B5 = d->f[qb[c][3]][q];
        double L = c == 0 ? d->Lx : c == 1 ? d->Ly : 0.0;
        for (size_t i = 0; i < d->n; i++) {
            double b1 = dt * v[i];
            R0[i] = wrap(r0[i] + b1 + b2[i] + b3[i] + b4[i] + b5[i], L);
            double B1 = b1 + 2 * b2[i] + 3 * b3[i] + 4 * b4[i] + 5 * b5[i];
            B2[i] = b2[i] + 3 * b3[i] + 6 * b4[i] + 10 * b5[i];
            B3[i] = b3[i] + 4 * b4[i] + 10 * b5[i];
            B4[i] = b4[i] + 5 * b5[i];
            B5[i] = b5[i];
            V[i] = B1 / dt;
        }
    }
}

static void correct_gear(gr_dem *d, int q)
{
    double dt = d->par.dt, h2 = 0.5 * dt * dt;
    static const int q0[3] = {F_X, F_Y, F_TH}, qv[3] = {F_VX, F_VY, F_W};
    static const int qb[3][4] = {{F_B2X, F_B3X, F_B4X, F_B5X}, {F_B2Y, F_B3Y, F_B4Y, F_B5Y},
                                 {F_B2T, F_B3T, F_B4T, F_B5T}};
    int ndof = d->rot ? 3 : 2;
    for (int c = 0; c < ndof; c++) {
        double *R0 = d->f[q0[c]][q], *V = d->f[qv[c]][q];
        double *B2 = d->f[qb[c][0]][q], *B3 = d->f[qb[c][1]][q], *B4 = d->f[qb[c][2]][q], *B5 = d->f[qb[c][3]][q];
        const double *F = d->f[c == 0 ? F_FX : c == 1 ? F_FY : F_TQ][q];
        const double *inv = c == 2 ? d->iI : d->im;
        double L = c == 0 ? d->Lx : c == 1 ? d->Ly : 0.0;
        for (size_t i = 0; i < d->n; i++) {
            double a = F[i] * inv[i] - (c == 1 ? d->gf[i] : 0.0);
            double del = h2 * a - B2[i];
            R0[i] = wrap(R0[i] + gear_c[0] * del, L);
            V[i] += gear_c[1] * del / dt;
            B2[i] += gear_c[2] * del;
            B3[i] += gear_c[3] * del;
            B4[i] += gear_c[4] * del;
            B5[i] += gear_c[5] * del;
        }
    }
}

static int open_gates(gr_dem *d, gr_err *err)
{
    unsigned char *gone = calloc(d->n + 1, 1);
    if (!gone)
        return gr_fail(err, GR_ERUN, "out of memory");
    int any = 0;
    for (size_t i = 0; i < d->n; i++)
        if (d->flags[i] & GR_PF_GATE)
            gone[i] = 1, any = 1;
    int rc = any ? gr_dem_compact(d, gone, err) : GR_OK;
    free(gone);
    d->gates_open = 1;
    return rc;
}

/* Grains below the exit or past an open side leave; reinserted at the top
 * when the silo says so. */
static int handle_exits(gr_dem *d, gr_err *err)
{
    const gr_scene *sc = &d->sc;
    int p = d->cur;
    double xlo = sc->side[GR_LEFT] == GR_BC_OPEN ? 0.0 : -INFINITY;
    double xhi = sc->side[GR_RIGHT] == GR_BC_OPEN ? sc->width : INFINITY;
    double ylo = sc->side[GR_BOTTOM] == GR_BC_OPEN ? 0.0 : -INFINITY;
    double yhi = sc->side[GR_TOP] == GR_BC_OPEN ? sc->height : INFINITY;
    if (sc->silo.present)
        ylo = fmax(ylo, sc->silo.exit_below);
    if (!isfinite(xlo) && !isfinite(xhi) && !isfinite(ylo) && !isfinite(yhi))
        return GR_OK;
    const double *x = d->f[F_X][p], *y = d->f[F_Y][p];
    size_t nout = 0;
    for (size_t i = 0; i < d->n; i++)
        nout += d->im[i] != 0 && (x[i] < xlo || x[i] > xhi || y[i] < ylo || y[i] > yhi);
    if (!nout)
        return GR_OK;
    int reinsert = sc->silo.present && sc->silo.reinsert;
    unsigned char *gone = calloc(d->n + 1, 1);
    if (!gone)
        return gr_fail(err, GR_ERUN, "out of memory");
    int any_gone = 0;
    for (size_t i = 0; i < d->n; i++) {
        if (!(d->im[i] != 0 && (x[i] < xlo || x[i] > xhi || y[i] < ylo || y[i] > yhi)))
            continue;
        d->outflow++;
        double nx, ny;
        if (reinsert) {
            if (gr_dem_snapshot(d, d->scratch, err)) {
                free(gone);
                return err->code;
            }
            if (gr_reinsert_spot(sc, d->scratch, d->rad[i], d->rng, 1000, &nx, &ny)) {
                d->f[F_X][p][i] = nx;
                d->f[F_Y][p][i] = ny;
                d->f[F_VX][p][i] = 0.0;
                d->f[F_VY][p][i] = 0.0;
                d->f[F_FX][p][i] = d->f[F_FY][p][i] = 0.0;
                if (d->rot)
                    d->f[F_W][p][i] = d->f[F_TQ][p][i] = 0.0;
                if (d->par.integrator == GR_DEM_GEAR)
                    for (int f = F_TH; f < F_NFIELDS; f++)
                        d->f[f][p][i] = 0.0;
                continue;
            }
            /* no free spot: the grain is lost, and says so in its flags */
        }
        gone[i] = 1;
        any_gone = 1;
    }
    int rc = any_gone ? gr_dem_compact(d, gone, err) : GR_OK;
    free(gone);
    return rc;
}

static int report_nonfinite(gr_dem *d, int q, gr_err *err)
{
    for (size_t i = 0; i < d->n; i++) {
        double s = d->f[F_X][q][i] + d->f[F_Y][q][i] + d->f[F_VX][q][i] + d->f[F_VY][q][i] +
                   (d->rot ? d->f[F_W][q][i] : 0.0);
        if (!isfinite(s))
            return gr_fail(err, GR_ERUN,
                           "unstable at t = %.9g: grain id %lld has a non-finite position or velocity (overlap %.4g of a diameter in that step); lower dt",
                           d->t + d->par.dt, (long long)d->tag_id[d->tag[i]], d->max_ovl);
    }
    return gr_fail(err, GR_ERUN, "unstable at t = %.9g: non-finite kinetic energy", d->t + d->par.dt);
}

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

static int rebuild_now(gr_dem *d, gr_err *err)
{
    if (gr_dem_sort(d, err) || gr_dem_build_list(d, d->f[F_X][d->cur], d->f[F_Y][d->cur], err))
        return err->code;
    return GR_OK;
}

/* After a committed early-mode step: whether the next one starts with a
 * rebuild (an unfused step knows no drift bound: it always does). */
static void plan_rebuild(gr_dem *d, int fused, double moved)
{
    if (!fused || moved + 2.0 * d->par.dt * sqrt(gr_dem_eval_vmax2(d)) > d->par.skin)
        d->need_build = 1;
}

/* After the new forces and velocities: the energy check, then the new
 * state becomes the current one and grains that left are handled. */
static int commit(gr_dem *d, int q, uint64_t E, double tn, double ek, gr_err *err)
{
    double dt = d->par.dt;
    if (!isfinite(ek)) {
        gr_dem_hist_undo_at(d, E);
        return report_nonfinite(d, q, err);
    }
    /* kinetic plus elastic energy: the elastic part returns to motion at
     * every rebound, which is no jump */
    double em = ek + d->eel_eval;
    if (em > (1.0 + d->par.energy_jump) * d->ekin_last + d->e_floor) {
        gr_dem_hist_undo_at(d, E);
        /* name the fastest grain: where the energy went */
        size_t arg = 0;
        double best = -1;
        for (size_t i = 0; i < d->n; i++) {
            double v2 = d->f[F_VX][q][i] * d->f[F_VX][q][i] + d->f[F_VY][q][i] * d->f[F_VY][q][i];
            if (v2 > best)
                best = v2, arg = i;
        }
        return gr_fail(err, GR_ERUN,
                       "unstable at t = %.9g: kinetic plus elastic energy jumped from %.6g to %.6g in one step (bound energy_jump = %g); fastest grain id %lld at speed %.4g, largest overlap %.4g of a diameter; lower dt",
                       tn, d->ekin_last, em, d->par.energy_jump, (long long)d->tag_id[d->tag[arg]], sqrt(best), d->max_ovl);
    }
    d->ekin_last = em;
    d->cur = q;
    d->step = E;
    d->t = tn;
    for (int k = 0; k < d->nseg; k++)
        d->wall_impulse += d->seg_force[3 * k + 2] * dt;
    d->wall_time += dt;
    return handle_exits(d, err);
}

int gr_dem_step(gr_dem *d, gr_err *err)
{
    if (!d->gates_open && d->t >= d->sc.silo.open_time && open_gates(d, err))
        return err->code;
    int p = d->cur, q = 1 - p;
    double dt = d->par.dt;
    uint64_t E = d->step + 1;
    double tn = d->t0 + (double)E * dt;
    int mode = d->par.neighbour;
    double moved = 0;
    const int ahead = early(d);
    if (ahead) {
        if (d->need_build && rebuild_now(d, err))
            return err->code;
        moved = predict_verlet(d, p, q, 1);
    } else {
        switch (d->par.integrator) {
        case GR_DEM_GEAR: predict_gear(d, p, q); break;
        case GR_DEM_EULER: predict_euler(d, p, q); break;
        default:
            moved = predict_verlet(d, p, q, mode == GR_DEM_NB_VERLET && !d->need_build);
            break;
        }
        if (mode == GR_DEM_NB_VERLET && d->par.integrator != GR_DEM_VERLET && !d->need_build) {
            for (size_t i = 0; i < d->n; i++) {
                double dx = gr_dem_image(d->f[F_X][q][i] - d->xref[i], d->Lx);
                double dy = gr_dem_image(d->f[F_Y][q][i] - d->yref[i], d->Ly);
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
    gr_dem_eval_run(d);
    if (gr_dem_eval_end(d, d->seg_force, err)) {
        gr_dem_hist_undo_at(d, E);
        return err->code;
    }
    double ek;
    if (fused) {
        ek = gr_dem_eval_kinetic(d);
    } else if (d->par.integrator == GR_DEM_VERLET) {
        ek = correct_verlet(d, p, q);
    } else {
        if (d->par.integrator == GR_DEM_GEAR)
            correct_gear(d, q);
        ek = kinetic(d, q);
    }
    if (commit(d, q, E, tn, ek, err))
        return err->code;
    if (ahead)
        plan_rebuild(d, fused, moved);
    return GR_OK;
}

/* What the threaded Verlet loop carries from one step to the next. */
typedef struct {
    int stop, p, q, track, fused, early, flow;
    uint64_t done, E;
    double tn;
    size_t nb;
} vt_step;

/* The start of a step, run by one thread: stop test, gates, buffers, and
 * (with Verlet lists) the force evaluation's set-up, which needs neither
 * the new positions nor a barrier of its own unless the list is rebuilt. */
static int vt_start(gr_dem *d, vt_step *v, double t_end, uint64_t max_steps, gr_err *err)
{
    const double eps = 1e-6 * d->par.dt;
    v->fused = v->flow = 0;
    v->stop = !(d->t < t_end - eps && (max_steps == 0 || v->done < max_steps));
    if (v->stop)
        return GR_OK;
    if (!d->gates_open && d->t >= d->sc.silo.open_time && open_gates(d, err))
        return v->stop = 1, err->code;
    v->p = d->cur, v->q = 1 - v->p;
    v->E = d->step + 1;
    v->tn = d->t0 + (double)v->E * d->par.dt;
    v->early = early(d);
    if (v->early && d->need_build && rebuild_now(d, err))
        return v->stop = 1, err->code;
    v->track = d->par.neighbour == GR_DEM_NB_VERLET && !d->need_build;
    v->nb = (d->n + DEM_BLOCK - 1) / DEM_BLOCK;
    if (v->track) {
        d->f_zeroed = 1; /* the drift zeroes the new forces */
        if (gr_dem_eval_begin(d, v->q, v->tn, v->E, d->par.dt, d->par.neighbour, err))
            return v->stop = 1, err->code;
        v->fused = gr_dem_eval_fuse_kick(d, v->p);
        v->flow = v->early && v->fused && gr_dem_eval_flow_begin(d);
    }
    return GR_OK;
}

/* Velocity Verlet on several threads, many steps in one parallel region.
 * With Verlet lists and two colours a step is the one-barrier step of
 * dem_flow.c, then the serial end, which also starts the next step. Else
 * a step waits at the drift (over blocks), each colour of strips (two or
 * three; with Verlet lists the colours also kick), the kick over blocks
 * (linked cells), and the serial end; linked cells, or a list rebuild
 * outside the look-ahead rule (decided by every thread from the same block
 * maxima), add a serial section after the drift. The work and every sum are
 * split exactly as in gr_dem_step, so the runs are the same bits. */
static int advance_verlet_threads(gr_dem *d, double t_end, uint64_t max_steps, gr_err *err)
{
    const int mode = d->par.neighbour, nth = nthreads(d);
    int rc = GR_OK, stop_b = 0;
    vt_step v = {0};
    size_t per = (size_t)d->strips.n + 1;
    int *order = malloc((size_t)nth * per * sizeof *order);
    if (!order)
        return gr_fail(err, GR_ERUN, "out of memory");
#pragma omp parallel num_threads(nth)
    {
#pragma omp single
        rc = vt_start(d, &v, t_end, max_steps, err);
        while (!v.stop) {
            const int p = v.p, q = v.q;
            const size_t nb = v.nb;
            if (v.flow) {
                gr_dem_eval_flow(d, p, q, order, per);
#pragma omp barrier
            } else {
#pragma omp for schedule(static)
                for (size_t b = 0; b < nb; b++)
                    predict_block(d, p, q, v.track, b);
                /* every thread reads the same maxima: the same decision */
                double moved = v.track ? moved_from_blocks(d) : 0.0;
                if (!v.track || (!v.early && moved > d->par.skin)) {
#pragma omp single
                    {
                        d->f_zeroed = 1;
                        if (maybe_rebuild(d, p, q, mode, moved, err) ||
                            gr_dem_eval_begin(d, q, v.tn, v.E, d->par.dt, mode, err))
                            rc = err->code, stop_b = 1;
                        else
                            v.fused = gr_dem_eval_fuse_kick(d, p);
                    }
                    if (stop_b)
                        break;
                }
                /* read before the colours' barriers: past them, the end of
                 * the step may already be setting up the next */
                const int fused = v.fused, ncol = gr_dem_eval_ncolours(d);
                for (int col = 0; col < ncol; col++)
                    gr_dem_eval_colour(d, col);
                /* the kick writes only the new buffer: harmless if the step
                 * is refused; with Verlet lists the colours did it */
                if (!fused) {
#pragma omp for schedule(static)
                    for (size_t b = 0; b < nb; b++)
                        correct_block(d, p, q, b);
                }
            }
#pragma omp single
            {
                double ek = v.fused ? gr_dem_eval_kinetic(d) : kinetic_from_blocks(d, nb);
                if (gr_dem_eval_end(d, d->seg_force, err)) {
                    gr_dem_hist_undo_at(d, v.E);
                    rc = err->code, v.stop = 1;
                } else if (commit(d, q, v.E, v.tn, ek, err)) {
                    rc = err->code, v.stop = 1;
                } else {
                    /* the drift's maxima: per strip in the one-barrier step, per
                     * block otherwise (no kick over blocks has overwritten them
                     * when the kick was fused) */
                    if (v.early)
                        plan_rebuild(d, v.fused, !v.fused ? 0.0 : v.flow ? gr_dem_eval_moved(d) : moved_from_blocks(d));
                    v.done++;
                    rc = vt_start(d, &v, t_end, max_steps, err);
                }
            }
        }
    }
    free(order);
    return rc;
}

int gr_dem_advance(gr_dem *d, double t_end, uint64_t max_steps, gr_err *err)
{
    if (d->par.integrator == GR_DEM_CVODE)
        return gr_dem_cv_advance(d, t_end, max_steps, err);
    if (d->par.integrator == GR_DEM_VERLET && nthreads(d) > 1 && d->par.neighbour != GR_DEM_NB_BRUTE)
        return advance_verlet_threads(d, t_end, max_steps, err);
    uint64_t done = 0;
    double eps = 1e-6 * d->par.dt;
    while (d->t < t_end - eps && (max_steps == 0 || done < max_steps)) {
        if (gr_dem_step(d, err))
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
