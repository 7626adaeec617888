/* The grains as the outside sees them: at the present time, in id order,
 * wrapped into a periodic box. Low in the layers: a reinsertion (collide.c)
 * looks for room in a snapshot. */
#include <math.h>

#include "edmd_int.h"

int gr_edmd_snapshot(gr_edmd *s, gr_particles *out, gr_err *err)
{
    out->n = 0;
    if (gr_particles_reserve(out, s->n, err))
        return err->code;
    double t = s->t, Ly = s->H - s->ybot;
    for (size_t k = 0; k < s->n; k++) {
        size_t i = s->order[k];
        const edmd_p *p = &s->p[i];
        int gone = s->gone[i];
        double g = edmd_g_of(p, s->g);
        double x = gone ? p->x : edmd_x_at(p, t), y = gone ? p->y : edmd_y_at(p, t, g);
        if (s->periodic_x)
            x -= s->W * floor(x / s->W);
        if (s->periodic_y)
            y -= Ly * floor((y - s->ybot) / Ly);
        long j = gr_particles_push(out, x, y, p->r, s->m[i], gone ? GR_PF_GONE : 0, s->species[i], err);
        if (j < 0)
            return err->code;
        out->vx[j] = gone ? 0.0 : p->vx;
        out->vy[j] = gone ? 0.0 : edmd_vy_at(p, t, g);
        out->omega[j] = s->w[i];
        out->inertia[j] = s->inertia[i];
        out->id[j] = s->id[i];
    }
    return GR_OK;
}
