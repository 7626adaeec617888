/* Geometry of disks and wall segments, and the motion of a vibrating floor. */
#ifndef GR_GEOM_H
#define GR_GEOM_H

#include "scene_types.h"
#include "vec2.h"

/* Closest point of segment [a,b] to p; *t in [0,1] is its parameter. */
gr_v2 gr_seg_closest(gr_v2 a, gr_v2 b, gr_v2 p, double *t);
/* Distance from p to segment [a,b]. */
double gr_seg_distance(gr_v2 a, gr_v2 b, gr_v2 p);

/* Contact of a disk (centre c, radius r) with segment [a,b]: returns 1 when
 * they overlap, with the overlap depth, the unit normal pointing from the
 * wall to the disk centre and the contact point on the segment. */
int gr_disk_segment_contact(gr_v2 a, gr_v2 b, gr_v2 c, double r,
                            double *overlap, gr_v2 *normal, gr_v2 *point);

/* Is segment s present at time t (a gate vanishes at its open_time)? */
static inline int gr_segment_active(const gr_segment *s, double t) { return t < s->open_time; }

/* Vertical floor displacement and velocity at time t. The high-frequency
 * limits have zero displacement; their velocity is drawn per collision by
 * the method (see docs/scene-format.md), so these return 0 for them. */
double gr_floor_offset(const gr_floor *f, double t);
double gr_floor_velocity(const gr_floor *f, double t);

/* Minimum image of a separation along a periodic length L (L <= 0: none). */
static inline double gr_min_image(double d, double L)
{
    if (L > 0.0) {
        if (d > 0.5 * L)
            d -= L;
        else if (d < -0.5 * L)
            d += L;
    }
    return d;
}

/* A coordinate moved by less than L back into [0, L) (L <= 0: none). */
static inline double gr_wrap(double x, double L)
{
    if (L > 0) {
        if (x >= L)
            x -= L;
        else if (x < 0)
            x += L;
    }
    return x;
}

#endif
