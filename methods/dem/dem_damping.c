/* The normal damping of the linear law from a restitution coefficient.
 *
 * A scene states either the damping (gamma_n, the soft methods' parameter)
 * or the restitution e (what the hard methods take); the soft DEM honours e
 * by choosing gamma_n so that an isolated binary collision rebounds with
 * exactly e. For the linear spring-dashpot the restitution does not depend
 * on the impact speed (Hertz with this dashpot does, so it is refused). The
 * formula e(gamma_n) is common/scene/restitution.c: inverted here, used as
 * it is by the hard methods, so both directions are one law. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>

#include "dem.h"
#include "restitution.h"

/* gamma giving restitution e: e falls monotonically with gamma, so bisect
 * on the damping ratio b / w0 (to machine precision: 200 halvings). */
static double gamma_for(double kn, double meff, int clip, double e)
{
    if (e >= 1.0)
        return 0.0;
    double z_lo = 0.0, z_hi = 1.0;
    while (gr_linear_restitution(kn, 2.0 * meff * z_hi * sqrt(kn / meff), meff, clip) > e && z_hi < 1e12)
        z_hi *= 2.0;
    for (int k = 0; k < 200 && z_hi - z_lo > 1e-15 * z_hi; k++) {
        double z = 0.5 * (z_lo + z_hi);
        if (gr_linear_restitution(kn, 2.0 * meff * z * sqrt(kn / meff), meff, clip) > e)
            z_lo = z;
        else
            z_hi = z;
    }
    return 2.0 * meff * 0.5 * (z_lo + z_hi) * sqrt(kn / meff);
}

__attribute__((format(printf, 4, 5))) static int refuse(const gr_scene *sc, const char *key, gr_err *err,
                                                        const char *why, ...)
{
    char where[1200], msg[600];
    gr_scene_where(sc, "material", key, where, sizeof where);
    va_list ap;
    va_start(ap, why);
    vsnprintf(msg, sizeof msg, why, ap);
    va_end(ap);
    return gr_fail(err, GR_EINPUT, "%s: %s", where, msg);
}

/* e = 0 needs infinite damping when the contact cannot pull. */
static int reachable(const gr_scene *sc, const char *key, double e, double meff, gr_err *err)
{
    if (e > 0.0 || !sc->mat.clip_attraction)
        return GR_OK;
    return refuse(sc, key, err,
                  "a restitution of %g is out of reach of a dashpot without attraction (e > 0 for "
                  "every finite damping); give a restitution above 0, gamma_n, or clip_attraction = no "
                  "(critical damping %g gives e = 0)",
                  e, 2.0 * sqrt(sc->mat.kn * meff));
}

/* Pairs: gamma_n from e, or e checked against a given gamma_n. */
static int pair_gamma(const gr_scene *sc, double e, double meff, double *gamma, gr_err *err)
{
    const gr_material *m = &sc->mat;
    if (!gr_scene_find(sc, "material", "gamma_n")) {
        if (reachable(sc, "restitution", e, meff, err))
            return err->code;
        *gamma = gamma_for(m->kn, meff, m->clip_attraction, e);
        return GR_OK;
    }
    double e_given = gr_linear_restitution(m->kn, m->gamma_n, meff, m->clip_attraction);
    if (fabs(e_given - e) > 5e-3)
        return refuse(sc, "restitution", err,
                      "%g disagrees with the restitution %.4g that kn and gamma_n give for two mean "
                      "grains; give one of restitution and gamma_n (restitution alone sets gamma_n)",
                      e, e_given);
    *gamma = m->gamma_n;
    return GR_OK;
}

int gr_dem_damping(const gr_scene *sc, const gr_particles *init, double *gn, double *gw, gr_err *err)
{
    const gr_material *m = &sc->mat;
    *gn = *gw = m->gamma_n;
    if (isnan(m->restitution) && isnan(m->wall_restitution))
        return GR_OK;
    if (m->normal == GR_NORMAL_HERTZ)
        return refuse(sc, isnan(m->restitution) ? "wall_restitution" : "restitution", err,
                      "with normal = hertz this dashpot's restitution depends on the impact speed, so "
                      "the soft DEM cannot honour %g; give gamma_n alone",
                      isnan(m->restitution) ? m->wall_restitution : m->restitution);
    double mm = gr_mean_mobile_mass(init);
    if (!isnan(m->restitution) && pair_gamma(sc, m->restitution, 0.5 * mm, gn, err))
        return err->code;
    /* Walls: their own restitution when given; else the pairs' restitution
     * when it set gamma_n; else (gamma_n given) the same gamma_n, as before. */
    if (!isnan(m->wall_restitution)) {
        if (reachable(sc, "wall_restitution", m->wall_restitution, mm, err))
            return err->code;
        *gw = gamma_for(m->kn, mm, m->clip_attraction, m->wall_restitution);
    } else if (!gr_scene_find(sc, "material", "gamma_n")) {
        *gw = gamma_for(m->kn, mm, m->clip_attraction, m->restitution);
    } else {
        *gw = *gn;
    }
    return GR_OK;
}
