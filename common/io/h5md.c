/* H5MD writer: the layout of docs/output-format.md, written as the run goes
 * and flushed after every write. */
#include "h5md_impl.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "scene_types.h"

const gr_elem_def gr_h5md_pdefs[NPE] = {
    {"position", "d", GR_T_F64, 2, 0},
    {"velocity", "d tau-1", GR_T_F64, 2, 0},
    {"omega", "tau-1", GR_T_F64, 1, 0},
    {"flags", "1", GR_T_U32, 1, 0},
    {"radius", "d", GR_T_F64, 1, 1},
    {"mass", "m", GR_T_F64, 1, 1},
    {"inertia", "m d+2", GR_T_F64, 1, 1},
    {"species", "1", GR_T_I32, 1, 1},
    {"id", "1", GR_T_I64, 1, 1},
};

static const char *author_name(const gr_h5md_opts *o)
{
    if (o->author && o->author[0])
        return o->author;
    const char *a = getenv("GRANO_AUTHOR");
    if (a && a[0])
        return a;
    a = getenv("USER");
    return a && a[0] ? a : "unknown";
}

/* h5md/ metadata and parameters/: everything known before the first frame. */
static int build_layout(gr_h5md *h, const gr_scene *sc, const gr_h5md_opts *o, gr_err *err)
{
    const int version[2] = {1, 1}, units_version[2] = {1, 0}, dim = 2;
    hid_t g = gr_h5_mkgroup(h->file, "h5md");
    int bad = g < 0 || gr_h5_attr_int(g, "version", version, 2);
    gr_h5_close(g);
    g = bad ? -1 : gr_h5_mkgroup(h->file, "h5md/author");
    bad = bad || g < 0 || gr_h5_attr_str(g, "name", author_name(o), 0);
    gr_h5_close(g);
    g = bad ? -1 : gr_h5_mkgroup(h->file, "h5md/creator");
    bad = bad || g < 0 || gr_h5_attr_str(g, "name", "grano", 0) ||
          gr_h5_attr_str(g, "version", o->version ? o->version : GRANO_VERSION, 0);
    gr_h5_close(g);
    g = bad ? -1 : gr_h5_mkgroup(h->file, "h5md/modules/units");
    bad = bad || g < 0 || gr_h5_attr_int(g, "version", units_version, 2) ||
          gr_h5_attr_str(g, "system",
                         "grano reduced units: d grain diameter, m grain mass, "
                         "tau = sqrt(d/g) (or d/V0 for event-driven scenes without gravity)", 0);
    gr_h5_close(g);
    if (bad)
        return gr_h5_fail(err, GR_ERUN, "cannot write the h5md metadata group");

    g = gr_h5_mkgroup(h->file, "parameters");
    bad = g < 0 || gr_h5_dset_str(g, "scene", sc->text ? sc->text : "") ||
          gr_h5_dset_str(g, "scene_name", sc->name) || gr_h5_dset_str(g, "scene_path", sc->path) ||
          gr_h5_dset_str(g, "method", o->method ? o->method : "") ||
          gr_h5_dset_u64(g, "seed", o->seed) ||
          gr_h5_dset_str(g, "grano_version", o->version ? o->version : GRANO_VERSION) ||
          (o->derived && o->derived[0] && gr_h5_dset_str(g, "derived", o->derived));
    gr_h5_close(g);
    if (bad)
        return gr_h5_fail(err, GR_ERUN, "cannot write the parameters group");

    h->traj = gr_h5_mkgroup(h->file, "particles/trajectory");
    h->box = h->traj >= 0 ? gr_h5_mkgroup(h->traj, "box") : -1;
    const char *bnd[2] = {
        sc->side[GR_LEFT] == GR_BC_PERIODIC && sc->side[GR_RIGHT] == GR_BC_PERIODIC ? "periodic" : "none",
        sc->side[GR_BOTTOM] == GR_BC_PERIODIC && sc->side[GR_TOP] == GR_BC_PERIODIC ? "periodic" : "none"};
    if (h->box < 0 || gr_h5_attr_int(h->box, "dimension", &dim, 0) ||
        gr_h5_attr_strs(h->box, "boundary", bnd, 2, 0))
        return gr_h5_fail(err, GR_ERUN, "cannot write particles/trajectory/box");
    h->width = sc->width;
    h->height = sc->height;
    return GR_OK;
}

gr_h5md *gr_h5md_alloc(void)
{
    gr_h5md *h = calloc(1, sizeof *h);
    if (!h)
        return NULL;
    h->file = h->traj = h->box = h->step = h->time = h->edges = -1;
    h->obs_step = h->obs_time = -1;
    for (int k = 0; k < NPE; k++)
        h->pe[k].group = h->pe[k].value = -1;
    for (int k = 0; k < GR_OBS_MAX; k++)
        h->oe[k].group = h->oe[k].value = -1;
    return h;
}

static void close_handles(gr_h5md *h)
{
    for (int k = 0; k < NPE; k++) {
        gr_h5_close(h->pe[k].value);
        gr_h5_close(h->pe[k].group);
        free(h->pe[k].prev);
    }
    for (int k = 0; k < GR_OBS_MAX; k++) {
        gr_h5_close(h->oe[k].value);
        gr_h5_close(h->oe[k].group);
    }
    gr_h5_close(h->obs_step);
    gr_h5_close(h->obs_time);
    gr_h5_close(h->step);
    gr_h5_close(h->time);
    gr_h5_close(h->edges);
    gr_h5_close(h->box);
    gr_h5_close(h->traj);
}

/* Close every handle (the file too when owned) and free h; returns the
 * status of closing the file. */
herr_t gr_h5md_release(gr_h5md *h)
{
    close_handles(h);
    herr_t st = 0;
    if (h->owned && h->file >= 0)
        st = H5Fclose(h->file);
    free(h->buf);
    free(h->times);
    free(h->path);
    free(h->part);
    free(h->xdmf);
    free(h->h5name);
    free(h);
    return st;
}

static void free_writer(gr_h5md *h)
{
    (void)gr_h5md_release(h);
}

int gr_h5md_write_sidecar(gr_h5md *h, gr_err *err)
{
    if (!h->xdmf)
        return GR_OK;
    gr_xdmf_attr a[NPE - 1];
    size_t na = 0;
    for (int k = E_VEL; k < NPE; k++)
        if (k != E_MASS && k != E_INERTIA) /* derived, and the XML grows per frame */
            a[na++] = (gr_xdmf_attr){gr_h5md_pdefs[k].name, h->pe[k].series, gr_h5md_pdefs[k].ncomp, gr_h5md_pdefs[k].type};
    int rc = gr_xdmf_write(h->xdmf, h->h5name, h->file, h->n, h->frames, h->times, a, na, err);
    if (!rc)
        h->xdmf_frames = h->frames;
    return rc;
}

/* The sidecar holds one grid per frame and is rewritten whole: after each
 * of the first 100 frames, then each time the count has grown by 5 %, so
 * the total cost stays proportional to the number of frames (amortised). */
static int update_sidecar(gr_h5md *h, gr_err *err)
{
    if (h->frames <= 100 || h->frames - h->xdmf_frames >= h->frames / 20)
        return gr_h5md_write_sidecar(h, err);
    return GR_OK;
}

char *gr_h5_catstr(const char *a, const char *b)
{
    size_t la = strlen(a), lb = strlen(b);
    char *s = malloc(la + lb + 1);
    if (s) {
        memcpy(s, a, la);
        memcpy(s + la, b, lb + 1);
    }
    return s;
}

static gr_h5md *create_impl(const char *path, const gr_scene *sc, const gr_h5md_opts *o,
                            gr_err *err)
{
    if (!path || !path[0]) {
        gr_fail(err, GR_EINPUT, "no output file given");
        return NULL;
    }
    struct stat st;
    if (stat(path, &st) == 0) {
        if (S_ISDIR(st.st_mode)) {
            gr_fail(err, GR_EINPUT, "output file %s is a directory", path);
            return NULL;
        }
        if (!o->force) {
            gr_fail(err, GR_EINPUT, "output file %s already exists; use --force to overwrite it", path);
            return NULL;
        }
    }
    gr_h5md *h = gr_h5md_alloc();
    char *part = gr_h5_catstr(path, ".part");
    if (!h || !part || !(h->path = strdup(path)) ||
        (!o->no_xdmf && !(h->xdmf = gr_h5_catstr(path, ".xdmf")))) {
        gr_fail(err, GR_ERUN, "out of memory");
        goto fail;
    }
    const char *slash = strrchr(path, '/');
    if (!(h->h5name = strdup(slash ? slash + 1 : path))) {
        gr_fail(err, GR_ERUN, "out of memory");
        goto fail;
    }
    h->owned = 1;
    if (gr_h5md_set_obs(h, o)) {
        gr_fail(err, GR_ERUN, "observables: %zu declared; at most %d, and at least one written, are allowed",
                gr_obs_count(o->obs ? o->obs : gr_obs_particle_set), GR_OBS_MAX);
        goto fail;
    }
    hid_t fapl = gr_h5_fapl(), fcpl = gr_h5_paged_fcpl();
    h->file = fapl < 0 || fcpl < 0 ? -1 : H5Fcreate(part, H5F_ACC_TRUNC, fcpl, fapl);
    gr_h5_close(fapl);
    gr_h5_close(fcpl);
    if (h->file < 0) {
        gr_h5_fail(err, GR_EINPUT, "cannot create output file %s", path);
        goto fail;
    }
    if (build_layout(h, sc, o, err))
        goto fail_unlink;
    if (H5Fflush(h->file, H5F_SCOPE_GLOBAL) < 0) {
        gr_h5_fail(err, GR_ERUN, "cannot write %s", path);
        goto fail_unlink;
    }
    if (gr_h5md_write_sidecar(h, err))
        goto fail_unlink;
    h->part = part;
    return h;
fail_unlink:
    free_writer(h);
    h = NULL;
    unlink(part);
fail:
    free(part);
    if (h)
        free_writer(h);
    return NULL;
}

gr_h5md *gr_h5md_create(const char *path, const gr_scene *sc, const gr_h5md_opts *o,
                        gr_err *err)
{
    gr_h5md_opts zero = {0};
    if (!sc) {
        gr_fail(err, GR_ERUN, "gr_h5md_create: no scene");
        return NULL;
    }
    gr_h5md *h = NULL;
    GR_H5_GUARD(err, !h, h = create_impl(path, sc, o ? o : &zero, err));
    return h;
}

gr_h5md *gr_h5md_attach(hid_t file, const gr_scene *sc, const gr_h5md_opts *o, gr_err *err)
{
    gr_h5md_opts zero = {0};
    gr_h5md *h = gr_h5md_alloc();
    if (!h) {
        gr_fail(err, GR_ERUN, "out of memory");
        return NULL;
    }
    h->file = file;
    gr_h5md_set_obs(h, o ? o : &zero);
    int rc;
    GR_H5_GUARD(err, rc, rc = build_layout(h, sc, o ? o : &zero, err));
    if (rc) {
        free_writer(h);
        return NULL;
    }
    return h;
}

/* A time-dependent element group whose step and time are hard links to
 * those of the element owning them (H5MD: equal sampling, shared axes). */
static hid_t series_group(hid_t loc, const char *name, hid_t owner_group)
{
    hid_t g = gr_h5_mkgroup(loc, name);
    if (g < 0)
        return -1;
    if (H5Lcreate_hard(owner_group, "step", g, "step", H5P_DEFAULT, H5P_DEFAULT) < 0 ||
        H5Lcreate_hard(owner_group, "time", g, "time", H5P_DEFAULT, H5P_DEFAULT) < 0) {
        H5Gclose(g);
        return -1;
    }
    return g;
}

static hid_t series_value(hid_t g, const gr_elem_def *d, size_t n)
{
    hsize_t item[2] = {n, (hsize_t)d->ncomp};
    int rank = n ? (d->ncomp > 1 ? 2 : 1) : (d->ncomp > 1 ? 1 : 0);
    const hsize_t *dims = n ? item : item + 1;
    hid_t v = gr_h5_ext_create(g, "value", d->type, rank, dims);
    if (v >= 0 && gr_h5_unit(v, d->unit)) {
        H5Dclose(v);
        return -1;
    }
    return v;
}

/* Owner of step/time: a group with both, time in tau. */
static hid_t owner_group(hid_t loc, const char *name, hid_t *step, hid_t *time)
{
    hid_t g = gr_h5_mkgroup(loc, name);
    if (g < 0)
        return -1;
    *step = gr_h5_ext_create(g, "step", GR_T_I64, 0, NULL);
    *time = gr_h5_ext_create(g, "time", GR_T_F64, 0, NULL);
    if (*step < 0 || *time < 0 || gr_h5_unit(*time, "tau")) {
        H5Gclose(g);
        return -1;
    }
    return g;
}

static const void *pack_particles(const gr_particles *p, int k, double *buf)
{
    switch (k) {
    case E_POS:
    case E_VEL: {
        const double *a = k == E_POS ? p->x : p->vx, *b = k == E_POS ? p->y : p->vy;
        for (size_t i = 0; i < p->n; i++) {
            buf[2 * i] = a[i];
            buf[2 * i + 1] = b[i];
        }
        return buf;
    }
    case E_OMEGA: return p->omega;
    case E_FLAGS: return p->flags;
    case E_RADIUS: return p->radius;
    case E_MASS: return p->mass;
    case E_INERTIA: return p->inertia;
    case E_SPECIES: return p->species;
    default: return p->id;
    }
}

static int create_trajectory(gr_h5md *h, const gr_particles *p)
{
    size_t n = p->n;
    gr_elem *pos = &h->pe[E_POS];
    pos->group = owner_group(h->traj, "position", &h->step, &h->time);
    if (pos->group < 0)
        return -1;
    pos->series = 1;
    if ((pos->value = series_value(pos->group, &gr_h5md_pdefs[E_POS], n)) < 0)
        return -1;
    /* The box never changes, but H5MD wants box step/time to be those of
     * position when edges is time-dependent; writing it per frame keeps
     * readers that expect edges/value (VMD, MDAnalysis) happy. */
    static const gr_elem_def edges = {"edges", "d", GR_T_F64, 2, 0};
    hid_t eg = series_group(h->box, "edges", pos->group);
    if (eg < 0)
        return -1;
    h->edges = series_value(eg, &edges, 0);
    H5Gclose(eg);
    if (h->edges < 0)
        return -1;
    for (int k = E_VEL; k < NPE; k++) {
        gr_elem *e = &h->pe[k];
        if (gr_h5md_pdefs[k].once) {
            size_t bytes = n * gr_h5_tsize(gr_h5md_pdefs[k].type);
            hsize_t dims[2] = {n, 0};
            e->value = gr_h5_fixed_create(h->traj, gr_h5md_pdefs[k].name, gr_h5md_pdefs[k].type, dims,
                                          pack_particles(p, k, h->buf));
            if (e->value < 0 || gr_h5_unit(e->value, gr_h5md_pdefs[k].unit) || !(e->prev = malloc(bytes)))
                return -1;
            memcpy(e->prev, pack_particles(p, k, h->buf), bytes);
        } else {
            e->series = 1;
            e->group = series_group(h->traj, gr_h5md_pdefs[k].name, pos->group);
            if (e->group < 0 || (e->value = series_value(e->group, &gr_h5md_pdefs[k], n)) < 0)
                return -1;
        }
    }
    return 0;
}

/* A quantity stored once changed: turn it into a time-dependent element
 * whose first rows repeat the stored values. */
static int promote(gr_h5md *h, int k)
{
    gr_elem *e = &h->pe[k];
    H5Dclose(e->value);
    e->value = -1;
    if (H5Ldelete(h->traj, gr_h5md_pdefs[k].name, H5P_DEFAULT) < 0)
        return -1;
    e->group = series_group(h->traj, gr_h5md_pdefs[k].name, h->pe[E_POS].group);
    if (e->group < 0 || (e->value = series_value(e->group, &gr_h5md_pdefs[k], h->n)) < 0)
        return -1;
    for (size_t f = 0; f < h->frames; f++)
        if (gr_h5_ext_append(e->value, gr_h5md_pdefs[k].type, e->prev))
            return -1;
    e->series = 1;
    free(e->prev);
    e->prev = NULL;
    return 0;
}

static int check_finite(const gr_particles *p, double time, gr_err *err)
{
    for (size_t i = 0; i < p->n; i++) {
        const char *what = !isfinite(p->x[i]) || !isfinite(p->y[i]) ? "position"
                           : !isfinite(p->vx[i]) || !isfinite(p->vy[i]) ? "velocity"
                           : !isfinite(p->omega[i]) ? "angular velocity" : NULL;
        if (what)
            return gr_fail(err, GR_ERUN,
                           "grain id %lld (index %zu) has a non-finite %s at t = %.17g; "
                           "frame not written", (long long)p->id[i], i, what, time);
    }
    return GR_OK;
}

static int push_time(gr_h5md *h, double t)
{
    if (h->frames + 1 > h->times_cap) {
        size_t cap = h->times_cap ? 2 * h->times_cap : 64;
        double *q = realloc(h->times, cap * sizeof *q);
        if (!q)
            return -1;
        h->times = q;
        h->times_cap = cap;
    }
    h->times[h->frames] = t;
    return 0;
}

static int frame_impl(gr_h5md *h, uint64_t step, double time, const gr_particles *p, gr_err *err)
{
    if (h->broken)
        return gr_fail(err, GR_ERUN, "an earlier write to %s failed; no further frames",
                       h->path ? h->path : "the file");
    if (!p || p->n == 0)
        return gr_fail(err, GR_ERUN, "a trajectory frame needs at least one grain");
    if (h->frames && p->n != h->n)
        return gr_fail(err, GR_ERUN, "frame with %zu grains, but this file holds %zu per frame",
                       p->n, h->n);
    if (!isfinite(time) || (h->frames && time < h->last_time))
        return gr_fail(err, GR_ERUN, "frame time %.17g is not after the previous one (%.17g)",
                       time, h->last_time);
    if (check_finite(p, time, err))
        return err->code;
    if (!h->frames) {
        free(h->buf);
        if (!(h->buf = malloc(2 * p->n * sizeof(double))))
            return gr_fail(err, GR_ERUN, "out of memory");
        h->n = p->n;
        if (create_trajectory(h, p)) {
            h->broken = 1;
            return gr_h5_fail(err, GR_ERUN, "cannot create the trajectory in %s", h->path ? h->path : "the file");
        }
    }
    if (push_time(h, time))
        return gr_fail(err, GR_ERUN, "out of memory");
    h->broken = 1;
    for (int k = 0; k < NPE; k++) {
        gr_elem *e = &h->pe[k];
        const void *row = pack_particles(p, k, h->buf);
        if (!e->series) {
            if (!h->frames || !memcmp(row, e->prev, h->n * gr_h5_tsize(gr_h5md_pdefs[k].type)))
                continue;
            if (gr_h5md_edit(h) || promote(h, k))
                return gr_h5_fail(err, GR_ERUN, "cannot make %s time-dependent", gr_h5md_pdefs[k].name);
        }
        if (gr_h5_ext_append(e->value, gr_h5md_pdefs[k].type, row))
            return gr_h5_fail(err, GR_ERUN, "cannot append to particles/trajectory/%s", gr_h5md_pdefs[k].name);
    }
    double edges[2] = {h->width, h->height};
    int64_t s = (int64_t)step;
    if (gr_h5_ext_append(h->edges, GR_T_F64, edges) || gr_h5_ext_append(h->step, GR_T_I64, &s) ||
        gr_h5_ext_append(h->time, GR_T_F64, &time))
        return gr_h5_fail(err, GR_ERUN, "cannot append the frame step and time");
    h->frames++;
    h->last_time = time;
    if (H5Fflush(h->file, H5F_SCOPE_GLOBAL) < 0)
        return gr_h5_fail(err, GR_ERUN, "cannot flush %s", h->path ? h->path : "the file");
    h->broken = 0;
    return gr_h5md_edited(h, err) ? err->code : update_sidecar(h, err);
}

int gr_h5md_write_frame(gr_h5md *h, uint64_t step, double time, const gr_particles *p,
                        gr_err *err)
{
    int rc;
    GR_H5_GUARD(err, rc, rc = frame_impl(h, step, time, p, err));
    return rc;
}

int gr_h5md_set_obs(gr_h5md *h, const gr_h5md_opts *o)
{
    h->odefs = o->obs ? o->obs : gr_obs_particle_set;
    h->noe = gr_obs_count(h->odefs);
    h->oskip = o->obs_skip;
    for (h->o0 = 0; h->o0 < h->noe && (h->oskip >> h->o0 & 1); h->o0++)
        ;
    return h->o0 < h->noe && h->noe <= GR_OBS_MAX ? 0 : -1;
}

/* observables/<name>: a series whose value carries its unit, meaning and,
 * for a validity counter, the key that changes the limit. */
static int obs_element(gr_h5md *h, hid_t og, size_t k)
{
    const gr_obs_def *d = &h->odefs[k];
    gr_elem_def ed = {d->name, d->unit, d->integer ? GR_T_I64 : GR_T_F64, d->ncomp, 0};
    gr_elem *e = &h->oe[k];
    e->group = k == h->o0 ? owner_group(og, d->name, &h->obs_step, &h->obs_time)
                          : series_group(og, d->name, h->oe[h->o0].group);
    e->series = 1;
    if (e->group < 0 || (e->value = series_value(e->group, &ed, 0)) < 0)
        return -1;
    return (d->doc && gr_h5_attr_str(e->value, "description", d->doc, 0)) ||
           (d->key && gr_h5_attr_str(e->value, "validity_key", d->key, 0));
}

static int obs_impl(gr_h5md *h, const gr_obs *o, gr_err *err)
{
    if (!isfinite(o->t) || (h->nobs && o->t < h->last_obs_time))
        return gr_fail(err, GR_ERUN, "observable time %.17g is not after the previous one (%.17g)",
                       o->t, h->last_obs_time);
    if (!h->nobs && h->oe[h->o0].group < 0) {
        hid_t og = gr_h5md_edit(h) ? -1 : gr_h5_mkgroup(h->file, "observables");
        int bad = og < 0;
        for (size_t k = h->o0; k < h->noe && !bad; k++)
            bad = !(h->oskip >> k & 1) && obs_element(h, og, k);
        gr_h5_close(og);
        if (bad)
            return gr_h5_fail(err, GR_ERUN, "cannot create the observables group");
    }
    int64_t step = (int64_t)o->steps;
    for (size_t k = h->o0; k < h->noe; k++) {
        if (h->oskip >> k & 1)
            continue;
        const gr_obs_def *d = &h->odefs[k];
        const void *v = gr_obs_value(o, h->odefs, k);
        int64_t iv = d->integer ? (int64_t)*(const uint64_t *)v : 0;
        if (gr_h5_ext_append(h->oe[k].value, d->integer ? GR_T_I64 : GR_T_F64, d->integer ? (const void *)&iv : v))
            return gr_h5_fail(err, GR_ERUN, "cannot append to observables/%s", d->name);
    }
    if (gr_h5_ext_append(h->obs_step, GR_T_I64, &step) ||
        gr_h5_ext_append(h->obs_time, GR_T_F64, &o->t))
        return gr_h5_fail(err, GR_ERUN, "cannot append the observables step and time");
    h->nobs++;
    h->last_obs_time = o->t;
    if (H5Fflush(h->file, H5F_SCOPE_GLOBAL) < 0)
        return gr_h5_fail(err, GR_ERUN, "cannot flush %s", h->path ? h->path : "the file");
    return gr_h5md_edited(h, err);
}

int gr_h5md_write_obs(gr_h5md *h, const gr_obs *o, gr_err *err)
{
    int rc;
    GR_H5_GUARD(err, rc, rc = obs_impl(h, o, err));
    return rc;
}

/* Every handle the writer holds, for gr_h5_swmr_copy to reopen. */
static size_t handles(gr_h5md *h, hid_t **objs)
{
    size_t n = 0;
    hid_t *fixed[] = {&h->traj, &h->box, &h->step, &h->time, &h->edges, &h->obs_step, &h->obs_time};
    for (size_t k = 0; k < sizeof fixed / sizeof *fixed; k++)
        objs[n++] = fixed[k];
    for (int k = 0; k < NPE; k++) {
        objs[n++] = &h->pe[k].group;
        objs[n++] = &h->pe[k].value;
    }
    for (int k = 0; k < GR_OBS_MAX; k++) {
        objs[n++] = &h->oe[k].group;
        objs[n++] = &h->oe[k].value;
    }
    return n;
}

int gr_h5md_publish(gr_h5md *h, gr_err *err)
{
    int rc = GR_OK, st = 0;
    if (!h->published && h->owned && h->part)
        GR_H5_GUARD(err, st < 0, st = gr_h5_swmr_start(h->file, h->part, h->path));
    if (st)
        rc = st < 0 ? gr_h5_fail(err, GR_ERUN, "cannot switch %s to SWMR writing", h->part)
                    : gr_fail(err, GR_ERUN, "cannot rename %s to %s: %s", h->part, h->path, strerror(errno));
    if (!rc)
        h->published = 1;
    return rc;
}

int gr_h5md_edit(gr_h5md *h)
{
    if (!h->published)
        return 0;
    hid_t *objs[7 + 2 * NPE + 2 * GR_OBS_MAX];
    size_t n = handles(h, objs);
    h->published = 0;
    h->republish = 1;
    if (gr_h5_swmr_copy(&h->file, objs, n, h->path, h->part)) {
        /* the file at path is whole (closed before the copy); the copy
         * must never be renamed over it */
        unlink(h->part);
        h->published = 1;
        h->republish = 0;
        h->broken = 1;
        return -1;
    }
    return 0;
}

int gr_h5md_edited(gr_h5md *h, gr_err *err)
{
    if (!h->republish)
        return GR_OK;
    h->republish = 0;
    return gr_h5md_publish(h, err);
}

int gr_h5md_flush(gr_h5md *h, gr_err *err)
{
    int rc = GR_OK;
    GR_H5_GUARD(err, rc, if (H5Fflush(h->file, H5F_SCOPE_GLOBAL) < 0)
                    rc = gr_h5_fail(err, GR_ERUN, "cannot flush %s", h->path ? h->path : "the file"));
    return rc;
}

hid_t gr_h5md_file_of(const gr_h5md *h)
{
    return h->file;
}

const char *gr_h5md_path_of(const gr_h5md *h)
{
    return h->path ? h->path : "the file";
}

size_t gr_h5md_frames(const gr_h5md *h)
{
    return h->frames;
}

int gr_h5md_close(gr_h5md *h, gr_err *err)
{
    if (!h)
        return GR_OK;
    int rc = gr_h5md_flush(h, err);
    if (!rc)
        rc = gr_h5md_write_sidecar(h, err);
    char *path = h->path ? strdup(h->path) : NULL;
    /* never published (a run that ended at its first sample, a course's
     * table): it appears whole at its path now */
    char *part = h->owned && !h->published && h->part ? strdup(h->part) : NULL;
    GR_H5_GUARD(err, rc, if (gr_h5md_release(h) < 0 && !rc)
                    rc = gr_h5_fail(err, GR_ERUN, "cannot close %s", path ? path : "the output file"));
    if (part && !rc && rename(part, path) != 0)
        rc = gr_fail(err, GR_ERUN, "cannot rename %s to %s: %s", part, path, strerror(errno));
    free(part);
    free(path);
    return rc;
}

void gr_h5md_free(gr_h5md *h)
{
    if (h)
        GR_H5_QUIET(free_writer(h));
}
