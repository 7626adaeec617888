/* Neighbour search: the spatial sort (grains in cell order), Verlet half
 * lists with a skin and the candidate wall segments per grain, and the
 * pieces (dem_sortlist.h) with which dem_team.c builds the same list on
 * the threads of a step. Above the cells (dem_cells.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dem.h"
#include "dem_sortlist.h"
#include "geom.h"

/* The per-grain arrays a sort reorders, and the bytes of the largest
 * grain's entry. live: for a step about to drift every grain, whose
 * other buffer's basic fields and list reference positions are about to
 * be written over: those are left as they are. The cells of the grains
 * move with them. */
int gr_dem_perm_table(gr_dem *d, int live, perm_arr *e, size_t *emax)
{
    int m = 0;
    size_t hc = d->hist_on ? (size_t)d->hist.cap : 0;
#define ADD(a, sz) if (a) e[m++] = (perm_arr){(a), (sz)};
    for (int f = 0; f < F_NFIELDS; f++)
        for (int p = 0; p < 2; p++)
            if (!(live && f < F_NBASIC && p != d->cur))
                ADD(d->f[f][p], sizeof(double))
    ADD(d->rad, 8) ADD(d->im, 8) ADD(d->iI, 8) ADD(d->gf, 8) ADD(d->mass, 8) ADD(d->inertia, 8)
    if (!live) {
        ADD(d->xref, 8) ADD(d->yref, 8)
    }
    ADD(d->ext_fx, 8) ADD(d->ext_fy, 8)
    ADD(d->tag, 4) ADD(d->flags, 4) ADD(d->species, 4) ADD(d->cells.cell, 4)
    if (hc) {
        gr_dem_hist *h = &d->hist;
        ADD(h->partner, 4 * hc) ADD(h->partner_old, 4 * hc) ADD(h->z, 8 * hc) ADD(h->z_old, 8 * hc)
        ADD(h->stamp, 8 * hc) ADD(h->stamp_old, 8 * hc)
    }
#undef ADD
    *emax = hc > 1 ? 8 * hc : 8;
    return m;
}

/* New slots [k0, k1) of one array reordered by perm (new slot k holds
 * old perm[k]), gathered into out. */
void gr_dem_perm_gather(const perm_arr *e, const int32_t *perm, size_t k0, size_t k1, void *out)
{
    const char *a = e->a;
    char *t = out;
    if (e->esz == 8) {
        for (size_t k = k0; k < k1; k++)
            memcpy(t + 8 * (k - k0), a + 8 * (size_t)perm[k], 8);
    } else if (e->esz == 4) {
        for (size_t k = k0; k < k1; k++)
            memcpy(t + 4 * (k - k0), a + 4 * (size_t)perm[k], 4);
    } else {
        for (size_t k = k0; k < k1; k++)
            memcpy(t + e->esz * (k - k0), a + e->esz * (size_t)perm[k], e->esz);
    }
}

/* Reorder one array by perm, through tmp. */
static void permute_one(const perm_arr *e, const int32_t *perm, size_t n, void *tmp)
{
    gr_dem_perm_gather(e, perm, 0, n, tmp);
    memcpy(e->a, tmp, n * e->esz);
}

int gr_dem_sort(gr_dem *d, gr_err *err)
{
    int q = d->cur;
    if (gr_dem_bin(d, d->f[F_X][q], d->f[F_Y][q], err))
        return err->code;
    perm_arr e[PERM_MAX];
    size_t emax;
    int m = gr_dem_perm_table(d, 0, e, &emax);
    void *tmp = malloc(d->n * emax + 16);
    if (!tmp)
        return gr_fail(err, GR_ERUN, "out of memory for the spatial sort");
    for (int k = 0; k < m; k++)
        permute_one(&e[k], d->cells.idx, d->n, tmp);
    free(tmp);
    /* after the permutation grain k sits in slot k */
    for (size_t i = 0; i < d->n; i++)
        d->cells.idx[i] = (int32_t)i;
    d->since_sort = 0;
    d->pre_E = 0; /* a drift done ahead was not permuted */
    return GR_OK;
}

void gr_dem_strips_index(gr_dem *d)
{
    gr_dem_strips *s = &d->strips;
    for (int k = 0; k <= s->n; k++)
        s->i0[k] = d->cells.start[(size_t)s->row0[k] * (size_t)d->cells.nx];
}

int gr_dem_grow_i32(int32_t **a, size_t *cap, size_t need)
{
    if (need <= *cap)
        return 0;
    size_t c = need + need / 2 + 64;
    int32_t *p = realloc(*a, c * sizeof *p);
    if (!p)
        return 1;
    *a = p;
    *cap = c;
    return 0;
}

/* Grain i's partners j > i within reach (radii plus skin) in the 3 x 3
 * cells around its own, appended to b->j and sorted by index; sorted: the
 * grains are in cell order (cells.idx, the identity, may still be being
 * written). */
static int list_pairs(const gr_dem *d, const double *x, const double *y, size_t i, int sorted, dem_listbuf *b)
{
    const gr_dem_cells *g = &d->cells;
    int32_t c = g->cell[i];
    int cx = c % g->nx, cy = c / g->nx;
    int fi = (d->flags[i] & GR_PF_FIXED) != 0;
    double xi = x[i], yi = y[i], ri = d->rad[i], skin = d->par.skin;
    size_t row = b->nj;
    for (int oy = -1; oy <= 1; oy++) {
        int yy = cy + oy;
        if (yy < 0 || yy >= g->ny) {
            if (!g->py)
                continue;
            yy = (yy + g->ny) % g->ny;
        }
        for (int ox = -1; ox <= 1; ox++) {
            int xx = cx + ox;
            if (xx < 0 || xx >= g->nx) {
                if (!g->px)
                    continue;
                xx = (xx + g->nx) % g->nx;
            }
            int32_t cc = yy * g->nx + xx;
            for (int32_t a = g->start[cc]; a < g->start[cc + 1]; a++) {
                int32_t j = sorted ? a : g->idx[a];
                if ((size_t)j <= i || (fi && (d->flags[j] & GR_PF_FIXED)))
                    continue;
                double dx = gr_min_image(x[j] - xi, d->Lx), dy = gr_min_image(y[j] - yi, d->Ly);
                double rc = ri + d->rad[j] + skin;
                if (dx * dx + dy * dy < rc * rc) {
                    if (gr_dem_grow_i32(&b->j, &b->capj, b->nj + 1))
                        return 1;
                    b->j[b->nj++] = j;
                }
            }
        }
    }
    /* neighbours in cell order are not sorted by index: sort the row so
     * that the list does not depend on how cells were scanned */
    for (size_t a = row + 1; a < b->nj; a++) {
        int32_t v = b->j[a];
        size_t k = a;
        while (k > row && b->j[k - 1] > v) {
            b->j[k] = b->j[k - 1];
            k--;
        }
        b->j[k] = v;
    }
    return 0;
}

/* The same partners when the grains are in cell order (just sorted) and
 * no side is periodic: the partners j > i are the grains after i in its
 * cell and the cell to its right, then those of the three cells above —
 * two runs of consecutive indices, already in order. Every candidate is
 * written, and kept when within reach: no branch to mispredict. */
static int pairs_forward(const gr_dem *d, const double *x, const double *y, size_t i, dem_listbuf *b)
{
    const gr_dem_cells *g = &d->cells;
    const int32_t *st = g->start;
    int32_t c = g->cell[i];
    int nx = g->nx, cx = c % nx, cy = c / nx;
    size_t r[2][2] = {{i + 1, (size_t)st[c + 1 + (cx + 1 < nx)]}, {0, 0}};
    if (cy + 1 < g->ny)
        r[1][0] = (size_t)st[c + nx - (cx > 0)], r[1][1] = (size_t)st[c + nx + 1 + (cx + 1 < nx)];
    if (gr_dem_grow_i32(&b->j, &b->capj, b->nj + (r[0][1] - r[0][0]) + (r[1][1] - r[1][0])))
        return 1;
    const double *restrict rad = d->rad;
    const uint32_t *restrict fl = d->flags;
    int32_t *restrict out = b->j;
    const int fi = (fl[i] & GR_PF_FIXED) != 0;
    const double xi = x[i], yi = y[i], ri = rad[i], skin = d->par.skin;
    size_t m = b->nj;
    for (int k = 0; k < 2; k++) {
        for (size_t j = r[k][0]; j < r[k][1]; j++) {
            double dx = x[j] - xi, dy = y[j] - yi;
            double rc = ri + rad[j] + skin;
            out[m] = (int32_t)j;
            m += (dx * dx + dy * dy < rc * rc) & !(fi & ((fl[j] & GR_PF_FIXED) != 0));
        }
    }
    b->nj = m;
    return 0;
}

/* Mobile grain i's candidate segments, appended to b->s. */
static int list_segments(const gr_dem *d, const double *x, const double *y, size_t i, dem_listbuf *b)
{
    const gr_dem_cells *g = &d->cells;
    int32_t c = g->cell[i];
    double reach = d->rad[i] + d->par.skin + gr_dem_seg_margin(d);
    for (int32_t k = g->cell_seg_start[c]; k < g->cell_seg_start[c + 1]; k++) {
        const gr_dem_seg *s = &d->seg[g->cell_seg[k]];
        if (gr_dem_seg_dist(s->x0, s->y0, s->x1, s->y1, x[i], y[i]) < reach) {
            if (gr_dem_grow_i32(&b->s, &b->caps, b->ns + 1))
                return 1;
            b->s[b->ns++] = g->cell_seg[k];
        }
    }
    return 0;
}

/* Grains [i0, i1): pairs and segments appended to b, their starts (in b)
 * in nb_start and sg_start, positions at the build in xref, yref; sorted:
 * as in list_pairs. */
int gr_dem_list_run(gr_dem *d, const double *x, const double *y, size_t i0, size_t i1, int sorted, dem_listbuf *b)
{
    const int forward = sorted && !d->cells.px && !d->cells.py;
    for (size_t i = i0; i < i1; i++) {
        d->nb_start[i] = (int32_t)b->nj;
        d->sg_start[i] = (int32_t)b->ns;
        if (forward ? pairs_forward(d, x, y, i, b) : list_pairs(d, x, y, i, sorted, b))
            return 1;
        if (!(d->flags[i] & GR_PF_FIXED) && list_segments(d, x, y, i, b))
            return 1;
        d->xref[i] = x[i];
        d->yref[i] = y[i];
    }
    return 0;
}

/* The grain of each list pair in [i0, i1), whose pairs end at end. */
void gr_dem_list_owners(gr_dem *d, size_t i0, size_t i1, int32_t end)
{
    for (size_t i = i0; i < i1; i++) {
        int32_t e = i + 1 < i1 ? d->nb_start[i + 1] : end;
        for (int32_t k = d->nb_start[i]; k < e; k++)
            d->nb_i[k] = (int32_t)i;
    }
}

int gr_dem_list_starts(gr_dem *d, gr_err *err)
{
    size_t n = d->n;
    int32_t *ns = realloc(d->nb_start, (n + 1) * sizeof *ns);
    if (ns)
        d->nb_start = ns;
    int32_t *ss = realloc(d->sg_start, (n + 1) * sizeof *ss);
    if (ss)
        d->sg_start = ss;
    return ns && ss ? GR_OK : gr_fail(err, GR_ERUN, "out of memory for the neighbour list");
}

/* The list's ends (cnt pairs, scnt segments) and the owners' array. */
int gr_dem_list_finish(gr_dem *d, size_t cnt, size_t scnt, gr_err *err)
{
    d->nb_start[d->n] = (int32_t)cnt;
    d->sg_start[d->n] = (int32_t)scnt;
    if (cnt > INT32_MAX / 2)
        return gr_fail(err, GR_ERUN, "neighbour list too long (%zu pairs)", cnt);
    int32_t *owner = realloc(d->nb_i, (d->nb_cap + 1) * sizeof *owner);
    if (!owner)
        return gr_fail(err, GR_ERUN, "out of memory for the neighbour list");
    d->nb_i = owner;
    gr_dem_strips_index(d);
    d->need_build = 0;
    d->builds++;
    d->list_gen++;
    return GR_OK;
}

/* Build the half list from the grains' current order and positions (the
 * caller sorted them first, or restored a saved order). */
int gr_dem_build_list(gr_dem *d, const double *x, const double *y, gr_err *err)
{
    if (gr_dem_bin(d, x, y, err) || gr_dem_list_starts(d, err))
        return err->code;
    dem_listbuf b = {.j = d->nb_j, .s = d->sg_j, .capj = d->nb_cap, .caps = d->sg_cap};
    int fail = gr_dem_list_run(d, x, y, 0, d->n, 0, &b);
    d->nb_j = b.j, d->nb_cap = b.capj, d->sg_j = b.s, d->sg_cap = b.caps;
    if (fail)
        return gr_fail(err, GR_ERUN, "out of memory for the neighbour list");
    if (gr_dem_list_finish(d, b.nj, b.ns, err))
        return err->code;
    gr_dem_list_owners(d, 0, d->n, (int32_t)b.nj);
    return GR_OK;
}
