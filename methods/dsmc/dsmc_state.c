/* State of the DSMC backend: creation from a scene (the collision rule,
 * the cells, the validity limits), freeing, observables and the
 * wall-pressure window. Calls dsmc_cells.c for the grid. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dsmc_int.h"
#include "restitution.h"

void gr_dsmc_free(gr_dsmc *d)
{
    if (!d)
        return;
    gr_particles_free(d->view);
    free(d->x), free(d->y), free(d->vx), free(d->vy), free(d->tmp);
    free(d->rank), free(d->cell), free(d->order), free(d->ids), free(d->last), free(d->prev);
    free(d->start), free(d->hist), free(d->cv);
    free(d);
}

/* Smooth disks only: any tangential law or rough collisions are refused by
 * name (the scene feature check lets a tangential restitution of -1 by). */
static int set_law(gr_dsmc *d, const gr_scene *sc, const gr_particles *init, gr_err *err)
{
    const gr_material *m = &sc->mat;
    gr_restitution rs;
    if (gr_scene_restitution(sc, init, &rs, err))
        return err->code;
    double tr = m->tangential_restitution;
    const char *key = m->tangential != GR_TANG_NONE ? "tangential" : (!isnan(tr) && tr != -1.0) ? "tangential_restitution" : NULL;
    if (key) {
        char where[1200];
        gr_scene_where(sc, "material", key, where, sizeof where);
        return gr_fail(err, GR_EINPUT, "%s: dsmc collides smooth disks only (no tangential law, no rough collisions)",
                       where);
    }
    d->alpha = isnan(rs.e) ? 1.0 : rs.e;
    d->alpha_w = isnan(rs.e_wall) ? d->alpha : rs.e_wall;
    d->g = sc->gravity;
    d->W = sc->species[0].weight > 0 ? sc->species[0].weight : 1.0;
    d->Lx = sc->width, d->Ly = sc->height;
    double len[4] = {d->Ly, d->Ly, d->Lx, d->Lx};
    for (int k = 0; k < 4; k++)
        d->wall_len += sc->side[k] == GR_BC_WALL ? len[k] : 0.0;
    d->walls_any = d->wall_len > 0;
    return GR_OK;
}

static int alloc_particles(gr_dsmc *d, size_t n, gr_err *err)
{
    size_t m = n + 1;
    d->x = malloc(m * sizeof *d->x), d->y = malloc(m * sizeof *d->y);
    d->vx = malloc(m * sizeof *d->vx), d->vy = malloc(m * sizeof *d->vy), d->tmp = malloc(m * sizeof *d->tmp);
    d->rank = malloc(m * sizeof *d->rank), d->cell = malloc(m * sizeof *d->cell);
    d->order = malloc(m * sizeof *d->order), d->ids = malloc(m * sizeof *d->ids);
    d->last = malloc(m * sizeof *d->last), d->prev = malloc(m * sizeof *d->prev);
    if (!d->x || !d->y || !d->vx || !d->vy || !d->tmp || !d->rank || !d->cell || !d->order || !d->ids || !d->last ||
        !d->prev)
        return gr_fail(err, GR_ERUN, "out of memory for %zu particles", n);
    if (n > GR_DSMC_RANK)
        return gr_fail(err, GR_EINPUT, "dsmc takes at most %u particles, the scene has %zu", GR_DSMC_RANK, n);
    return GR_OK;
}

/* Grains in id order; one diameter and one mass for all (monodisperse). */
static int load_grains(gr_dsmc *d, const gr_particles *init, gr_err *err)
{
    size_t n = init->n;
    gr_id_index *ix = malloc((n + 1) * sizeof *ix);
    if (!ix || alloc_particles(d, n, err)) {
        free(ix);
        return err->code ? err->code : gr_fail(err, GR_ERUN, "out of memory");
    }
    gr_id_index_sort(init->id, n, ix);
    int64_t dup = gr_id_index_duplicate(ix, n);
    int rc = dup >= 0 ? gr_fail(err, GR_EINPUT, "two grains share the id %lld", (long long)dup) : GR_OK;
    d->n = n;
    for (size_t t = 0; t < n && !rc; t++) {
        size_t i = ix[t].i;
        double r = init->radius[i], m = init->mass[i];
        d->x[t] = init->x[i], d->y[t] = init->y[i], d->vx[t] = init->vx[i], d->vy[t] = init->vy[i];
        d->ids[t] = init->id[i];
        d->last[t] = d->prev[t] = GR_DSMC_RANK;
        d->rank[t] = (uint32_t)t | ((init->flags[i] & GR_PF_GONE) ? GR_DSMC_GONE : 0u);
        if (init->flags[i] & GR_PF_FIXED)
            rc = gr_fail(err, GR_EINPUT, "grain id %lld is fixed: dsmc has no wall grains", (long long)init->id[i]);
        else if (!(r > 0 && m > 0))
            rc = gr_fail(err, GR_EINPUT, "grain id %lld has radius %g and mass %g; both must be positive",
                         (long long)init->id[i], r, m);
        else if (t > 0 && (2 * r != d->sigma || m != d->mass))
            rc = gr_fail(err, GR_EINPUT, "dsmc takes one diameter and one mass: grain id %lld differs",
                         (long long)init->id[i]);
        d->sigma = 2 * r, d->mass = m;
    }
    free(ix);
    if (!rc && n == 0)
        rc = gr_scene_no_grains(&d->sc, err);
    return rc;
}

/* Kinetic temperature per grain, T = m <|v - <v>|^2> / 2. */
static double temperature(const gr_dsmc *d)
{
    double sx = 0, sy = 0, s2 = 0;
    for (size_t i = 0; i < d->n; i++)
        sx += d->vx[i], sy += d->vy[i], s2 += d->vx[i] * d->vx[i] + d->vy[i] * d->vy[i];
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
    int k = __builtin_ctz(bit);
    d->lim_val[k] = val, d->lim_max[k] = lim;
    return GR_OK;
}

/* Cells along one axis of length L: with `cell` given, sides of about
 * that; else the fewest cells no wider than hi (the mean free path: the
 * larger the cell, the smaller the cell effects) unless that makes them
 * narrower than lo (the sides the limits below need), then the most
 * cells at least lo wide. */
static int cells_along(double L, double given, double lo, double hi)
{
    double k = given > 0 ? floor(L / given) : ceil(L / hi);
    if (!(given > 0) && L / k < lo)
        k = floor(L / lo);
    return (int)fmax(1.0, fmin(4096.0, k));
}

/* The smallest side, in W sigma, at which the cell effect on the cooling
 * rate (partners that shared cells collide again while their velocities
 * are still correlated) stays under 1 % (docs/methods/dsmc.md, cells):
 * it grows with the dissipation and the density. */
static double pool_side(const gr_dsmc *d, double lambda)
{
    return GR_DSMC_POOL_K * (1.0 - d->alpha * d->alpha) * fmin(1.0, d->sigma / (GR_DSMC_POOL_LAMBDA * lambda));
}

/* Periodic on every side, no gravity: nothing sets a gradient that cells
 * must resolve, so their side may exceed the mean free path. */
static int homogeneous(const gr_dsmc *d)
{
    for (int k = 0; k < 4; k++)
        if (d->sc.side[k] != GR_BC_PERIODIC)
            return 0;
    return d->g == 0.0;
}

/* The cells, then the limits, at the density the grains see: dt <= tau / 2 (tau = 1 / nu,
 * nu = 2 sqrt(pi) n sigma sqrt(T/m)), cell <= lambda (both divided by chi
 * in the Enskog mode; where the scene can hold a gradient), mean particles per cell >= ppc_min,
 * and cells of at least pool_side W d. With cell = 0 the cells meet them all where the scene allows. */
/* The number density the grains see, sum over bins of N_b (N_b - 1) / A_b
 * over N (times W): the mean density where the gas is homogeneous (for
 * grains placed at random), the bed's where grains fill part of the domain
 * (a bed on a floor, a cluster), where the mean over the domain would
 * give cells and limits for a gas that is not there. Bins of about 32
 * grains. */
static double seen_density(const gr_dsmc *d)
{
    int bx, by;
    size_t live;
    double A = d->Lx * d->Ly, *cnt = gr_dsmc_bins(d, &bx, &by, &live), s = 0;
    if (!cnt || live < 2) {
        free(cnt);
        return (double)d->n * d->W / A;
    }
    for (size_t b = 0; b < (size_t)bx * (size_t)by; b++)
        s += cnt[b] * (cnt[b] - 1.0);
    free(cnt);
    double n = s / (A / ((double)bx * by)) / (double)live * d->W;
    return n > 0 ? n : (double)d->n * d->W / A;
}

static int make_cells(gr_dsmc *d, gr_err *err)
{
    double n = seen_density(d);
    /* the Enskog rate is chi times faster: mean free time and path / chi */
    double chi = d->par.enskog ? gr_dsmc_chi(fmin(0.9, n * M_PI * d->sigma * d->sigma / 4)) : 1.0;
    double lambda = 1.0 / (2.0 * M_SQRT2 * n * d->sigma * chi);
    double pool_min = pool_side(d, lambda) * d->W * d->sigma;
    double ppc_side = sqrt(d->par.ppc_min * d->W / n); /* particles per cell where the grains are */
    double lo = fmax(pool_min, fmax(ppc_side, d->sigma));
    double given = d->par.cell * d->sigma;
    d->nx = cells_along(d->Lx, given, lo, lambda), d->ny = cells_along(d->Ly, given, lo, lambda);
    d->cw = d->Lx / d->nx, d->ch = d->Ly / d->ny;
    gr_dsmc_grid(d);
    size_t nc = gr_dsmc_ncells(d);
    d->start = calloc(nc + 2, sizeof *d->start);
    if (!d->start)
        return gr_fail(err, GR_ERUN, "out of memory for %zu cells", nc);
    double T = temperature(d), tau = 1.0 / (2.0 * sqrt(M_PI) * n * d->sigma * chi * sqrt(T / d->mass));
    double ppc = n / d->W * d->cw * d->ch, side = fmin(d->cw, d->ch);
    if (limit(d, T > 0 && d->par.dt > 0.5 * tau, GR_DSMC_BAD_DT, "dt", "dt", d->par.dt, 0.5 * tau, err) ||
        limit(d, !homogeneous(d) && fmax(d->cw, d->ch) > lambda, GR_DSMC_BAD_CELL, "cell", "the cell side",
              fmax(d->cw, d->ch), lambda, err) ||
        limit(d, ppc < d->par.ppc_min, GR_DSMC_BAD_PPC, "ppc_min", "the mean of particles per cell", ppc,
              d->par.ppc_min, err) ||
        limit(d, side < pool_min, GR_DSMC_BAD_RECOLLIDE, "cell", "the cell side", side, pool_min, err))
        return err->code;
    return GR_OK;
}

int gr_dsmc_create(const gr_scene *sc, const gr_particles *init, const gr_dsmc_params *par, uint64_t key,
                   gr_rng *floor_rng, gr_dsmc **out, gr_err *err)
{
    *out = NULL;
    gr_dsmc *d = calloc(1, sizeof *d);
    if (!d)
        return gr_fail(err, GR_ERUN, "out of memory");
    d->sc = *sc;
    d->par = *par;
    d->key = key, d->floor_rng = floor_rng;
    if (set_law(d, sc, init, err) || load_grains(d, init, err) || make_cells(d, err)) {
        int rc = err->code;
        gr_dsmc_free(d);
        return rc;
    }
    *out = d;
    return GR_OK;
}

/* The grains in id order in d->view (allocated at the first call, so that
 * a run that never outputs does not pay for it). */
static int fill_view(gr_dsmc *d, gr_err *err)
{
    if (!d->view && !(d->view = gr_particles_create(d->n + 1, err)))
        return err->code;
    gr_particles *v = d->view;
    v->n = d->n;
    double r = 0.5 * d->sigma, I = gr_disk_inertia(d->mass, r);
    for (size_t k = 0; k < d->n; k++) {
        size_t t = d->rank[k] & GR_DSMC_RANK;
        v->x[t] = d->x[k], v->y[t] = d->y[k], v->vx[t] = d->vx[k], v->vy[t] = d->vy[k], v->omega[t] = 0;
        v->radius[t] = r, v->mass[t] = d->mass, v->inertia[t] = I, v->species[t] = 0;
        v->id[t] = d->ids[t], v->flags[t] = (d->rank[k] & GR_DSMC_GONE) ? GR_PF_GONE : 0u;
    }
    return GR_OK;
}

int gr_dsmc_snapshot(gr_dsmc *d, gr_particles *out, gr_err *err)
{
    if (fill_view(d, err))
        return err->code;
    return gr_particles_copy(out, d->view, err);
}

int gr_dsmc_observe(gr_dsmc *d, gr_obs *o, gr_err *err)
{
    if (fill_view(d, err))
        return err->code;
    gr_obs_from_particles(d->view, d->g, o);
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
    d->virial = 0;
}

double gr_dsmc_bytes_per_particle(const gr_dsmc *d)
{
    double per = 5.0 * sizeof *d->x + 5.0 * sizeof *d->rank + sizeof *d->ids;
    double nc = (double)gr_dsmc_ncells(d);
    return per * (double)(d->n + 1) / (double)d->n + (nc + 2) * sizeof *d->start / (double)d->n;
}
