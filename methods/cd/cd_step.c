/* A time step of the Moreau-Jean scheme: free velocities, contacts within
 * the gap margin, warm start, the sweeps, the theta update of positions,
 * the stability checks before anything is committed, then gates, grains
 * leaving and reinsertion. Calls cd_contacts.c and cd_solve.c. */
#include <math.h>
#include <string.h>

#include "cd_int.h"
#include "geom.h"
#include "init.h"

static void open_gates(gr_cd *d)
{
    for (size_t i = 0; i < d->n; i++)
        if ((d->p->flags[i] & GR_PF_GATE) && !d->skip[i])
            d->p->flags[i] |= GR_PF_GONE, d->skip[i] = 1;
    d->gates_open = 1;
}

/* Free velocities into the new-velocity arrays; returns the detection
 * margin: gap diameters, and at least twice the largest displacement a
 * grain (or the floor) makes in the step, so no contact closes unseen. */
static double free_velocities(gr_cd *d)
{
    const gr_particles *p = d->p;
    double dt = d->par.dt, v2 = 0;
    for (size_t i = 0; i < d->n; i++) {
        int mob = d->im[i] != 0 && !d->skip[i];
        d->vx[i] = mob ? p->vx[i] : 0.0;
        d->vy[i] = mob ? p->vy[i] - d->g * dt : 0.0;
        d->w[i] = mob ? p->omega[i] : 0.0;
        v2 = fmax(v2, fmax(d->vx[i] * d->vx[i] + d->vy[i] * d->vy[i], p->vx[i] * p->vx[i] + p->vy[i] * p->vy[i]));
    }
    double vf = d->sc.floor.motion == GR_FLOOR_FIXED ? 0.0 : d->sc.floor.amplitude * d->sc.floor.omega * 2;
    return fmax(d->par.gap * d->dmax, 2 * dt * (sqrt(v2) + vf));
}

/* New positions; non-finite velocities or positions and overlaps beyond
 * half the smaller diameter stop the run before the step is committed. */
static int new_positions(gr_cd *d, gr_err *err)
{
    const gr_particles *p = d->p;
    double dt = d->par.dt, th = d->par.theta, tn = d->t + dt;
    d->max_ovl = 0;
    for (size_t i = 0; i < d->n; i++) {
        d->x1[i] = p->x[i] + dt * ((1 - th) * p->vx[i] + th * d->vx[i]);
        d->y1[i] = p->y[i] + dt * ((1 - th) * p->vy[i] + th * d->vy[i]);
        if (d->Lx > 0)
            d->x1[i] -= d->Lx * floor(d->x1[i] / d->Lx);
        if (d->Ly > 0)
            d->y1[i] -= d->Ly * floor(d->y1[i] / d->Ly);
        const char *what = !isfinite(d->vx[i] + d->vy[i]) ? "velocity" : !isfinite(d->w[i]) ? "angular velocity"
                         : !isfinite(d->x1[i] + d->y1[i]) ? "position" : NULL;
        if (what)
            return gr_fail(err, GR_ERUN, "unstable at t = %.9g: grain id %lld has a non-finite %s; lower dt",
                           tn, (long long)p->id[i], what);
    }
    for (size_t k = 0; k < d->cur.n; k++) {
        const gr_cd_contact *c = &d->cur.c[k];
        double un, ut;
        gr_cd_rel(d, c, &un, &ut);
        double ovl = -(c->g + dt * ((1 - th) * c->un0 + th * un)) / c->dmin;
        d->max_ovl = fmax(d->max_ovl, ovl);
        if (ovl > 0.5)
            return gr_fail(err, GR_ERUN,
                           "unstable at t = %.9g: grain id %lld overlaps %s %lld by %.4g of a diameter (bound 0.5); lower dt or tol",
                           tn, (long long)p->id[c->i], (size_t)c->j < d->n ? "grain id" : "wall",
                           (long long)((size_t)c->j < d->n ? p->id[c->j] : c->j - (int64_t)d->n), ovl);
    }
    return GR_OK;
}

/* Grains below the exit or past an open side leave; reinserted at the top
 * when the silo says so, else flagged gone. */
static int handle_exits(gr_cd *d, gr_err *err)
{
    const gr_scene *sc = &d->sc;
    gr_particles *p = d->p;
    double xlo = sc->side[GR_LEFT] == GR_BC_OPEN ? 0.0 : -INFINITY;
    double xhi = sc->side[GR_RIGHT] == GR_BC_OPEN ? sc->width : INFINITY;
    double ylo = sc->side[GR_BOTTOM] == GR_BC_OPEN ? 0.0 : -INFINITY;
    double yhi = sc->side[GR_TOP] == GR_BC_OPEN ? sc->height : INFINITY;
    if (sc->silo.present)
        ylo = fmax(ylo, sc->silo.exit_below);
    int reinsert = sc->silo.present && sc->silo.reinsert;
    for (size_t i = 0; i < d->n; i++) {
        if (d->skip[i] || d->im[i] == 0)
            continue;
        if (!(p->x[i] < xlo || p->x[i] > xhi || p->y[i] < ylo || p->y[i] > yhi))
            continue;
        d->outflow++;
        double nx, ny;
        if (reinsert && gr_reinsert_spot(sc, p, p->radius[i], d->reinsert_rng, 1000, &nx, &ny)) {
            p->x[i] = nx, p->y[i] = ny;
            p->vx[i] = p->vy[i] = p->omega[i] = 0.0;
            continue;
        }
        p->flags[i] |= GR_PF_GONE;
        d->skip[i] = 1;
        d->lost++;
    }
    (void)err;
    return GR_OK;
}

/* The new state becomes the current one. */
static int commit(gr_cd *d, const gr_cd_solve_info *si, gr_err *err)
{
    gr_particles *p = d->p;
    for (size_t i = 0; i < d->n; i++) {
        if (d->im[i] == 0 || d->skip[i])
            continue;
        p->x[i] = d->x1[i], p->y[i] = d->y1[i];
        p->vx[i] = d->vx[i], p->vy[i] = d->vy[i], p->omega[i] = d->w[i];
    }
    for (size_t k = 0; k < d->cur.n; k++)
        if ((size_t)d->cur.c[k].j >= d->n)
            d->wall_impulse += d->cur.c[k].rn;
    d->wall_time += d->par.dt;
    d->step++;
    d->t = (double)d->step * d->par.dt;
    d->sweeps += (uint64_t)si->sweeps;
    d->nonconv += !si->converged;
    d->forced += si->forced_open > 0;
    d->last_residual = si->residual;
    d->last_active = si->active, d->last_sliding = si->sliding;
    gr_cd_list tmp = d->prev;
    d->prev = d->cur;
    d->cur = tmp;
    return handle_exits(d, err);
}

int gr_cd_begin(gr_cd *d, gr_err *err)
{
    if (!d->gates_open && d->t >= d->sc.silo.open_time)
        open_gates(d);
    double margin = free_velocities(d);
    return gr_cd_detect(d, margin, err);
}

int gr_cd_step(gr_cd *d, gr_err *err)
{
    if (gr_cd_begin(d, err))
        return err->code;
    if (d->par.warm) {
        gr_cd_warm_start(d);
        for (size_t k = 0; k < d->cur.n; k++)
            gr_cd_apply(d, &d->cur.c[k], d->cur.c[k].rn, d->cur.c[k].rt);
    }
    gr_cd_solve_info si;
    if (gr_cd_solve(d, &si, err))
        return err->code;
    if (!si.converged && d->par.strict)
        return gr_fail(err, GR_ERUN,
                       "[cd] strict: step %llu (t = %.9g) did not converge in max_iter = %ld sweeps: residual %.3g > tol %g over %zu contacts",
                       (unsigned long long)d->step + 1, d->t + d->par.dt, d->par.max_iter, si.residual,
                       d->par.tol, d->cur.n);
    if (new_positions(d, err))
        return err->code;
    return commit(d, &si, err);
}

int gr_cd_advance(gr_cd *d, double t_end, uint64_t max_steps, gr_err *err)
{
    uint64_t done = 0;
    double eps = 1e-6 * d->par.dt;
    while (d->t < t_end - eps && (max_steps == 0 || done < max_steps)) {
        if (gr_cd_step(d, err))
            return err->code;
        done++;
    }
    return GR_OK;
}
