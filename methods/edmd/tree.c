/* The event queue as the slides' complete binary tree: each leaf holds
 * the earliest event of one particle's list (a copy of its slab's slot 0,
 * in an array of its own so that siblings share lines) and each inner
 * node the earlier of its children, so the next event is at the root and
 * an update costs log2 N comparisons. One of the two queues behind
 * edmd_queue (edmd_int.h); calendar.c is the other. */
#include <stdlib.h>
#include <string.h>

#include "edmd_int.h"

/* The leaves and nodes: groups of K siblings start on 64-byte lines. */
static int tree_init(gr_edmd *s)
{
    size_t lb = ((size_t)s->P * sizeof *s->lf + 63) & ~(size_t)63;
    s->lf = edmd_big_alloc(lb);
    s->node = edmd_big_alloc(lb);
    if (!s->lf || !s->node)
        return GR_ERUN;
    memset(s->node, 0, lb);
    for (int32_t i = 0; i < s->P; i++)
        s->lf[i] = (edmd_ev){EDMD_INF, 0, 0};
    return GR_OK;
}

/* Nodes hold the winner's time beside its index, so a comparison reads the
 * sibling nodes (one cache line) instead of chasing the leaves at random.
 * Ties go to the lower index, so simultaneous events pop in a fixed order.
 * K = 2 is the slides' complete binary tree (node k has children 2k, 2k+1);
 * K = 4 elides every other level of it (children 4k..4k+3): half the
 * levels, the same comparisons, half the cache lines per update. */
static inline int earlier(double ta, int32_t a, double tb, int32_t b)
{
    return ta < tb || (ta == tb && a < b);
}

static void update(gr_edmd *s, int32_t i)
{
    edmd_node *node = s->node;
    const edmd_ev *lf = s->lf;
    const int b = s->tshift, K = 1 << b;
    int32_t k = (s->P + i) >> b;
    int32_t g = (k << b) - s->P;
    int32_t w = g;
    double tw = lf[g].t;
    for (int q = 1; q < K; q++)
        if (lf[g + q].t < tw) { /* ties keep the lower index */
            tw = lf[g + q].t;
            w = g + q;
        }
    for (;;) {
        if (node[k].i == w && node[k].t == tw)
            return; /* unchanged: nothing above changes either */
        node[k].t = tw;
        node[k].i = w;
        if (k == 1)
            return;
        const edmd_node *sib = &node[k & ~(K - 1)];
        for (int q = 0; q < K; q++)
            if (earlier(sib[q].t, sib[q].i, tw, w)) {
                tw = sib[q].t;
                w = sib[q].i;
            }
        k >>= b;
    }
}

/* The path from grain i's leaf to the root is known before the update:
 * asking for all its lines at once overlaps their misses (the lower levels
 * of a large tree are never cached) with the work done before the update. */
static void tree_prefetch(const gr_edmd *s, int32_t i)
{
    const int b = s->tshift;
    __builtin_prefetch(&s->lf[i], 1);
    for (int32_t k = (s->P + i) >> b; k > 1; k >>= b)
        __builtin_prefetch(&s->node[k], 1);
}

/* The leaves are refreshed from the slabs first: after a schedule, a
 * re-sort or a load, every grain's slot 0 may be new. */
static int tree_build(gr_edmd *s)
{
    for (size_t i = 0; i < s->n; i++)
        s->lf[i] = *edmd_slab(s, (int32_t)i);
    int32_t P = s->P;
    const int b = s->tshift, K = 1 << b;
    /* level d holds nodes K^d .. 2 K^d - 1 (for K = 4 the gaps between
     * levels are unused); the last level's children are the leaves */
    int32_t first = P / K;
    for (; first >= 1; first /= K) {
        for (int32_t k = first; k < 2 * first; k++) {
            int32_t c = k << b, w;
            double tw;
            if (c >= P) {
                w = c - P;
                tw = s->lf[w].t;
                for (int q = 1; q < K; q++)
                    if (s->lf[c - P + q].t < tw) {
                        tw = s->lf[c - P + q].t;
                        w = c - P + q;
                    }
            } else {
                w = s->node[c].i;
                tw = s->node[c].t;
                for (int q = 1; q < K; q++)
                    if (earlier(s->node[c + q].t, s->node[c + q].i, tw, w)) {
                        tw = s->node[c + q].t;
                        w = s->node[c + q].i;
                    }
            }
            s->node[k].i = w;
            s->node[k].t = tw;
        }
    }
    return GR_OK;
}

/* Grain i's slot 0 may have changed: its leaf, then the path to the root. */
static int tree_update(gr_edmd *s, int32_t i)
{
    s->lf[i] = *edmd_slab(s, i);
    update(s, i);
    return GR_OK;
}

/* The root: an event time of INF when no event is left. */
static int32_t tree_top(gr_edmd *s, double *t)
{
    *t = s->node[1].t;
    return s->node[1].i;
}

/* The root is read anew at every top: nothing to do. */
static void tree_pop(gr_edmd *s) { (void)s; }

static void tree_free(gr_edmd *s)
{
    free(s->lf);
    free(s->node);
}

const edmd_queue edmd_queue_tree = {
    .init = tree_init,
    .build = tree_build,
    .update = tree_update,
    .top = tree_top,
    .pop = tree_pop,
    .prefetch = tree_prefetch,
    .free = tree_free,
    .looks_ahead = 0,
};
