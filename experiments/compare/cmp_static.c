/* grano compare's resting column and pile: the force on the floor, read
 * from the method's contact network (dem and cd give one) or, for a method
 * of instantaneous collisions, from its stress at the floor, against the
 * static answer, and the packing fraction of the bulk.
 *
 * The static answer is Janssen's law in 2-D: the walls' friction carries
 * part of the weight, and the floor feels
 *   F = g M (lambda / z) (1 - exp(-z / lambda)),  lambda = W / (2 mu K),
 * z = M / (rho W) the fill height at the bulk's areal mass density rho.
 * Without friction lambda is infinite and F = g M (hydrostatic). K is not
 * a material constant: it depends on how far the walls' friction is
 * mobilised. The case's floor sinks slowly through the run, so the grains
 * slide down the walls and mobilise it fully, as Janssen assumes; K is
 * then taken as Jaky's at-rest coefficient K0 = 1 - sin(phi), tan(phi) =
 * mu (docs/comparison.md says how it was chosen and how well it holds).
 */
#include <math.h>
#include <stdlib.h>

#include "cmp.h"
#include "contacts.h"
#include "refs.h"
#include "stats.h"

#define NBLOCKS 10

/* The floor's index in the methods' wall list: the domain sides that are
 * walls (left, right, bottom, top), then the segments (common/stress.h). */
static int64_t floor_wall(const gr_scene *sc)
{
    return -1 - ((sc->side[GR_LEFT] == GR_BC_WALL) + (sc->side[GR_RIGHT] == GR_BC_WALL));
}

static double janssen_lambda(const gr_scene *sc)
{
    double k0 = 1 - sin(atan(sc->mat.mu));
    return sc->mat.tangential != GR_TANG_NONE && sc->mat.mu > 0 ? sc->width / (2 * sc->mat.mu * k0) : INFINITY;
}

/* The floor's force from a method without a contact network (hard
 * disks, DSMC): its collisional and kinetic stress over the window since
 * the last call, in the bottom row of cells 1 d high, plus the weight that
 * row's own grains put on the floor. In a static column the force through
 * height y is F - g (mass below y); averaged over the row it is
 * F - g sum m_i (1 - y_i / h), which is exact for grains stacked one
 * above the other and close for a packing. p NULL: start the window. */
static int floor_from_stress(gr_sim *s, const gr_scene *sc, const gr_particles *p, double *base, gr_err *err)
{
    int ny = (int)fmax(1, round(sc->height / sc->species[0].diameter));
    double global[4], *cells = malloc((size_t)ny * 4 * sizeof *cells), h = sc->height / ny, w = 0;
    if (!cells)
        return gr_fail(err, GR_ERUN, "out of memory");
    int rc = gr_sim_stress(s, 1, ny, global, cells, err);
    for (size_t i = 0; !rc && p && i < p->n; i++)
        if (!(p->flags[i] & (GR_PF_FIXED | GR_PF_GONE)) && p->y[i] < h)
            w += p->mass[i] * (1 - fmax(p->y[i], 0) / h);
    *base = rc ? NAN : sc->width * cells[3] + sc->gravity * w;
    free(cells);
    return rc;
}

/* The floor's force over Janssen's, and the packing fraction of the bulk
 * (grains with centres between a quarter and three quarters of the
 * height of the highest grain's top), at the present time: from the
 * contact network where the method gives one, else from its stress. */
static int pile_now(gr_sim *s, const gr_scene *sc, gr_particles *p, gr_contacts *k, double *ratio, double *phi,
                    gr_err *err)
{
    if (sc->side[GR_BOTTOM] != GR_BC_WALL)
        return gr_fail(err, GR_EINPUT, "%s: the column cases need a floor ([domain] bottom = wall)", sc->path);
    double base = 0, M = 0, top = 0, a = 0, mb = 0;
    if (gr_sim_snapshot(s, p, err))
        return err->code;
    if (gr_method_ops(gr_sim_type(s)) & GR_OP_CONTACTS) {
        if (gr_sim_contacts(s, k, err))
            return err->code;
        for (size_t r = 0; r < k->n; r++)
            if (k->j[r] == floor_wall(sc))
                base += k->fn[r];
    } else if (floor_from_stress(s, sc, p, &base, err))
        return err->code;
    for (size_t i = 0; i < p->n; i++)
        if (!(p->flags[i] & (GR_PF_FIXED | GR_PF_GONE)))
            M += p->mass[i], top = fmax(top, p->y[i] + p->radius[i]);
    for (size_t i = 0; i < p->n; i++)
        if (!(p->flags[i] & (GR_PF_FIXED | GR_PF_GONE)) && p->y[i] >= top / 4 && p->y[i] < 3 * top / 4)
            a += M_PI * p->radius[i] * p->radius[i], mb += p->mass[i];
    double band = sc->width * top / 2, lambda = janssen_lambda(sc), z = M / (mb / band * sc->width);
    double share = isinf(lambda) ? 1 : lambda / z * (1 - exp(-z / lambda));
    *ratio = base / (sc->gravity * M * share);
    *phi = a / band;
    return GR_OK;
}

/* Over the last third of the run, NBLOCKS instants: the floor's force
 * over Janssen's (value, block-averaged) and the bulk packing fraction
 * (aux). */
int cmp_measure_column(const cmp_case *c, gr_sim *s, const gr_scene *sc, cmp_meas *out, gr_err *err)
{
    (void)c;
    double R[NBLOCKS], phi[NBLOCKS], t0 = sc->run.until * 2 / 3, sem;
    gr_particles *p = gr_particles_create(0, err);
    gr_contacts *k = p ? gr_contacts_create(64, err) : NULL;
    int rc = !k;
    double first;
    int by_stress = !(gr_method_ops(gr_sim_type(s)) & GR_OP_CONTACTS);
    if (!rc && by_stress) /* the first window of the stress starts at t0 */
        rc = cmp_advance(s, sc, out, t0, err) || floor_from_stress(s, sc, NULL, &first, err);
    for (int b = 0; b < NBLOCKS && !rc; b++)
        rc = cmp_advance(s, sc, out, t0 + (sc->run.until - t0) * (b + 1) / NBLOCKS, err) ||
             pile_now(s, sc, p, k, &R[b], &phi[b], err);
    gr_contacts_free(k);
    gr_particles_free(p);
    if (rc)
        return err->code ? err->code : GR_ERUN;
    gr_block_average(R, NBLOCKS, 1, NULL, &out->value, &out->sem);
    gr_block_average(phi, NBLOCKS, 1, NULL, &out->aux, &sem);
    gr_obs o;
    if (gr_sim_observe(s, &o, err))
        return err->code;
    out->steps = (double)o.steps;
    return GR_OK;
}

/* 1 (the floor carries Janssen's share); aux: the packing fraction of
 * rigid equal disks stacked one above the other, pi d / (4 W), when the
 * channel is narrower than two diameters (none otherwise: a random
 * packing's fraction is not a static answer). */
double cmp_ref_column(const gr_scene *sc, double *aux_ref)
{
    double d = sc->species[0].diameter;
    *aux_ref = sc->nspecies == 1 && sc->species[0].polydispersity == 0 && sc->width < 2 * d
                   ? M_PI * d / (4 * sc->width)
                   : NAN;
    return 1;
}

/* The thesis's 2-D Beverloo law at the silo's orifice, with C = 1.316 and
 * k = 1.83 that grano silo-flow fits on the thesis's material and phi =
 * 0.848, the bulk packing of its full-size silo (docs/experiments.md);
 * the silo case's material differs, so this stands beside the long dem
 * run (its reference), not in its place. aux: none. */
double cmp_ref_silo(const gr_scene *sc, double *aux_ref)
{
    *aux_ref = NAN;
    return exp_beverloo_2d(1.316, 1.83, 0.848, sc->gravity, sc->silo.orifice, sc->species[0].diameter);
}
