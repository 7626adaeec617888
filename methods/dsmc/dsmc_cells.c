/* The grid of collision cells, shifted every step by a random offset, and
 * the counting sort of the particles by cell. Why shift: the particles
 * that share a fixed cell share it for as long as they take to cross it,
 * colliding among themselves while the cell's mean velocity stays theirs;
 * in an inelastic gas the cell's relative velocities then run colder than
 * the gas, and it cools too slowly (docs/methods/dsmc.md, cells). A new
 * offset each step changes which neighbours share a cell. Calls no other
 * file of the backend. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dsmc_int.h"
#include "dsmc_rng.h"

/* Steps between permutations of the arrays into cell order (gr_dsmc_sort):
 * 1, 4, 16 gave 2.7, 3.5, 3.5 x 10^7 moves/s at N = 10^6. */
#define GR_DSMC_GATHER 8

static int periodic_x(const gr_dsmc *d) { return d->sc.side[GR_LEFT] == GR_BC_PERIODIC; }
static int periodic_y(const gr_dsmc *d) { return d->sc.side[GR_BOTTOM] == GR_BC_PERIODIC; }

/* Along a periodic side the shifted grid wraps round (n cells); along
 * walls or open sides it has one cell more, the first and last cut. */
void gr_dsmc_grid(gr_dsmc *d)
{
    d->gx = d->nx + !periodic_x(d), d->gy = d->ny + !periodic_y(d);
}

/* Width of cell k along an axis of length L: [k w - o, (k + 1) w - o]
 * cut to [0, L] where the axis does not wrap. */
static double width(int k, double o, double w, double L, int wraps)
{
    if (wraps)
        return w;
    double lo = k * w - o, hi = lo + w;
    return fmin(hi, L) - fmax(lo, 0.0);
}

double gr_dsmc_cell_area(const gr_dsmc *d, size_t c)
{
    int cx = (int)(c % (size_t)d->gx), cy = (int)(c / (size_t)d->gx);
    return width(cx, d->ox, d->cw, d->Lx, d->gx == d->nx) * width(cy, d->oy, d->ch, d->Ly, d->gy == d->ny);
}

static void gather(double **a, double **tmp, const uint32_t *restrict order, size_t n, int T)
{
    double *restrict src = *a, *restrict dst = *tmp;
#pragma omp parallel for schedule(static) num_threads(T) if (T > 1)
    for (size_t k = 0; k < n; k++)
        dst[k] = src[order[k]];
    *tmp = src, *a = dst;
}

/* The same for an index array, with the spent cell[] as the buffer. */
static void gather32(uint32_t **a, uint32_t **buf, const uint32_t *restrict order, size_t n, int T)
{
    uint32_t *restrict src = *a, *restrict dst = *buf;
#pragma omp parallel for schedule(static) num_threads(T) if (T > 1)
    for (size_t k = 0; k < n; k++)
        dst[k] = src[order[k]];
    *buf = src, *a = dst;
}

/* Every GR_DSMC_GATHER steps the arrays themselves are permuted into cell
 * order (order[] then the identity), so that a cell's particles sit
 * together in memory; in between particles mostly stay near their cell
 * and order[] stays nearly sequential, and the permutation (a third of a
 * step's time at N = 10^6) is saved. */
static void permute(gr_dsmc *d, int T)
{
    size_t n = d->n;
    const uint32_t *order = d->order;
    gather(&d->x, &d->tmp, order, n, T);
    gather(&d->y, &d->tmp, order, n, T);
    gather(&d->vx, &d->tmp, order, n, T);
    gather(&d->vy, &d->tmp, order, n, T);
    gather32(&d->rank, &d->cell, order, n, T);
    gather32(&d->last, &d->cell, order, n, T);
    gather32(&d->prev, &d->cell, order, n, T);
    uint32_t *o = d->order;
#pragma omp parallel for schedule(static) num_threads(T) if (T > 1)
    for (size_t k = 0; k < n; k++)
        o[k] = (uint32_t)k;
}

/* Counting sort on T threads (one alike), each over its slice of the
 * particles: a histogram per slice, the cells' starts by one pass over the
 * cells, each slice's places within a cell after the slices before it, so
 * that the order is the serial sort's (stable in array order) for every T.
 * One thread calls the three passes without a parallel region: a region,
 * even one an if clause turns off, costs microseconds a step, which is a
 * small gas's whole step. */
static void sort_count(gr_dsmc *d, int t, int T)
{
    size_t nc = gr_dsmc_ncells(d), n = d->n, w = nc + 1;
    size_t lo = n * (size_t)t / (size_t)T, hi = n * (size_t)(t + 1) / (size_t)T;
    uint32_t *restrict cell = d->cell, *h = d->hist + (size_t)t * w;
    memset(h, 0, w * sizeof *h);
    for (size_t i = lo; i < hi; i++) {
        cell[i] = (d->rank[i] & GR_DSMC_GONE) ? (uint32_t)nc : gr_dsmc_cell_of(d, d->x[i], d->y[i]);
        h[cell[i]]++;
    }
}

static void sort_starts(gr_dsmc *d, int T)
{
    size_t w = gr_dsmc_ncells(d) + 1;
    uint32_t *restrict start = d->start, *hist = d->hist, sum = 0;
    for (size_t c = 0; c < w; c++) {
        start[c] = sum;
        for (int u = 0; u < T; u++) {
            uint32_t k = hist[(size_t)u * w + c];
            hist[(size_t)u * w + c] = sum, sum += k;
        }
    }
    start[w] = sum;
}

static void sort_place(gr_dsmc *d, int t, int T)
{
    size_t n = d->n, w = gr_dsmc_ncells(d) + 1;
    size_t lo = n * (size_t)t / (size_t)T, hi = n * (size_t)(t + 1) / (size_t)T;
    const uint32_t *restrict cell = d->cell;
    uint32_t *restrict order = d->order, *h = d->hist + (size_t)t * w;
    for (size_t i = lo; i < hi; i++)
        order[h[cell[i]]++] = (uint32_t)i;
}

static void sort_threads(gr_dsmc *d, int T)
{
    if (T == 1) {
        sort_count(d, 0, 1), sort_starts(d, 1), sort_place(d, 0, 1);
        return;
    }
#pragma omp parallel num_threads(T)
    {
        int t = gr_dsmc_thread();
        sort_count(d, t, T);
#pragma omp barrier
#pragma omp single
        sort_starts(d, T);
        sort_place(d, t, T);
    }
}

/* This step's offset (drawn from the collisions' stream at a counter no
 * cell uses), then a counting sort by cell, the particles gone last:
 * order[] lists a cell's particles from start[c], stable (in array
 * order, so that the order within a cell depends on nothing but the
 * state). */
int gr_dsmc_sort(gr_dsmc *d, gr_err *err)
{
    gr_dsmc_rng r;
    gr_dsmc_rng_init(&r, d->key, d->step, GR_DSMC_RNG_GRID);
    d->ox = gr_dsmc_uniform(&r) * d->cw, d->oy = gr_dsmc_uniform(&r) * d->ch;
    size_t nc = gr_dsmc_ncells(d);
    int T = d->par.threads > 1 ? d->par.threads : 1;
    if (d->hist_threads < T) {
        uint32_t *h = realloc(d->hist, (size_t)T * (nc + 1) * sizeof *h);
        if (!h)
            return gr_fail(err, GR_ERUN, "out of memory for the sort's histograms of %d threads", T);
        d->hist = h, d->hist_threads = T;
    }
    sort_threads(d, T);
    if (d->step % GR_DSMC_GATHER == 0)
        permute(d, T);
    return GR_OK;
}
