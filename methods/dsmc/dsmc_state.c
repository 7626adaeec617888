/* State of the DSMC backend: creation from a scene (the collision rule,
 * the cells, the validity limits), freeing, observables and the
 * wall-pressure window. Calls no other file of the backend. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dsmc_int.h"

void gr_dsmc_free(gr_dsmc *d)
{
    if (!d)
        return;
    gr_particles_free(d->p);
    free(d->gmax), free(d->start), free(d->order), free(d->cell);
    free(d);
}

/* Smooth disks only: any tangential law or rough collisions are refused by
 * name (the scene feature check lets a tangential restitution of -1 by). */
static int set_law(gr_dsmc *d, const gr_scene *sc, gr_err *err)
{
    const gr_material *m = &sc->mat;
    double tr = m->tangential_restitution;
    const char *key = m->tangential != GR_TANG_NONE ? "tangential" : (!isnan(tr) && tr != -1.0) ? "tangential_restitution" : NULL;
    if (key) {
        char where[1200];
        gr_scene_where(sc, "material", key, where, sizeof where);
        return gr_fail(err, GR_EINPUT, "%s: dsmc collides smooth disks only (no tangential law, no rough collisions)",
                       where);
    }
    d->alpha = isnan(m->restitution) ? 1.0 : m->restitution;
    d->alpha_w = isnan(m->wall_restitution) ? d->alpha : m->wall_restitution;
    d->g = sc->gravity;
    d->W = sc->species[0].weight > 0 ? sc->species[0].weight : 1.0;
    d->Lx = sc->width, d->Ly = sc->height;
    double len[4] = {d->Ly, d->Ly, d->Lx, d->Lx};
    for (int k = 0; k < 4; k++)
        d->wall_len += sc->side[k] == GR_BC_WALL ? len[k] : 0.0;
    return GR_OK;
}

/* Grains in id order; one diameter and one mass for all (monodisperse). */
static int load_grains(gr_dsmc *d, const gr_particles *init, gr_err *err)
{
    size_t n = init->n;
    gr_id_index *ix = malloc((n + 1) * sizeof *ix);
    if (!(d->p = gr_particles_create(n + 1, err)) || !ix) {
        free(ix);
        return err->code ? err->code : gr_fail(err, GR_ERUN, "out of memory");
    }
    gr_id_index_sort(init->id, n, ix);
    int64_t dup = gr_id_index_duplicate(ix, n);
    int rc = dup >= 0 ? gr_fail(err, GR_EINPUT, "two grains share the id %lld", (long long)dup) : GR_OK;
    d->n = d->p->n = n;
    for (size_t t = 0; t < n && !rc; t++) {
        gr_particles_copy_one(d->p, t, init, ix[t].i);
        double r = d->p->radius[t], m = d->p->mass[t];
        if (d->p->flags[t] & GR_PF_FIXED)
            rc = gr_fail(err, GR_EINPUT, "grain id %lld is fixed: dsmc has no wall grains", (long long)d->p->id[t]);
        else if (!(r > 0 && m > 0))
            rc = gr_fail(err, GR_EINPUT, "grain id %lld has radius %g and mass %g; both must be positive",
                         (long long)d->p->id[t], r, m);
        else if (t > 0 && (2 * r != d->sigma || m != d->mass))
            rc = gr_fail(err, GR_EINPUT, "dsmc takes one diameter and one mass: grain id %lld differs",
                         (long long)d->p->id[t]);
        d->sigma = 2 * r, d->mass = m;
    }
    free(ix);
    if (!rc && n == 0)
        rc = gr_fail(err, GR_EINPUT, "the scene has no grains");
    return rc;
}

/* Kinetic temperature per grain, T = m <|v - <v>|^2> / 2. */
static double temperature(const gr_dsmc *d)
{
    double sx = 0, sy = 0, s2 = 0;
    for (size_t i = 0; i < d->n; i++)
        sx += d->p->vx[i], sy += d->p->vy[i], s2 += d->p->vx[i] * d->p->vx[i] + d->p->vy[i] * d->p->vy[i];
    double n = (double)d->n;
    return 0.5 * d->mass * (s2 / n - (sx * sx + sy * sy) / (n * n));
}

/* One validity limit: an input error naming the key under strict, else a
 * bit of `bad` (the counter validity_warnings). */
static int limit(gr_dsmc *d, int broken, unsigned bit, const char *key, const char *what, double val, double lim,
                 gr_err *err)
{
    if (!broken)
        return GR_OK;
    if (d->par.strict) {
        char where[1200];
        gr_scene_where(&d->sc, "dsmc", key, where, sizeof where);
        return gr_fail(err, GR_EINPUT, "%s: [dsmc] %s: %s is %g, the limit is %g (strict = yes)", where, key, what,
                       val, lim);
    }
    d->bad |= bit;
    return GR_OK;
}

/* Cells of side `cell` diameters, or half the mean free path
 * lambda = 1 / (2 sqrt 2 n sigma) but at least a diameter; then the
 * limits: dt <= tau / 2 (tau = 1 / nu, nu = 2 sqrt(pi) n sigma sqrt(T/m)),
 * cell <= lambda, mean particles per cell >= ppc_min. */
static int make_cells(gr_dsmc *d, gr_err *err)
{
    double n = (double)d->n * d->W / (d->Lx * d->Ly);
    double lambda = 1.0 / (2.0 * M_SQRT2 * n * d->sigma);
    double side = d->par.cell > 0 ? d->par.cell * d->sigma : fmax(0.5 * lambda, d->sigma);
    d->nx = (int)fmax(1.0, fmin(4096.0, floor(d->Lx / side)));
    d->ny = (int)fmax(1.0, fmin(4096.0, floor(d->Ly / side)));
    d->cw = d->Lx / d->nx, d->ch = d->Ly / d->ny;
    size_t nc = (size_t)d->nx * (size_t)d->ny;
    d->gmax = calloc(nc, sizeof *d->gmax), d->start = calloc(nc + 1, sizeof *d->start);
    d->order = calloc(d->n + 1, sizeof *d->order), d->cell = calloc(d->n + 1, sizeof *d->cell);
    if (!d->gmax || !d->start || !d->order || !d->cell)
        return gr_fail(err, GR_ERUN, "out of memory for %zu cells", nc);
    double T = temperature(d), tau = 1.0 / (2.0 * sqrt(M_PI) * n * d->sigma * sqrt(T / d->mass));
    double ppc = (double)d->n / (double)nc;
    if (limit(d, T > 0 && d->par.dt > 0.5 * tau, GR_DSMC_BAD_DT, "dt", "dt", d->par.dt, 0.5 * tau, err) ||
        limit(d, fmax(d->cw, d->ch) > lambda, GR_DSMC_BAD_CELL, "cell", "the cell side", fmax(d->cw, d->ch),
              lambda, err) ||
        limit(d, ppc < d->par.ppc_min, GR_DSMC_BAD_PPC, "ppc_min", "the mean of particles per cell", ppc,
              d->par.ppc_min, err))
        return err->code;
    return GR_OK;
}

int gr_dsmc_create(const gr_scene *sc, const gr_particles *init, const gr_dsmc_params *par,
                   gr_rng *const rng[3], gr_dsmc **out, gr_err *err)
{
    *out = NULL;
    gr_dsmc *d = calloc(1, sizeof *d);
    if (!d)
        return gr_fail(err, GR_ERUN, "out of memory");
    d->sc = *sc;
    d->par = *par;
    d->pair_rng = rng[0], d->imp_rng = rng[1], d->floor_rng = rng[2];
    if (set_law(d, sc, err) || load_grains(d, init, err) || make_cells(d, err)) {
        int rc = err->code;
        gr_dsmc_free(d);
        return rc;
    }
    *out = d;
    return GR_OK;
}

int gr_dsmc_observe(gr_dsmc *d, gr_obs *o, gr_err *err)
{
    (void)err;
    gr_obs_from_particles(d->p, d->g, o);
    o->t = d->t;
    o->steps = d->step;
    o->outflow = 0;
    o->max_overlap = NAN;
    o->wall_pressure = d->wall_time > 0 && d->wall_len > 0 ? d->wall_mom / d->wall_time / d->wall_len : NAN;
    return GR_OK;
}

void gr_dsmc_reset_window(gr_dsmc *d)
{
    d->wall_mom = 0;
    d->wall_time = 0;
}
