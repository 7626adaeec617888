/* State of the contact dynamics backend: creation from a scene and its
 * grains (the contact law, walls, grains in id order), freeing, snapshot,
 * observables and the wall-pressure window. Calls no other file of the
 * backend (the step is above it only through cd_method.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cd_int.h"
#include "restitution.h"
#include "geom.h"

void gr_cd_free(gr_cd *d)
{
    if (!d)
        return;
    gr_particles_free(d->p);
    free(d->im), free(d->iI), free(d->vx), free(d->vy), free(d->w), free(d->x1), free(d->y1);
    free(d->skip), free(d->wall), free(d->cur.c), free(d->prev.c), free(d->perm), free(d->key), free(d->racc);
    gr_grid_free(d->grid);
    free(d);
}

/* Coulomb friction only: the soft tangential laws have no meaning between
 * rigid bodies. A tangential restitution (rough collisions) is the formal
 * tangential velocity's coefficient, with Coulomb's bound. */
static int set_law(gr_cd *d, const gr_scene *sc, const gr_particles *init, gr_err *err)
{
    const gr_material *m = &sc->mat;
    gr_restitution rs;
    if (gr_scene_restitution(sc, init, &rs, err))
        return err->code;
    if (m->tangential != GR_TANG_NONE && m->tangential != GR_TANG_COULOMB) {
        char where[1200];
        gr_scene_where(sc, "material", "tangential", where, sizeof where);
        return gr_fail(err, GR_EINPUT,
                       "%s: contact dynamics takes Coulomb friction between rigid grains (tangential = coulomb, or absent); viscous, regularised and spring laws are soft-contact models",
                       where);
    }
    double tr = m->tangential_restitution;
    int rough = !isnan(tr) && tr != -1.0;
    d->mu = m->tangential == GR_TANG_COULOMB || rough ? m->mu : 0.0;
    d->en = isnan(rs.e) ? 0.0 : rs.e;
    d->enw = isnan(rs.e_wall) ? d->en : rs.e_wall;
    d->et = d->etw = rough ? tr : 0.0;
    d->g = sc->gravity;
    d->Lx = sc->side[GR_LEFT] == GR_BC_PERIODIC ? sc->width : 0.0;
    d->Ly = sc->side[GR_BOTTOM] == GR_BC_PERIODIC ? sc->height : 0.0;
    return GR_OK;
}

static int add_wall(gr_cd *d, double x0, double y0, double x1, double y1, double open_time, int vib,
                    gr_err *err)
{
    gr_cd_wall *s = realloc(d->wall, (size_t)(d->nwall + 1) * sizeof *s);
    if (!s)
        return gr_fail(err, GR_ERUN, "out of memory");
    d->wall = s;
    d->wall[d->nwall++] = (gr_cd_wall){x0, y0, x1, y1, open_time, vib};
    return GR_OK;
}

/* The domain's wall sides (the bottom follows a vibrating floor), then the
 * scene's segments. */
static int make_walls(gr_cd *d, gr_err *err)
{
    const gr_scene *sc = &d->sc;
    double W = sc->width, H = sc->height;
    int vib = sc->floor.motion != GR_FLOOR_FIXED;
    if ((sc->side[GR_LEFT] == GR_BC_WALL && add_wall(d, 0, 0, 0, H, INFINITY, 0, err)) ||
        (sc->side[GR_RIGHT] == GR_BC_WALL && add_wall(d, W, 0, W, H, INFINITY, 0, err)) ||
        (sc->side[GR_BOTTOM] == GR_BC_WALL && add_wall(d, 0, 0, W, 0, INFINITY, vib, err)) ||
        (sc->side[GR_TOP] == GR_BC_WALL && add_wall(d, 0, H, W, H, INFINITY, 0, err)))
        return err->code;
    for (int k = 0; k < sc->nsegments; k++) {
        const gr_segment *s = &sc->segments[k];
        if (add_wall(d, s->x0, s->y0, s->x1, s->y1, s->open_time, s->vibrating, err))
            return err->code;
    }
    return GR_OK;
}

static int alloc_arrays(gr_cd *d, size_t n, gr_err *err)
{
    size_t m = n + 1;
    d->im = calloc(m, sizeof(double)), d->iI = calloc(m, sizeof(double));
    d->vx = calloc(m, sizeof(double)), d->vy = calloc(m, sizeof(double)), d->w = calloc(m, sizeof(double));
    d->x1 = calloc(m, sizeof(double)), d->y1 = calloc(m, sizeof(double));
    d->skip = calloc(m, 1);
    d->p = gr_particles_create(m, err);
    if (!d->p)
        return err->code;
    if (!d->im || !d->iI || !d->vx || !d->vy || !d->w || !d->x1 || !d->y1 || !d->skip)
        return gr_fail(err, GR_ERUN, "out of memory for %zu grains", n);
    return GR_OK;
}

/* Grain t of the id order from init[i]: fixed grains at rest with zero
 * inverse mass; periodic coordinates in [0, L). */
static int load_grain(gr_cd *d, size_t t, const gr_particles *init, size_t i, gr_err *err)
{
    gr_particles *p = d->p;
    gr_particles_copy_one(p, t, init, i);
    int fixed = (p->flags[t] & GR_PF_FIXED) != 0, gone = (p->flags[t] & GR_PF_GONE) != 0;
    if (!gone && (!(p->radius[t] > 0) || (!fixed && !(p->mass[t] > 0))))
        return gr_fail(err, GR_EINPUT, "grain id %lld has radius %g and mass %g; both must be positive",
                       (long long)p->id[t], p->radius[t], p->mass[t]);
    if (!(p->inertia[t] > 0))
        p->inertia[t] = gr_disk_inertia(p->mass[t], p->radius[t]);
    if (fixed)
        p->vx[t] = p->vy[t] = p->omega[t] = 0.0;
    d->im[t] = fixed || gone ? 0.0 : 1.0 / p->mass[t];
    d->iI[t] = fixed || gone ? 0.0 : 1.0 / p->inertia[t];
    d->skip[t] = (unsigned char)gone;
    if (!gone)
        d->dmax = fmax(d->dmax, 2 * p->radius[t]);
    if (d->Lx > 0)
        p->x[t] -= d->Lx * floor(p->x[t] / d->Lx);
    if (d->Ly > 0)
        p->y[t] -= d->Ly * floor(p->y[t] / d->Ly);
    return GR_OK;
}

static int load_grains(gr_cd *d, const gr_particles *init, gr_err *err)
{
    size_t n = init->n;
    gr_id_index *ix = malloc((n + 1) * sizeof *ix);
    if (!ix)
        return gr_fail(err, GR_ERUN, "out of memory");
    gr_id_index_sort(init->id, n, ix);
    int64_t dup = gr_id_index_duplicate(ix, n);
    int rc = dup >= 0 ? gr_fail(err, GR_EINPUT, "two grains share the id %lld", (long long)dup) : GR_OK;
    d->n = n;
    d->p->n = n;
    for (size_t t = 0; t < n && !rc; t++)
        rc = load_grain(d, t, init, ix[t].i, err);
    free(ix);
    if (!rc && !(d->dmax > 0))
        rc = gr_scene_no_grains(&d->sc, err);
    return rc;
}

int gr_cd_create(const gr_scene *sc, const gr_particles *init, const gr_cd_params *par,
                 gr_rng *order_rng, gr_rng *reinsert_rng, gr_cd **out, gr_err *err)
{
    *out = NULL;
    gr_cd *d = calloc(1, sizeof *d);
    if (!d)
        return gr_fail(err, GR_ERUN, "out of memory");
    d->sc = *sc;
    d->par = *par;
    d->order_rng = order_rng, d->reinsert_rng = reinsert_rng;
    d->gates_open = !(sc->silo.present && isfinite(sc->silo.open_time));
    if (set_law(d, sc, init, err) || alloc_arrays(d, init->n, err) || load_grains(d, init, err) ||
        make_walls(d, err)) {
        int rc = err->code;
        gr_cd_free(d);
        return rc;
    }
    *out = d;
    return GR_OK;
}

int gr_cd_snapshot(gr_cd *d, gr_particles *out, gr_err *err)
{
    return gr_particles_copy(out, d->p, err);
}

int gr_cd_observe(gr_cd *d, gr_obs *o, gr_err *err)
{
    (void)err;
    gr_obs_from_particles(d->p, d->g, o);
    o->t = d->t;
    o->steps = d->step;
    o->outflow = d->outflow;
    o->max_overlap = d->max_ovl;
    double len = 0;
    for (int k = 0; k < d->nwall; k++)
        len += hypot(d->wall[k].x1 - d->wall[k].x0, d->wall[k].y1 - d->wall[k].y0);
    o->wall_pressure = d->wall_time > 0 && len > 0 ? d->wall_impulse / d->wall_time / len : NAN;
    return GR_OK;
}

void gr_cd_reset_window(gr_cd *d)
{
    d->wall_impulse = 0;
    d->wall_time = 0;
}
