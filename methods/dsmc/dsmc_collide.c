/* Collisions of one step, cell by cell: Bird's no-time-counter scheme for
 * hard disks of diameter sigma, whose cross-section in 2-D is the width
 * 2 sigma swept by impact parameters b in [-sigma, sigma]. Calls no other
 * file of the backend. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dsmc_int.h"

static int cell_of(const gr_dsmc *d, double x, double y)
{
    int cx = (int)floor(x / d->cw), cy = (int)floor(y / d->ch);
    cx = cx < 0 ? 0 : cx >= d->nx ? d->nx - 1 : cx;
    cy = cy < 0 ? 0 : cy >= d->ny ? d->ny - 1 : cy;
    return cy * d->nx + cx;
}

/* Counting sort of the particles present by cell, in id order within a
 * cell so that the pair draws do not depend on anything but the state. */
static void sort_cells(gr_dsmc *d)
{
    size_t nc = (size_t)d->nx * (size_t)d->ny;
    memset(d->start, 0, (nc + 1) * sizeof *d->start);
    for (size_t i = 0; i < d->n; i++) {
        d->cell[i] = (d->p->flags[i] & GR_PF_GONE) ? -1 : cell_of(d, d->p->x[i], d->p->y[i]);
        if (d->cell[i] >= 0)
            d->start[d->cell[i] + 1]++;
    }
    for (size_t c = 0; c < nc; c++)
        d->start[c + 1] += d->start[c];
    for (size_t i = 0; i < d->n; i++)
        if (d->cell[i] >= 0)
            d->order[d->start[d->cell[i]]++] = i;
    for (size_t c = nc; c > 0; c--)
        d->start[c] = d->start[c - 1];
    d->start[0] = 0;
}

/* The inelastic smooth-disk rule for equal masses: the normal n makes the
 * angle asin(b / sigma) with the relative velocity, b uniform; the normal
 * relative velocity is reversed and scaled by alpha, momentum is kept. */
static void collide_pair(gr_dsmc *d, size_t i, size_t j, double gx, double gy, double g)
{
    gr_particles *p = d->p;
    double s = 2.0 * gr_rng_uniform(d->imp_rng) - 1.0, c = sqrt(1.0 - s * s);
    double ux = gx / g, uy = gy / g;
    double nx = c * ux - s * uy, ny = c * uy + s * ux;
    double k = 0.5 * (1.0 + d->alpha) * g * c;
    p->vx[i] -= k * nx, p->vy[i] -= k * ny;
    p->vx[j] += k * nx, p->vy[j] += k * ny;
}

/* Speed bound for a cell whose running maximum is still zero: twice its
 * fastest particle bounds every relative speed in it. */
static double cell_bound(const gr_dsmc *d, size_t a, size_t m)
{
    double v2 = 0;
    for (size_t k = a; k < a + m; k++) {
        size_t i = d->order[k];
        v2 = fmax(v2, d->p->vx[i] * d->p->vx[i] + d->p->vy[i] * d->p->vy[i]);
    }
    return 2.0 * sqrt(v2);
}

static void collide_cell(gr_dsmc *d, size_t c)
{
    size_t a = d->start[c], m = d->start[c + 1] - a;
    if (m < 2)
        return;
    if (!(d->gmax[c] > 0) && !((d->gmax[c] = cell_bound(d, a, m)) > 0))
        return;
    double area = d->cw * d->ch;
    double rate = d->W * 2.0 * d->sigma / area;
    if (d->par.enskog)
        rate *= gr_dsmc_chi(fmin(0.9, (double)m * d->W * M_PI * d->sigma * d->sigma / 4.0 / area));
    double want = 0.5 * (double)m * (double)(m - 1) * rate * d->gmax[c] * d->par.dt;
    uint64_t nc = (uint64_t)floor(want + gr_rng_uniform(d->pair_rng));
    d->cand += nc;
    for (uint64_t k = 0; k < nc; k++) {
        size_t u = gr_rng_below(d->pair_rng, m), w = gr_rng_below(d->pair_rng, m - 1);
        w += w >= u;
        size_t i = d->order[a + u], j = d->order[a + w];
        double gx = d->p->vx[i] - d->p->vx[j], gy = d->p->vy[i] - d->p->vy[j];
        double g = sqrt(gx * gx + gy * gy);
        if (g > d->gmax[c])
            d->gmax[c] = g;
        if (gr_rng_uniform(d->pair_rng) * d->gmax[c] >= g)
            continue;
        collide_pair(d, i, j, gx, gy, g);
        d->pairs++;
    }
}

int gr_dsmc_collide(gr_dsmc *d, gr_err *err)
{
    (void)err;
    sort_cells(d);
    size_t nc = (size_t)d->nx * (size_t)d->ny;
    for (size_t c = 0; c < nc; c++)
        collide_cell(d, c);
    return GR_OK;
}
