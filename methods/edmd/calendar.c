/* The calendar queue of Paul (J. Comput. Phys. 221 (2007) 615), as an
 * alternative to the complete binary tree: one entry (t, i) per grain, its
 * earliest event, in time buckets of width w. Buckets are 64-byte lines in
 * a ring of nb; an entry b = floor(t / w) buckets ahead of the last bucket
 * loaded goes to its line if b is less than a year (nb buckets) ahead, to
 * an overflow array otherwise, which is re-read at each year's start.
 * Buckets are loaded in order into the front, a short array sorted by
 * (t, i): the same order as the tree, so both pop the same events.
 *
 * Entries are never removed: a grain whose earliest event changes gets a
 * new entry, and the old one is dropped when it reaches the front (its time
 * is no longer the grain's leaf time). An insert thus writes one line, and
 * the front holds the next events in order, so the engine can fetch their
 * grains and cells several events ahead (lookahead.c). One of the two
 * queues behind edmd_queue (edmd_int.h); tree.c is the other. */
#include <stdlib.h>
#include <string.h>

#include "edmd_int.h"

static inline double bucket_x(const gr_edmd *s, double t) { return t * s->cal_inv_w; }

static int front_reserve(gr_edmd *s, int32_t extra)
{
    if (s->fr_n + extra <= s->fr_cap)
        return GR_OK;
    if (s->fr_head > 0) { /* slide the live part to the start */
        memmove(s->fr, s->fr + s->fr_head, (size_t)(s->fr_n - s->fr_head) * sizeof *s->fr);
        s->fr_n -= s->fr_head;
        s->fr_head = 0;
        if (s->fr_n + extra <= s->fr_cap)
            return GR_OK;
    }
    int32_t cap = s->fr_cap ? 2 * s->fr_cap : 64;
    while (cap < s->fr_n + extra)
        cap *= 2;
    edmd_qe *f = realloc(s->fr, (size_t)cap * sizeof *f);
    if (!f)
        return GR_ERUN;
    s->fr = f;
    s->fr_cap = cap;
    return GR_OK;
}

static inline int qe_before(const edmd_qe *a, const edmd_qe *b)
{
    return a->t < b->t || (a->t == b->t && a->i < b->i);
}

/* Into the front, sorted: the new entry is usually among the last. */
static int front_insert(gr_edmd *s, double t, int32_t i)
{
    if (front_reserve(s, 1))
        return GR_ERUN;
    edmd_qe e = {t, i, 0};
    int32_t k = s->fr_n;
    while (k > s->fr_head && qe_before(&e, &s->fr[k - 1])) {
        s->fr[k] = s->fr[k - 1];
        k--;
    }
    s->fr[k] = e;
    s->fr_n++;
    return GR_OK;
}

static int32_t chunk_new(gr_edmd *s)
{
    if (s->ch_free >= 0) {
        int32_t c = s->ch_free;
        s->ch_free = s->chunk[c].more - 1;
        return c;
    }
    if (s->ch_n == s->ch_cap) {
        int32_t cap = s->ch_cap ? 2 * s->ch_cap : 1024;
        edmd_slot *c = realloc(s->chunk, (size_t)cap * sizeof *c);
        if (!c)
            return -1;
        s->chunk = c;
        s->ch_cap = cap;
    }
    return s->ch_n++;
}

/* Append to ring line `slot`, or to the first chunk of its chain with
 * room (chunks are addressed by index: chunk_new may move them). */
static int slot_put(gr_edmd *s, size_t slot, double t, int32_t i)
{
    edmd_slot *q = &s->cal[slot];
    int32_t qc = -1;
    while (q->n == EDMD_SLOT_N) {
        if (!q->more) {
            int32_t c = chunk_new(s);
            if (c < 0)
                return GR_ERUN;
            q = qc >= 0 ? &s->chunk[qc] : &s->cal[slot];
            q->more = c + 1;
            s->chunk[c].n = 0;
            s->chunk[c].more = 0;
        }
        qc = q->more - 1;
        q = &s->chunk[qc];
    }
    q->t[q->n] = t;
    q->i[q->n] = i;
    q->n++;
    return GR_OK;
}

/* Where an entry goes, given the last bucket loaded. */
static int place(gr_edmd *s, double t, int32_t i)
{
    double x = bucket_x(s, t);
    double bc = (double)s->cal_b;
    if (!(x >= bc + 1.0))
        return front_insert(s, t, i);
    if (x < bc + (double)s->cal_nb + 1.0) {
        int64_t b = (int64_t)x;
        s->cal_count++;
        return slot_put(s, (size_t)(b & (int64_t)(s->cal_nb - 1)), t, i);
    }
    if (s->ov_n == s->ov_cap) {
        size_t cap = s->ov_cap ? 2 * s->ov_cap : 1024;
        edmd_qe *o = realloc(s->ov, cap * sizeof *o);
        if (!o)
            return GR_ERUN;
        s->ov = o;
        s->ov_cap = cap;
    }
    s->ov[s->ov_n++] = (edmd_qe){t, i, 0};
    return GR_OK;
}

/* Pending entries whose bucket is b go to their line. */
static int pend_flush(gr_edmd *s, int all, int64_t b)
{
    int m = 0;
    for (int k = 0; k < s->pd_n; k++) {
        const edmd_pend *e = &s->pd[k];
        if (all || e->b == b) {
            if (slot_put(s, (size_t)(e->b & (int64_t)(s->cal_nb - 1)), e->t, e->i))
                return GR_ERUN;
        } else {
            s->pd[m++] = *e;
        }
    }
    s->pd_n = m;
    return GR_OK;
}

/* Entries bound for the ring are held back a few inserts, their line
 * requested meanwhile: the line of a random bucket is rarely cached. */
static int cal_push(gr_edmd *s, int32_t i)
{
    double t = edmd_slab(s, i)->t;
    if (t == EDMD_INF)
        return GR_OK;
    double x = bucket_x(s, t), bc = (double)s->cal_b;
    if (!(x >= bc + 1.0) || !(x < bc + (double)s->cal_nb + 1.0))
        return place(s, t, i);
    int64_t b = (int64_t)x;
    edmd_pf(&s->cal[b & (int64_t)(s->cal_nb - 1)]);
    if (s->pd_n == EDMD_PEND) { /* the older half goes in */
        for (int k = 0; k < EDMD_PEND / 2; k++) {
            const edmd_pend *e = &s->pd[k];
            if (slot_put(s, (size_t)(e->b & (int64_t)(s->cal_nb - 1)), e->t, e->i))
                return GR_ERUN;
        }
        memmove(s->pd, s->pd + EDMD_PEND / 2, (EDMD_PEND - EDMD_PEND / 2) * sizeof *s->pd);
        s->pd_n = EDMD_PEND - EDMD_PEND / 2;
    }
    s->pd[s->pd_n++] = (edmd_pend){t, b, i};
    s->cal_count++;
    return GR_OK;
}

/* Overflow entries now less than a year ahead go to their buckets; those of
 * grains whose earliest event has changed are dropped. */
static int migrate(gr_edmd *s)
{
    size_t m = 0;
    double lim = (double)s->cal_b + (double)s->cal_nb + 1.0;
    for (size_t k = 0; k < s->ov_n; k++) {
        edmd_qe e = s->ov[k];
        if (edmd_slab(s, e.i)->t != e.t)
            continue;
        if (bucket_x(s, e.t) < lim) {
            if (place(s, e.t, e.i))
                return GR_ERUN;
        } else {
            s->ov[m++] = e;
        }
    }
    s->ov_n = m;
    return GR_OK;
}

static int cmp_qe(const void *a, const void *b)
{
    const edmd_qe *x = a, *y = b;
    return qe_before(x, y) ? -1 : qe_before(y, x);
}

/* A width far from the present event rate (a lattice start relaxing, a
 * gas cooling, a silo filling) leaves buckets crowded or empty: every
 * eighth of a year, rebuild at the next pop if the live entries per
 * bucket are off by more than 1.6, with the width that gives
 * EDMD_CAL_FILL at the measured rate. */
static void check_width(gr_edmd *s)
{
    if (s->cal_steps < (s->cal_nb < 512 ? 64 : s->cal_nb / 8))
        return;
    double live = (double)s->cal_loaded - (double)s->cal_skipped;
    double fill = live > 0.0 ? live / (double)s->cal_steps : 0.0;
    if (fill > 1.6 * EDMD_CAL_FILL || fill < EDMD_CAL_FILL / 1.6 || s->ov_n > 2 * s->cal_nb) {
        s->cal_retune = 1;
        s->cal_w_next = fill > 0.0 ? EDMD_CAL_FILL / (fill * s->cal_inv_w) : 0.0;
    }
    s->cal_loaded = s->cal_skipped = s->cal_steps = 0;
}

/* Sort the cnt entries just loaded at the front's end: by insertion when
 * they are a few. */
static void sort_loaded(gr_edmd *s, int32_t first, int32_t cnt)
{
    if (cnt > 32) {
        qsort(s->fr + first, (size_t)cnt, sizeof *s->fr, cmp_qe);
        return;
    }
    for (int32_t k = first + 1; k < s->fr_n; k++) {
        edmd_qe e = s->fr[k];
        int32_t m = k;
        while (m > first && qe_before(&e, &s->fr[m - 1])) {
            s->fr[m] = s->fr[m - 1];
            m--;
        }
        s->fr[m] = e;
    }
}

/* Move bucket line q and its chain of chunks to the front's end (the
 * chunks go back to the free list). */
static int unload_bucket(gr_edmd *s, edmd_slot *q)
{
    int32_t cnt = q->n;
    for (int32_t c = q->more; c; c = s->chunk[c - 1].more)
        cnt += s->chunk[c - 1].n;
    if (front_reserve(s, cnt))
        return GR_ERUN;
    int32_t first = s->fr_n;
    edmd_slot *c = q;
    for (;;) {
        for (int k = 0; k < c->n; k++)
            s->fr[s->fr_n++] = (edmd_qe){c->t[k], c->i[k], 0};
        int32_t nx = c->more;
        if (c != q) {
            c->more = s->ch_free + 1;
            s->ch_free = (int32_t)(c - s->chunk);
        }
        if (!nx)
            break;
        c = &s->chunk[nx - 1];
    }
    s->cal_count -= cnt;
    s->cal_loaded += (size_t)cnt;
    q->n = 0;
    q->more = 0;
    sort_loaded(s, first, cnt);
    return GR_OK;
}

/* Load the next bucket into the front (its entries are all later than the
 * front's). */
static int load_next(gr_edmd *s)
{
    /* a year starts: the overflow's entries of the coming year go to their
     * buckets (before cal_b moves, so that the one about to load is among
     * them) */
    if (((s->cal_b + 1) & (int64_t)(s->cal_nb - 1)) == 0 && s->ov_n && migrate(s))
        return GR_ERUN;
    check_width(s);
    s->cal_b++;
    s->cal_steps++;
    if (s->pd_n && pend_flush(s, 0, s->cal_b))
        return GR_ERUN;
    edmd_slot *q = &s->cal[s->cal_b & (int64_t)(s->cal_nb - 1)];
    /* buckets are read in order, but slowly and between random lines: the
     * hardware does not see the stream */
    edmd_pf(&s->cal[(s->cal_b + 4) & (int64_t)(s->cal_nb - 1)]);
    /* and the spill line of a full bucket two ahead, whose line is in by now */
    int32_t m2 = s->cal[(s->cal_b + 2) & (int64_t)(s->cal_nb - 1)].more;
    if (m2)
        edmd_pf(&s->chunk[m2 - 1]);
    return q->n ? unload_bucket(s, q) : GR_OK;
}

static int cal_build(gr_edmd *s);

/* The grain of the earliest event, its entry at fr[fr_head]; -1 if none.
 * Also loads buckets until EDMD_CAL_AHEAD entries are ahead, as long as some
 * are in the ring. */
static int32_t front_top(gr_edmd *s)
{
    if (s->cal_retune && cal_build(s))
        return -2;
    for (;;) {
        while (s->fr_n - s->fr_head < EDMD_CAL_AHEAD && s->cal_count > 0)
            if (load_next(s))
                return -2;
        if (s->fr_head == s->fr_n) {
            if (s->ov_n == 0)
                return -1;
            /* nothing within a year: jump to the earliest overflow entry */
            double xmin = EDMD_INF;
            for (size_t k = 0; k < s->ov_n; k++)
                if (edmd_slab(s, s->ov[k].i)->t == s->ov[k].t && bucket_x(s, s->ov[k].t) < xmin)
                    xmin = bucket_x(s, s->ov[k].t);
            if (xmin == EDMD_INF) {
                s->ov_n = 0;
                return -1;
            }
            s->cal_b = (int64_t)xmin - 1;
            if (migrate(s))
                return -2;
            continue;
        }
        const edmd_qe *e = &s->fr[s->fr_head];
        if (edmd_slab(s, e->i)->t == e->t)
            return e->i;
        s->fr_head++; /* superseded */
        s->cal_skipped++;
        if (s->fr_head == s->fr_n)
            s->fr_head = s->fr_n = 0;
    }
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* The width from the event density near the present, nv q / dq with dq
 * the q-quantile of the grains' times to their next event (q = 1/8, over
 * a sample), so that a few far events (a grain at rest, a long flight)
 * do not widen the buckets; nv is the number of grains with an event. */
static double width_estimate(const gr_edmd *s, size_t nv)
{
    enum { NS = 1024 };
    double d[NS];
    size_t ns = 0, stride = nv > NS ? (s->n + NS - 1) / NS : 1;
    for (size_t i = 0; i < s->n && ns < NS; i += stride)
        if (edmd_slab(s, (int32_t)i)->t != EDMD_INF)
            d[ns++] = edmd_slab(s, (int32_t)i)->t - s->t;
    if (!ns)
        return 1.0;
    qsort(d, ns, sizeof *d, cmp_double);
    size_t k = ns / 8;
    double dq = d[k];
    for (size_t m = k + 1; !(dq > 0.0) && m < ns; m++)
        dq = d[m];
    /* (k + 1) / ns of the nv grains have their event within dq */
    return EDMD_CAL_FILL * dq / ((double)(k + 1) / (double)ns * (double)nv);
}

/* An empty ring of nb buckets of width w, its first bucket that of t0. */
static int ring_reset(gr_edmd *s, size_t nb, double w, double t0)
{
    if (nb != s->cal_nb || !s->cal) {
        free(s->cal);
        s->cal = edmd_big_alloc(nb * sizeof *s->cal);
        if (!s->cal)
            return GR_ERUN;
        s->cal_nb = nb;
    }
    memset(s->cal, 0, nb * sizeof *s->cal);
    s->ch_n = 0;
    s->ch_free = -1;
    s->cal_count = 0;
    s->ov_n = 0;
    s->fr_head = s->fr_n = 0;
    s->pd_n = 0;
    s->cal_loaded = s->cal_skipped = s->cal_steps = 0;
    s->cal_retune = 0;
    s->cal_inv_w = 1.0 / w;
    double x0 = t0 < EDMD_INF ? bucket_x(s, t0) : bucket_x(s, s->t);
    if (!(x0 < 4e18))
        x0 = 0.0;
    s->cal_b = (int64_t)x0 - 1;
    return GR_OK;
}

/* Width and size from the pending events, then every grain's entry. */
static int cal_build(gr_edmd *s)
{
    size_t nv = 0;
    for (size_t i = 0; i < s->n; i++)
        nv += edmd_slab(s, (int32_t)i)->t != EDMD_INF;
    double w = width_estimate(s, nv);
    if (s->cal_w_next > 0.0 && isfinite(s->cal_w_next))
        w = s->cal_w_next;
    s->cal_w_next = 0.0;
    if (!(w > 0.0) || !isfinite(w))
        w = 1.0;
    if (w < 1e-300)
        w = 1e-300;
    double tmin = EDMD_INF;
    for (size_t i = 0; i < s->n; i++)
        tmin = edmd_slab(s, (int32_t)i)->t < tmin ? edmd_slab(s, (int32_t)i)->t : tmin;
    size_t nb = 16;
    while (nb < nv / EDMD_CAL_SLOTDIV)
        nb *= 2;
    if (ring_reset(s, nb, w, tmin))
        return GR_ERUN;
    for (size_t i = 0; i < s->n; i++)
        if (cal_push(s, (int32_t)i))
            return GR_ERUN;
    return GR_OK;
}

static void cal_free(gr_edmd *s)
{
    free(s->cal);
    free(s->chunk);
    free(s->fr);
    free(s->ov);
}

/* Everything is allocated by the first build. */
static int cal_init(gr_edmd *s)
{
    (void)s;
    return GR_OK;
}

static int32_t cal_top(gr_edmd *s, double *t)
{
    int32_t i = front_top(s);
    *t = i >= 0 ? edmd_slab(s, i)->t : EDMD_INF;
    return i;
}

/* The top entry is consumed (the grain's next entry is queued by its
 * update); the coming events' lines are requested. */
static void cal_pop(gr_edmd *s)
{
    s->fr_head++;
    if (s->P >= EDMD_PREFETCH_P)
        edmd_lookahead(s);
}

/* The look-ahead has requested the lines an update reads. */
static void cal_prefetch(const gr_edmd *s, int32_t i)
{
    (void)s;
    (void)i;
}

const edmd_queue edmd_queue_calendar = {
    .init = cal_init,
    .build = cal_build,
    .update = cal_push,
    .top = cal_top,
    .pop = cal_pop,
    .prefetch = cal_prefetch,
    .free = cal_free,
    .looks_ahead = 1,
};
