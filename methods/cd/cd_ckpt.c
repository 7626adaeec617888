/* Save and load the full state: grains in id order, counters, the window,
 * and the last step's contacts with their impulses (the warm start of the
 * next step, without which a restart would not continue bit for bit).
 * Calls no other file of the backend. */
#include <stdlib.h>

#include "cd_int.h"

enum { M_N, M_STEP, M_OUTFLOW, M_LOST, M_NONCONV, M_SWEEPS, M_GATES, M_ACTIVE, M_SLIDING, M_NC, M_COUNT };
enum { R_T, R_RES, R_OVL, R_WIMP, R_WTIME, R_COUNT };

static int save_contacts(const gr_cd *d, gr_ckpt *ck, gr_err *err)
{
    size_t nc = d->prev.n, m = nc ? nc : 1;
    int64_t *key = calloc(2 * m, sizeof *key);
    double *r = calloc(2 * m, sizeof *r);
    int rc = key && r ? GR_OK : gr_fail(err, GR_ERUN, "out of memory");
    for (size_t k = 0; k < nc && !rc; k++) {
        key[2 * k] = d->prev.c[k].i, key[2 * k + 1] = d->prev.c[k].j;
        r[2 * k] = d->prev.c[k].rn, r[2 * k + 1] = d->prev.c[k].rt;
    }
    if (!rc && (gr_ckpt_put_i64(ck, "cd_contact_ids", key, 2 * nc, err) ||
                gr_ckpt_put_f64(ck, "cd_contact_impulses", r, 2 * nc, err)))
        rc = err->code;
    free(key), free(r);
    return rc;
}

int gr_cd_save(const gr_cd *d, gr_ckpt *ck, gr_err *err)
{
    int64_t meta[M_COUNT] = {
        [M_N] = (int64_t)d->n, [M_STEP] = (int64_t)d->step, [M_OUTFLOW] = (int64_t)d->outflow,
        [M_LOST] = (int64_t)d->lost, [M_NONCONV] = (int64_t)d->nonconv, [M_SWEEPS] = (int64_t)d->sweeps,
        [M_GATES] = d->gates_open, [M_ACTIVE] = (int64_t)d->last_active,
        [M_SLIDING] = (int64_t)d->last_sliding, [M_NC] = (int64_t)d->prev.n};
    double real[R_COUNT] = {[R_T] = d->t, [R_RES] = d->last_residual, [R_OVL] = d->max_ovl,
                            [R_WIMP] = d->wall_impulse, [R_WTIME] = d->wall_time};
    const gr_particles *p = d->p;
    size_t n = d->n;
    if (gr_ckpt_put_i64(ck, "cd_meta", meta, M_COUNT, err) || gr_ckpt_put_f64(ck, "cd_real", real, R_COUNT, err) ||
        gr_ckpt_put_f64(ck, "cd_x", p->x, n, err) || gr_ckpt_put_f64(ck, "cd_y", p->y, n, err) ||
        gr_ckpt_put_f64(ck, "cd_vx", p->vx, n, err) || gr_ckpt_put_f64(ck, "cd_vy", p->vy, n, err) ||
        gr_ckpt_put_f64(ck, "cd_omega", p->omega, n, err) || gr_ckpt_put_u32(ck, "cd_flags", p->flags, n, err))
        return err->code;
    return save_contacts(d, ck, err);
}

static int load_contacts(gr_cd *d, gr_ckpt *ck, size_t nc, gr_err *err)
{
    size_t m = nc ? nc : 1;
    gr_cd_contact *c = calloc(m, sizeof *c);
    int64_t *key = calloc(2 * m, sizeof *key);
    double *r = calloc(2 * m, sizeof *r);
    int rc = c && key && r ? GR_OK : gr_fail(err, GR_ERUN, "out of memory");
    if (!rc && (gr_ckpt_get_i64(ck, "cd_contact_ids", key, 2 * nc, err) ||
                gr_ckpt_get_f64(ck, "cd_contact_impulses", r, 2 * nc, err)))
        rc = err->code;
    for (size_t k = 0; k < nc && !rc; k++)
        c[k] = (gr_cd_contact){.i = key[2 * k], .j = key[2 * k + 1], .rn = r[2 * k], .rt = r[2 * k + 1]};
    free(key), free(r);
    if (rc) {
        free(c);
        return rc;
    }
    free(d->prev.c);
    d->prev = (gr_cd_list){c, nc, m};
    return GR_OK;
}

int gr_cd_load(gr_cd *d, gr_ckpt *ck, gr_err *err)
{
    int64_t meta[M_COUNT];
    double real[R_COUNT];
    if (gr_ckpt_get_i64(ck, "cd_meta", meta, M_COUNT, err) || gr_ckpt_get_f64(ck, "cd_real", real, R_COUNT, err))
        return err->code;
    if (meta[M_N] != (int64_t)d->n)
        return gr_fail(err, GR_EINPUT, "checkpoint: %lld grains, the scene gives %zu", (long long)meta[M_N], d->n);
    gr_particles *p = d->p;
    size_t n = d->n;
    if (gr_ckpt_get_f64(ck, "cd_x", p->x, n, err) || gr_ckpt_get_f64(ck, "cd_y", p->y, n, err) ||
        gr_ckpt_get_f64(ck, "cd_vx", p->vx, n, err) || gr_ckpt_get_f64(ck, "cd_vy", p->vy, n, err) ||
        gr_ckpt_get_f64(ck, "cd_omega", p->omega, n, err) || gr_ckpt_get_u32(ck, "cd_flags", p->flags, n, err) ||
        load_contacts(d, ck, (size_t)meta[M_NC], err))
        return err->code;
    for (size_t i = 0; i < n; i++)
        d->skip[i] = (p->flags[i] & GR_PF_GONE) != 0;
    d->step = (uint64_t)meta[M_STEP], d->outflow = (uint64_t)meta[M_OUTFLOW], d->lost = (uint64_t)meta[M_LOST];
    d->nonconv = (uint64_t)meta[M_NONCONV], d->sweeps = (uint64_t)meta[M_SWEEPS];
    d->gates_open = (int)meta[M_GATES];
    d->last_active = (size_t)meta[M_ACTIVE], d->last_sliding = (size_t)meta[M_SLIDING];
    d->t = real[R_T], d->last_residual = real[R_RES], d->max_ovl = real[R_OVL];
    d->wall_impulse = real[R_WIMP], d->wall_time = real[R_WTIME];
    return GR_OK;
}
