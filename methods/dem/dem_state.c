/* State of the DEM backend: creation from a scene and its particles and
 * freeing, energies, observables and the tests' hooks. Above the step's
 * layers (it evaluates the first forces, starts CVODE). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dem.h"
#include "geom.h"
#include "rng.h"


void gr_dem_free(gr_dem *d)
{
    if (!d)
        return;
    gr_dem_cv_free(d);
    gr_rng_free(d->own_rng);
    gr_dem_eval_free(d->ev);
    gr_dem_team_free(d->team);
    for (int f = 0; f < F_NFIELDS; f++)
        for (int p = 0; p < 3; p++)
            free(d->f[f][p]);
    free(d->rad), free(d->im), free(d->iI), free(d->gf), free(d->mass), free(d->inertia);
    free(d->tag), free(d->flags), free(d->species), free(d->xref), free(d->yref);
    free(d->ext_fx), free(d->ext_fy);
    gr_particles_free(d->gone);
    gr_particles_free(d->scratch);
    free(d->tag_id);
    free(d->seg);
    free(d->seg_force);
    free(d->blk);
    free(d->cells.start), free(d->cells.idx), free(d->cells.cell);
    free(d->cells.cell_seg_start), free(d->cells.cell_seg);
    free(d->strips.row0), free(d->strips.i0);
    free(d->nb_start), free(d->nb_j), free(d->nb_i), free(d->sg_start), free(d->sg_j);
    gr_dem_hist *h = &d->hist;
    free(h->partner), free(h->partner_old), free(h->z), free(h->z_old), free(h->stamp), free(h->stamp_old);
    free(d);
}

static int add_seg(gr_dem *d, double x0, double y0, double x1, double y1, double open_time,
                   int vibrating, gr_err *err)
{
    gr_dem_seg *s = realloc(d->seg, (size_t)(d->nseg + 1) * sizeof *s);
    if (!s)
        return gr_fail(err, GR_ERUN, "out of memory");
    d->seg = s;
    d->seg[d->nseg++] = (gr_dem_seg){x0, y0, x1, y1, open_time, vibrating};
    return GR_OK;
}

static int make_segments(gr_dem *d, gr_err *err)
{
    const gr_scene *sc = &d->sc;
    double W = sc->width, H = sc->height;
    int vib = sc->floor.motion != GR_FLOOR_FIXED;
    if (sc->side[GR_LEFT] == GR_BC_WALL && add_seg(d, 0, 0, 0, H, INFINITY, 0, err))
        return err->code;
    if (sc->side[GR_RIGHT] == GR_BC_WALL && add_seg(d, W, 0, W, H, INFINITY, 0, err))
        return err->code;
    if (sc->side[GR_BOTTOM] == GR_BC_WALL && add_seg(d, 0, 0, W, 0, INFINITY, vib, err))
        return err->code;
    if (sc->side[GR_TOP] == GR_BC_WALL && add_seg(d, 0, H, W, H, INFINITY, 0, err))
        return err->code;
    for (int k = 0; k < sc->nsegments; k++) {
        const gr_segment *s = &sc->segments[k];
        if (add_seg(d, s->x0, s->y0, s->x1, s->y1, s->open_time, s->vibrating, err))
            return err->code;
    }
    d->seg_force = calloc((size_t)(d->nseg + 1) * 3, sizeof(double));
    return d->seg_force ? GR_OK : gr_fail(err, GR_ERUN, "out of memory");
}

int gr_dem_prepare(gr_dem *d, gr_err *err)
{
    double cutoff = 2.0 * d->rmax + (d->par.neighbour == GR_DEM_NB_VERLET ? d->par.skin : 0.0);
    if (gr_dem_cells_setup(d, cutoff, err))
        return err->code;
    if (d->par.neighbour != GR_DEM_NB_BRUTE && gr_dem_sort(d, err))
        return err->code;
    if (d->par.neighbour == GR_DEM_NB_VERLET &&
        gr_dem_build_list(d, d->f[F_X][d->cur], d->f[F_Y][d->cur], err))
        return err->code;
    return GR_OK;
}

/* The contact law and the domain from the scene; refuses the combinations
 * the backend cannot run (GR_EINPUT naming the key). */
static int set_law(gr_dem *d, const gr_scene *sc, const gr_particles *init, gr_err *err)
{
    const gr_material *m = &sc->mat;
    if (gr_dem_damping(sc, init, &d->gn, &d->gw, err))
        return err->code;
    d->normal = m->normal;
    d->tang = m->tangential;
    d->kn = m->kn, d->kt = m->kt, d->gt = m->gamma_t, d->mu = m->mu;
    d->clip = m->clip_attraction;
    d->rot = d->tang != GR_TANG_NONE;
    d->hist_on = d->tang == GR_TANG_SPRING;
    d->g = sc->gravity;
    d->Lx = sc->side[GR_LEFT] == GR_BC_PERIODIC ? sc->width : 0.0;
    d->Ly = sc->side[GR_BOTTOM] == GR_BC_PERIODIC ? sc->height : 0.0;
    if (d->tang == GR_TANG_NONE && !isnan(m->tangential_restitution) && m->tangential_restitution != -1.0) {
        char where[1200];
        gr_scene_where(sc, "material", "tangential_restitution", where, sizeof where);
        return gr_fail(err, GR_EINPUT,
                       "%s: the soft DEM takes friction from [material] tangential (coulomb, viscous, regularised or spring), not from a tangential restitution",
                       where);
    }
    if (d->hist_on && d->par.integrator == GR_DEM_CVODE)
        return gr_fail(err, GR_EINPUT, "[dem] integrator = cvode cannot carry the tangential spring's history; use verlet or gear");
    if (d->hist_on && !(d->kt > 0))
        return gr_fail(err, GR_EINPUT, "[material] tangential = spring needs kt > 0");
    return GR_OK;
}

/* Tags are the ranks of the ids: the grains sorted by id in ix (entry t
 * holds the index in init of tag t), which the caller frees. */
static int tag_order(gr_dem *d, const gr_particles *init, gr_id_index **ix, gr_err *err)
{
    size_t nt = init->n;
    d->ntag = nt;
    *ix = malloc((nt + 1) * sizeof **ix);
    d->tag_id = malloc((nt + 1) * sizeof *d->tag_id);
    d->gone = gr_particles_create(nt + 1, err);
    if (!*ix || !d->tag_id || !d->gone)
        return d->gone ? gr_fail(err, GR_ERUN, "out of memory") : err->code;
    gr_id_index_sort(init->id, nt, *ix);
    int64_t dup = gr_id_index_duplicate(*ix, nt);
    if (dup >= 0)
        return gr_fail(err, GR_EINPUT, "two grains share the id %lld", (long long)dup);
    return GR_OK;
}

/* Every grain, live or gone, goes to the tag-indexed record; the live ones
 * must have a positive radius and (unless fixed) mass. Sets the diameter
 * range and the history's slots, and returns the live count in *live. */
static int record_grains(gr_dem *d, const gr_particles *init, const gr_id_index *ix, size_t *live,
                         gr_err *err)
{
    size_t nt = d->ntag;
    double rmin = INFINITY;
    d->gone->n = nt;
    *live = 0;
    for (size_t t = 0; t < nt; t++) {
        size_t i = ix[t].i;
        d->tag_id[t] = init->id[i];
        gr_particles_copy_one(d->gone, t, init, i);
        if (init->flags[i] & GR_PF_GONE)
            continue;
        ++*live;
        d->rmax = fmax(d->rmax, init->radius[i]);
        rmin = fmin(rmin, init->radius[i]);
        if (!(init->radius[i] > 0) || (!(init->flags[i] & GR_PF_FIXED) && !(init->mass[i] > 0)))
            return gr_fail(err, GR_EINPUT, "grain id %lld has radius %g and mass %g; both must be positive",
                           (long long)init->id[i], init->radius[i], init->mass[i]);
    }
    if (*live == 0)
        return gr_scene_no_grains(&d->sc, err);
    d->dmax = 2 * d->rmax;
    d->dmin = 2 * rmin;
    if (d->hist_on) {
        double a = asin(rmin / (rmin + d->rmax));
        d->hist.cap = (int)floor(M_PI / a + 1e-9) + 4;
    }
    return GR_OK;
}

/* Live grain i of init into slot k of buffer 0, as tag t. */
static void load_grain(gr_dem *d, size_t k, const gr_particles *init, size_t i, size_t t)
{
    int fixed = (init->flags[i] & GR_PF_FIXED) != 0;
    d->f[F_X][0][k] = init->x[i];
    d->f[F_Y][0][k] = init->y[i];
    d->f[F_VX][0][k] = fixed ? 0.0 : init->vx[i];
    d->f[F_VY][0][k] = fixed ? 0.0 : init->vy[i];
    if (d->rot)
        d->f[F_W][0][k] = fixed ? 0.0 : init->omega[i];
    d->rad[k] = init->radius[i];
    d->mass[k] = init->mass[i];
    d->inertia[k] = init->inertia[i] > 0 ? init->inertia[i] : gr_disk_inertia(init->mass[i], init->radius[i]);
    d->im[k] = fixed ? 0.0 : 1.0 / init->mass[i];
    d->iI[k] = fixed ? 0.0 : 1.0 / d->inertia[k];
    d->gf[k] = fixed ? 0.0 : d->g;
    d->tag[k] = (int32_t)t;
    d->flags[k] = init->flags[i];
    d->species[k] = init->species[i];
    d->nmobile += !fixed;
    /* periodic positions live in [0, L) */
    if (d->Lx > 0)
        d->f[F_X][0][k] -= d->Lx * floor(d->f[F_X][0][k] / d->Lx);
    if (d->Ly > 0)
        d->f[F_Y][0][k] -= d->Ly * floor(d->f[F_Y][0][k] / d->Ly);
}

/* The live grains, in id order, into the arrays (buffer 0 current). */
static int load_grains(gr_dem *d, const gr_particles *init, const gr_id_index *ix, size_t live,
                       gr_err *err)
{
    if (gr_dem_grow(d, live + 16, err))
        return err->code;
    d->cur = 0;
    for (size_t t = 0; t < d->ntag; t++)
        if (!(init->flags[ix[t].i] & GR_PF_GONE))
            load_grain(d, d->n++, init, ix[t].i, t);
    return GR_OK;
}

/* Walls, scratch, the reinsertion generator, gates, cells and lists. */
static int set_scene(gr_dem *d, gr_err *err)
{
    const gr_scene *sc = &d->sc;
    if (make_segments(d, err))
        return err->code;
    d->scratch = gr_particles_create(d->ntag + 1, err);
    if (!d->scratch)
        return err->code;
    if (sc->silo.present && sc->silo.reinsert && !d->rng) {
        /* used without an instance (per-method tests): a stream of its own */
        if (!(d->rng = d->own_rng = gr_rng_create(sc->seed, GR_STREAM_DEM_REINSERT, err)))
            return err->code;
    }
    d->gates_open = !(sc->silo.present && isfinite(sc->silo.open_time));
    return gr_dem_prepare(d, err);
}

/* Forces of the initial state (Gear's second derivative from them), its
 * energy, and the floor under which energy jumps are not checked. */
static int first_forces(gr_dem *d, gr_err *err)
{
    int p = d->cur;
    if (d->par.integrator == GR_DEM_CVODE) {
        if (gr_dem_cv_create(d, err))
            return err->code;
    } else {
        if (gr_dem_eval_at(d, p, d->t, 0, 0.0, d->par.neighbour, d->seg_force, err))
            return err->code;
        if (d->par.integrator == GR_DEM_GEAR) {
            double h2 = 0.5 * d->par.dt * d->par.dt;
            for (size_t i = 0; i < d->n; i++) {
                d->f[F_B2X][p][i] = h2 * d->f[F_FX][p][i] * d->im[i];
                d->f[F_B2Y][p][i] = h2 * (d->f[F_FY][p][i] * d->im[i] - d->gf[i]);
                d->f[F_B2T][p][i] = d->rot ? h2 * d->f[F_TQ][p][i] * d->iI[i] : 0.0;
            }
        }
    }
    double ek, msum = 0;
    for (size_t i = 0; i < d->n; i++)
        msum += d->im[i] != 0 ? d->mass[i] : 0.0;
    d->e_floor = msum * (d->g * d->dmax + 0.005 * d->par.v_impact * d->par.v_impact);
    gr_dem_energy(d, &ek, NULL);
    d->ekin_last = ek + d->eel_eval;
    d->e_ref = NAN;
    return GR_OK;
}

int gr_dem_create(const gr_scene *sc, const gr_particles *init, const gr_dem_params *par, gr_rng *reinsert,
                  gr_dem **out, gr_err *err)
{
    *out = NULL;
    gr_dem *d = calloc(1, sizeof *d);
    if (!d)
        return gr_fail(err, GR_ERUN, "out of memory");
    d->sc = *sc;
    d->par = *par;
    d->rng = reinsert;
    gr_id_index *ix = NULL;
    size_t live = 0;
    int rc = set_law(d, sc, init, err) || tag_order(d, init, &ix, err) ||
             record_grains(d, init, ix, &live, err) || load_grains(d, init, ix, live, err);
    free(ix);
    if (rc || set_scene(d, err) || first_forces(d, err)) {
        rc = err->code;
        gr_dem_free(d);
        return rc;
    }
    *out = d;
    return GR_OK;
}

void gr_dem_energy(gr_dem *d, double *ekin, double *eel)
{
    int p = d->cur;
    double ek = 0;
    for (size_t i = 0; i < d->n; i++) {
        if (d->im[i] == 0)
            continue;
        double vx = d->f[F_VX][p][i], vy = d->f[F_VY][p][i];
        ek += 0.5 * d->mass[i] * (vx * vx + vy * vy);
        if (d->rot) {
            double w = d->f[F_W][p][i];
            ek += 0.5 * d->inertia[i] * w * w;
        }
    }
    *ekin = ek;
    if (!eel)
        return;
    /* elastic energy: all overlapping pairs and walls, by brute force over
     * the cells (a diagnostic, not on the hot path) */
    double e = 0;
    const double *x = d->f[F_X][p], *y = d->f[F_Y][p];
    double a = d->normal == GR_NORMAL_HERTZ ? 2.5 : 2.0;
    for (size_t i = 0; i < d->n; i++) {
        for (size_t j = i + 1; j < d->n; j++) {
            double dx = gr_min_image(x[j] - x[i], d->Lx), dy = gr_min_image(y[j] - y[i], d->Ly);
            double rs = d->rad[i] + d->rad[j];
            if (dx * dx + dy * dy < rs * rs) {
                double xi = rs - sqrt(dx * dx + dy * dy);
                e += d->kn * pow(xi, a) / a;
            }
        }
    }
    for (size_t i = 0; i < d->n; i++) {
        if (d->flags[i] & GR_PF_FIXED)
            continue;
        for (int k = 0; k < d->nseg; k++) {
            const gr_dem_seg *sg = &d->seg[k];
            if (!(d->t < sg->open_time))
                continue;
            double ex = sg->x1 - sg->x0, ey = sg->y1 - sg->y0, l2 = ex * ex + ey * ey;
            double u = l2 > 0 ? ((x[i] - sg->x0) * ex + (y[i] - sg->y0) * ey) / l2 : 0.0;
            u = u < 0 ? 0 : u > 1 ? 1 : u;
            double dist = hypot(x[i] - sg->x0 - u * ex, y[i] - sg->y0 - u * ey);
            if (dist < d->rad[i])
                e += d->kn * pow(d->rad[i] - dist, a) / a;
        }
    }
    *eel = e;
}

int gr_dem_observe(gr_dem *d, gr_obs *o, gr_err *err)
{
    if (gr_dem_snapshot(d, d->scratch, err))
        return err->code;
    gr_obs_from_particles(d->scratch, d->g, o);
    o->t = d->t;
    o->steps = d->step;
    o->outflow = d->outflow;
    o->max_overlap = d->max_ovl;
    double len = 0;
    for (int k = 0; k < d->nseg; k++)
        len += hypot(d->seg[k].x1 - d->seg[k].x0, d->seg[k].y1 - d->seg[k].y0);
    o->wall_pressure = d->wall_time > 0 && len > 0 ? d->wall_impulse / d->wall_time / len : NAN;
    return GR_OK;
}

void gr_dem_reset_window(gr_dem *d)
{
    d->wall_impulse = 0;
    d->wall_time = 0;
}

int gr_dem_set_external(gr_dem *d, long tag, double fx, double fy, gr_err *err)
{
    if (gr_dem_external_arrays(d, err))
        return err->code;
    long i = gr_dem_index(d, tag);
    if (i < 0)
        return gr_fail(err, GR_EINPUT, "no live grain with tag %ld", tag);
    d->ext_fx[i] = fx;
    d->ext_fy[i] = fy;
    return GR_OK;
}

void gr_dem_lock_rotation(gr_dem *d, long tag)
{
    long i = gr_dem_index(d, tag);
    if (i >= 0)
        d->iI[i] = 0.0;
}

void gr_dem_segment_force(const gr_dem *d, int s, double *fx, double *fy)
{
    *fx = d->seg_force[3 * s];
    *fy = d->seg_force[3 * s + 1];
}

double gr_dem_memory(const gr_dem *d)
{
    double b = 0;
    for (int f = 0; f < F_NFIELDS; f++)
        for (int p = 0; p < 3; p++)
            b += d->f[f][p] ? (double)d->cap * sizeof(double) : 0;
    const double *arr[] = {d->rad, d->im, d->iI, d->gf, d->mass, d->inertia,
                           d->xref, d->yref, d->ext_fx, d->ext_fy};
    for (size_t k = 0; k < sizeof arr / sizeof *arr; k++)
        b += arr[k] ? (double)d->cap * sizeof(double) : 0;
    b += (double)d->cap * (sizeof(int32_t) * 2 + sizeof(uint32_t));
    b += (double)(2 * d->nb_cap + d->sg_cap + 2 * (d->n + 1)) * sizeof(int32_t);
    b += (double)d->cells.cap * 2 * sizeof(int32_t);
    b += (double)(d->cells.nx * d->cells.ny + 1) * sizeof(int32_t);
    if (d->hist_on)
        b += (double)d->cap * d->hist.cap * (2 * sizeof(int32_t) + 2 * sizeof(double) + 2 * sizeof(uint64_t));
    b += (double)d->ntag * (sizeof(double) * 8 + sizeof(uint32_t) + sizeof(int64_t) * 2 + sizeof(int32_t));
    return b + gr_dem_team_bytes(d->team);
}
