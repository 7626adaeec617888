/* Helpers shared by the edmd tests: hand-built scenes (zeroed, fields set)
 * and lattice starts, so the tests depend on no scene file. */
#ifndef EDMD_TEST_H
#define EDMD_TEST_H

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "edmd.h"
#include "particles.h"
#include "scene.h"

/* A W x H box of equal disks (d = 1, m = 1), sides walls or periodic. */
static inline gr_scene edmd_box(double W, double H, int periodic, double alpha)
{
    gr_scene sc;
    memset(&sc, 0, sizeof sc);
    snprintf(sc.path, sizeof sc.path, "(test scene)");
    sc.width = W;
    sc.height = H;
    for (int k = 0; k < 4; k++)
        sc.side[k] = periodic ? GR_BC_PERIODIC : GR_BC_WALL;
    sc.mat.restitution = alpha;
    sc.mat.tangential_restitution = NAN;
    sc.mat.wall_restitution = NAN;
    sc.mat.mu = 0.5;
    sc.nspecies = 1;
    sc.species[0].diameter = 1.0;
    sc.species[0].density = 4.0 / M_PI;
    sc.floor.motion = GR_FLOOR_FIXED;
    sc.seed = 1;
    return sc;
}

/* n disks of diameter 1 on a square lattice filling [x0,x0+W] x [y0,y0+H]
 * row by row, speeds v0 in uniformly random directions (mean momentum
 * removed when zero_p), from seed. */
static inline gr_particles *edmd_lattice(long n, double x0, double y0, double W, double H, double v0,
                                         int zero_p, unsigned long seed)
{
    gr_err e = {0};
    gr_particles *p = gr_particles_create((size_t)n, &e);
    long nx = (long)ceil(sqrt((double)n * W / H));
    long ny = (n + nx - 1) / nx;
    double ax = W / nx, ay = H / ny;
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(r, seed);
    double px = 0, py = 0;
    for (long k = 0; k < n; k++) {
        long i = gr_particles_push(p, x0 + (k % nx + 0.5) * ax, y0 + (k / nx + 0.5) * ay, 0.5, 1.0, 0, 0, &e);
        double th = 2 * M_PI * gsl_rng_uniform(r);
        p->vx[i] = v0 * cos(th);
        p->vy[i] = v0 * sin(th);
        px += p->vx[i];
        py += p->vy[i];
    }
    if (zero_p)
        for (long k = 0; k < n; k++) {
            p->vx[k] -= px / n;
            p->vy[k] -= py / n;
        }
    gsl_rng_free(r);
    return p;
}

static inline double edmd_energy(const gr_particles *p, double g)
{
    double e = 0;
    for (size_t i = 0; i < p->n; i++)
        e += 0.5 * p->mass[i] * (p->vx[i] * p->vx[i] + p->vy[i] * p->vy[i]) +
             0.5 * p->inertia[i] * p->omega[i] * p->omega[i] + p->mass[i] * g * p->y[i];
    return e;
}

/* Largest overlap (in diameters) over all pairs, brute force. */
static inline double edmd_max_overlap(const gr_particles *p, double Lx, double Ly)
{
    double worst = 0;
    for (size_t i = 0; i < p->n; i++)
        for (size_t j = i + 1; j < p->n; j++) {
            double dx = p->x[j] - p->x[i], dy = p->y[j] - p->y[i];
            if (Lx > 0) dx -= Lx * round(dx / Lx);
            if (Ly > 0) dy -= Ly * round(dy / Ly);
            double ov = p->radius[i] + p->radius[j] - sqrt(dx * dx + dy * dy);
            if (ov > worst)
                worst = ov;
        }
    return worst;
}

#endif
