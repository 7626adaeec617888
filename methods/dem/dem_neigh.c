/* Neighbour search: the spatial sort (grains in cell order), Verlet half
 * lists with a skin and the candidate wall segments per grain, built on
 * the threads of the step when it has several (the same list as on one).
 * Above the cells (dem_cells.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dem.h"
#include "dem_sync.h"
#include "geom.h"

#ifdef _OPENMP
#include <omp.h>
#endif

/* One thread's share of a rebuild (gr_dem_rebuild), kept across rebuilds:
 * the pairs and segments of its run of grains, then copied into the list
 * at their place, and the sort's scratch array. */
typedef struct {
    int32_t *j, *s;
    size_t capj, caps, nj, ns, offj, offs;
    void *tmp;
    size_t captmp;
    int fail;
    char pad[64]; /* threads write their own entries: no shared cache line */
} team_buf;

struct gr_dem_team {
    int cap;
    team_buf *b;
    size_t *rows; /* cap + 1: thread t sorts and lists grains [rows[t], rows[t + 1]) */
};

void gr_dem_team_free(struct gr_dem_team *tm)
{
    if (!tm)
        return;
    for (int t = 0; t < tm->cap; t++)
        free(tm->b[t].j), free(tm->b[t].s), free(tm->b[t].tmp);
    free(tm->b), free(tm->rows);
    free(tm);
}

double gr_dem_team_bytes(const struct gr_dem_team *tm)
{
    double b = 0;
    for (int t = 0; tm && t < tm->cap; t++)
        b += (double)((tm->b[t].capj + tm->b[t].caps) * sizeof(int32_t) + tm->b[t].captmp);
    return b;
}

/* A per-grain array to reorder: esz bytes per grain. */
typedef struct {
    void *a;
    size_t esz;
} perm_arr;

enum { PERM_MAX = 2 * F_NFIELDS + 20 };

/* The per-grain arrays a sort reorders, and the bytes of the largest
 * grain's entry. live: for a step about to drift every grain, whose
 * other buffer's basic fields and list reference positions are about to
 * be written over: those are left as they are. The cells of the grains
 * move with them. */
static int perm_table(gr_dem *d, int live, perm_arr *e, size_t *emax)
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
static void gather(const perm_arr *e, const int32_t *perm, size_t k0, size_t k1, void *out)
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
    gather(e, perm, 0, n, tmp);
    memcpy(e->a, tmp, n * e->esz);
}

int gr_dem_sort(gr_dem *d, gr_err *err)
{
    int q = d->cur;
    if (gr_dem_bin(d, d->f[F_X][q], d->f[F_Y][q], err))
        return err->code;
    perm_arr e[PERM_MAX];
    size_t emax;
    int m = perm_table(d, 0, e, &emax);
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

static void strips_index(gr_dem *d)
{
    gr_dem_strips *s = &d->strips;
    for (int k = 0; k <= s->n; k++)
        s->i0[k] = d->cells.start[(size_t)s->row0[k] * (size_t)d->cells.nx];
}

static int grow_i32(int32_t **a, size_t *cap, size_t need)
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
static int list_pairs(const gr_dem *d, const double *x, const double *y, size_t i, int sorted, team_buf *b)
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
                    if (grow_i32(&b->j, &b->capj, b->nj + 1))
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
static int pairs_forward(const gr_dem *d, const double *x, const double *y, size_t i, team_buf *b)
{
    const gr_dem_cells *g = &d->cells;
    const int32_t *st = g->start;
    int32_t c = g->cell[i];
    int nx = g->nx, cx = c % nx, cy = c / nx;
    size_t r[2][2] = {{i + 1, (size_t)st[c + 1 + (cx + 1 < nx)]}, {0, 0}};
    if (cy + 1 < g->ny)
        r[1][0] = (size_t)st[c + nx - (cx > 0)], r[1][1] = (size_t)st[c + nx + 1 + (cx + 1 < nx)];
    if (grow_i32(&b->j, &b->capj, b->nj + (r[0][1] - r[0][0]) + (r[1][1] - r[1][0])))
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
static int list_segments(const gr_dem *d, const double *x, const double *y, size_t i, team_buf *b)
{
    const gr_dem_cells *g = &d->cells;
    int32_t c = g->cell[i];
    double reach = d->rad[i] + d->par.skin + gr_dem_seg_margin(d);
    for (int32_t k = g->cell_seg_start[c]; k < g->cell_seg_start[c + 1]; k++) {
        const gr_dem_seg *s = &d->seg[g->cell_seg[k]];
        if (gr_dem_seg_dist(s->x0, s->y0, s->x1, s->y1, x[i], y[i]) < reach) {
            if (grow_i32(&b->s, &b->caps, b->ns + 1))
                return 1;
            b->s[b->ns++] = g->cell_seg[k];
        }
    }
    return 0;
}

/* Grains [i0, i1): pairs and segments appended to b, their starts (in b)
 * in nb_start and sg_start, positions at the build in xref, yref; sorted:
 * as in list_pairs. */
static int list_run(gr_dem *d, const double *x, const double *y, size_t i0, size_t i1, int sorted, team_buf *b)
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
static void owners(gr_dem *d, size_t i0, size_t i1, int32_t end)
{
    for (size_t i = i0; i < i1; i++) {
        int32_t e = i + 1 < i1 ? d->nb_start[i + 1] : end;
        for (int32_t k = d->nb_start[i]; k < e; k++)
            d->nb_i[k] = (int32_t)i;
    }
}

static int starts(gr_dem *d, gr_err *err)
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
static int list_finish(gr_dem *d, size_t cnt, size_t scnt, gr_err *err)
{
    d->nb_start[d->n] = (int32_t)cnt;
    d->sg_start[d->n] = (int32_t)scnt;
    if (cnt > INT32_MAX / 2)
        return gr_fail(err, GR_ERUN, "neighbour list too long (%zu pairs)", cnt);
    int32_t *owner = realloc(d->nb_i, (d->nb_cap + 1) * sizeof *owner);
    if (!owner)
        return gr_fail(err, GR_ERUN, "out of memory for the neighbour list");
    d->nb_i = owner;
    strips_index(d);
    d->need_build = 0;
    d->builds++;
    d->list_gen++;
    return GR_OK;
}

/* Build the half list from the grains' current order and positions (the
 * caller sorted them first, or restored a saved order). */
int gr_dem_build_list(gr_dem *d, const double *x, const double *y, gr_err *err)
{
    if (gr_dem_bin(d, x, y, err) || starts(d, err))
        return err->code;
    team_buf b = {.j = d->nb_j, .s = d->sg_j, .capj = d->nb_cap, .caps = d->sg_cap};
    int fail = list_run(d, x, y, 0, d->n, 0, &b);
    d->nb_j = b.j, d->nb_cap = b.capj, d->sg_j = b.s, d->sg_cap = b.caps;
    if (fail)
        return gr_fail(err, GR_ERUN, "out of memory for the neighbour list");
    if (list_finish(d, b.nj, b.ns, err))
        return err->code;
    owners(d, 0, d->n, (int32_t)b.nj);
    return GR_OK;
}

/* ---- the rebuild on the threads of a team -----------------------------
 * Each thread sorts and lists the grains it will step: those of its run of
 * strips in the one-barrier step that came before (the cut changes
 * seldom), an equal share of the grains otherwise. Each grain's row of
 * every array and of the list is then written by the thread that steps
 * it, and stays in that core's caches: with whole arrays shared out, half
 * of each thread's grains came from the other core's after every rebuild
 * (on cores that share no cache, 8000 lines of 330 ns each way for the
 * 5000-grain silo, every 110-160 steps). The list is the same whatever the
 * split: each grain's row is built by one thread, the runs joined in
 * order. */

/* Thread t's grains [r[t], r[t + 1]), on the cells of the new order. */
static void team_rows(const gr_dem *d, int T, size_t *r)
{
    int cut[65];
    const size_t n = d->n;
    const gr_dem_cells *g = &d->cells;
    if (T <= 64 && d->strips.n > 0 && gr_dem_eval_flow_cut(d, T, cut)) {
        for (int t = 0; t <= T; t++)
            r[t] = (size_t)g->start[(size_t)d->strips.row0[cut[t]] * (size_t)g->nx];
        r[T] = n;
        return;
    }
    for (int t = 0; t <= T; t++)
        r[t] = n * (size_t)t / (size_t)T;
}

/* One thread of the team: the bins, the scratch for T threads, the split. */
static int team_prepare(gr_dem *d, int T, gr_err *err)
{
    perm_arr e[PERM_MAX];
    size_t emax;
    perm_table(d, 1, e, &emax);
    size_t tmp_bytes = d->n * emax + 16;
    struct gr_dem_team *tm = d->team;
    if (!tm && !(tm = d->team = calloc(1, sizeof *tm)))
        return gr_fail(err, GR_ERUN, "out of memory for the neighbour list");
    if (tm->cap < T) {
        team_buf *b = realloc(tm->b, (size_t)T * sizeof *b);
        if (b)
            tm->b = b;
        size_t *rows = realloc(tm->rows, ((size_t)T + 1) * sizeof *rows);
        if (rows)
            tm->rows = rows;
        if (!b || !rows)
            return gr_fail(err, GR_ERUN, "out of memory for the neighbour list");
        memset(b + tm->cap, 0, (size_t)(T - tm->cap) * sizeof *b);
        tm->cap = T;
    }
    for (int t = 0; t < T; t++) {
        team_buf *b = &tm->b[t];
        b->nj = b->ns = 0, b->fail = 0;
        if (b->captmp < tmp_bytes) {
            free(b->tmp);
            if (!(b->tmp = malloc(tmp_bytes)))
                return b->captmp = 0, gr_fail(err, GR_ERUN, "out of memory for the spatial sort");
            b->captmp = tmp_bytes;
        }
    }
    int p = d->cur;
    if (gr_dem_bin(d, d->f[F_X][p], d->f[F_Y][p], err) || starts(d, err))
        return err->code;
    team_rows(d, T, tm->rows);
    return GR_OK;
}

/* One thread of the team, after every run is built: where each goes. */
static int team_join(gr_dem *d, int T, gr_err *err)
{
    struct gr_dem_team *tm = d->team;
    size_t cnt = 0, scnt = 0;
    int fail = 0;
    for (int t = 0; t < T; t++) {
        team_buf *b = &tm->b[t];
        b->offj = cnt, b->offs = scnt;
        cnt += b->nj, scnt += b->ns;
        fail |= b->fail;
    }
    if (fail || grow_i32(&d->nb_j, &d->nb_cap, cnt) || grow_i32(&d->sg_j, &d->sg_cap, scnt))
        return gr_fail(err, GR_ERUN, "out of memory for the neighbour list");
    d->since_sort = 0;
    d->pre_E = 0; /* a drift done ahead was not permuted */
    return list_finish(d, cnt, scnt, err);
}

/* Thread t's rows of every array in the new order. The arrays go in
 * batches that fit every thread's scratch over its rows: each thread
 * gathers its rows of a batch, and once all have (the old order is read
 * everywhere), writes them back. */
static void team_permute(gr_dem *d, gr_dem_meet_t *mt, int T, int t)
{
    perm_arr e[PERM_MAX];
    size_t emax;
    const int m = perm_table(d, 1, e, &emax);
    const struct gr_dem_team *tm = d->team;
    const size_t *r = tm->rows, n = d->n, r0 = r[t], r1 = r[t + 1];
    size_t most = 1;
    for (int u = 0; u < T; u++)
        most = r[u + 1] - r[u] > most ? r[u + 1] - r[u] : most;
    /* bytes per grain of a batch: every array fits (most <= n, or no grains) */
    const size_t budget = most <= n ? n * emax / most : emax;
    char *tmp = tm->b[t].tmp;
    for (int k0 = 0, k1; k0 < m; k0 = k1) {
        size_t bytes = 0;
        for (k1 = k0; k1 < m && bytes + e[k1].esz <= budget; k1++)
            bytes += e[k1].esz;
        char *o = tmp;
        for (int k = k0; k < k1; k++)
            gather(&e[k], d->cells.idx, r0, r1, o), o += (r1 - r0) * e[k].esz;
        gr_dem_meet_all(mt, T);
        o = tmp;
        for (int k = k0; k < k1; k++)
            memcpy((char *)e[k].a + r0 * e[k].esz, o, (r1 - r0) * e[k].esz), o += (r1 - r0) * e[k].esz;
    }
}

int gr_dem_rebuild_team(gr_dem *d, gr_dem_meet_t *mt, gr_err *err)
{
    const int T = omp_get_num_threads(), t = omp_get_thread_num();
    if (gr_dem_meet(mt, T))
        mt->val = team_prepare(d, T, err), gr_dem_meet_release(mt);
    if (mt->val)
        return mt->val;
    /* after the binning, which may move the cells' arrays */
    team_permute(d, mt, T, t);
    gr_dem_meet_all(mt, T);
    /* after the permutation grain k sits in slot k */
    struct gr_dem_team *tm = d->team;
    team_buf *b = &tm->b[t];
    const size_t i0 = tm->rows[t], i1 = tm->rows[t + 1];
    for (size_t i = i0; i < i1; i++)
        d->cells.idx[i] = (int32_t)i;
    const double *x = d->f[F_X][d->cur], *y = d->f[F_Y][d->cur];
    b->fail = list_run(d, x, y, i0, i1, 1, b);
    if (gr_dem_meet(mt, T))
        mt->val = team_join(d, T, err), gr_dem_meet_release(mt);
    if (mt->val)
        return mt->val;
    if (b->nj) /* a buffer never grown is NULL, which memcpy may not take */
        memcpy(d->nb_j + b->offj, b->j, b->nj * sizeof *b->j);
    if (b->ns)
        memcpy(d->sg_j + b->offs, b->s, b->ns * sizeof *b->s);
    for (size_t i = i0; i < i1; i++) {
        d->nb_start[i] += (int32_t)b->offj;
        d->sg_start[i] += (int32_t)b->offs;
    }
    owners(d, i0, i1, (int32_t)(b->offj + b->nj));
    return GR_OK;
}

int gr_dem_rebuild(gr_dem *d, gr_err *err)
{
    if (omp_in_parallel()) { /* one thread of a team that is not calling it */
        if (gr_dem_sort(d, err) || gr_dem_build_list(d, d->f[F_X][d->cur], d->f[F_Y][d->cur], err))
            return err->code;
        return GR_OK;
    }
    int nth = gr_dem_threads(d), rc = GR_OK;
    gr_dem_meet_t mt;
    gr_dem_meet_init(&mt);
    if (nth == 1)
        return gr_dem_rebuild_team(d, &mt, err);
#pragma omp parallel num_threads(nth)
    {
        int r = gr_dem_rebuild_team(d, &mt, err);
        gr_dem_meet_all(&mt, omp_get_num_threads());
#pragma omp master
        rc = r;
    }
    return rc;
}
