/* An exact oracle for the homogeneous cooling state of smooth inelastic
 * hard disks of equal mass: a Kac process (no space) of N velocities, whose
 * N -> infinity limit is the inelastic Boltzmann equation, written apart
 * from methods/dsmc. Pairs and impact directions are drawn uniformly and
 * accepted with |g.n| / G (G >= |g| for every pair), which weights each
 * collision by the flux of hard disks. The kernel is homogeneous of degree
 * one in the velocities, so the law of the sequence of collisions does not
 * depend on the scale of the gas: rescaling to T = 1 changes nothing but
 * the rounding, and counting collisions replaces the clock. */
#ifndef GR_KAC_H
#define GR_KAC_H

#include <stdint.h>

typedef struct {
    double alpha;       /* normal restitution */
    int n;              /* velocities */
    int transient;      /* collisions per particle skipped */
    int samples;        /* a2 samples, one per collision per particle */
    int block;          /* samples per block of the standard error */
    unsigned long seed; /* of the one random stream */
} kac_opts;

typedef struct {
    double a2;          /* the N -> infinity estimate: sample mean + 1/N */
    double err;         /* standard error of the block means */
    double accept;      /* accepted / drawn pairs */
    uint64_t collisions;
} kac_result;

/* The scaled HCS at o->alpha: a Maxwellian start, then after every N/2
 * collisions (one per particle) zero momentum and T = 1 again and, after
 * the transient, a2 = <c^4> / (2 <c^2>^2) - 1 sampled. 0, or -1 for
 * options out of range (alpha in [0, 1], n >= 2, two blocks
 * at least) or when memory runs out. */
int kac_hcs(const kac_opts *o, kac_result *r);

#endif
