/* Checkpoints: the full state, event lists included, so that a loaded run
 * pops the very same events in the same order as the uninterrupted one
 * (re-predicting on load would round some floor roots differently). */
#include <stdlib.h>
#include <string.h>

#include "edmd_int.h"

/* The scalar state, as one blob. */
#define SCALARS(X)                                                                                 \
    X(t) X(t_prev_coll) X(stuck) X(cnt) X(steps) X(m_t) X(m_K) X(m_Krot) X(m_U) X(m_Smvy) X(m_Sm)  \
    X(a_t0) X(a_K) X(a_Krot) X(a_U) X(a_mom) X(a_virial) X(a_inj) X(a_diss) X(a_pair0) X(a_wall0) \
    X(e_inj) X(e_diss) X(obs_t0) X(obs_mom) X(ecap) X(last_sort) X(outflow)

#define SIZE_OF(f) +sizeof(((gr_edmd *)0)->f)
enum { SCALAR_BYTES = 0 SCALARS(SIZE_OF) };

static void pack(const gr_edmd *s, unsigned char *b)
{
#define PUT(f)                        \
    memcpy(b, &s->f, sizeof s->f); \
    b += sizeof s->f;
    SCALARS(PUT)
#undef PUT
}

static void unpack(gr_edmd *s, const unsigned char *b)
{
#define GET(f)                        \
    memcpy(&s->f, b, sizeof s->f); \
    b += sizeof s->f;
    SCALARS(GET)
#undef GET
}

static size_t ncells(const gr_edmd *s) { return (size_t)s->nx * (size_t)s->ny; }

/* The "edmd.leaves" dataset: each grain's earliest event (its slot 0, INF
 * for an empty slab) for every leaf of the tree, whichever queue runs. The
 * queue is a function of the slabs and is rebuilt from them on load, so
 * the leaves are written for the layout's sake and only checked on load. */
static edmd_ev *leaves(const gr_edmd *s)
{
    edmd_ev *lf = malloc((size_t)s->P * sizeof *lf);
    if (!lf)
        return NULL;
    for (int32_t i = 0; i < s->P; i++)
        lf[i] = (size_t)i < s->n && s->p[i].nev ? *edmd_slab(s, i) : (edmd_ev){EDMD_INF, 0, 0};
    return lf;
}

int gr_edmd_save(const gr_edmd *s, gr_ckpt *ck, gr_err *err)
{
    edmd_ev *lf = leaves(s);
    if (!lf)
        return gr_fail(err, GR_ERUN, "edmd: out of memory for the checkpoint");
    int rc = GR_OK;
    unsigned char sc[SCALAR_BYTES];
    pack(s, sc);
    uint64_t dims[5] = {s->n, (uint64_t)s->ecap, ncells(s), (uint64_t)s->P, s->cacc != NULL};
    size_t n = s->n, nc = ncells(s);
    if (gr_ckpt_put_u64(ck, "edmd.dims", dims, 5, err) ||
        gr_ckpt_put_bytes(ck, "edmd.scalars", sc, sizeof sc, err) ||
        gr_ckpt_put_bytes(ck, "edmd.particles", s->p, n * sizeof *s->p, err) ||
        gr_ckpt_put_f64(ck, "edmd.omega", s->w, n, err) ||
        gr_ckpt_put_f64(ck, "edmd.tlast", s->tlast, n, err) ||
        gr_ckpt_put_f64(ck, "edmd.tacc", s->tacc, n, err) ||
        gr_ckpt_put_bytes(ck, "edmd.chead", s->chead, nc * sizeof *s->chead, err) ||
        gr_ckpt_put_bytes(ck, "edmd.events", s->ev, n * (size_t)s->ecap * sizeof *s->ev, err) ||
        gr_ckpt_put_bytes(ck, "edmd.leaves", lf, (size_t)s->P * sizeof *lf, err) ||
        (s->own_rng && gr_rng_save(s->own_rng, ck, "edmd.rng", err)))
        rc = err->code;
    free(lf);
    if (rc)
        return rc;
    /* a re-sort renumbers the grains: save the numbering */
    if (gr_ckpt_put_i64(ck, "edmd.id", s->id, n, err) ||
        gr_ckpt_put_f64(ck, "edmd.mass", s->m, n, err) ||
        gr_ckpt_put_f64(ck, "edmd.inertia", s->inertia, n, err) ||
        gr_ckpt_put_bytes(ck, "edmd.species", s->species, n * sizeof *s->species, err) ||
        gr_ckpt_put_bytes(ck, "edmd.order", s->order, n * sizeof *s->order, err) ||
        gr_ckpt_put_bytes(ck, "edmd.gone", s->gone, n, err))
        return err->code;
    if (s->cacc && gr_ckpt_put_f64(ck, "edmd.fields", (const double *)s->cacc, nc * EDMD_CELLACC_N, err))
        return err->code;
    if (s->stress && gr_stress_acc_save(s->stress, ck, "edmd.stress", err))
        return err->code;
    return GR_OK;
}

/* The dimensions and the slabs' room: a checkpoint may have slabs of
 * another size than this run's. */
static int load_dims(gr_edmd *s, gr_ckpt *ck, gr_err *err)
{
    uint64_t dims[5];
    if (gr_ckpt_get_u64(ck, "edmd.dims", dims, 5, err))
        return err->code;
    size_t n = s->n, nc = ncells(s);
    if (dims[0] != n || dims[2] != nc || dims[3] != (uint64_t)s->P || dims[4] != (s->cacc != NULL))
        return gr_fail(err, GR_EINPUT,
                       "edmd: the checkpoint holds %llu grains on %llu cells, this scene %zu on %zu "
                       "(or fields differ): not the same scene",
                       (unsigned long long)dims[0], (unsigned long long)dims[2], n, nc);
    if (dims[1] != (uint64_t)s->ecap) {
        edmd_ev *ev = edmd_ev_alloc(n * (size_t)dims[1]);
        if (!ev)
            return gr_fail(err, GR_ERUN, "edmd: out of memory for the event lists");
        free(s->ev);
        s->ev = ev;
        s->ecap = (int32_t)dims[1];
    }
    return GR_OK;
}

int gr_edmd_load(gr_edmd *s, gr_ckpt *ck, gr_err *err)
{
    if (load_dims(s, ck, err))
        return err->code;
    size_t n = s->n, nc = ncells(s);
    edmd_ev *lf = malloc((size_t)s->P * sizeof *lf);
    if (!lf)
        return gr_fail(err, GR_ERUN, "edmd: out of memory for the checkpoint");
    unsigned char sc[SCALAR_BYTES];
    int rc = GR_OK;
    if (gr_ckpt_get_bytes(ck, "edmd.scalars", sc, sizeof sc, err) ||
        gr_ckpt_get_bytes(ck, "edmd.particles", s->p, n * sizeof *s->p, err) ||
        gr_ckpt_get_f64(ck, "edmd.omega", s->w, n, err) ||
        gr_ckpt_get_f64(ck, "edmd.tlast", s->tlast, n, err) ||
        gr_ckpt_get_f64(ck, "edmd.tacc", s->tacc, n, err) ||
        gr_ckpt_get_bytes(ck, "edmd.chead", s->chead, nc * sizeof *s->chead, err) ||
        gr_ckpt_get_bytes(ck, "edmd.events", s->ev, n * (size_t)s->ecap * sizeof *s->ev, err) ||
        gr_ckpt_get_bytes(ck, "edmd.leaves", lf, (size_t)s->P * sizeof *lf, err) ||
        (s->own_rng && gr_rng_load(s->own_rng, ck, "edmd.rng", err)))
        rc = err->code;
    free(lf);
    if (rc)
        return rc;
    if (gr_ckpt_get_i64(ck, "edmd.id", s->id, n, err) ||
        gr_ckpt_get_f64(ck, "edmd.mass", s->m, n, err) ||
        gr_ckpt_get_f64(ck, "edmd.inertia", s->inertia, n, err) ||
        gr_ckpt_get_bytes(ck, "edmd.species", s->species, n * sizeof *s->species, err) ||
        gr_ckpt_get_bytes(ck, "edmd.order", s->order, n * sizeof *s->order, err) ||
        gr_ckpt_get_bytes(ck, "edmd.gone", s->gone, n, err))
        return err->code;
    if (s->cacc && gr_ckpt_get_f64(ck, "edmd.fields", (double *)s->cacc, nc * EDMD_CELLACC_N, err))
        return err->code;
    /* the stress window, if the run had opened one (tacc above holds its grains' times) */
    if (gr_stress_acc_load(&s->stress, ck, "edmd.stress", s->W, s->H, s->periodic_x, s->periodic_y, err))
        return err->code;
    unpack(s, sc);
    /* a gate that opened by s->t has woken the sleepers already */
    s->t_gate = edmd_next_gate(s, s->t);
    /* The queue is a function of the slabs (ties go to the lower index in
     * both the tree and the calendar): rebuilt, not stored, so either queue
     * resumes a checkpoint written with the other. */
    if (s->q->build(s))
        return gr_fail(err, GR_ERUN, "edmd: out of memory for the event queue");
    return GR_OK;
}
