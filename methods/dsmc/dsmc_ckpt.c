/* Save and load the full state: particles in their (cell) order with
 * their ranks and recent partners, counters and the window. The collisions' random numbers are
 * counted by step and cell, so no generator state is needed. Calls no
 * other file of the backend. */
#include "dsmc_int.h"

enum { M_N, M_STEP, M_PAIRS, M_WALLS, M_CAND, M_LOST, M_NCELL, M_STAND, M_COUNT };
enum { R_T, R_WMOM, R_WTIME, R_VIRIAL, R_COUNT };

/* The densest region seen and the steps packed beyond a gas. */
static int put_dense(const gr_dsmc *d, gr_ckpt *ck, gr_err *err)
{
    double v[6] = {(double)d->dense_steps, d->dense[0], d->dense[1], d->dense[2], d->dense[3], d->dense[4]};
    return gr_ckpt_put_f64(ck, "dsmc_dense", v, 6, err);
}

static int get_dense(gr_dsmc *d, gr_ckpt *ck, gr_err *err)
{
    double v[6];
    if (gr_ckpt_get_f64(ck, "dsmc_dense", v, 6, err))
        return err->code;
    d->dense_steps = (uint64_t)v[0];
    for (int k = 0; k < 5; k++)
        d->dense[k] = v[k + 1];
    return GR_OK;
}

int gr_dsmc_save(const gr_dsmc *d, gr_ckpt *ck, gr_err *err)
{
    size_t nc = (size_t)d->nx * (size_t)d->ny, n = d->n;
    int64_t meta[M_COUNT] = {[M_N] = (int64_t)n, [M_STEP] = (int64_t)d->step, [M_PAIRS] = (int64_t)d->pairs,
                             [M_WALLS] = (int64_t)d->walls, [M_CAND] = (int64_t)d->cand,
                             [M_LOST] = (int64_t)d->lost, [M_NCELL] = (int64_t)nc,
                             [M_STAND] = (int64_t)d->stand_ins};
    double real[R_COUNT] = {[R_T] = d->t, [R_WMOM] = d->wall_mom, [R_WTIME] = d->wall_time, [R_VIRIAL] = d->virial};
    if (gr_ckpt_put_i64(ck, "dsmc_meta", meta, M_COUNT, err) || gr_ckpt_put_f64(ck, "dsmc_real", real, R_COUNT, err) ||
        gr_ckpt_put_f64(ck, "dsmc_x", d->x, n, err) || gr_ckpt_put_f64(ck, "dsmc_y", d->y, n, err) ||
        gr_ckpt_put_f64(ck, "dsmc_vx", d->vx, n, err) || gr_ckpt_put_f64(ck, "dsmc_vy", d->vy, n, err) ||
        gr_ckpt_put_u32(ck, "dsmc_rank", d->rank, n, err) || gr_ckpt_put_u32(ck, "dsmc_last", d->last, n, err) ||
        gr_ckpt_put_u32(ck, "dsmc_prev", d->prev, n, err) || put_dense(d, ck, err))
        return err->code;
    return GR_OK;
}

int gr_dsmc_load(gr_dsmc *d, gr_ckpt *ck, gr_err *err)
{
    int64_t meta[M_COUNT];
    double real[R_COUNT];
    size_t nc = (size_t)d->nx * (size_t)d->ny, n = d->n;
    if (gr_ckpt_get_i64(ck, "dsmc_meta", meta, M_COUNT, err) || gr_ckpt_get_f64(ck, "dsmc_real", real, R_COUNT, err))
        return err->code;
    if (meta[M_N] != (int64_t)n || meta[M_NCELL] != (int64_t)nc)
        return gr_fail(err, GR_EINPUT, "checkpoint: %lld particles in %lld cells, the scene gives %zu in %zu",
                       (long long)meta[M_N], (long long)meta[M_NCELL], n, nc);
    if (gr_ckpt_get_f64(ck, "dsmc_x", d->x, n, err) || gr_ckpt_get_f64(ck, "dsmc_y", d->y, n, err) ||
        gr_ckpt_get_f64(ck, "dsmc_vx", d->vx, n, err) || gr_ckpt_get_f64(ck, "dsmc_vy", d->vy, n, err) ||
        gr_ckpt_get_u32(ck, "dsmc_rank", d->rank, n, err) || gr_ckpt_get_u32(ck, "dsmc_last", d->last, n, err) ||
        gr_ckpt_get_u32(ck, "dsmc_prev", d->prev, n, err) || get_dense(d, ck, err))
        return err->code;
    d->step = (uint64_t)meta[M_STEP], d->pairs = (uint64_t)meta[M_PAIRS], d->walls = (uint64_t)meta[M_WALLS];
    d->cand = (uint64_t)meta[M_CAND], d->lost = (uint64_t)meta[M_LOST], d->stand_ins = (uint64_t)meta[M_STAND];
    d->t = real[R_T], d->wall_mom = real[R_WMOM], d->wall_time = real[R_WTIME], d->virial = real[R_VIRIAL];
    return GR_OK;
}
