/* The per-grain arrays of the DEM state: growing them, dropping grains
 * that left (recorded by tag), and the snapshot in the caller's order.
 * Below the step, which drops grains, and the state's creation. */
#include <stdlib.h>
#include <string.h>

#include "dem.h"

static int field_used(const gr_dem *d, int f)
{
    if (f == F_W || f == F_TQ)
        return d->rot;
    if (f >= F_TH)
        return d->par.integrator == GR_DEM_GEAR;
    return 1;
}

/* Unused bytes after each per-grain array, a page and more: the next
 * array's first grains (thread 0's) are then across a page boundary from
 * this one's last (the last thread's), which the hardware prefetchers
 * streaming through those do not cross. */
#define DEM_TAIL (4096 + 128)

int gr_dem_grow(gr_dem *d, size_t cap, gr_err *err)
{
    if (cap <= d->cap)
        return GR_OK;
    size_t old = d->cap;
#define GROW(T, a)                                                                 \
    {                                                                              \
        T *p_ = realloc((a), cap * sizeof(T) + DEM_TAIL);                          \
        if (!p_)                                                                   \
            return gr_fail(err, GR_ERUN, "out of memory for %zu grains", cap);     \
        memset(p_ + old, 0, (cap - old) * sizeof(T));                              \
        (a) = p_;                                                                  \
    }
    for (int f = 0; f < F_NFIELDS; f++)
        if (field_used(d, f))
            for (int p = 0; p < (f < F_NBASIC ? 3 : 2); p++)
                GROW(double, d->f[f][p]);
    GROW(double, d->rad) GROW(double, d->im) GROW(double, d->iI) GROW(double, d->gf)
    GROW(double, d->mass) GROW(double, d->inertia) GROW(double, d->xref) GROW(double, d->yref)
    GROW(int32_t, d->tag) GROW(uint32_t, d->flags) GROW(int32_t, d->species)
    if (d->ext_fx) {
        GROW(double, d->ext_fx) GROW(double, d->ext_fy)
    }
    if (d->hist_on) {
        size_t hc = (size_t)d->hist.cap, oc = old * hc, nc = cap * hc;
        gr_dem_hist *h = &d->hist;
#define GROWH(T, a, fillv)                                                         \
        {                                                                          \
            T *p_ = realloc((a), nc * sizeof(T));                                  \
            if (!p_)                                                               \
                return gr_fail(err, GR_ERUN, "out of memory for contact history"); \
            for (size_t k = oc; k < nc; k++)                                       \
                p_[k] = fillv;                                                     \
            (a) = p_;                                                              \
        }
        GROWH(int32_t, h->partner, -1) GROWH(int32_t, h->partner_old, -1)
        GROWH(double, h->z, 0.0) GROWH(double, h->z_old, 0.0)
        GROWH(uint64_t, h->stamp, 0) GROWH(uint64_t, h->stamp_old, 0)
#undef GROWH
    }
#undef GROW
    size_t nb = 2 * (cap / DEM_BLOCK + 1);
    double *blk = realloc(d->blk, nb * sizeof *blk);
    if (!blk)
        return gr_fail(err, GR_ERUN, "out of memory");
    d->blk = blk;
    d->cap = cap;
    return GR_OK;
}

long gr_dem_index(const gr_dem *d, long tag)
{
    for (size_t i = 0; i < d->n; i++)
        if (d->tag[i] == tag)
            return (long)i;
    return -1;
}

/* Grain i's current state, with extra flags, into the record of its tag. */
static void record(gr_dem *d, size_t i, uint32_t extra_flags)
{
    int p = d->cur;
    gr_particles *g = d->gone;
    size_t t = (size_t)d->tag[i];
    g->x[t] = d->f[F_X][p][i];
    g->y[t] = d->f[F_Y][p][i];
    g->vx[t] = d->f[F_VX][p][i];
    g->vy[t] = d->f[F_VY][p][i];
    g->omega[t] = d->rot ? d->f[F_W][p][i] : 0.0;
    g->flags[t] = d->flags[i] | extra_flags;
}

int gr_dem_compact(gr_dem *d, const unsigned char *gone, gr_err *err)
{
    (void)err;
    d->pre_E = 0; /* a drift done ahead was not compacted */
    size_t hc = d->hist_on ? (size_t)d->hist.cap : 0;
    size_t k = 0;
    for (size_t i = 0; i < d->n; i++) {
        if (gone[i]) {
            record(d, i, GR_PF_GONE);
            if (!(d->flags[i] & GR_PF_FIXED))
                d->nmobile--;
            continue;
        }
        if (k != i) {
#define MV(a) if (a) (a)[k] = (a)[i];
            for (int f = 0; f < F_NFIELDS; f++)
                for (int p = 0; p < 2; p++)
                    MV(d->f[f][p]);
            MV(d->rad) MV(d->im) MV(d->iI) MV(d->gf)
            MV(d->mass) MV(d->inertia) MV(d->xref) MV(d->yref) MV(d->ext_fx) MV(d->ext_fy)
            MV(d->tag) MV(d->flags) MV(d->species)
#undef MV
            if (hc) {
                gr_dem_hist *h = &d->hist;
#define MVR(a) memcpy((a) + k * hc, (a) + i * hc, hc * sizeof *(a));
                MVR(h->partner) MVR(h->partner_old) MVR(h->z) MVR(h->z_old) MVR(h->stamp) MVR(h->stamp_old)
#undef MVR
            }
        }
        k++;
    }
    d->n = k;
    d->need_build = 1;
    return GR_OK;
}

int gr_dem_snapshot(gr_dem *d, gr_particles *out, gr_err *err)
{
    if (gr_particles_copy(out, d->gone, err))
        return err->code;
    int p = d->cur;
    for (size_t i = 0; i < d->n; i++) {
        size_t t = (size_t)d->tag[i];
        out->x[t] = d->f[F_X][p][i];
        out->y[t] = d->f[F_Y][p][i];
        out->vx[t] = d->f[F_VX][p][i];
        out->vy[t] = d->f[F_VY][p][i];
        out->omega[t] = d->rot ? d->f[F_W][p][i] : 0.0;
        out->flags[t] = d->flags[i];
    }
    return GR_OK;
}

/* The external force arrays (tests), zero, once a force is set or a
 * checkpoint that had them is loaded; they then move with the grains. */
int gr_dem_external_arrays(gr_dem *d, gr_err *err)
{
    if (d->ext_fx)
        return GR_OK;
    d->ext_fx = calloc(d->cap, sizeof(double));
    d->ext_fy = calloc(d->cap, sizeof(double));
    if (!d->ext_fx || !d->ext_fy)
        return gr_fail(err, GR_ERUN, "out of memory");
    return GR_OK;
}
