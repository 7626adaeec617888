/* The fillings of silo-flow and silo-start (silo_fill.h): fill and settle
 * with an orifice closed, once per realisation. */
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "parts.h"
#include "progress.h"
#include "silo_fill.h"

/* The filling's parameters: a part with this key is reused by every
 * orifice, by both commands and by a later run. */
static int fill_key(const silo_fills *f, size_t r, char *buf, size_t n)
{
    const silo_cfg *b = f->base;
    int k = snprintf(buf, n, "silo-fill 3 n=%ld W=%.17g H=%.17g base=%.17g hopper=%d outlet=%.17g Dfill=%.17g seed=%llu method=%s dt=%.17g ke=%.17g",
                     b->n, b->width, b->height, b->base, b->hopper, b->outlet, f->orifice, (unsigned long long)(f->seed + r),
                     b->method->name, b->dt, b->ke_tol);
    silo_key_params(b, buf, n);
    return k;
}

void silo_fill_label(size_t unit, void *ctx, char *buf, size_t n)
{
    (void)ctx;
    snprintf(buf, n, "r%02zu", unit);
}

void silo_fill_key(size_t unit, void *ctx, char *buf, size_t n)
{
    fill_key(ctx, unit, buf, n);
}

int silo_fill_unit(size_t unit, const char *part, const char *key, void *ctx, volatile double *progress, gr_err *err)
{
    const silo_fills *f = ctx;
    silo_cfg cfg = *f->base;
    cfg.orifice = f->orifice;
    cfg.seed = f->seed + unit;
    silo_settled set;
    double w0 = gr_wall_seconds(), c0 = (double)clock() / CLOCKS_PER_SEC;
    int rc = silo_fill(&cfg, &set, progress, err);
    if (rc)
        return rc;
    double cost[5] = {gr_wall_seconds() - w0, (double)clock() / CLOCKS_PER_SEC - c0, 0, 0, 0};
    gr_ckpt *ck = gr_ckpt_create(part, err);
    rc = ck ? GR_OK : err->code;
    if (!rc) rc = gr_ckpt_put_bytes(ck, "key", key, strlen(key), err);
    if (!rc) rc = exp_put_particles(ck, "settled", set.p, err);
    if (!rc) rc = exp_put_scalar(ck, "t_settle", set.t_settle, err);
    if (!rc && unit == 0 && set.filling) rc = exp_put_particles(ck, "filling", set.filling, err);
    if (!rc && unit == 0 && set.filling) rc = exp_put_scalar(ck, "t_filling", set.t_filling, err);
    if (!rc) rc = gr_ckpt_put_f64(ck, "cost", cost, 5, err);
    if (!rc && set.ntrace) rc = gr_ckpt_put_f64(ck, "trace", set.trace, set.ntrace * SILO_TRACE, err);
    if (rc && ck)
        gr_ckpt_discard(ck);
    else if (!rc)
        rc = gr_ckpt_close(ck, err);
    silo_settled_free(&set);
    return rc;
}

int silo_fill_path(const silo_fills *f, size_t r, char *path, size_t n)
{
    char label[32], key[2048];
    silo_fill_label(r, NULL, label, sizeof label);
    snprintf(path, n, "%s/parts/fill-%s.part", f->dir, label);
    fill_key(f, r, key, sizeof key);
    return exp_part_key_matches(path, key);
}

int silo_fill_load(const silo_fills *f, size_t r, silo_settled *set, double *fill_cost, gr_err *err)
{
    char path[1200];
    silo_fill_path(f, r, path, sizeof path);
    *set = (silo_settled){0};
    gr_ckpt *ck = gr_ckpt_open(path, err);
    if (!ck)
        return err->code;
    set->p = gr_particles_create(0, err);
    int rc = set->p ? exp_get_particles(ck, "settled", set->p, err) : err->code;
    set->t_settle = exp_get_scalar(ck, "t_settle");
    exp_get_cost(ck, fill_cost);
    size_t nf = 0;
    gr_err ig = {0};
    if (!rc && !gr_ckpt_len(ck, "filling", &nf, &ig) && nf > 0) {
        set->filling = gr_particles_create(0, err);
        rc = set->filling ? exp_get_particles(ck, "filling", set->filling, err) : err->code;
        set->t_filling = exp_get_scalar(ck, "t_filling");
    }
    gr_ckpt_close(ck, NULL);
    if (!rc)
        set->top = silo_top(set->p);
    else
        silo_settled_free(set);
    return rc;
}
