/* Spatial re-sorting: grains renumbered along a Morton (Z) curve over the
 * cells, so that a grain's neighbours, their events and their queue
 * entries sit close in memory. Large systems lose that order as grains
 * diffuse, and the cost per event then grows with N through cache misses;
 * a re-sort every few tens of collisions per grain keeps it flat. The
 * event lists move with the grains, so a sorted run executes the same
 * events as an unsorted one (up to the order of exactly simultaneous
 * events of different grains, which follows the numbering). */
#include <stdlib.h>
#include <string.h>

#include "edmd_int.h"

typedef struct {
    uint64_t key;
    int32_t c;
} cell_key;

static int cmp_key(const void *a, const void *b)
{
    uint64_t x = ((const cell_key *)a)->key, y = ((const cell_key *)b)->key;
    return x < y ? -1 : x > y;
}

static uint64_t spread(uint32_t v)
{
    uint64_t x = v;
    x = (x | (x << 16)) & 0x0000ffff0000ffffULL;
    x = (x | (x << 8)) & 0x00ff00ff00ff00ffULL;
    x = (x | (x << 4)) & 0x0f0f0f0f0f0f0f0fULL;
    x = (x | (x << 2)) & 0x3333333333333333ULL;
    x = (x | (x << 1)) & 0x5555555555555555ULL;
    return x;
}

int edmd_sort_setup(gr_edmd *s, gr_err *err)
{
    size_t nc = (size_t)s->nx * (size_t)s->ny;
    cell_key *k = malloc(nc * sizeof *k);
    s->corder = malloc(nc * sizeof *s->corder);
    if (!k || !s->corder) {
        free(k);
        return gr_fail(err, GR_ERUN, "edmd: out of memory for the cell order");
    }
    for (size_t c = 0; c < nc; c++) {
        uint32_t ix = (uint32_t)(c % (size_t)s->nx), iy = (uint32_t)(c / (size_t)s->nx);
        k[c].key = spread(ix) | (spread(iy) << 1);
        k[c].c = (int32_t)c;
    }
    qsort(k, nc, sizeof *k, cmp_key);
    for (size_t c = 0; c < nc; c++)
        s->corder[c] = k[c].c;
    free(k);
    return GR_OK;
}

#define PERMUTE(arr, T)                           \
    do {                                          \
        T *tmp_ = (T *)buf;                       \
        for (size_t k_ = 0; k_ < n; k_++)         \
            tmp_[k_] = (arr)[perm[k_]];           \
        memcpy((arr), tmp_, n * sizeof(T));       \
    } while (0)

/* The sort's room: allocated at the first sort, the slabs again when
 * they have grown. */
static int sort_room(gr_edmd *s)
{
    size_t n = s->n, nev = n * (size_t)s->ecap;
    if (!s->sort_p) {
        s->sort_p = edmd_big_alloc(n * sizeof *s->sort_p);
        s->sort_perm = malloc(n * sizeof *s->sort_perm);
        s->sort_inv = malloc(n * sizeof *s->sort_inv);
        s->sort_buf = edmd_big_alloc(n * sizeof(double)); /* the widest per-grain field */
        if (!s->sort_p || !s->sort_perm || !s->sort_inv || !s->sort_buf)
            return GR_ERUN;
    }
    if (s->sort_ev_n != nev) {
        free(s->sort_ev);
        s->sort_ev_n = 0;
        s->sort_ev = edmd_ev_alloc(nev);
        if (!s->sort_ev)
            return GR_ERUN;
        s->sort_ev_n = nev;
    }
    return GR_OK;
}

/* The event lists move with their grains, partners renamed (predicting
 * them again would cost a full schedule, a second or so at N = 1e6, and
 * could round some times differently); the queue is rebuilt from them. */
static void move_slabs(gr_edmd *s, const int32_t *perm, const int32_t *inv)
{
    size_t n = s->n, cap = (size_t)s->ecap;
    edmd_ev *ev = s->sort_ev;
    for (size_t j = 0; j < n; j++) {
        const edmd_ev *src = s->ev + (size_t)perm[j] * cap;
        edmd_ev *dst = ev + j * cap;
        dst[0] = (edmd_ev){EDMD_INF, 0, 0}; /* if empty */
        for (int32_t k = 0; k < s->p[j].nev; k++) {
            dst[k] = src[k];
            if (dst[k].partner >= 0)
                dst[k].partner = inv[dst[k].partner];
        }
    }
    s->sort_ev = s->ev;
    s->ev = ev;
}

int edmd_sort(gr_edmd *s, gr_err *err)
{
    size_t n = s->n, nc = (size_t)s->nx * (size_t)s->ny;
    if (sort_room(s))
        return gr_fail(err, GR_ERUN, "edmd: out of memory while sorting %zu grains", n);
    int32_t *perm = s->sort_perm, *inv = s->sort_inv;
    void *buf = s->sort_buf;
    size_t k = 0;
    for (size_t q = 0; q < nc; q++)
        for (int32_t i = s->chead[s->corder[q]]; i >= 0; i = s->p[i].cnext)
            perm[k++] = i;
    for (size_t i = 0; i < n; i++) /* grains that left, in their order */
        if (s->gone[i])
            perm[k++] = (int32_t)i;
    for (size_t j = 0; j < n; j++)
        inv[perm[j]] = (int32_t)j;
    edmd_p *np = s->sort_p;
    for (size_t j = 0; j < n; j++)
        np[j] = s->p[perm[j]];
    s->sort_p = s->p;
    s->p = np;
    PERMUTE(s->w, double);
    PERMUTE(s->m, double);
    PERMUTE(s->inertia, double);
    PERMUTE(s->tlast, double);
    PERMUTE(s->tacc, double);
    PERMUTE(s->id, int64_t);
    PERMUTE(s->species, int32_t);
    PERMUTE(s->gone, uint8_t);
    for (size_t j = 0; j < n; j++)
        s->order[j] = (size_t)inv[s->order[j]];
    /* cell lists in the new numbering, each in increasing index */
    for (size_t c = 0; c < nc; c++)
        s->chead[c] = -1;
    for (size_t j = n; j-- > 0;) {
        edmd_p *p = &s->p[j];
        if (s->gone[j])
            continue;
        p->cnext = s->chead[p->cell];
        s->chead[p->cell] = (int32_t)j;
    }
    move_slabs(s, perm, inv);
    s->last_sort = s->steps;
    if (s->q->build(s))
        return gr_fail(err, GR_ERUN, "edmd: out of memory for the event queue");
    return GR_OK;
}
