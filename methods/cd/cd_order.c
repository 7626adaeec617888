/* The visiting order of the sweeps. Bottom layer: calls no other file of
 * the backend. */
#include <stdlib.h>

#include "cd_int.h"

static int by_height(const void *a, const void *b)
{
    const gr_cd_key *x = a, *y = b;
    if (x->y != y->y)
        return x->y > y->y ? -1 : 1;
    return x->k < y->k ? -1 : x->k > y->k;
}

/* Contacts by the height of their contact point, top first; ties by
 * position in the list, so that the order does not depend on qsort's. */
static void height_order(gr_cd *d, size_t n)
{
    const double *y = d->p->y, *r = d->p->radius;
    for (size_t k = 0; k < n; k++) {
        const gr_cd_contact *c = &d->cur.c[k];
        d->key[k] = (gr_cd_key){y[c->i] - r[c->i] * c->ny, k};
    }
    qsort(d->key, n, sizeof *d->key, by_height);
    for (size_t k = 0; k < n; k++)
        d->perm[k] = d->key[k].k;
}

static void reverse(size_t *o, size_t n)
{
    for (size_t k = 0; k < n / 2; k++) {
        size_t t = o[k];
        o[k] = o[n - 1 - k], o[n - 1 - k] = t;
    }
}

void gr_cd_visit_order(gr_cd *d, size_t n, long s)
{
    size_t *o = d->perm;
    if (d->par.order == GR_CD_HEIGHT) {
        if (s == 1)
            height_order(d, n);
        else
            reverse(o, n);
        return;
    }
    if (d->par.order == GR_CD_RANDOM) {
        for (size_t k = 0; k < n; k++)
            o[k] = (size_t)gr_rng_below(d->order_rng, n);
        return;
    }
    for (size_t k = 0; k < n; k++)
        o[k] = k;
    if (d->par.order == GR_CD_SYMMETRIC && s % 2 == 0)
        reverse(o, n);
    if (d->par.order == GR_CD_SHUFFLED) {
        for (size_t k = n; k > 1; k--) {
            size_t m = (size_t)gr_rng_below(d->order_rng, k), t = o[k - 1];
            o[k - 1] = o[m], o[m] = t;
        }
    }
}
