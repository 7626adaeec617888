/* The spatial sort and the Verlet list rebuilt on the threads of a step
 * (gr_dem_rebuild_team), or of a region of its own (gr_dem_rebuild): the
 * same list as dem_neigh.c's serial sort and build. Above the list
 * (dem_neigh.c) and the one-barrier step's cut (dem_flow.c). */
#include <stdlib.h>
#include <string.h>

#include "dem.h"
#include "dem_sortlist.h"
#include "dem_sync.h"

#ifdef _OPENMP
#include <omp.h>
#endif

struct gr_dem_team {
    int cap;
    dem_listbuf *b;
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

/* Thread t's grains [r[t], r[t + 1]), on the strips of the new order. */
static void team_rows(gr_dem *d, int T, size_t *r)
{
    int cut[65];
    if (T <= 64 && gr_dem_eval_flow_cut(d, T, cut)) {
        gr_dem_strips_index(d);
        for (int t = 0; t <= T; t++)
            r[t] = (size_t)d->strips.i0[cut[t]];
        return;
    }
    for (int t = 0; t <= T; t++)
        r[t] = d->n * (size_t)t / (size_t)T;
}

/* One thread of the team: the bins, the scratch for T threads, the split. */
static int team_prepare(gr_dem *d, int T, gr_err *err)
{
    perm_arr e[PERM_MAX];
    size_t emax;
    gr_dem_perm_table(d, 1, e, &emax);
    size_t tmp_bytes = d->n * emax + 16;
    struct gr_dem_team *tm = d->team;
    if (!tm && !(tm = d->team = calloc(1, sizeof *tm)))
        return gr_fail(err, GR_ERUN, "out of memory for the neighbour list");
    if (tm->cap < T) {
        dem_listbuf *b = realloc(tm->b, (size_t)T * sizeof *b);
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
        dem_listbuf *b = &tm->b[t];
        b->nj = b->ns = 0, b->fail = 0;
        if (b->captmp < tmp_bytes) {
            free(b->tmp);
            if (!(b->tmp = malloc(tmp_bytes)))
                return b->captmp = 0, gr_fail(err, GR_ERUN, "out of memory for the spatial sort");
            b->captmp = tmp_bytes;
        }
    }
    int p = d->cur;
    if (gr_dem_bin(d, d->f[F_X][p], d->f[F_Y][p], err) || gr_dem_list_starts(d, err))
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
        dem_listbuf *b = &tm->b[t];
        b->offj = cnt, b->offs = scnt;
        cnt += b->nj, scnt += b->ns;
        fail |= b->fail;
    }
    if (fail || gr_dem_grow_i32(&d->nb_j, &d->nb_cap, cnt) || gr_dem_grow_i32(&d->sg_j, &d->sg_cap, scnt))
        return gr_fail(err, GR_ERUN, "out of memory for the neighbour list");
    d->since_sort = 0;
    d->pre_E = 0; /* a drift done ahead was not permuted */
    return gr_dem_list_finish(d, cnt, scnt, err);
}

/* Thread t's rows of every array in the new order. The arrays go in
 * batches that fit every thread's scratch over its rows: each thread
 * gathers its rows of a batch, and once all have (the old order is read
 * everywhere), writes them back. */
static void team_permute(gr_dem *d, gr_dem_meet_t *mt, int T, int t)
{
    perm_arr e[PERM_MAX];
    size_t emax;
    const int m = gr_dem_perm_table(d, 1, e, &emax);
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
            gr_dem_perm_gather(&e[k], d->cells.idx, r0, r1, o), o += (r1 - r0) * e[k].esz;
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
    dem_listbuf *b = &tm->b[t];
    const size_t i0 = tm->rows[t], i1 = tm->rows[t + 1];
    for (size_t i = i0; i < i1; i++)
        d->cells.idx[i] = (int32_t)i;
    const double *x = d->f[F_X][d->cur], *y = d->f[F_Y][d->cur];
    b->fail = gr_dem_list_run(d, x, y, i0, i1, 1, b);
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
    gr_dem_list_owners(d, i0, i1, (int32_t)(b->offj + b->nj));
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
