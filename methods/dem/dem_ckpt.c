/* Save and load the full state: grains in their internal (sorted) order,
 * the positions of the last list build (so the reloaded list, and with it
 * every floating-point sum, is the same), contact history, the record of
 * grains that left, and the reinsertion generator. */
#include <string.h>

#include "dem.h"
#include "rng.h"

enum { META_N, META_NTAG, META_STEP, META_OUTFLOW, META_GATES, META_NSEG, META_HCAP,
       META_INTEG, META_NEIGH, META_SINCE_SORT, META_NEED_BUILD, META_ROT, META_EXT, META_BUILDS,
       META_COUNT };
enum { R_T, R_T0, R_EKIN, R_WIMP, R_WTIME, R_MAXOVL, R_DT, R_COUNT };

static const char *field_name(int f)
{
    static const char *const names[F_NFIELDS] = {
        "x", "y", "vx", "vy", "omega", "fx", "fy", "torque", "theta",
        "gear_b2x", "gear_b2y", "gear_b2t", "gear_b3x", "gear_b3y", "gear_b3t",
        "gear_b4x", "gear_b4y", "gear_b4t", "gear_b5x", "gear_b5y", "gear_b5t"};
    return names[f];
}

int gr_dem_save(const gr_dem *d, gr_ckpt *ck, gr_err *err)
{
    if (d->par.integrator == GR_DEM_CVODE) {
        char where[1200];
        gr_scene_where(&d->sc, "dem", "integrator", where, sizeof where);
        return gr_fail(err, GR_EINPUT, "%s: cvode (a reference integrator) cannot be checkpointed; use verlet, gear or euler", where);
    }
    int64_t meta[META_COUNT] = {
        [META_N] = (int64_t)d->n, [META_NTAG] = (int64_t)d->ntag, [META_STEP] = (int64_t)d->step,
        [META_OUTFLOW] = (int64_t)d->outflow, [META_GATES] = d->gates_open, [META_NSEG] = d->nseg,
        [META_HCAP] = d->hist_on ? d->hist.cap : 0, [META_INTEG] = d->par.integrator,
        [META_NEIGH] = d->par.neighbour, [META_SINCE_SORT] = (int64_t)d->since_sort,
        [META_NEED_BUILD] = d->need_build, [META_ROT] = d->rot, [META_EXT] = d->ext_fx != NULL,
        [META_BUILDS] = (int64_t)d->builds};
    double real[R_COUNT] = {[R_T] = d->t, [R_T0] = d->t0, [R_EKIN] = d->ekin_last,
                            [R_WIMP] = d->wall_impulse, [R_WTIME] = d->wall_time,
                            [R_MAXOVL] = d->max_ovl, [R_DT] = d->par.dt};
    size_t n = d->n;
    int p = d->cur;
    if (gr_ckpt_put_i64(ck, "dem_meta", meta, META_COUNT, err) ||
        gr_ckpt_put_f64(ck, "dem_real", real, R_COUNT, err))
        return err->code;
    char name[64];
    for (int f = 0; f < F_NFIELDS; f++) {
        if (!d->f[f][p])
            continue;
        snprintf(name, sizeof name, "dem_%s", field_name(f));
        if (gr_ckpt_put_f64(ck, name, d->f[f][p], n, err))
            return err->code;
    }
#define PUTD(nm, a) if (gr_ckpt_put_f64(ck, nm, a, n, err)) return err->code;
    PUTD("dem_radius", d->rad) PUTD("dem_mass", d->mass) PUTD("dem_inertia", d->inertia)
    PUTD("dem_inv_mass", d->im) PUTD("dem_inv_inertia", d->iI) PUTD("dem_gravity_factor", d->gf)
    PUTD("dem_xref", d->xref) PUTD("dem_yref", d->yref)
    if (d->ext_fx) {
        PUTD("dem_ext_fx", d->ext_fx) PUTD("dem_ext_fy", d->ext_fy)
    }
#undef PUTD
    if (gr_ckpt_put_bytes(ck, "dem_tag", d->tag, n * sizeof *d->tag, err) ||
        gr_ckpt_put_u32(ck, "dem_flags", d->flags, n, err) ||
        gr_ckpt_put_bytes(ck, "dem_species", d->species, n * sizeof *d->species, err))
        return err->code;
    if (d->hist_on) {
        size_t hn = n * (size_t)d->hist.cap;
        if (gr_ckpt_put_bytes(ck, "dem_hist_partner", d->hist.partner, hn * sizeof(int32_t), err) ||
            gr_ckpt_put_f64(ck, "dem_hist_zeta", d->hist.z, hn, err) ||
            gr_ckpt_put_u64(ck, "dem_hist_stamp", d->hist.stamp, hn, err))
            return err->code;
    }
    const gr_particles *g = d->gone;
    size_t nt = d->ntag;
    if (gr_ckpt_put_f64(ck, "dem_rec_x", g->x, nt, err) || gr_ckpt_put_f64(ck, "dem_rec_y", g->y, nt, err) ||
        gr_ckpt_put_f64(ck, "dem_rec_vx", g->vx, nt, err) || gr_ckpt_put_f64(ck, "dem_rec_vy", g->vy, nt, err) ||
        gr_ckpt_put_f64(ck, "dem_rec_omega", g->omega, nt, err) ||
        gr_ckpt_put_u32(ck, "dem_rec_flags", g->flags, nt, err))
        return err->code;
    /* a caller's reinsertion stream (the instance's) is saved by the caller */
    if (d->own_rng && gr_rng_save(d->own_rng, ck, "dem_rng_reinsert", err))
        return err->code;
    return GR_OK;
}

/* The checkpoint's sizes and settings against this state's; makes room
 * for its live grains. */
static int load_check(gr_dem *d, const int64_t *meta, const double *real, gr_err *err)
{
    if (meta[META_NTAG] != (int64_t)d->ntag || meta[META_NSEG] != d->nseg ||
        meta[META_HCAP] != (d->hist_on ? d->hist.cap : 0) || meta[META_INTEG] != d->par.integrator ||
        meta[META_NEIGH] != d->par.neighbour || meta[META_ROT] != d->rot || real[R_DT] != d->par.dt)
        return gr_fail(err, GR_EINPUT,
                       "dem checkpoint: made from another scene or other [dem] parameters (grains %lld/%zu, walls %lld/%d, integrator, neighbour search or dt differ)",
                       (long long)meta[META_NTAG], d->ntag, (long long)meta[META_NSEG], d->nseg);
    size_t n = (size_t)meta[META_N];
    if (n > d->ntag)
        return gr_fail(err, GR_EINPUT, "dem checkpoint: %zu live grains for %zu in the scene", n, d->ntag);
    if (gr_dem_grow(d, n + 16, err))
        return err->code;
    return meta[META_EXT] ? gr_dem_external_arrays(d, err) : GR_OK;
}

/* The n live grains' arrays into buffer 0, with their contact history. */
static int load_grains(gr_dem *d, gr_ckpt *ck, size_t n, int ext, gr_err *err)
{
    char name[64];
    for (int f = 0; f < F_NFIELDS; f++) {
        if (!d->f[f][0])
            continue;
        snprintf(name, sizeof name, "dem_%s", field_name(f));
        if (gr_ckpt_get_f64(ck, name, d->f[f][0], n, err))
            return err->code;
    }
#define GETD(nm, a) if (gr_ckpt_get_f64(ck, nm, a, n, err)) return err->code;
    GETD("dem_radius", d->rad) GETD("dem_mass", d->mass) GETD("dem_inertia", d->inertia)
    GETD("dem_inv_mass", d->im) GETD("dem_inv_inertia", d->iI) GETD("dem_gravity_factor", d->gf)
    GETD("dem_xref", d->xref) GETD("dem_yref", d->yref)
    if (ext) {
        GETD("dem_ext_fx", d->ext_fx) GETD("dem_ext_fy", d->ext_fy)
    }
#undef GETD
    if (gr_ckpt_get_bytes(ck, "dem_tag", d->tag, n * sizeof *d->tag, err) ||
        gr_ckpt_get_u32(ck, "dem_flags", d->flags, n, err) ||
        gr_ckpt_get_bytes(ck, "dem_species", d->species, n * sizeof *d->species, err))
        return err->code;
    if (d->hist_on) {
        size_t hn = n * (size_t)d->hist.cap;
        if (gr_ckpt_get_bytes(ck, "dem_hist_partner", d->hist.partner, hn * sizeof(int32_t), err) ||
            gr_ckpt_get_f64(ck, "dem_hist_zeta", d->hist.z, hn, err) ||
            gr_ckpt_get_u64(ck, "dem_hist_stamp", d->hist.stamp, hn, err))
            return err->code;
        memcpy(d->hist.partner_old, d->hist.partner, hn * sizeof(int32_t));
        memcpy(d->hist.z_old, d->hist.z, hn * sizeof(double));
        memcpy(d->hist.stamp_old, d->hist.stamp, hn * sizeof(uint64_t));
    }
    return GR_OK;
}

/* The record of every tag, and the reinsertion generator. */
static int load_record(gr_dem *d, gr_ckpt *ck, gr_err *err)
{
    gr_particles *g = d->gone;
    size_t nt = d->ntag;
    if (gr_ckpt_get_f64(ck, "dem_rec_x", g->x, nt, err) || gr_ckpt_get_f64(ck, "dem_rec_y", g->y, nt, err) ||
        gr_ckpt_get_f64(ck, "dem_rec_vx", g->vx, nt, err) || gr_ckpt_get_f64(ck, "dem_rec_vy", g->vy, nt, err) ||
        gr_ckpt_get_f64(ck, "dem_rec_omega", g->omega, nt, err) ||
        gr_ckpt_get_u32(ck, "dem_rec_flags", g->flags, nt, err))
        return err->code;
    if (d->own_rng && gr_rng_load(d->own_rng, ck, "dem_rng_reinsert", err))
        return err->code;
    return GR_OK;
}

int gr_dem_load(gr_dem *d, gr_ckpt *ck, gr_err *err)
{
    if (d->par.integrator == GR_DEM_CVODE)
        return gr_fail(err, GR_EINPUT, "[dem] integrator = cvode cannot be restarted from a checkpoint");
    int64_t meta[META_COUNT];
    double real[R_COUNT];
    if (gr_ckpt_get_i64(ck, "dem_meta", meta, META_COUNT, err) ||
        gr_ckpt_get_f64(ck, "dem_real", real, R_COUNT, err))
        return gr_err_prefix(err, "dem checkpoint: ");
    if (load_check(d, meta, real, err))
        return err->code;
    size_t n = (size_t)meta[META_N];
    d->n = n;
    d->cur = 0;
    if (load_grains(d, ck, n, meta[META_EXT] != 0, err) || load_record(d, ck, err))
        return gr_err_prefix(err, "dem checkpoint: ");
    d->step = (uint64_t)meta[META_STEP];
    d->outflow = (uint64_t)meta[META_OUTFLOW];
    d->gates_open = (int)meta[META_GATES];
    d->since_sort = (uint64_t)meta[META_SINCE_SORT];
    d->t = real[R_T];
    d->t0 = real[R_T0];
    d->ekin_last = real[R_EKIN];
    d->e_ref = NAN;
    d->wall_impulse = real[R_WIMP];
    d->wall_time = real[R_WTIME];
    d->max_ovl = real[R_MAXOVL];
    d->nmobile = 0;
    for (size_t i = 0; i < n; i++)
        d->nmobile += !(d->flags[i] & GR_PF_FIXED);
    /* the list of the original run was built at xref in this order */
    if (d->par.neighbour == GR_DEM_NB_VERLET && gr_dem_build_list(d, d->xref, d->yref, err))
        return err->code;
    d->builds = (uint64_t)meta[META_BUILDS];
    d->need_build = (int)meta[META_NEED_BUILD];
    return GR_OK;
}
