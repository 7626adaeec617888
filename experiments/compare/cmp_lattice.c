/* grano compare's rows for the lattice gas where its model states a case's
 * quantity in its own terms (CMP_OWN rows, docs/comparison.md): each run
 * also gives the lattice's own mean-field answer for the state it
 * realised (tests/oracle/lattice.h, written apart from the backend), since
 * a random fill's particle count moves that answer by more than the
 * tolerance.
 *
 * Column: the lattice gas at rest between a floor and a ceiling, periodic
 * sideways. Its exclusion keeps gravity from acting on a full channel's
 * particle, so the floor carries a fraction of the nominal weight N m g
 * that the mean-field hydrostatics gives; the grains' answer is 1.
 * Cooling: the granular rules' dissipative collisions turn movers into
 * rest particles; the moving population's fall against the Boltzmann map
 * of the same rules. */
#include <math.h>
#include <stdlib.h>

#include "cmp.h"
#include "fields.h"
#include "params.h"
#include "lattice.h"
#include "stats.h"

#define NBLOCKS 10
#define NSUB 20 /* occupation samples per block */

typedef struct {
    double a, h, m; /* spacing, lane spacing, particle mass */
    int ni, nj;     /* rows, lanes */
    double dt, g, p; /* the step, gravity's and dissipation's probabilities per node and step */
} lattice;

/* whole: refuse a domain that is not whole rows and lanes (the backend
 * drops the remainder) */
static int lattice_of(gr_sim *s, const gr_scene *sc, int whole, lattice *l, gr_err *err)
{
    gr_param_values pv;
    if (gr_params_read(sc, "lgca", gr_sim_type(s)->params, &pv, err))
        return err->code;
    l->dt = gr_param_get(&pv, "dt"), l->g = gr_param_get(&pv, "g"), l->p = gr_param_get(&pv, "p");
    l->a = gr_scene_max_diameter(sc), l->h = l->a * sqrt(3.0) / 2;
    l->m = sc->species[0].density * M_PI * l->a * l->a / 4;
    l->ni = (int)floor(sc->height / l->a + 1e-9), l->nj = (int)floor(sc->width / l->h + 1e-9);
    if (sc->side[GR_LEFT] == GR_BC_PERIODIC)
        l->nj &= ~1;
    if (isnan(l->g)) /* the backend's default (docs/methods/lgca.md) */
        l->g = sc->gravity * l->dt * l->dt / l->a;
    if (whole && (fabs(l->ni * l->a - sc->height) > 1e-9 * sc->height ||
                  fabs(l->nj * l->h - sc->width) > 1e-9 * sc->width))
        return gr_fail(err, GR_EINPUT, "%s: the lattice case needs whole rows and lanes: height %g = rows x %g, "
                       "width %g = lanes x %g", sc->path, sc->height, l->a, sc->width, l->h);
    return GR_OK;
}

int cmp_measure_lattice_column(const cmp_case *c, gr_sim *s, const gr_scene *sc, cmp_meas *out, gr_err *err)
{
    (void)c;
    lattice l;
    if (lattice_of(s, sc, 1, &l, err))
        return err->code;
    if (sc->side[GR_BOTTOM] != GR_BC_WALL || sc->side[GR_TOP] != GR_BC_WALL || !(l.g > 0))
        return gr_fail(err, GR_EINPUT, "%s: the lattice column needs a floor, a ceiling and gravity", sc->path);
    int rows = l.ni - 2; /* the fluid rows between the wall rows */
    double t0 = sc->run.until / 2, R[NBLOCKS], mid[NBLOCKS], global[4], nsum = 0;
    double *cells = malloc((size_t)l.ni * 4 * sizeof *cells), *d = malloc((size_t)rows * sizeof *d);
    gr_field *f = cells && d ? gr_field_create(1, l.ni, 0, 0, sc->width, l.a, err) : NULL;
    int rc = !f;
    if (!rc) /* the stress window starts once the gas has settled */
        rc = cmp_advance(s, sc, out, t0, err) || gr_sim_stress(s, 1, l.ni, global, cells, err);
    for (int b = 0; b < NBLOCKS && !rc; b++) {
        gr_field_clear(f);
        for (int k = 1; k <= NSUB && !rc; k++)
            rc = cmp_advance(s, sc, out, t0 + (sc->run.until - t0) * (b * NSUB + k) / (NBLOCKS * NSUB), err) ||
                 gr_sim_fields(s, f, 1, err); /* the particles per row, into f's counts */
        if (rc || (rc = gr_sim_stress(s, 1, l.ni, global, cells, err)))
            break;
        double n = 0, nm = 0;
        for (int i = 1; i <= rows; i++)
            n += f->num[i] / f->wsum;
        for (int i = 1 + rows / 4; i <= rows - rows / 4; i++)
            nm += f->num[i] / f->wsum / (7.0 * l.nj * (rows - 2 * (rows / 4)));
        /* the flux through the first fluid row carries the weight of it and all above */
        R[b] = sc->width * cells[4 + 3] / (sc->gravity * l.m * n);
        mid[b] = nm, nsum += n;
    }
    double dbar = nsum / NBLOCKS / (7.0 * l.nj * rows);
    if (!rc && gr_lattice_column(dbar, l.g, rows, d))
        rc = gr_fail(err, GR_ERUN, "%s: no hydrostatic profile of mean occupation %g at g = %g", sc->path, dbar, l.g);
    if (!rc) {
        double sem;
        gr_block_average(R, NBLOCKS, 1, NULL, &out->value, &out->sem);
        gr_block_average(mid, NBLOCKS, 1, NULL, &out->aux, &sem);
        out->own = 3 * d[0] / (7 * l.g * dbar * rows);
        out->own_aux = 0;
        for (int i = rows / 4; i < rows - rows / 4; i++)
            out->own_aux += d[i] / (rows - 2 * (rows / 4));
        gr_obs o;
        if (!(rc = gr_sim_observe(s, &o, err)))
            out->steps = (double)o.steps;
    }
    gr_field_free(f);
    free(cells), free(d);
    return rc ? (err->code ? err->code : GR_ERUN) : GR_OK;
}

/* Movers and rest particles now, from the observables: every mover has
 * kinetic energy m c^2 / 2. */
static int populations(gr_sim *s, const lattice *l, double *moving, double *rest, uint64_t *steps, gr_err *err)
{
    gr_obs o;
    if (gr_sim_observe(s, &o, err))
        return err->code;
    double c = l->a / l->dt;
    *moving = round(2 * o.ekin_trans / (l->m * c * c));
    *rest = (double)o.n_mobile - *moving;
    *steps = o.steps;
    return GR_OK;
}

int cmp_measure_lattice_cooling(const cmp_case *c, gr_sim *s, const gr_scene *sc, cmp_meas *out, gr_err *err)
{
    (void)c;
    lattice l;
    if (lattice_of(s, sc, 0, &l, err))
        return err->code;
    for (int k = 0; k < 4; k++)
        if (sc->side[k] != GR_BC_PERIODIC)
            return gr_fail(err, GR_EINPUT, "%s: the lattice's cooling needs a periodic box", sc->path);
    if (sc->gravity != 0)
        return gr_fail(err, GR_EINPUT, "%s: the lattice's cooling needs no gravity", sc->path);
    double nodes = (double)l.ni * l.nj, m0 = 0, r0 = 0, mh = 0, rh = 0, m1 = 0, r1 = 0;
    uint64_t st0 = 0, sth = 0, st1 = 0;
    int rc = populations(s, &l, &m0, &r0, &st0, err) || cmp_advance(s, sc, out, sc->run.until / 2, err) ||
             populations(s, &l, &mh, &rh, &sth, err) || cmp_advance(s, sc, out, sc->run.until, err) ||
             populations(s, &l, &m1, &r1, &st1, err);
    if (rc)
        return err->code ? err->code : GR_ERUN;
    if (!(m0 > 0))
        return gr_fail(err, GR_EINPUT, "%s: the lattice's cooling starts with no moving particle", sc->path);
    double f0 = m0 / (6 * nodes), q0 = r0 / nodes, f, r;
    if (gr_lattice_cooling(f0, q0, l.p, (long)(st1 - st0), &f, &r))
        return gr_fail(err, GR_ERUN, "%s: no Boltzmann map at f = %g, r = %g, p = %g", sc->path, f0, q0, l.p);
    out->value = m1 / m0, out->aux = mh / m0, out->sem = NAN;
    out->own = f / f0;
    gr_lattice_cooling(f0, q0, l.p, (long)(sth - st0), &f, &r);
    out->own_aux = f / f0;
    out->steps = (double)(st1 - st0);
    return GR_OK;
}
