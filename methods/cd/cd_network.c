/* The contact network of the last step: each contact's impulse over the
 * step, as a force (impulse / dt), for `[run] contacts = yes`. */
#include "cd_int.h"

int gr_cd_contacts(const gr_cd *d, gr_contacts *out, gr_err *err)
{
    out->n = 0;
    const double inv_dt = 1.0 / d->par.dt;
    for (size_t k = 0; k < d->prev.n; k++) {
        const gr_cd_contact *c = &d->prev.c[k];
        if (c->rn == 0.0 && c->rt == 0.0)
            continue; /* open: detected within the gap margin, no force */
        int64_t i = d->p->id[c->i];
        int64_t j = (size_t)c->j < d->n ? d->p->id[c->j] : -1 - (int64_t)((size_t)c->j - d->n);
        if (gr_contacts_push(out, i, j, c->rn * inv_dt, c->rt * inv_dt, err))
            return err->code;
    }
    return GR_OK;
}
