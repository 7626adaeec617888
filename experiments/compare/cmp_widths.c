/* Case "silo-widths": the shape of the flow rate against the orifice width,
 * Q(D) / Q(D_ref), which needs no unit of time. A lattice gas has its own
 * (a particle moves one site per step, whatever the grains' speed), so its
 * absolute rate is not comparable with dem's without a calibration; the
 * ratio of two of its own rates is.
 *
 * One unit runs the scene's orifice (D_ref, on the instance it is given)
 * and the two others of WIDTHS on fresh instances of the same method, the
 * same seed and settings, each measured as the silo case measures. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cmp.h"
#include "init.h"
#include "refs.h"

#define D_REF 6.0
/* value: Q(4)/Q(6), which tells the laws apart best (Beverloo's 0.375, a
 * flow linear in D 0.667); aux: Q(8)/Q(6). On a lattice the orifice is a
 * whole number of lanes, which moves Q(8)/Q(6) by a few % up and down as
 * the resolution changes; Q(4)/Q(6) settles monotonically
 * (docs/comparison.md). */
static const double widths[2] = {4, 8};

/* Beverloo's law as the thesis fits it (cmp_ref_silo): its shape only. */
static double beverloo(const gr_scene *sc, double D)
{
    return exp_beverloo_2d(1.316, 1.83, 0.848, sc->gravity, D, sc->species[0].diameter);
}

double cmp_ref_silo_widths(const gr_scene *sc, double *aux_ref)
{
    *aux_ref = beverloo(sc, widths[1]) / beverloo(sc, D_REF);
    return beverloo(sc, widths[0]) / beverloo(sc, D_REF);
}

/* The silo measurement at orifice D on a fresh instance of s's method. */
static int rate_at(const cmp_case *c, const gr_sim *s, const gr_scene *sc, double D, cmp_meas *m, gr_err *err)
{
    char set[64];
    snprintf(set, sizeof set, "silo.orifice=%.17g", D);
    gr_scene *sd = cmp_scene_with(sc, set, err);
    gr_particles *p = sd ? gr_particles_create(0, err) : NULL;
    gr_sim *sim = NULL;
    exp_watch w;
    int rc = !p || gr_init_particles(sd, p, err) || gr_sim_create(gr_sim_type(s), sd, p, &sim, err);
    if (!rc) {
        exp_watch_init(&w, sim, &sd->run);
        m->watch = &w;
        rc = cmp_measure_silo(c, sim, sd, m, err);
        m->watch = NULL;
    }
    gr_sim_free(sim);
    gr_particles_free(p);
    gr_scene_free(sd);
    return rc ? (err->code ? err->code : GR_ERUN) : GR_OK;
}

/* r = a / b and its error bar from theirs. */
static double ratio(const cmp_meas *a, const cmp_meas *b, double *sem)
{
    double r = a->value / b->value;
    *sem = fabs(r) * hypot(a->sem / a->value, b->sem / b->value);
    return r;
}

int cmp_measure_silo_widths(const cmp_case *c, gr_sim *s, const gr_scene *sc, cmp_meas *out, gr_err *err)
{
    if (fabs(sc->silo.orifice - D_REF) > 1e-9)
        return gr_fail(err, GR_EINPUT, "%s: case %s needs [silo] orifice = %g (its reference width)", sc->path,
                       c->name, D_REF);
    cmp_meas ref = {.watch = out->watch}, q0 = {0}, q1 = {0};
    int rc = cmp_measure_silo(c, s, sc, &ref, err) || rate_at(c, s, sc, widths[0], &q0, err) ||
             rate_at(c, s, sc, widths[1], &q1, err);
    if (rc)
        return err->code ? err->code : GR_ERUN;
    if (!(ref.value > 0))
        return gr_fail(err, GR_ERUN, "%s: nothing flowed through the orifice of %g d", sc->path, D_REF);
    double aux_sem;
    out->value = ratio(&q0, &ref, &out->sem);
    out->aux = ratio(&q1, &ref, &aux_sem);
    out->steps = ref.steps + q0.steps + q1.steps;
    return GR_OK;
}
