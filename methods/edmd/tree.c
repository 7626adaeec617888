/* Event calendar of the slides: every particle owns a linked list of the
 * events it predicted; each leaf of a complete binary tree holds the
 * earliest event of one particle's list and each inner node the earlier of
 * its two children, so the next event is at the root and an update costs
 * log2 N comparisons. Events live in one pool with a free list (indices,
 * not pointers, so the pool can grow and be checkpointed as bytes). */
#include <stdlib.h>
#include <string.h>

#include "edmd_int.h"

int edmd_events_init(gr_edmd *s, gr_err *err)
{
    int32_t P = 2; /* at least two leaves: every leaf has a sibling */
    while ((size_t)P < s->n)
        P *= 2;
    s->P = P;
    s->tmin = malloc((size_t)P * sizeof *s->tmin);
    s->emin = malloc((size_t)P * sizeof *s->emin);
    s->node = malloc((size_t)(2 * P) * sizeof *s->node);
    s->ncap = (int32_t)(16 * s->n + 64);
    s->ev = malloc((size_t)s->ncap * sizeof *s->ev);
    if (!s->tmin || !s->emin || !s->node || !s->ev)
        return gr_fail(err, GR_ERUN, "edmd: out of memory for the event calendar of %zu grains", s->n);
    for (int32_t i = 0; i < P; i++) {
        s->tmin[i] = EDMD_INF;
        s->emin[i] = -1;
    }
    for (int32_t e = 0; e < s->ncap; e++)
        s->ev[e].next = e + 1 < s->ncap ? e + 1 : -1;
    s->freelist = 0;
    s->nfree = s->ncap;
    for (size_t i = 0; i < s->n; i++)
        s->p[i].head = -1;
    edmd_tree_build(s);
    return GR_OK;
}

static int grow(gr_edmd *s)
{
    int32_t old = s->ncap;
    if (old > INT32_MAX / 2)
        return GR_ERUN;
    int32_t cap = old * 2;
    edmd_ev *ev = realloc(s->ev, (size_t)cap * sizeof *ev);
    if (!ev)
        return GR_ERUN;
    s->ev = ev;
    for (int32_t e = old; e < cap; e++)
        ev[e].next = e + 1 < cap ? e + 1 : s->freelist;
    s->freelist = old;
    s->nfree += cap - old;
    s->ncap = cap;
    return GR_OK;
}

int edmd_ev_push(gr_edmd *s, int32_t i, double t, int kind, int32_t partner, uint32_t pncol)
{
    if (s->freelist < 0 && grow(s))
        return GR_ERUN;
    int32_t e = s->freelist;
    edmd_ev *v = &s->ev[e];
    s->freelist = v->next;
    s->nfree--;
    v->t = t;
    v->kind = kind;
    v->partner = partner;
    v->pncol = pncol;
    v->next = s->p[i].head;
    s->p[i].head = e;
    if (t < s->tmin[i]) {
        s->tmin[i] = t;
        s->emin[i] = e;
    }
    return GR_OK;
}

void edmd_list_clear(gr_edmd *s, int32_t i)
{
    int32_t e = s->p[i].head;
    if (e >= 0) {
        int32_t last = e, k = 1;
        while (s->ev[last].next >= 0) {
            last = s->ev[last].next;
            k++;
        }
        s->ev[last].next = s->freelist;
        s->freelist = e;
        s->nfree += k;
    }
    s->p[i].head = -1;
    s->tmin[i] = EDMD_INF;
    s->emin[i] = -1;
}

/* Unlink event e from i's list and find the new earliest in the same pass.
 * Ties keep the event nearest the head, i.e. the latest predicted. */
void edmd_list_remove(gr_edmd *s, int32_t i, int32_t e)
{
    int32_t *link = &s->p[i].head;
    double best = EDMD_INF;
    int32_t be = -1;
    while (*link >= 0) {
        int32_t k = *link;
        if (k == e) {
            *link = s->ev[k].next;
            s->ev[k].next = s->freelist;
            s->freelist = k;
            s->nfree++;
            continue;
        }
        if (s->ev[k].t < best) {
            best = s->ev[k].t;
            be = k;
        }
        link = &s->ev[k].next;
    }
    s->tmin[i] = best;
    s->emin[i] = be;
}

/* Earlier of two particles' minima; ties go to the lower index, so the
 * order of simultaneous events is deterministic. */
static inline int32_t better(const double *tmin, int32_t a, int32_t b)
{
    return tmin[b] < tmin[a] || (tmin[b] == tmin[a] && b < a) ? b : a;
}

void edmd_tree_update(gr_edmd *s, int32_t i)
{
    int32_t P = s->P;
    int32_t *node = s->node;
    const double *tmin = s->tmin;
    int32_t k = (P + i) >> 1;
    int32_t c = i ^ 1; /* sibling leaf */
    int32_t w = better(tmin, i, c);
    node[k] = w;
    while (k > 1) {
        int32_t sib = node[k ^ 1];
        int32_t nw = (k & 1) ? better(tmin, sib, w) : better(tmin, w, sib);
        k >>= 1;
        w = nw;
        node[k] = w;
    }
}

void edmd_tree_build(gr_edmd *s)
{
    int32_t P = s->P;
    for (int32_t k = P - 1; k >= 1; k--) {
        int32_t a, b;
        if (2 * k >= P) {
            a = 2 * k - P;
            b = 2 * k + 1 - P;
        } else {
            a = s->node[2 * k];
            b = s->node[2 * k + 1];
        }
        s->node[k] = better(s->tmin, a, b);
    }
}
