/* A small inline 2D vector: value type, no allocation. */
#ifndef GR_VEC2_H
#define GR_VEC2_H

#include <math.h>

typedef struct {
    double x, y;
} gr_v2;

static inline gr_v2 gr_v2_make(double x, double y) { return (gr_v2){x, y}; }
static inline gr_v2 gr_v2_add(gr_v2 a, gr_v2 b) { return (gr_v2){a.x + b.x, a.y + b.y}; }
static inline gr_v2 gr_v2_sub(gr_v2 a, gr_v2 b) { return (gr_v2){a.x - b.x, a.y - b.y}; }
static inline gr_v2 gr_v2_scale(gr_v2 a, double s) { return (gr_v2){a.x * s, a.y * s}; }
static inline gr_v2 gr_v2_axpy(double s, gr_v2 a, gr_v2 b) { return (gr_v2){s * a.x + b.x, s * a.y + b.y}; }
static inline double gr_v2_dot(gr_v2 a, gr_v2 b) { return a.x * b.x + a.y * b.y; }
/* z component of the 3D cross product: the 2D "perp dot". */
static inline double gr_v2_cross(gr_v2 a, gr_v2 b) { return a.x * b.y - a.y * b.x; }
static inline double gr_v2_norm2(gr_v2 a) { return a.x * a.x + a.y * a.y; }
static inline double gr_v2_norm(gr_v2 a) { return sqrt(a.x * a.x + a.y * a.y); }
/* Rotated by +90 degrees: the tangent of a contact whose normal is a. */
static inline gr_v2 gr_v2_perp(gr_v2 a) { return (gr_v2){-a.y, a.x}; }

#endif
