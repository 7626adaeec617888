/* Wall segments of the scene (the silo's walls and base, its gate, hopper
 * slopes, [wall.NAME] lines): infinite-mass walls a disk meets either on a
 * face (a quadratic in time, also under gravity: the distance to a line
 * is a parabola) or at an end point (a circle of radius R about the end:
 * quadratic without gravity, a quartic with it, solved by the bounded
 * subdivision of the floor). A gate takes part only before its open_time. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "edmd_int.h"

/* First s >= 0 at which h0 + v s + acc s^2 / 2 reaches 0 from above. */
static double first_zero(double h0, double v, double acc)
{
    if (acc <= 0.0)
        return edmd_fall_time(h0, v, -acc);
    if (v >= 0.0)
        return EDMD_INF;
    if (h0 <= 0.0)
        return 0.0;
    double disc = v * v - 2.0 * acc * h0;
    if (disc < 0.0)
        return EDMD_INF;
    return 2.0 * h0 / (sqrt(disc) - v);
}

double edmd_segment_normal(const gr_edmd *s, int k, double x, double y, double *nx, double *ny)
{
    const gr_segment *q = &s->seg[k];
    double L = s->seg_len[k], ex = (q->x1 - q->x0) / L, ey = (q->y1 - q->y0) / L;
    double u = (x - q->x0) * ex + (y - q->y0) * ey;
    u = u < 0.0 ? 0.0 : u > L ? L : u;
    double dx = x - (q->x0 + u * ex), dy = y - (q->y0 + u * ey), d = sqrt(dx * dx + dy * dy);
    if (d > 0.0) {
        *nx = dx / d;
        *ny = dy / d;
    } else { /* centre on the segment: push along its normal */
        *nx = -ey;
        *ny = ex;
    }
    return d;
}

/* A static end point: the pair-time formula with a partner at rest. */
static double point_time_free(const edmd_p *p, double ex, double ey, double a)
{
    double qx = edmd_x_at(p, a) - ex, qy = p->y + p->vy * (a - p->t) - ey;
    double bb = qx * p->vx + qy * p->vy;
    if (bb >= 0.0)
        return EDMD_INF;
    double c = qx * qx + qy * qy - p->r * p->r;
    if (c <= 0.0)
        return a;
    double disc = bb * bb - (p->vx * p->vx + p->vy * p->vy) * c;
    if (disc < 0.0)
        return EDMD_INF;
    return a + c / (sqrt(disc) - bb);
}

double edmd_segment_time(const gr_edmd *s, int32_t i, int k, double t_from, double horizon)
{
    const gr_segment *q = &s->seg[k];
    const edmd_p *p = &s->p[i];
    double a = t_from > p->t ? t_from : p->t, g = s->g;
    if (a >= q->open_time)
        return EDMD_INF;
    double L = s->seg_len[k], ex = (q->x1 - q->x0) / L, ey = (q->y1 - q->y0) / L, nx = -ey, ny = ex;
    double x = edmd_x_at(p, a), y = edmd_y_at(p, a, g), vy = edmd_vy_at(p, a, g);
    double d = (x - q->x0) * nx + (y - q->y0) * ny, side = d >= 0.0 ? 1.0 : -1.0;
    double best = EDMD_INF;
    /* the face: the distance to the line reaches R on the grain's side */
    double sf = first_zero(side * d - p->r, side * (p->vx * nx + vy * ny), -side * g * ny);
    if (sf < EDMD_INF) {
        double tc = a + sf;
        double u = (edmd_x_at(p, tc) - q->x0) * ex + (edmd_y_at(p, tc, g) - q->y0) * ey;
        if (u >= 0.0 && u <= L)
            best = tc;
    }
    /* the ends, before the face time or the horizon */
    double b = fmin(best, horizon);
    if (g > 0.0 && !(b < EDMD_INF))
        b = a + edmd_fall_time(y - s->ybot + 1.0, vy, g); /* it has crossed cells by then */
    double ends[2][2] = {{q->x0, q->y0}, {q->x1, q->y1}};
    for (int e = 0; e < 2; e++) {
        double te = g > 0.0 ? edmd_point_time(s, p, ends[e][0], ends[e][1], a, b)
                            : point_time_free(p, ends[e][0], ends[e][1], a);
        if (te < best)
            best = te;
    }
    return best < q->open_time ? best : EDMD_INF;
}

/* Per cell, the segments a grain whose centre is in the cell can touch:
 * those within R_max of the cell's rectangle (tested on the segment's
 * bounding box widened by R_max, which may include a few more). */
int edmd_segments_setup(gr_edmd *s, const gr_scene *sc, gr_err *err)
{
    s->nseg = sc->nsegments;
    size_t nc = (size_t)s->nx * (size_t)s->ny;
    s->cseg_start = calloc(nc + 1, sizeof *s->cseg_start);
    if (!s->cseg_start)
        return gr_fail(err, GR_ERUN, "edmd: out of memory for the segment lists");
    if (!s->nseg)
        return GR_OK;
    s->seg = malloc((size_t)s->nseg * sizeof *s->seg);
    s->seg_len = malloc((size_t)s->nseg * sizeof *s->seg_len);
    if (!s->seg || !s->seg_len)
        return gr_fail(err, GR_ERUN, "edmd: out of memory for the segments");
    memcpy(s->seg, sc->segments, (size_t)s->nseg * sizeof *s->seg);
    for (int k = 0; k < s->nseg; k++) {
        const gr_segment *q = &s->seg[k];
        s->seg_len[k] = hypot(q->x1 - q->x0, q->y1 - q->y0);
        if (!(s->seg_len[k] > 0.0))
            return gr_fail(err, GR_EINPUT, "%s:%d: a wall segment of zero length", sc->path, q->line);
    }
    for (int pass = 0; pass < 2; pass++) {
        size_t total = 0;
        for (size_t c = 0; c < nc; c++) {
            double x0 = (double)(c % (size_t)s->nx) * s->cw, y0 = s->ybot + (double)(c / (size_t)s->nx) * s->ch;
            if (pass)
                s->cseg_start[c] = (int32_t)total;
            for (int k = 0; k < s->nseg; k++) {
                const gr_segment *q = &s->seg[k];
                double m = s->rmax * 1.001 + 1e-9;
                if (fmin(q->x0, q->x1) - m > x0 + s->cw || fmax(q->x0, q->x1) + m < x0 ||
                    fmin(q->y0, q->y1) - m > y0 + s->ch || fmax(q->y0, q->y1) + m < y0)
                    continue;
                if (pass)
                    s->cseg[total] = k;
                total++;
            }
        }
        if (pass)
            s->cseg_start[nc] = (int32_t)total;
        else if (!(s->cseg = malloc((total + 1) * sizeof *s->cseg)))
            return gr_fail(err, GR_ERUN, "edmd: out of memory for the segment lists");
    }
    return GR_OK;
}
