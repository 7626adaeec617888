/* The end of a step: the energy checks, the commit of the new state, the
 * grains that leave (and their reinsertion), the gates; undoing a refused
 * step's contact history. Below the step. */
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

int gr_dem_open_gates(gr_dem *d, gr_err *err)
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

static void band_add(gr_particles *b, double x, double y, double r)
{
    b->x[b->n] = x;
    b->y[b->n] = y;
    b->radius[b->n] = r;
    b->flags[b->n++] = 0;
}

/* The grains a spot in the reinsertion band could overlap, into
 * d->scratch: those within their radius and a diameter of margin of the
 * band's height. gr_reinsert_spot tests a spot against every grain it is
 * given, so this spares it (and a snapshot of the whole silo per
 * reinserted grain) the rest of the silo; the spot found is the same. */
static int band_grains(gr_dem *d, int p, gr_err *err)
{
    const gr_silo *s = &d->sc.silo;
    gr_particles *b = d->scratch;
    const double *x = d->f[F_X][p], *y = d->f[F_Y][p];
    /* grains found in the band, then the grains reinserted (from below the exit) */
    if (gr_particles_reserve(b, d->n, err))
        return err->code;
    b->n = 0;
    for (size_t i = 0; i < d->n; i++)
        if (y[i] > s->reinsert_bottom - d->rad[i] - 1.0 && y[i] < s->reinsert_top + d->rad[i] + 1.0)
            band_add(b, x[i], y[i], d->rad[i]);
    return GR_OK;
}

/* Grains below the exit or past an open side leave; reinserted at the top
 * when the silo says so. */
static int handle_exits(gr_dem *d, gr_err *err)
{
    const gr_scene *sc = &d->sc;
    int p = d->cur;
    double box[4];
    /* the drift counted them: no pass over all grains when none left */
    int known = d->exits_known;
    d->exits_known = 0;
    if (!gr_dem_exit_box(d, box) || (known && atomic_load_explicit(&d->exits, memory_order_relaxed) == 0))
        return GR_OK;
    double xlo = box[0], xhi = box[1], ylo = box[2], yhi = box[3];
    const double *x = d->f[F_X][p], *y = d->f[F_Y][p];
    if (!known) {
        size_t nout = 0;
        for (size_t i = 0; i < d->n; i++)
            nout += d->im[i] != 0 && (x[i] < xlo || x[i] > xhi || y[i] < ylo || y[i] > yhi);
        if (!nout)
            return GR_OK;
    }
    int reinsert = sc->silo.present && sc->silo.reinsert;
    unsigned char *gone = NULL; /* grains lost (no spot to reinsert them) */
    int any_gone = 0, band = 0;
    for (size_t i = 0; i < d->n; i++) {
        if (!(d->im[i] != 0 && (x[i] < xlo || x[i] > xhi || y[i] < ylo || y[i] > yhi)))
            continue;
        d->pre_E = 0; /* the drift done ahead has the grains where they were */
        d->outflow++;
        double nx, ny;
        if (reinsert) {
            if (!band && band_grains(d, p, err)) {
                free(gone);
                return err->code;
            }
            band = 1;
            if (gr_reinsert_spot(sc, d->scratch, d->rad[i], d->rng, 1000, &nx, &ny)) {
                band_add(d->scratch, nx, ny, d->rad[i]);
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
        if (!gone && !(gone = calloc(d->n + 1, 1)))
            return gr_fail(err, GR_ERUN, "out of memory");
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

/* Nothing feeds energy in: no moving floor or wall, no reinsertion, no
 * external force. */
static int undriven(const gr_dem *d)
{
    if (d->sc.floor.motion != GR_FLOOR_FIXED || d->sc.silo.reinsert || d->ext_fx)
        return 0;
    for (int k = 0; k < d->nseg; k++)
        if (d->seg[k].vibrating)
            return 0;
    return 1;
}

/* An undriven system can only lose mechanical energy (kinetic, elastic and
 * gravitational). Explicit Euler gains it a little each step (+19 % in
 * 5 tau on a settling bed that Verlet holds to 1e-5), too slowly for the
 * one-step jump check: stop once it has grown by a tenth, plus a tenth of
 * the jump check's floor. Checked every 16 steps; the reference is taken
 * at the first check after a start or a restart. */
#define DEM_GROWTH_EVERY 16
static int energy_growth(gr_dem *d, int q, double em, double tn, gr_err *err)
{
    if ((d->step + 1) % DEM_GROWTH_EVERY || !undriven(d))
        return GR_OK;
    double ep = 0;
    const double *y = d->f[F_Y][q];
    for (size_t i = 0; i < d->n; i++)
        if (d->im[i] != 0 && !(d->flags[i] & GR_PF_GONE))
            ep += d->mass[i] * d->g * y[i];
    double e = em + ep;
    if (isnan(d->e_ref)) {
        d->e_ref = e;
        return GR_OK;
    }
    if (e > 1.1 * d->e_ref + 0.1 * d->e_floor)
        return gr_fail(err, GR_ERUN,
                       "unstable at t = %.9g: the mechanical energy of an undriven system grew from %.6g to %.6g (more than 10 %%); the integrator (%s) or dt (%g) does not hold it: use verlet or lower dt",
                       tn, d->e_ref, e, d->par.integrator == GR_DEM_EULER ? "euler" : d->par.integrator == GR_DEM_GEAR ? "gear" : "verlet", d->par.dt);
    return GR_OK;
}

/* After the new forces and velocities: the energy check, then the new
 * state becomes the current one and grains that left are handled. */
int gr_dem_commit(gr_dem *d, int q, uint64_t E, double tn, double ek, gr_err *err)
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
    if (energy_growth(d, q, em, tn, err)) {
        gr_dem_hist_undo_at(d, E);
        return err->code;
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
