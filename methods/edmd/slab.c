/* Every particle owns the list of the events it predicted (the slides'
 * scheme). A particle's list is a slab of a fixed capacity in one array
 * (not linked nodes scattered in a pool): clearing it is O(1) and scanning
 * it touches one or two cache lines. The earliest event is kept in slot 0,
 * where the event queue (tree.c or calendar.c) reads it: the lists know
 * nothing of the queue, the engine tells it when a slot 0 may have
 * changed. A full slab first drops its stale events; if still full, every
 * slab doubles. */
#include <stdlib.h>
#include <string.h>

#include "edmd_int.h"

int edmd_events_init(gr_edmd *s, gr_err *err)
{
    int K = 1 << s->tshift;
    int32_t P = K; /* at least one full group of leaves */
    while ((size_t)P < s->n)
        P *= K;
    s->P = P;
    /* Slabs double when some grain holds more valid events than fit. A
     * large system gets there early (at N = 1e6 within 2 collisions per
     * grain at packing fraction 0.6, 21 at 0.3), and doubling then stalls
     * the run for the copy into fresh memory (0.7 s at N = 1e6): large
     * systems start at the size they would reach. */
    s->ecap = s->n >= EDMD_PREFETCH_P ? 16 : 8;
    s->ev = edmd_ev_alloc(s->n * (size_t)s->ecap);
    if (!s->ev)
        return gr_fail(err, GR_ERUN, "edmd: out of memory for the event lists of %zu grains", s->n);
    for (size_t i = 0; i < s->n; i++) {
        s->p[i].nev = 0;
        *edmd_slab(s, (int32_t)i) = (edmd_ev){EDMD_INF, 0, 0};
    }
    if (s->q->init(s) || s->q->build(s))
        return gr_fail(err, GR_ERUN, "edmd: out of memory for the event queue of %zu grains", s->n);
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
        return;
    }
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
    return GR_OK;
}

void edmd_list_clear(gr_edmd *s, int32_t i)
{
    s->p[i].nev = 0;
    edmd_slab(s, i)->t = EDMD_INF;
}

/* Remove slot k (the last slot moves into it) and find the new earliest. */
void edmd_list_remove(gr_edmd *s, int32_t i, int32_t k)
{
    edmd_ev *v = edmd_slab(s, i);
    int32_t last = --s->p[i].nev;
    v[k] = v[last];
    rescan(s, i);
}
