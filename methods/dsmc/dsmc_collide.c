/* Collisions of one step, cell by cell: Bird's no-time-counter scheme for
 * hard disks of diameter sigma, whose cross-section in 2-D is the width
 * 2 sigma swept by impact parameters b in [-sigma, sigma]. Calls no other
 * file of the backend. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <Random123/philox.h>

#include "dsmc_int.h"

/* Steps between permutations of the arrays into cell order (sort_cells):
 * 1, 4, 16 gave 2.7, 3.5, 3.5 x 10^7 moves/s at N = 10^6. */
#define GR_DSMC_GATHER 8

/* The random numbers of one cell in one step: Philox2x64-10 (Random123)
 * keyed by the run's key, counted by (step, cell, draw), so that a cell's
 * draws depend on nothing but its contents and a restart needs no
 * generator state (docs/methods/dsmc.md: generator). */
typedef struct {
    philox2x64_key_t key;
    philox2x64_ctr_t ctr;
    uint64_t buf[2];
    int left;
} cell_rng;

static void cell_rng_init(cell_rng *r, uint64_t key, uint64_t step, size_t cell)
{
    r->key.v[0] = key;
    r->ctr.v[0] = step, r->ctr.v[1] = (uint64_t)cell << 32;
    r->left = 0;
}

static inline uint64_t next64(cell_rng *r)
{
    if (!r->left) {
        philox2x64_ctr_t o = philox2x64(r->ctr, r->key);
        r->ctr.v[1]++;
        r->buf[0] = o.v[0], r->buf[1] = o.v[1], r->left = 2;
    }
    return r->buf[--r->left];
}

/* [0, 1) from the top 53 bits. */
static inline double uniform(cell_rng *r) { return (double)(next64(r) >> 11) * 0x1.0p-53; }

/* [0, m): the bias of the 53-bit product is below m / 2^53. */
static inline size_t below(cell_rng *r, size_t m)
{
    size_t k = (size_t)(uniform(r) * (double)m);
    return k < m ? k : m - 1;
}

static uint32_t cell_of(const gr_dsmc *d, double x, double y)
{
    int cx = (int)floor(x / d->cw), cy = (int)floor(y / d->ch);
    cx = cx < 0 ? 0 : cx >= d->nx ? d->nx - 1 : cx;
    cy = cy < 0 ? 0 : cy >= d->ny ? d->ny - 1 : cy;
    return (uint32_t)(cy * d->nx + cx);
}

static void gather(double **a, double **tmp, const uint32_t *restrict order, size_t n)
{
    double *restrict src = *a, *restrict dst = *tmp;
    for (size_t k = 0; k < n; k++)
        dst[k] = src[order[k]];
    *tmp = src, *a = dst;
}

/* Counting sort by cell, the particles gone last (cell nc): order[] lists
 * a cell's particles from start[c], stable (in array order, so that the
 * order within a cell depends on nothing but the state). Every
 * GR_DSMC_GATHER steps the arrays themselves are permuted into that order
 * (order[] then the identity), so that a cell's particles sit together in
 * memory; in between particles mostly stay in their cell and order[] stays
 * nearly sequential, and the permutation (a third of a step's time at
 * N = 10^6) is saved. */
static void sort_cells(gr_dsmc *d)
{
    size_t nc = (size_t)d->nx * (size_t)d->ny, n = d->n;
    uint32_t *restrict cell = d->cell, *restrict start = d->start, *restrict order = d->order;
    memset(start, 0, (nc + 2) * sizeof *start);
    for (size_t i = 0; i < n; i++) {
        cell[i] = (d->rank[i] & GR_DSMC_GONE) ? (uint32_t)nc : cell_of(d, d->x[i], d->y[i]);
        start[cell[i] + 1]++;
    }
    for (size_t c = 0; c <= nc; c++)
        start[c + 1] += start[c];
    for (size_t i = 0; i < n; i++)
        order[start[cell[i]]++] = (uint32_t)i;
    for (size_t c = nc + 1; c > 0; c--)
        start[c] = start[c - 1];
    start[0] = 0;
    if (d->step % GR_DSMC_GATHER)
        return;
    gather(&d->x, &d->tmp, order, n);
    gather(&d->y, &d->tmp, order, n);
    gather(&d->vx, &d->tmp, order, n);
    gather(&d->vy, &d->tmp, order, n);
    /* cell[] is spent: it takes the ranks in the new order */
    for (size_t k = 0; k < n; k++)
        cell[k] = d->rank[order[k]];
    d->cell = d->rank, d->rank = cell;
    for (size_t k = 0; k < n; k++)
        order[k] = (uint32_t)k;
}

/* A partner displaced through a wall is put back on it (at a radius from
 * it: the next flight bounces it); through a periodic side, wrapped. */
static void keep_inside(gr_dsmc *d, size_t i)
{
    const gr_bc *s = d->sc.side;
    double r = 0.5 * d->sigma;
    if (s[GR_LEFT] == GR_BC_PERIODIC)
        d->x[i] -= d->Lx * floor(d->x[i] / d->Lx);
    if (s[GR_BOTTOM] == GR_BC_PERIODIC)
        d->y[i] -= d->Ly * floor(d->y[i] / d->Ly);
    if (s[GR_LEFT] == GR_BC_WALL && d->x[i] < r)
        d->x[i] = r;
    if (s[GR_RIGHT] == GR_BC_WALL && d->x[i] > d->Lx - r)
        d->x[i] = d->Lx - r;
    if (s[GR_BOTTOM] == GR_BC_WALL && d->y[i] < r)
        d->y[i] = r;
    if (s[GR_TOP] == GR_BC_WALL && d->y[i] > d->Ly - r)
        d->y[i] = d->Ly - r;
}

/* The Enskog displacement (the consistent Boltzmann algorithm of
 * Alexander, Garcia and Alder, PRL 74, 5212 (1995)): after the collision
 * the partners jump apart along the normal, i by -delta n and j by
 * +delta n. Carrying their new momenta, the jump moves momentum
 * delta (p_j' - p_i').n = delta m alpha g_n across the pair, which equals
 * the collisional transfer sigma J = sigma m (1 + alpha) g_n / 2 of hard
 * disks for delta = sigma (1 + alpha) / (2 alpha) (sigma when elastic, as
 * in the paper). */
static void displace(gr_dsmc *d, size_t i, size_t j, double nx, double ny)
{
    double delta = d->sigma * (1.0 + d->alpha) / (2.0 * d->alpha);
    d->x[i] -= delta * nx, d->y[i] -= delta * ny;
    d->x[j] += delta * nx, d->y[j] += delta * ny;
    keep_inside(d, i);
    keep_inside(d, j);
}

/* The inelastic smooth-disk rule for equal masses: the normal n makes the
 * angle asin(b / sigma) with the relative velocity, b uniform; the normal
 * relative velocity is reversed and scaled by alpha, momentum is kept. */
static void collide_pair(gr_dsmc *d, cell_rng *r, size_t i, size_t j, double gx, double gy, double g)
{
    double s = 2.0 * uniform(r) - 1.0, c = sqrt(1.0 - s * s);
    double ux = gx / g, uy = gy / g;
    double nx = c * ux - s * uy, ny = c * uy + s * ux;
    double k = 0.5 * (1.0 + d->alpha) * g * c;
    d->vx[i] -= k * nx, d->vy[i] -= k * ny;
    d->vx[j] += k * nx, d->vy[j] += k * ny;
    d->virial += d->sigma * d->mass * k;
    gr_dsmc_stress_pair(d, i, j, nx, ny, k);
    if (d->par.enskog)
        displace(d, i, j, nx, ny);
}

/* The bound g_max of the relative speeds in the cell, exact for this
 * step: no pair of it differs by more than twice the largest distance of
 * a velocity from the cell's mean. Bird's running maximum (kept across
 * steps, raised when a candidate exceeds it) counts too few candidates in
 * a cell that rarely holds two particles and was first met when the gas
 * was colder: in a vibrated bed with cells of 2 d it lost 18 % of edmd's
 * collisions (docs/methods/dsmc.md). The bound costs one pass over the
 * cell's particles, which are contiguous. */
static double cell_bound(const gr_dsmc *d, size_t a, size_t m)
{
    double mx = 0, my = 0, v2 = 0;
    const uint32_t *o = d->order;
    for (size_t k = a; k < a + m; k++)
        mx += d->vx[o[k]], my += d->vy[o[k]];
    mx /= (double)m, my /= (double)m;
    for (size_t k = a; k < a + m; k++) {
        double ux = d->vx[o[k]] - mx, uy = d->vy[o[k]] - my, u2 = ux * ux + uy * uy;
        v2 = u2 > v2 ? u2 : v2; /* not fmax: a libm call here (NaN rules) */
    }
    return 2.0 * sqrt(v2);
}

/* The packing fraction chi is evaluated at: from the particles of the
 * (up to eight) neighbouring cells, not the cell's own. The own count is
 * at least 2 whenever a pair is drawn, so with few particles per cell it
 * would overestimate the density where the collisions are counted (a
 * cell of 2 x 2 d holding 2 disks is at eta 0.39, chi 2.2, in a gas at
 * eta 0.005); the neighbours' count is independent of it. A single cell
 * has no neighbours and uses its own. */
static double cell_eta(const gr_dsmc *d, size_t c, size_t m)
{
    int cx = (int)(c % (size_t)d->nx), cy = (int)(c / (size_t)d->nx), k = 0;
    size_t cnt = 0;
    for (int y = cy - 1; y <= cy + 1; y++)
        for (int x = cx - 1; x <= cx + 1; x++)
            if ((x != cx || y != cy) && x >= 0 && x < d->nx && y >= 0 && y < d->ny) {
                size_t e = (size_t)y * (size_t)d->nx + (size_t)x;
                cnt += d->start[e + 1] - d->start[e], k++;
            }
    double per = k ? (double)cnt / k : (double)m;
    return fmin(0.9, per * d->W * M_PI * d->sigma * d->sigma / 4.0 / (d->cw * d->ch));
}

static void collide_cell(gr_dsmc *d, size_t c)
{
    size_t a = d->start[c], m = d->start[c + 1] - a;
    if (m < 2)
        return;
    double gmax = cell_bound(d, a, m);
    if (!(gmax > 0))
        return;
    cell_rng r;
    cell_rng_init(&r, d->key, d->step, c);
    double area = d->cw * d->ch;
    double rate = d->W * 2.0 * d->sigma / area;
    if (d->par.enskog)
        rate *= gr_dsmc_chi(cell_eta(d, c, m));
    double want = 0.5 * (double)m * (double)(m - 1) * rate * gmax * d->par.dt;
    uint64_t nc = (uint64_t)floor(want + uniform(&r));
    d->cand += nc;
    for (uint64_t k = 0; k < nc; k++) {
        size_t u = below(&r, m), w = below(&r, m - 1);
        w += w >= u;
        size_t i = d->order[a + u], j = d->order[a + w];
        double gx = d->vx[i] - d->vx[j], gy = d->vy[i] - d->vy[j];
        double g = sqrt(gx * gx + gy * gy);
        if (uniform(&r) * gmax >= g)
            continue;
        collide_pair(d, &r, i, j, gx, gy, g);
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
