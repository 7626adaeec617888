/* The Enskog mode's collisions: Montanero and Santos' Enskog simulation
 * Monte Carlo (Phys. Rev. E 54, 438 (1996)). A candidate of particle i
 * draws the impact direction s first, uniform on the circle, then its
 * partner j from the cell that holds r_i + sigma s, where a hard disk
 * touching i would sit; it is accepted with probability
 * n chi(n) (g.s)+ / omega_max, n the density around that cell. The momentum of a
 * collision then crosses a cell boundary as often as between hard disks
 * (whose centres lie on either side of it), so no partner is displaced and
 * the pairs of a small cell do not thin, as they did under the consistent
 * Boltzmann algorithm's jump (docs/methods/dsmc.md, Enskog mode). Calls
 * only dsmc_int.h's inlines (the cell of a point, recent partners). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "dsmc_int.h"
#include "dsmc_rng.h"

/* Cells from a cell to any point within sigma of its particles. */
int gr_dsmc_esmc_reach(const gr_dsmc *d)
{
    int R = (int)ceil(d->sigma / fmin(d->cw, d->ch));
    return R < 1 ? 1 : R;
}

static inline size_t count(const gr_dsmc *d, size_t e) { return d->start[e + 1] - d->start[e]; }

/* Cell (x, y) of the grid, wrapped along a periodic axis; SIZE_MAX past
 * the end of another. */
static inline size_t at(const gr_dsmc *d, int x, int y)
{
    if (x < 0 || x >= d->gx) {
        if (d->gx != d->nx)
            return SIZE_MAX;
        x = (x % d->gx + d->gx) % d->gx;
    }
    if (y < 0 || y >= d->gy) {
        if (d->gy != d->ny)
            return SIZE_MAX;
        y = (y % d->gy + d->gy) % d->gy;
    }
    return (size_t)y * (size_t)d->gx + (size_t)x;
}

/* Times cell k appears among the 3 cells c - 1 .. c + 1 of an axis of g
 * (wrapped when periodic; more than once in a grid under 3 wide). */
static inline int times(int k, int c, int g, int wraps)
{
    int t = 0;
    for (int x = c - 1; x <= c + 1; x++)
        t += (wraps ? (x + g) % g : x) == k;
    return t;
}

/* Number density (real grains) of the 3 x 3 cells around cell c, without
 * particle i of cell A: the density i sees around the place of its
 * partner. A wider square than the partner's cell, because the pairs of
 * neighbouring cells run thinner than the gas: a collision across a cell
 * boundary kicks the partners apart along the line from one cell to the
 * other (the collisional transfer), and they leave each other's cells
 * more often than the flights bring them back; counted in the partner's
 * cell alone, the equilibrium rate fell 1.7 % short with cells of 8 d at
 * packing 0.04 (docs/methods/dsmc.md). Within the square they have mostly
 * stayed. */
static double block_n(const gr_dsmc *d, size_t c, size_t A)
{
    const gr_dsmc_cellv *v = &d->cv[c];
    int cx = (int)(c % (size_t)d->gx), cy = (int)(c / (size_t)d->gx);
    int ax = (int)(A % (size_t)d->gx), ay = (int)(A / (size_t)d->gx);
    int in = times(ax, cx, d->gx, d->gx == d->nx) * times(ay, cy, d->gy, d->gy == d->ny);
    double cnt = (double)v->cnt - in;
    return v->ba > 0 && cnt > 0 ? cnt * d->W / v->ba : 0.0;
}

/* chi at number density n (packing capped at 0.9). */
static inline double chi_n(const gr_dsmc *d, double n)
{
    return gr_dsmc_chi(fmin(0.9, n * M_PI * d->sigma * d->sigma / 4.0));
}

/* Width of cell k along an axis of length L (offset o, width w) that
 * centres can reach: cut to [r, L - r] where a side is a wall, to [0, L]
 * where it is open. The density of centres is what the collision rate
 * needs; counted over the whole area, a box of 20 d with walls at packing
 * 0.385 ran 13 % short of the hard-disk collisions (grano course pressure
 * --quick --method dsmc). */
static double reach_width(int k, double o, double w, double L, int wraps, gr_bc lo_side, gr_bc hi_side, double r)
{
    if (wraps)
        return w;
    double lo = k * w - o, hi = lo + w;
    double a = lo_side == GR_BC_WALL ? r : 0.0, b = hi_side == GR_BC_WALL ? L - r : L;
    double x = fmin(hi, b) - fmax(lo, a);
    return x > 0 ? x : 0.0;
}

/* Mean velocity and radius of cell c's velocities, and the area centres
 * can reach in it. */
static void prepare_cell(gr_dsmc *d, size_t c)
{
    gr_dsmc_cellv *v = &d->cv[c];
    size_t a = d->start[c], m = count(d, c);
    const uint32_t *o = d->order;
    double mx = 0, my = 0, r2 = 0;
    for (size_t k = a; k < a + m; k++)
        mx += d->vx[o[k]], my += d->vy[o[k]];
    if (m)
        mx /= (double)m, my /= (double)m;
    for (size_t k = a; k < a + m; k++) {
        double ux = d->vx[o[k]] - mx, uy = d->vy[o[k]] - my, u2 = ux * ux + uy * uy;
        r2 = u2 > r2 ? u2 : r2;
    }
    const gr_bc *s = d->sc.side;
    int cx = (int)(c % (size_t)d->gx), cy = (int)(c / (size_t)d->gx);
    double rad = 0.5 * d->sigma;
    v->mx = mx, v->my = my, v->r = sqrt(r2);
    v->a = reach_width(cx, d->ox, d->cw, d->Lx, d->gx == d->nx, s[GR_LEFT], s[GR_RIGHT], rad) *
           reach_width(cy, d->oy, d->ch, d->Ly, d->gy == d->ny, s[GR_BOTTOM], s[GR_TOP], rad);
}

/* The 3 x 3 sums as a sum of 3 along the row (hc, ha), then of 3 of
 * those along the column (cnt, ba): with every particle, n bounds
 * block_n's. */
static void prepare_row(gr_dsmc *d, size_t c)
{
    int cx = (int)(c % (size_t)d->gx), cy = (int)(c / (size_t)d->gx);
    uint32_t k = 0;
    double a = 0;
    for (int x = cx - 1; x <= cx + 1; x++) {
        size_t e = at(d, x, cy);
        if (e != SIZE_MAX)
            k += (uint32_t)count(d, e), a += d->cv[e].a;
    }
    d->cv[c].hc = k, d->cv[c].ha = a;
}

static void prepare_column(gr_dsmc *d, size_t c)
{
    int cx = (int)(c % (size_t)d->gx), cy = (int)(c / (size_t)d->gx);
    uint32_t k = 0;
    double a = 0;
    for (int y = cy - 1; y <= cy + 1; y++) {
        size_t e = at(d, cx, y);
        if (e != SIZE_MAX)
            k += d->cv[e].hc, a += d->cv[e].ha;
    }
    gr_dsmc_cellv *v = &d->cv[c];
    v->cnt = k, v->ba = a, v->n = a > 0 ? k * d->W / a : 0.0;
}

void gr_dsmc_esmc_prepare(gr_dsmc *d, int T)
{
    size_t nc = gr_dsmc_ncells(d);
    if (T == 1) {
        for (size_t c = 0; c < nc; c++)
            prepare_cell(d, c);
        for (size_t c = 0; c < nc; c++)
            prepare_row(d, c);
        for (size_t c = 0; c < nc; c++)
            prepare_column(d, c);
        return;
    }
#pragma omp parallel num_threads(T)
    {
#pragma omp for schedule(static)
        for (size_t c = 0; c < nc; c++)
            prepare_cell(d, c);
#pragma omp for schedule(static)
        for (size_t c = 0; c < nc; c++)
            prepare_row(d, c);
#pragma omp for schedule(static)
        for (size_t c = 0; c < nc; c++)
            prepare_column(d, c);
    }
}

/* omega_max of cell c: a bound of n chi (g.s) over its particles, n and
 * chi at the densest block whose centre is within the reach R (where B
 * can lie), g over the partners within R + 1 (block_other's), from this
 * step's bounds: |v_i - v_j| <= r_A + |vbar_A - vbar_B| + r_B. */
static double majorant(const gr_dsmc *d, size_t c, int R)
{
    int cx = (int)(c % (size_t)d->gx), cy = (int)(c / (size_t)d->gx);
    const gr_dsmc_cellv *va = &d->cv[c];
    double g2 = 0, nm = 0;
    for (int y = cy - R - 1; y <= cy + R + 1; y++)
        for (int x = cx - R - 1; x <= cx + R + 1; x++) {
            size_t e = at(d, x, y);
            if (e == SIZE_MAX)
                continue;
            const gr_dsmc_cellv *ve = &d->cv[e];
            if (abs(x - cx) <= R && abs(y - cy) <= R)
                nm = ve->n > nm ? ve->n : nm; /* not fmax: a libm call */
            if (!count(d, e))
                continue;
            double dx = va->mx - ve->mx, dy = va->my - ve->my, u = sqrt(dx * dx + dy * dy) + ve->r;
            g2 = u > g2 ? u : g2;
        }
    return nm * chi_n(d, nm) * (va->r + g2);
}

/* The partner's place r_i + sigma s, wrapped across periodic sides: 0 where
 * no disk can sit (its centre within a radius of a wall, or outside an
 * open side). */
static int partner_place(const gr_dsmc *d, double *x, double *y)
{
    const gr_bc *s = d->sc.side;
    double r = 0.5 * d->sigma;
    if (s[GR_LEFT] == GR_BC_PERIODIC)
        *x -= d->Lx * floor(*x / d->Lx);
    else if (*x < (s[GR_LEFT] == GR_BC_WALL ? r : 0.0) || *x > d->Lx - (s[GR_RIGHT] == GR_BC_WALL ? r : 0.0))
        return 0;
    if (s[GR_BOTTOM] == GR_BC_PERIODIC)
        *y -= d->Ly * floor(*y / d->Ly);
    else if (*y < (s[GR_BOTTOM] == GR_BC_WALL ? r : 0.0) || *y > d->Ly - (s[GR_TOP] == GR_BC_WALL ? r : 0.0))
        return 0;
    return 1;
}

/* The w-th place of a cell, in order, that is neither e1 nor e2 (places
 * in the cell, e1 < e2; SIZE_MAX for none): the w-th particle of the cell
 * other than the pair's, without a pass over the cell (one cell of 4000
 * would make every candidate cost 4000 reads). */
static inline size_t skip(size_t w, size_t e1, size_t e2)
{
    w += w >= e1;
    return w + (w >= e2);
}

/* A particle of the 3 x 3 cells around B other than i and j (j == i for
 * none), uniform by the draw u; (size_t)-1 when there is none. The
 * partner of a place whose cell holds nobody else: drawn around that
 * cell, so that the momentum a collision moves still crosses sigma on
 * average. Drawn from around i's own cell instead, it crossed nothing on
 * average, and with cells of 2 d at packing 0.3 (one in five cells empty)
 * the wall pressure fell 11-14 % short of the hard-disk equation of state
 * (grano compare --cases eos, dsmc.cell=2). */
static size_t block_other(const gr_dsmc *d, size_t B, double u, size_t i, size_t j, size_t A)
{
    int bx = (int)(B % (size_t)d->gx), by = (int)(B / (size_t)d->gx);
    int wx = d->gx == d->nx, wy = d->gy == d->ny;
    size_t cj = gr_dsmc_cell_of(d, d->x[j], d->y[j]);
    int ti = times((int)(A % (size_t)d->gx), bx, d->gx, wx) * times((int)(A / (size_t)d->gx), by, d->gy, wy);
    int tj = j == i ? 0 : times((int)(cj % (size_t)d->gx), bx, d->gx, wx) * times((int)(cj / (size_t)d->gx), by, d->gy, wy);
    size_t tot = d->cv[B].cnt, mine = (size_t)ti + (size_t)tj;
    if (tot <= mine)
        return (size_t)-1;
    size_t w = gr_dsmc_below(u, tot - mine);
    for (int y = by - 1; y <= by + 1; y++)
        for (int x = bx - 1; x <= bx + 1; x++) {
            size_t e = at(d, x, y);
            if (e == SIZE_MAX)
                continue;
            for (size_t q = d->start[e]; q < d->start[e + 1]; q++) {
                size_t l = d->order[q];
                if (l != i && l != j && !w--)
                    return l;
            }
        }
    return (size_t)-1;
}

/* The smooth inelastic rule along the line of centres s (from i to j),
 * g.s = gn > 0. */
static void collide(gr_dsmc *d, gr_dsmc_tally *y, size_t i, size_t j, double sx, double sy, double gn)
{
    double k = 0.5 * (1.0 + d->alpha) * gn;
    d->vx[i] -= k * sx, d->vy[i] -= k * sy;
    d->vx[j] += k * sx, d->vy[j] += k * sy;
    d->prev[i] = d->last[i], d->prev[j] = d->last[j];
    d->last[i] = d->rank[j] & GR_DSMC_RANK, d->last[j] = d->rank[i] & GR_DSMC_RANK;
    y->virial += d->sigma * d->mass * k;
    gr_dsmc_stress_pair(d, i, j, sx, sy, k);
    y->pairs++;
}

/* N_c = (1/2) N_A 2 pi sigma omega_max dt candidates (each collision moves
 * two particles, hence the half): i uniform in the cell, s uniform, j
 * uniform among the others of the cell B at r_i + sigma s, accepted with
 * n chi (g.s)+ / omega_max, n the density around B without i (block_n).
 * Where B holds nobody else, or only a recent partner of i, j comes from
 * the 3 x 3 cells around B (block_other): cells within the reach + 1. */
void gr_dsmc_esmc_cell(gr_dsmc *d, size_t c, gr_dsmc_tally *y)
{
    size_t a = d->start[c], m = count(d, c);
    double om = m ? majorant(d, c, gr_dsmc_esmc_reach(d)) : 0.0;
    if (!(om > 0))
        return;
    gr_dsmc_rng r;
    gr_dsmc_rng_init(&r, d->key, d->step, c);
    uint64_t nc = (uint64_t)floor(0.5 * (double)m * 2.0 * M_PI * d->sigma * om * d->par.dt + gr_dsmc_uniform(&r));
    y->cand += nc;
    for (uint64_t k = 0; k < nc; k++) {
        size_t ia = gr_dsmc_below(gr_dsmc_uniform(&r), m), i = d->order[a + ia];
        double th = 2.0 * M_PI * gr_dsmc_uniform(&r), sx = cos(th), sy = sin(th);
        double px = d->x[i] + d->sigma * sx, py = d->y[i] + d->sigma * sy;
        double u = gr_dsmc_uniform(&r), v = gr_dsmc_uniform(&r), w = gr_dsmc_uniform(&r);
        if (!partner_place(d, &px, &py))
            continue;
        size_t B = gr_dsmc_cell_of(d, px, py), bs = d->start[B], others = count(d, B) - (B == c);
        size_t pi = B == c ? ia : SIZE_MAX, jb = others ? skip(gr_dsmc_below(u, others), pi, SIZE_MAX) : 0;
        size_t j = others ? d->order[bs + jb] : block_other(d, B, u, i, i, c);
        if (j == (size_t)-1)
            continue;
        if (gr_dsmc_recent(d, i, j)) {
            size_t e1 = pi < jb ? pi : jb, e2 = pi < jb ? jb : pi;
            j = others > 1 ? d->order[bs + skip(gr_dsmc_below(w, others - 1), e1, e2)]
                           : block_other(d, B, w, i, j, c);
            if (j == (size_t)-1)
                continue;
            y->stand_ins++;
        }
        double gn = (d->vx[i] - d->vx[j]) * sx + (d->vy[i] - d->vy[j]) * sy;
        if (!(gn > 0))
            continue;
        double n = block_n(d, B, c);
        if (v * om < n * chi_n(d, n) * gn)
            collide(d, y, i, j, sx, sy, gn);
    }
}
