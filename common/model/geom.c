#include "geom.h"

#include <math.h>

gr_v2 gr_seg_closest(gr_v2 a, gr_v2 b, gr_v2 p, double *t)
{
    gr_v2 ab = gr_v2_sub(b, a);
    double l2 = gr_v2_norm2(ab);
    double s = l2 > 0 ? gr_v2_dot(gr_v2_sub(p, a), ab) / l2 : 0.0;
    s = s < 0 ? 0 : s > 1 ? 1 : s;
    if (t)
        *t = s;
    return gr_v2_axpy(s, ab, a);
}

double gr_seg_distance(gr_v2 a, gr_v2 b, gr_v2 p)
{
    return gr_v2_norm(gr_v2_sub(p, gr_seg_closest(a, b, p, NULL)));
}

int gr_disk_segment_contact(gr_v2 a, gr_v2 b, gr_v2 c, double r,
                            double *overlap, gr_v2 *normal, gr_v2 *point)
{
    gr_v2 q = gr_seg_closest(a, b, c, NULL);
    gr_v2 dq = gr_v2_sub(c, q);
    double dist = gr_v2_norm(dq);
    if (dist >= r)
        return 0;
    if (dist > 0) {
        *normal = gr_v2_scale(dq, 1.0 / dist);
    } else {
        /* Centre on the segment: push along its left normal, a choice
         * that is at least deterministic. */
        gr_v2 t = gr_v2_sub(b, a);
        *normal = gr_v2_scale(gr_v2_perp(t), 1.0 / gr_v2_norm(t));
    }
    *overlap = r - dist;
    *point = q;
    return 1;
}

/* Sawtooth: rises at constant speed from -A to A over a period, then drops. */
static double sawtooth_phase(double omega, double t)
{
    double u = omega * t / (2 * M_PI);
    return u - floor(u);
}

double gr_floor_offset(const gr_floor *f, double t)
{
    switch (f->motion) {
    case GR_FLOOR_SINE:
        return f->amplitude * cos(f->omega * t);
    case GR_FLOOR_SAWTOOTH:
        return f->amplitude * (2.0 * sawtooth_phase(f->omega, t) - 1.0);
    default:
        return 0.0;
    }
}

double gr_floor_velocity(const gr_floor *f, double t)
{
    switch (f->motion) {
    case GR_FLOOR_SINE:
        return -f->amplitude * f->omega * sin(f->omega * t);
    case GR_FLOOR_SAWTOOTH:
        return f->amplitude * f->omega / M_PI;
    default:
        return 0.0;
    }
}
