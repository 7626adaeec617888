/* Collisions of one step, cell by cell: Bird's no-time-counter scheme for
 * hard disks of diameter sigma, whose cross-section in 2-D is the width
 * 2 sigma swept by impact parameters b in [-sigma, sigma] (the Boltzmann
 * rate), or the Enskog mode's partners drawn where they touch
 * (dsmc_esmc.c), both in an order that does not depend on the threads.
 * Calls dsmc_cells.c (the grid), dsmc_partner.c (stand-ins) and
 * dsmc_esmc.c. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dsmc_int.h"
#include "dsmc_rng.h"

/* The inelastic smooth-disk rule for equal masses: the normal n makes the
 * angle asin(b / sigma) with the relative velocity, b uniform; the normal
 * relative velocity is reversed and scaled by alpha, momentum is kept. */

static void collide_pair(gr_dsmc *d, gr_dsmc_rng *r, gr_dsmc_tally *y, size_t i, size_t j, double gx, double gy, double g)
{
    double s = 2.0 * gr_dsmc_uniform(r) - 1.0, c = sqrt(1.0 - s * s);
    double ux = gx / g, uy = gy / g;
    double nx = c * ux - s * uy, ny = c * uy + s * ux;
    double k = 0.5 * (1.0 + d->alpha) * g * c;
    d->vx[i] -= k * nx, d->vy[i] -= k * ny;
    d->vx[j] += k * nx, d->vy[j] += k * ny;
    y->virial += d->sigma * d->mass * k;
    gr_dsmc_stress_pair(d, i, j, nx, ny, k);
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

/* The candidates of cell c (the Boltzmann rate): N_c = m (m - 1) / 2 W
 * 2 sigma g_max dt / A, each accepted with g / g_max; a pair of recent partners
 * meets a stand-in instead (dsmc_partner.c). A pair alone in its cell
 * takes its stand-ins from around it (p, its pool; NULL for a cell of
 * three or more), so its bound covers that pool. */
static void collide_cell(gr_dsmc *d, size_t c, const gr_dsmc_pool *p, gr_dsmc_tally *y)
{
    size_t a = d->start[c], m = d->start[c + 1] - a;
    double area = gr_dsmc_cell_area(d, c);
    if (m < 2 || !(area > 0))
        return;
    double gmax = m == 2 ? gr_dsmc_pool_bound(d, p, d->order[a], d->order[a + 1]) : cell_bound(d, a, m);
    if (!(gmax > 0))
        return;
    gr_dsmc_rng r;
    gr_dsmc_rng_init(&r, d->key, d->step, c);
    double rate = d->W * 2.0 * d->sigma / area;
    double want = 0.5 * (double)m * (double)(m - 1) * rate * gmax * d->par.dt;
    uint64_t nc = (uint64_t)floor(want + gr_dsmc_uniform(&r));
    y->cand += nc;
    for (uint64_t k = 0; k < nc; k++) {
        size_t u = gr_dsmc_below(gr_dsmc_uniform(&r), m), w = gr_dsmc_below(gr_dsmc_uniform(&r), m - 1);
        w += w >= u;
        size_t i = d->order[a + u], j = d->order[a + w];
        if (gr_dsmc_recent(d, i, j)) {
            size_t l = gr_dsmc_stand_in(d, gr_dsmc_uniform(&r), a, m, p, i, j);
            if (l == (size_t)-1)
                continue;
            j = gr_dsmc_uniform(&r) < 0.5 ? j : i, i = l;
            y->stand_ins++;
        }
        double gx = d->vx[i] - d->vx[j], gy = d->vy[i] - d->vy[j];
        double g = sqrt(gx * gx + gy * gy);
        if (gr_dsmc_uniform(&r) * gmax >= g)
            continue;
        d->prev[i] = d->last[i], d->prev[j] = d->last[j];
        d->last[i] = d->rank[j] & GR_DSMC_RANK, d->last[j] = d->rank[i] & GR_DSMC_RANK;
        collide_pair(d, &r, y, i, j, gx, gy, g);
        y->pairs++;
    }
}

/* Cells per block of the tallies. */
#define BLOCK 256

static inline size_t cell_count(const gr_dsmc *d, size_t c) { return d->start[c + 1] - d->start[c]; }

/* Pool p of cell c (of two) is the square of 3 x 3 cells around it, inside
 * the grid (no wrap): such cells of one colour (cx mod 3, cy mod 3) touch
 * disjoint particles. */
static int local_pool(const gr_dsmc *d, size_t c, const gr_dsmc_pool *p)
{
    int cx = (int)(c % (size_t)d->gx), cy = (int)(c / (size_t)d->gx);
    return cx >= 1 && cy >= 1 && cx <= d->gx - 2 && cy <= d->gy - 2 && p->lo[0] == cx - 1 && p->hi[0] == cx + 1 &&
           p->lo[1] == cy - 1 && p->hi[1] == cy + 1;
}

/* Row cy of colour k's cells of two whose pool is local. */
static void pairs_row(gr_dsmc *d, int k, int cy, gr_dsmc_tally *out)
{
    gr_dsmc_tally y = {0, 0, 0, 0.0};
    for (int cx = 1 + (k % 3 + 2) % 3; cx <= d->gx - 2; cx += 3) {
        size_t c = (size_t)cy * (size_t)d->gx + (size_t)cx;
        if (cell_count(d, c) != 2)
            continue;
        gr_dsmc_pool p = gr_dsmc_pool_of(d, c, 1);
        if (local_pool(d, c, &p))
            collide_cell(d, c, &p, &y);
    }
    *out = y;
}

/* The cells of two whose pool is local, colour by colour, a colour's rows
 * on the threads; each row's gr_dsmc_tally its own (rt: 9 x gy). One thread runs
 * the rows without a parallel region: nine regions a step, even turned
 * off by an if clause, cost more than a small gas's collisions. */
static void pairs_local(gr_dsmc *d, int T, gr_dsmc_tally *rt)
{
    for (int k = 0; k < 9; k++) {
        int cy0 = 1 + (k / 3 + 2) % 3;
        gr_dsmc_tally *r = rt + (size_t)k * (size_t)d->gy;
        if (T == 1) {
            for (int cy = cy0; cy <= d->gy - 2; cy += 3)
                pairs_row(d, k, cy, &r[cy]);
            continue;
        }
#pragma omp parallel for schedule(dynamic, 4) num_threads(T)
        for (int cy = cy0; cy <= d->gy - 2; cy += 3)
            pairs_row(d, k, cy, &r[cy]);
    }
}

/* Block b's cells of three or more. */
static void crowded_block(gr_dsmc *d, size_t b, size_t nc, gr_dsmc_tally *out)
{
    gr_dsmc_tally y = {0, 0, 0, 0.0}; /* on the thread's stack: neighbours in blk[] share cache lines */
    for (size_t c = b * BLOCK; c < nc && c < (b + 1) * BLOCK; c++)
        if (cell_count(d, c) > 2)
            collide_cell(d, c, NULL, &y);
    *out = y;
}

/* Cell c (at cx, cy) of the Enskog mode runs on the threads: its
 * candidates touch the cells within the reach + 1 (the partners around
 * the cell at r_i + sigma s), which must lie inside the grid. */
#define ESMC_SPAN 5 /* cells between cells of one colour: 2 (reach + 1) + 1 */
static int esmc_local(const gr_dsmc *d, int cx, int cy, int R)
{
    return R == 1 && cx >= 2 && cx <= d->gx - 3 && cy >= 2 && cy <= d->gy - 3;
}

/* Row cy of colour kx of the Enskog mode's cells, ESMC_SPAN apart along
 * each axis: their candidates touch disjoint particles. */
static void esmc_row(gr_dsmc *d, int kx, int cy, gr_dsmc_tally *out)
{
    gr_dsmc_tally y = {0, 0, 0, 0.0};
    for (int cx = 2 + kx; cx <= d->gx - 3; cx += ESMC_SPAN) {
        size_t c = (size_t)cy * (size_t)d->gx + (size_t)cx;
        if (cell_count(d, c))
            gr_dsmc_esmc_cell(d, c, &y);
    }
    *out = y;
}

/* The Enskog mode: the cells that esmc_local allows colour by colour
 * (cx mod 5, cy mod 5), a colour's rows on the threads (rt: 25 x gy
 * tallies), then the others (at the grid's edge, or all where cells are
 * narrower than sigma) one after the other in cell order. */
static int collide_esmc(gr_dsmc *d, int T, gr_err *err)
{
    const int K = ESMC_SPAN * ESMC_SPAN;
    size_t nc = gr_dsmc_ncells(d), nr = (size_t)K * (size_t)d->gy;
    if (!d->cv && !(d->cv = malloc(nc * sizeof *d->cv)))
        return gr_fail(err, GR_ERUN, "out of memory for the bounds of %zu cells", nc);
    gr_dsmc_esmc_prepare(d, T);
    int R = gr_dsmc_esmc_reach(d);
    gr_dsmc_tally *rt = calloc(nr + 1, sizeof *rt);
    if (!rt)
        return gr_fail(err, GR_ERUN, "out of memory for the tallies of %zu cells", nc);
    for (int k = 0; R == 1 && k < K; k++) {
        int cy0 = 2 + k / ESMC_SPAN, kx = k % ESMC_SPAN;
        gr_dsmc_tally *r = rt + (size_t)k * (size_t)d->gy;
        if (T == 1) {
            for (int cy = cy0; cy <= d->gy - 3; cy += ESMC_SPAN)
                esmc_row(d, kx, cy, &r[cy]);
            continue;
        }
#pragma omp parallel for schedule(dynamic, 4) num_threads(T)
        for (int cy = cy0; cy <= d->gy - 3; cy += ESMC_SPAN)
            esmc_row(d, kx, cy, &r[cy]);
    }
    for (size_t c = 0; c < nc; c++) {
        int cx = (int)(c % (size_t)d->gx), cy = (int)(c / (size_t)d->gx);
        if (cell_count(d, c) && !esmc_local(d, cx, cy, R))
            gr_dsmc_esmc_cell(d, c, &rt[nr]);
    }
    for (size_t b = 0; b <= nr; b++) {
        d->pairs += rt[b].pairs, d->cand += rt[b].cand, d->stand_ins += rt[b].stand_ins;
        d->virial += rt[b].virial;
    }
    free(rt);
    return GR_OK;
}

/* The Boltzmann rate in three passes. The cells of three or more touch
 * only their own particles (their stand-ins come from the cell), so they
 * run on the threads, in blocks. The cells of two, whose stand-ins and
 * bound reach into the cells around: those whose pool is the 3 x 3 square
 * inside the grid colour by colour on the threads, then the others one
 * after the other in cell order. The order is the same on any number of
 * threads, and so are the sums (per block or row, then in order). The
 * stress window's accumulator is shared: with it open, one thread. */
int gr_dsmc_collide(gr_dsmc *d, gr_err *err)
{
    if (gr_dsmc_sort(d, err))
        return err->code;
    int T = d->par.threads > 1 && !d->stress ? d->par.threads : 1;
    if (d->par.enskog)
        return collide_esmc(d, T, err);
    size_t nc = gr_dsmc_ncells(d), nb = (nc + BLOCK - 1) / BLOCK, nr = 9 * (size_t)d->gy;
    gr_dsmc_tally *blk = calloc(nb + nr + 1, sizeof *blk);
    if (!blk)
        return gr_fail(err, GR_ERUN, "out of memory for the tallies of %zu cells", nc);
    if (T == 1) {
        for (size_t b = 0; b < nb; b++)
            crowded_block(d, b, nc, &blk[b]);
    } else {
#pragma omp parallel for schedule(dynamic, 1) num_threads(T)
        for (size_t b = 0; b < nb; b++)
            crowded_block(d, b, nc, &blk[b]);
    }
    pairs_local(d, T, blk + nb);
    gr_dsmc_tally *rest = blk + nb + nr;
    for (size_t c = 0; c < nc; c++)
        if (cell_count(d, c) == 2) {
            gr_dsmc_pool p = gr_dsmc_pool_of(d, c, 1);
            if (!local_pool(d, c, &p))
                collide_cell(d, c, &p, rest);
        }
    for (size_t b = 0; b <= nb + nr; b++) {
        d->pairs += blk[b].pairs, d->cand += blk[b].cand, d->stand_ins += blk[b].stand_ins;
        d->virial += blk[b].virial;
    }
    free(blk);
    return GR_OK;
}
