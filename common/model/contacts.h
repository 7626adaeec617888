/* A contact network: one row per contact that carries a force, as the
 * methods that resolve contacts give it (docs/output-format.md, contacts/),
 * for force chains and stress. */
#ifndef GR_CONTACTS_H
#define GR_CONTACTS_H

#include <stddef.h>
#include <stdint.h>

#include "err.h"

typedef struct {
    size_t n, cap;
    int64_t *i, *j;   /* grain ids; j = -1 - k for wall k of the method's wall list */
    double *fn, *ft;  /* normal and tangential force on grain i (t = n rotated by +90 degrees) */
} gr_contacts;

gr_contacts *gr_contacts_create(size_t cap, gr_err *err);
void gr_contacts_free(gr_contacts *c);
int gr_contacts_reserve(gr_contacts *c, size_t cap, gr_err *err);
/* Append one row (grows as needed). */
int gr_contacts_push(gr_contacts *c, int64_t i, int64_t j, double fn, double ft, gr_err *err);

#endif
