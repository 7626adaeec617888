/* The state no event sequence may reach: a grain below the floor or cutting
 * a hard wall by more than round-off. A missed wall or floor contact leaves
 * every number finite (the grain just falls on), so the engine looks for
 * it and stops the run with a diagnostic instead of going on wrong. */
#include <math.h>

#include "edmd_int.h"

/* Height of the floor at time t (the domain bottom when it does not move:
 * the high-frequency limits keep it at y = 0). */
static double floor_at(const gr_edmd *s, double t)
{
    switch (s->floor) {
    case GR_FLOOR_SINE:
        return s->fA * cos(s->fomega * t);
    case GR_FLOOR_SAWTOOTH: {
        double T = 2.0 * M_PI / s->fomega;
        return -s->fA + s->fA * s->fomega / M_PI * (t - T * floor(t / T));
    }
    default:
        return 0.0;
    }
}

/* How far grain i cuts the floor or a hard wall at time t (<= 0: not). */
static double cut_depth(const gr_edmd *s, int32_t i, double t)
{
    const edmd_p *p = &s->p[i];
    double x = edmd_x_at(p, t), y = edmd_y_at(p, t, edmd_g_of(p, s->g)), d = -EDMD_INF;
    if (s->hard[GR_BOTTOM] || s->floor != GR_FLOOR_FIXED)
        d = fmax(d, floor_at(s, t) + p->r - y);
    if (s->hard[GR_TOP])
        d = fmax(d, y + p->r - s->H);
    if (s->hard[GR_LEFT])
        d = fmax(d, p->r - x);
    if (s->hard[GR_RIGHT])
        d = fmax(d, x + p->r - s->W);
    return d;
}

int edmd_check_inside(const gr_edmd *s, double t, gr_err *err)
{
    /* contacts are found to ~1e-14; the floor's phase omega t loses
     * ~1e-16 omega t to round-off, which A scales */
    double tol = 1e-9 + 1e-14 * s->fA * s->fomega * fabs(t);
    for (size_t k = 0; k < s->n; k++) {
        int32_t i = (int32_t)k;
        if (s->gone[i])
            continue;
        double d = cut_depth(s, i, t);
        if (d > tol)
            return gr_fail(err, GR_ERUN,
                           "edmd: grain %lld is %.3g below the floor or into a wall at t = %.17g "
                           "(y = %.6g): a contact was missed",
                           (long long)s->id[i], d, t, edmd_y_at(&s->p[i], t, edmd_g_of(&s->p[i], s->g)));
    }
    return GR_OK;
}
