/* Event calendar of the slides: every particle owns the list of the events
 * it predicted; each leaf of a complete binary tree holds the earliest event
 * of one particle's list and each inner node the earlier of its two
 * children, so the next event is at the root and an update costs log2 N
 * comparisons. A particle's list is a slab of a fixed capacity in one array
 * (not linked nodes scattered in a pool): clearing it is O(1) and scanning
 * it touches one or two cache lines. The earliest event is kept in slot 0.
 * A full slab first drops its stale events; if still full, every slab
 * doubles. The leaves (a copy of slot 0 in an array of their own, so that
 * siblings share lines) are kept for the tree only. */
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

#include "edmd_int.h"

/* Events land on random grains, so at large N nearly every access to the
 * grain, slab, leaf and tree arrays also misses the TLB with 4 KiB pages
 * (a 10^6-grain run spans some 250 MB). Arrays of 2 MiB or more are
 * aligned to 2 MiB and flagged for transparent huge pages (where the kernel
 * has them in madvise mode, as here, this is what turns them on; a refusal
 * is harmless). Smaller arrays start on 64-byte lines. */
void *edmd_big_alloc(size_t bytes)
{
    const size_t huge = (size_t)2 << 20;
    if (bytes < huge)
        return aligned_alloc(64, (bytes + 63) & ~(size_t)63);
    bytes = (bytes + huge - 1) & ~(huge - 1);
    void *m = aligned_alloc(huge, bytes);
#ifdef MADV_HUGEPAGE
    if (m)
        (void)madvise(m, bytes, MADV_HUGEPAGE);
#endif
    return m;
}

/* Slabs start on 64-byte lines (a slab of 8 events is two lines). */
edmd_ev *edmd_ev_alloc(size_t count)
{
    return edmd_big_alloc(count * sizeof(edmd_ev));
}

int edmd_events_init(gr_edmd *s, gr_err *err)
{
    int K = 1 << s->tshift;
    int32_t P = K; /* at least one full group of leaves */
    while ((size_t)P < s->n)
        P *= K;
    s->P = P;
    /* groups of K siblings start on 64-byte lines */
    size_t lb = ((size_t)P * sizeof *s->lf + 63) & ~(size_t)63;
    s->lf = edmd_big_alloc(lb);
    if (!s->use_cal) {
        s->node = edmd_big_alloc(lb);
        if (s->node)
            memset(s->node, 0, lb);
    }
    /* Slabs double when some grain holds more valid events than fit. A
     * large system gets there early (at N = 1e6 within 2 collisions per
     * grain at packing fraction 0.6, 21 at 0.3), and doubling then stalls
     * the run for the copy into fresh memory (0.7 s at N = 1e6): large
     * systems start at the size they would reach. */
    s->ecap = s->n >= EDMD_PREFETCH_P ? 16 : 8;
    s->ev = edmd_ev_alloc(s->n * (size_t)s->ecap);
    if (!s->lf || (!s->use_cal && !s->node) || !s->ev)
        return gr_fail(err, GR_ERUN, "edmd: out of memory for the event calendar of %zu grains", s->n);
    for (int32_t i = 0; i < P; i++)
        s->lf[i] = (edmd_ev){EDMD_INF, 0, 0};
    for (size_t i = 0; i < s->n; i++) {
        s->p[i].nev = 0;
        edmd_slab(s, (int32_t)i)->t = EDMD_INF;
    }
    if (s->use_cal)
        return edmd_cal_build(s) ? gr_fail(err, GR_ERUN, "edmd: out of memory for the calendar") : GR_OK;
    edmd_tree_build(s);
    return GR_OK;
}

/* Double every grain's slab; slots keep their numbers. */
static int grow(gr_edmd *s)
{
    size_t n = s->n, c = (size_t)s->ecap;
    if (c >= 16384) /* slots must fit the 16-bit counters */
        return GR_ERUN;
    edmd_ev *ev = edmd_ev_alloc(n * 2 * c);
    if (!ev)
        return GR_ERUN;
    for (size_t i = 0; i < n; i++) /* slot 0 even when empty: its INF */
        memcpy(ev + i * 2 * c, s->ev + i * c, (size_t)(s->p[i].nev > 0 ? s->p[i].nev : 1) * sizeof *ev);
    free(s->ev);
    s->ev = ev;
    s->ecap = (int32_t)(2 * c);
    return GR_OK;
}

/* The earliest event (the first of equal ones) to slot 0. */
static void rescan(gr_edmd *s, int32_t i)
{
    edmd_ev *v = edmd_slab(s, i);
    int32_t nev = s->p[i].nev;
    if (nev == 0) {
        v[0] = (edmd_ev){EDMD_INF, 0, 0};
    } else {
        int32_t be = 0;
        for (int32_t k = 1; k < nev; k++)
            if (v[k].t < v[be].t)
                be = k;
        if (be) {
            edmd_ev e = v[0];
            v[0] = v[be];
            v[be] = e;
        }
    }
    if (!s->use_cal)
        s->lf[i] = v[0];
}

/* Drop the pair events of a full slab whose partner has changed state
 * since (they would be dropped when popped anyway). */
static void compact(gr_edmd *s, int32_t i)
{
    edmd_ev *v = edmd_slab(s, i);
    int32_t m = 0;
    for (int32_t k = 0; k < s->p[i].nev; k++) {
        if (v[k].partner >= 0 && s->p[v[k].partner].ncol != v[k].pncol) {
            s->cnt.stale++;
            continue;
        }
        v[m++] = v[k];
    }
    s->p[i].nev = (int16_t)m;
    rescan(s, i);
}

int edmd_ev_push(gr_edmd *s, int32_t i, double t, int kind, int32_t partner, uint32_t pncol)
{
    edmd_p *p = &s->p[i];
    if (p->nev == s->ecap) {
        compact(s, i);
        if (p->nev == s->ecap && grow(s))
            return GR_ERUN;
    }
    int32_t k = p->nev++;
    edmd_ev *v = edmd_slab(s, i);
    edmd_ev e = {t, kind == EV_PAIR ? partner : -1 - (partner << 2 | kind), pncol};
    if (k > 0 && !(t < v[0].t)) { /* an empty slab's slot 0 is INF */
        v[k] = e;
        return GR_OK;
    }
    if (k > 0)
        v[k] = v[0];
    v[0] = e;
    if (!s->use_cal)
        s->lf[i] = e;
    return GR_OK;
}

void edmd_list_clear(gr_edmd *s, int32_t i)
{
    s->p[i].nev = 0;
    edmd_slab(s, i)->t = EDMD_INF;
    if (!s->use_cal)
        s->lf[i].t = EDMD_INF;
}

/* Remove slot k (the last slot moves into it) and find the new earliest. */
void edmd_list_remove(gr_edmd *s, int32_t i, int32_t k)
{
    edmd_ev *v = edmd_slab(s, i);
    int32_t last = --s->p[i].nev;
    v[k] = v[last];
    rescan(s, i);
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

void edmd_tree_update(gr_edmd *s, int32_t i)
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
void edmd_tree_prefetch(const gr_edmd *s, int32_t i)
{
    const int b = s->tshift;
    __builtin_prefetch(&s->lf[i], 1);
    for (int32_t k = (s->P + i) >> b; k > 1; k >>= b)
        __builtin_prefetch(&s->node[k], 1);
}

void edmd_tree_build(gr_edmd *s)
{
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
}
