#include "contacts.h"

#include <stdlib.h>

gr_contacts *gr_contacts_create(size_t cap, gr_err *err)
{
    gr_contacts *c = calloc(1, sizeof *c);
    if (!c || gr_contacts_reserve(c, cap ? cap : 16, err)) {
        if (!c)
            gr_fail(err, GR_ERUN, "out of memory for a contact network");
        gr_contacts_free(c);
        return NULL;
    }
    return c;
}

void gr_contacts_free(gr_contacts *c)
{
    if (!c)
        return;
    free(c->i), free(c->j), free(c->fn), free(c->ft);
    free(c);
}

int gr_contacts_reserve(gr_contacts *c, size_t cap, gr_err *err)
{
    if (cap <= c->cap)
        return GR_OK;
    int64_t *i = realloc(c->i, cap * sizeof *i);
    if (i)
        c->i = i;
    int64_t *j = i ? realloc(c->j, cap * sizeof *j) : NULL;
    if (j)
        c->j = j;
    double *fn = j ? realloc(c->fn, cap * sizeof *fn) : NULL;
    if (fn)
        c->fn = fn;
    double *ft = fn ? realloc(c->ft, cap * sizeof *ft) : NULL;
    if (!ft)
        return gr_fail(err, GR_ERUN, "out of memory for %zu contacts", cap);
    c->ft = ft;
    c->cap = cap;
    return GR_OK;
}

int gr_contacts_push(gr_contacts *c, int64_t i, int64_t j, double fn, double ft, gr_err *err)
{
    if (c->n == c->cap && gr_contacts_reserve(c, 2 * c->cap + 16, err))
        return err->code;
    c->i[c->n] = i, c->j[c->n] = j, c->fn[c->n] = fn, c->ft[c->n] = ft;
    c->n++;
    return GR_OK;
}
