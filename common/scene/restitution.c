/* The hard methods' restitution from the soft law's damping. The formula is
 * the one the soft DEM inverts (by bisection) to honour a restitution, so
 * a scene giving kn and gamma_n is one dissipation on every method:
 * without clipping the damped oscillator's e = exp(-pi b / w); with clipping
 * (no attraction) the contact ends where the force vanishes, before the
 * overlap does, and e follows Schwager and Poeschel, Granular Matter 9, 465
 * (2007), eqs. 19-21. */
#include "restitution.h"

#include <math.h>
#include <stdio.h>

double gr_linear_restitution(double kn, double gamma, double meff, int clip)
{
    double w0 = sqrt(kn / meff), b = gamma / (2.0 * meff);
    if (!clip) {
        if (b >= w0)
            return 0.0; /* critical or overdamped: the overlap never returns to zero */
        double w = sqrt(w0 * w0 - b * b);
        return exp(-M_PI * b / w);
    }
    if (b == 0.0)
        return 1.0;
    if (b < w0 * M_SQRT1_2) {
        double w = sqrt(w0 * w0 - b * b);
        return exp(-b / w * (M_PI - atan(2.0 * b * w / (w * w - b * b))));
    }
    if (b < w0) {
        double w = sqrt(w0 * w0 - b * b);
        return exp(-b / w * atan(2.0 * b * w / (b * b - w * w)));
    }
    if (b == w0)
        return exp(-2.0); /* the limit of both neighbouring branches */
    double W = sqrt(b * b - w0 * w0);
    return exp(-b / W * log((b + W) / (b - W)));
}

double gr_mean_mobile_mass(const gr_particles *init)
{
    double s = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < init->n; i++) {
        if (init->flags[i] & (GR_PF_FIXED | GR_PF_GONE))
            continue;
        s += init->mass[i];
        n++;
    }
    return n ? s / (double)n : 1.0;
}

int gr_scene_restitution(const gr_scene *sc, const gr_particles *init, gr_restitution *r, gr_err *err)
{
    const gr_material *m = &sc->mat;
    *r = (gr_restitution){.e = m->restitution, .e_wall = m->wall_restitution};
    /* Walls follow the soft DEM: their own restitution, else gamma_n when
     * the file gives it, else the pairs' restitution (the method's default). */
    if (!gr_scene_find(sc, "material", "gamma_n") || (!isnan(r->e) && !isnan(r->e_wall)))
        return GR_OK;
    if (m->normal == GR_NORMAL_HERTZ) {
        char where[1200];
        gr_scene_where(sc, "material", "gamma_n", where, sizeof where);
        return gr_fail(err, GR_EINPUT,
                       "%s: with normal = hertz, gamma_n gives a restitution that depends on the impact "
                       "speed (Schwager and Poeschel 2008), which a hard method cannot honour; add "
                       "[material] %s",
                       where, !isnan(r->e) ? "wall_restitution" : !isnan(r->e_wall) ? "restitution"
                                                                                : "restitution and wall_restitution");
    }
    double mm = gr_mean_mobile_mass(init);
    if (isnan(r->e)) {
        r->e = gr_linear_restitution(m->kn, m->gamma_n, 0.5 * mm, m->clip_attraction);
        r->derived |= 1;
    }
    if (isnan(r->e_wall)) {
        r->e_wall = gr_linear_restitution(m->kn, m->gamma_n, mm, m->clip_attraction);
        r->derived |= 2;
    }
    snprintf(r->note, sizeof r->note,
             "restitution %.6g (pairs)%s, wall_restitution %.6g%s, from kn %g and gamma_n %g for grains of "
             "the mean mass %g (m_eff %g on a pair, %g on a wall)%s",
             r->e, r->derived & 1 ? " derived" : " given", r->e_wall, r->derived & 2 ? " derived" : " given",
             m->kn, m->gamma_n, mm, 0.5 * mm, mm, m->clip_attraction ? ", clipped (no attraction)" : "");
    return GR_OK;
}
