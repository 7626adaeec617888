/* The lattice of a scene: its size, the wall nodes (the domain's wall sides
 * and the scene's segments, rasterised), the silo's exit and reinsertion
 * band, and the initial state (grains put on nodes, or random channel
 * occupations). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "apart.h"
#include "lgca_int.h"

/* Wall candidates before duplicates are merged. */
typedef struct {
    lgca_wall *w;
    size_t n, cap;
} wall_list;

static int wall_push(wall_list *l, int i, int j, unsigned mirror, uint64_t open_step)
{
    if (l->n == l->cap) {
        size_t cap = l->cap ? 2 * l->cap : 256;
        lgca_wall *q = realloc(l->w, cap * sizeof *q);
        if (!q)
            return GR_ERUN;
        l->w = q, l->cap = cap;
    }
    l->w[l->n++] = (lgca_wall){(uint32_t)i, (uint32_t)j, mirror, open_step};
    return GR_OK;
}

static int wall_cmp(const void *a, const void *b)
{
    const lgca_wall *x = a, *y = b;
    if (x->j != y->j)
        return x->j < y->j ? -1 : 1;
    if (x->i != y->i)
        return x->i < y->i ? -1 : 1;
    return x->open_step < y->open_step ? 1 : x->open_step > y->open_step ? -1 : 0;
}

/* The domain's wall sides: a lane or a row of wall nodes; where two meet,
 * the corner bounces back. */
static int side_walls(lgca *L, wall_list *l)
{
    const gr_scene *sc = L->sc;
    int rc = GR_OK;
    for (int j = 0; j < L->nj && !rc; j++)
        for (int i = 0; i < L->ni && !rc; i++) {
            int v = (j == 0 && sc->side[GR_LEFT] == GR_BC_WALL) ||
                    (j == L->nj - 1 && sc->side[GR_RIGHT] == GR_BC_WALL);
            int hz = (i == 0 && sc->side[GR_BOTTOM] == GR_BC_WALL) ||
                     (i == L->ni - 1 && sc->side[GR_TOP] == GR_BC_WALL);
            if (v || hz)
                rc = wall_push(l, i, j, v && hz ? 6u : v ? 3u : 0u, UINT64_MAX);
        }
    return rc;
}

/* A segment covers the nodes closer than 0.6 a to it (thick enough that no
 * particle hops across); its mirror is the lattice mirror axis nearest to
 * its direction. A gate opens at the first step at or after its time. */
static int segment_walls(lgca *L, const gr_segment *s, wall_list *l)
{
    double dx = s->x1 - s->x0, dy = s->y1 - s->y0, len2 = dx * dx + dy * dy, reach = 0.6 * L->a;
    double ang = atan2(dy, dx) * 180.0 / M_PI;
    unsigned m = (unsigned)((long)lround(ang / 30.0) % 6 + 6) % 6;
    uint64_t open = isfinite(s->open_time) ? (uint64_t)ceil(fmax(0.0, s->open_time) / L->par.dt - 1e-9) : UINT64_MAX;
    int j0 = (int)floor((fmin(s->x0, s->x1) - reach) / L->h - 1), j1 = (int)ceil((fmax(s->x0, s->x1) + reach) / L->h);
    int i0 = (int)floor((fmin(s->y0, s->y1) - reach) / L->a - 2), i1 = (int)ceil((fmax(s->y0, s->y1) + reach) / L->a);
    for (int j = j0 < 0 ? 0 : j0; j <= j1 && j < L->nj; j++)
        for (int i = i0 < 0 ? 0 : i0; i <= i1 && i < L->ni; i++) {
            double x, y;
            lgca_node_xy(L, i, j, &x, &y);
            double t = len2 > 0 ? ((x - s->x0) * dx + (y - s->y0) * dy) / len2 : 0;
            t = t < 0 ? 0 : t > 1 ? 1 : t;
            double ex = x - s->x0 - t * dx, ey = y - s->y0 - t * dy;
            if (ex * ex + ey * ey < reach * reach && wall_push(l, i, j, m, open))
                return GR_ERUN;
        }
    return GR_OK;
}

/* Merge duplicates: a permanent wall wins over a gate, the earlier gate
 * over a later one (sorted so the first of a node is the one kept). */
static int build_walls(lgca *L, gr_err *err)
{
    wall_list l = {NULL, 0, 0};
    int rc = side_walls(L, &l);
    for (int k = 0; k < L->sc->nsegments && !rc; k++)
        rc = segment_walls(L, &L->sc->segments[k], &l);
    if (rc) {
        free(l.w);
        return gr_fail(err, GR_ERUN, "out of memory");
    }
    if (l.n)
        qsort(l.w, l.n, sizeof *l.w, wall_cmp);
    size_t n = 0;
    for (size_t k = 0; k < l.n; k++)
        if (!n || l.w[k].i != l.w[n - 1].i || l.w[k].j != l.w[n - 1].j)
            l.w[n++] = l.w[k];
    L->walls = l.w, L->nwalls = n;
    for (size_t k = 0; k < n; k++)
        L->has_gates |= l.w[k].open_step != UINT64_MAX;
    for (size_t k = 0; k < n; k++)
        L->solid[(size_t)l.w[k].j * (size_t)L->nw + (l.w[k].i >> 6)] |= (uint64_t)1 << (l.w[k].i & 63);
    return GR_OK;
}

/* Rows of lane parity q whose node height is below y: i < rows_below. */
static int rows_below(const lgca *L, double y, int q)
{
    double x = y / L->a - 0.25 - 0.5 * q;
    int n = (int)ceil(x - 1e-12);
    return n < 0 ? 0 : n > L->ni ? L->ni : n;
}

static void silo_exits(lgca *L)
{
    const gr_silo *s = &L->sc->silo;
    if (!s->present)
        return;
    L->exits = 1;
    L->reinsert = s->reinsert;
    for (int q = 0; q < 2; q++) {
        L->exit_n[q] = rows_below(L, s->exit_below, q);
        L->band_i0[q] = rows_below(L, s->reinsert_bottom, q);
        L->band_i1[q] = rows_below(L, s->reinsert_top, q);
    }
    L->band_j0 = (int)ceil(s->x0 / L->h - 0.5);
    L->band_j1 = (int)ceil((s->x0 + s->width) / L->h - 0.5);
    L->band_j0 = L->band_j0 < 0 ? 0 : L->band_j0;
    L->band_j1 = L->band_j1 > L->nj ? L->nj : L->band_j1;
}

static int check_size(lgca *L, gr_err *err)
{
    const gr_scene *sc = L->sc;
    char where[1200];
    gr_scene_where(sc, "domain", "width", where, sizeof where);
    if (L->ni < 3 || L->nj < 4)
        return gr_fail(err, GR_EINPUT, "%s: the domain holds %d x %d lattice nodes of spacing %g; lgca needs at least 4 lanes and 3 rows",
                       where, L->nj, L->ni, L->a);
    if ((double)L->ni * L->nj * LGCA_CH > 1e12 || L->nw > (1 << 24))
        return gr_fail(err, GR_EINPUT, "%s: a lattice of %d x %d nodes is too large", where, L->nj, L->ni);
    return GR_OK;
}

/* Zeroed words apart from every other allocation (common/apart.h), for
 * all that the team's threads share: where two threads' parts of an array
 * meet (scratch, edge slots) neither writes the other's lines, and what
 * every thread reads at every word (the masks of valid and wall nodes,
 * the lane pointers, the struct) shares no line or pair of lines with
 * anything a thread writes. In malloc's small chunks, on two cores that
 * share no cache, the main thread ran 7 % slower than the other, which
 * waited for it every step: 3.46e9 site updates per CPU second against
 * 3.73e9 with everything apart (medians of 93 runs each of `grano bench
 * lgca --size 256 --threads 2`, alternated, AMD EPYC, 27 Nov 2026). The
 * masks alone apart gave 3.75e9, scratch and edge slots alone 3.48e9 (11
 * runs each; docs/performance.md). */
static uint64_t *zalloc_lines(size_t n)
{
    return gr_zalloc_apart(n * sizeof(uint64_t));
}

/* The lanes of each thread's block in an allocation of their own, followed
 * by 64 KiB that no lane uses. In one array, the two blocks of a 256^2
 * lattice (28 KiB each) ran 10 % slower on two threads than apart: 5.7e9
 * site updates per second against 6.2-6.4e9 with 8, 16 or 64 KiB or a
 * separate allocation between them (granular rules, p = 0.1, four runs
 * each, alternated, idle machine, 25 Nov 2026; `grano bench lgca --size 256
 * --threads 2 --rules granular --p 0.1`), as if the cores' prefetchers
 * fetched the lines the other core writes. The blocks are those of
 * lgca_steps' team (lanes nj t / T .. nj (t + 1) / T). */
static int alloc_lanes(lgca *L)
{
    int nj = L->nj, T = L->nthreads < nj / 2 ? L->nthreads : nj / 2;
    size_t lw = LGCA_CH * (size_t)L->nw;
    L->nseg = T;
    L->seg = (uint64_t **)zalloc_lines((size_t)T);
    L->seg_j = (int *)zalloc_lines((size_t)T + 1);
    L->lane = (uint64_t **)zalloc_lines((size_t)nj);
    if (!L->seg || !L->seg_j || !L->lane)
        return 0;
    for (int k = 0; k <= T; k++)
        L->seg_j[k] = (int)((long)nj * k / T);
    for (int k = 0; k < T; k++) {
        size_t n = (size_t)(L->seg_j[k + 1] - L->seg_j[k]) * lw, bytes = (n * sizeof(uint64_t) + 4095) & ~(size_t)4095;
        if (!(L->seg[k] = aligned_alloc(4096, bytes + 65536)))
            return 0;
        memset(L->seg[k], 0, bytes);
        for (int j = L->seg_j[k]; j < L->seg_j[k + 1]; j++)
            L->lane[j] = L->seg[k] + (size_t)(j - L->seg_j[k]) * lw;
    }
    return 1;
}

static int alloc_lattice(lgca *L, gr_err *err)
{
    size_t nj = (size_t)L->nj, nw = (size_t)L->nw, T = (size_t)L->nthreads;
    int lanes = alloc_lanes(L);
    L->solid = zalloc_lines(nj * nw);
    L->valid = zalloc_lines(nw);
    L->chunk = nw >= LGCA_CHUNK_WORDS ? 1 : (int)(LGCA_CHUNK_WORDS / nw);
    L->scratch = zalloc_lines(T * LGCA_SCRATCH * (size_t)L->chunk * nw);
    L->edge = zalloc_lines(2 * T * lgca_edge_slot(L));
    L->sweep = zalloc_lines(T * lgca_sweep_words(L));
    if (L->thr_stop && !(L->stop_mask = calloc(nj * nw, sizeof *L->stop_mask)))
        return gr_fail(err, GR_ERUN, "out of memory for a lattice of %d x %d nodes", L->nj, L->ni);
    if (!lanes || !L->solid || !L->valid || !L->scratch || !L->edge || !L->sweep)
        return gr_fail(err, GR_ERUN, "out of memory for a lattice of %d x %d nodes", L->nj, L->ni);
    for (int i = 0; i < L->ni; i++)
        L->valid[i >> 6] |= (uint64_t)1 << (i & 63);
    /* Where a thread's lanes stay in the caches the prefetches cost 1-3 %
     * (AMD EPYC, L2 1 MiB: 256^2, 1024^2, 2048^2 on one thread); from
     * 4096^2 (16 MiB) they gain 15-20 % (lgca_step.c, collide_block). */
    long l2 = sysconf(_SC_LEVEL2_CACHE_SIZE);
    size_t block = (nj + (size_t)L->nseg - 1) / (size_t)L->nseg * LGCA_CH * nw * sizeof(uint64_t);
    L->prefetch = block > 4 * (l2 > 0 ? (size_t)l2 : (size_t)1 << 20);
    return GR_OK;
}

int lgca_create(const gr_scene *sc, const lgca_params *par, const uint32_t key[2],
                const gr_particles *init, gr_rng *rng, lgca **out, gr_err *err)
{
    *out = NULL;
    lgca *L = (lgca *)zalloc_lines((sizeof(lgca) + 7) / 8);
    if (!L)
        return gr_fail(err, GR_ERUN, "out of memory");
    L->sc = sc;
    L->par = *par;
    L->key[0] = key[0], L->key[1] = key[1];
    L->a = gr_scene_max_diameter(sc);
    L->h = L->a * sqrt(3.0) / 2;
    L->mass = sc->species[0].density * M_PI * L->a * L->a / 4;
    L->per_i = sc->side[GR_BOTTOM] == GR_BC_PERIODIC;
    L->per_j = sc->side[GR_LEFT] == GR_BC_PERIODIC;
    for (int s = 0; s < 4; s++)
        L->open[s] = sc->side[s] == GR_BC_OPEN;
    L->ni = (int)floor(sc->height / L->a + 1e-9);
    L->nj = (int)floor(sc->width / L->h + 1e-9);
    if (L->per_j)
        L->nj &= ~1; /* lanes alternate their offset: a period is even */
    L->nw = (L->ni + 63) / 64;
    L->nthreads = par->threads;
    L->thr_p = (uint32_t)lround(par->p * 65536.0);
    L->thr_g = (uint32_t)lround(par->g * 65536.0);
    L->thr_b = (uint64_t)llround(par->b * 4294967296.0);
    L->thr_stop = (uint64_t)llround(par->stop * 4294967296.0);
    int rc = check_size(L, err);
    if (!rc)
        rc = alloc_lattice(L, err);
    if (!rc)
        rc = build_walls(L, err);
    if (!rc) {
        silo_exits(L);
        rc = lgca_init_state(L, init, rng, err);
    }
    if (rc) {
        lgca_free(L);
        return rc;
    }
    *out = L;
    return GR_OK;
}

void lgca_free(lgca *L)
{
    if (!L)
        return;
    for (int k = 0; L->seg && k < L->nseg; k++)
        free(L->seg[k]);
    free(L->seg), free(L->seg_j), free(L->lane);
    free(L->solid), free(L->valid), free(L->walls), free(L->scratch), free(L->edge), free(L->sweep);
    free(L->stop_mask);
    gr_stress_acc_free(L->stress);
    free(L);
}
