/* Continue a result file after a restart from a checkpoint: the writer's
 * state is rebuilt from the file, and every sample later than the
 * checkpoint is dropped, since the resumed run writes it again (bit for bit,
 * if the method restarts bit for bit). */
#include "h5md_impl.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "scene_types.h"

static int shrink(hid_t d, hsize_t rows)
{
    hsize_t dims[4];
    hid_t s = H5Dget_space(d);
    int rank = s >= 0 ? H5Sget_simple_extent_ndims(s) : -1;
    if (rank >= 1 && rank <= 4)
        H5Sget_simple_extent_dims(s, dims, NULL);
    gr_h5_close(s);
    if (rank < 1 || rank > 4)
        return -1;
    dims[0] = rows;
    return H5Dset_extent(d, dims) < 0 ? -1 : 0;
}

/* Leading samples of a series group whose time is <= t_keep; *times (may be
 * NULL) receives the times of all complete samples, *total their count. */
static int kept_rows(hid_t loc, const char *group, double t_keep, hsize_t *keep, double **times,
                     hsize_t *total)
{
    char p[300];
    hsize_t n = gr_h5_series_rows(loc, group);
    double *t = malloc((n ? n : 1) * sizeof *t);
    snprintf(p, sizeof p, "%s/time", group);
    if (!t || (n && gr_h5_read_path(loc, p, GR_T_F64, 0, n, t))) {
        free(t);
        return -1;
    }
    hsize_t k = 0;
    while (k < n && t[k] <= t_keep)
        k++;
    *keep = k;
    if (total)
        *total = n;
    if (times)
        *times = t;
    else
        free(t);
    return 0;
}

static int open_series(hid_t loc, const char *name, gr_elem *e, hsize_t keep)
{
    e->group = H5Gopen2(loc, name, H5P_DEFAULT);
    e->value = e->group >= 0 ? H5Dopen2(e->group, "value", H5P_DEFAULT) : -1;
    e->series = 1;
    return e->value < 0 || shrink(e->value, keep) ? -1 : 0;
}

static int reopen_trajectory(gr_h5md *h, double t_keep)
{
    hid_t traj = h->traj;
    double *t = NULL;
    hsize_t keep, total;
    if (kept_rows(traj, "position", t_keep, &keep, &t, &total))
        return -1;
    /* Complete frames: every element and the box hold them. */
    char p[64];
    for (int k = 1; k < NPE; k++)
        if (gr_h5_is_group(traj, gr_h5md_pdefs[k].name) &&
            gr_h5_series_rows(traj, gr_h5md_pdefs[k].name) < keep)
            keep = gr_h5_series_rows(traj, gr_h5md_pdefs[k].name);
    if (gr_h5_series_rows(traj, "box/edges") < keep)
        keep = gr_h5_series_rows(traj, "box/edges");
    if (!keep) {
        /* Nothing before the checkpoint: start the trajectory afresh (the
         * quantities stored once belong to the first frame). */
        free(t);
        for (int k = 0; k < NPE; k++)
            if (gr_h5_exists(traj, gr_h5md_pdefs[k].name) &&
                H5Ldelete(traj, gr_h5md_pdefs[k].name, H5P_DEFAULT) < 0)
                return -1;
        return gr_h5_exists(traj, "box/edges") && H5Ldelete(traj, "box/edges", H5P_DEFAULT) < 0 ? -1 : 0;
    }
    h->times = t;
    h->times_cap = total;
    h->frames = keep;
    h->last_time = t[keep - 1];
    gr_elem *pos = &h->pe[E_POS];
    if (open_series(traj, "position", pos, keep))
        return -1;
    h->step = H5Dopen2(pos->group, "step", H5P_DEFAULT);
    h->time = H5Dopen2(pos->group, "time", H5P_DEFAULT);
    h->edges = H5Dopen2(traj, "box/edges/value", H5P_DEFAULT);
    if (h->step < 0 || h->time < 0 || h->edges < 0 || shrink(h->step, keep) ||
        shrink(h->time, keep) || shrink(h->edges, keep))
        return -1;
    hsize_t dims[3] = {0};
    hid_t s = H5Dget_space(pos->value);
    if (H5Sget_simple_extent_ndims(s) != 3) {
        H5Sclose(s);
        return -1;
    }
    H5Sget_simple_extent_dims(s, dims, NULL);
    H5Sclose(s);
    h->n = dims[1];
    if (!(h->buf = malloc(2 * h->n * sizeof(double))))
        return -1;
    for (int k = 1; k < NPE; k++) {
        gr_elem *e = &h->pe[k];
        const gr_elem_def *d = &gr_h5md_pdefs[k];
        snprintf(p, sizeof p, "%s", d->name);
        if (gr_h5_is_group(traj, p)) {
            if (open_series(traj, p, e, keep))
                return -1;
        } else {
            e->value = H5Dopen2(traj, p, H5P_DEFAULT);
            if (e->value < 0 || !(e->prev = malloc(h->n * gr_h5_tsize(d->type))) ||
                H5Dread(e->value, gr_h5_mtype(d->type), H5S_ALL, H5S_ALL, H5P_DEFAULT, e->prev) < 0)
                return -1;
        }
    }
    return 0;
}

static int reopen_observables(gr_h5md *h, double t_keep)
{
    hid_t og = H5Gopen2(h->file, "observables", H5P_DEFAULT);
    if (og < 0)
        return -1;
    hsize_t keep = 0;
    int bad = kept_rows(og, h->odefs[h->o0].name, t_keep, &keep, NULL, NULL);
    for (size_t k = h->o0 + 1; k < h->noe && !bad; k++)
        if (!(h->oskip >> k & 1) && gr_h5_series_rows(og, h->odefs[k].name) < keep)
            keep = gr_h5_series_rows(og, h->odefs[k].name);
    for (size_t k = h->o0; k < h->noe && !bad; k++)
        bad = !(h->oskip >> k & 1) && open_series(og, h->odefs[k].name, &h->oe[k], keep);
    if (!bad) {
        h->obs_step = H5Dopen2(h->oe[h->o0].group, "step", H5P_DEFAULT);
        h->obs_time = H5Dopen2(h->oe[h->o0].group, "time", H5P_DEFAULT);
        bad = h->obs_step < 0 || h->obs_time < 0 || shrink(h->obs_step, keep) ||
              shrink(h->obs_time, keep) ||
              (keep && gr_h5_read_rows(h->obs_time, GR_T_F64, keep - 1, 1, &h->last_obs_time));
        h->nobs = keep;
    }
    gr_h5_close(og);
    return bad ? -1 : 0;
}

static herr_t shrink_field(hid_t g, const char *name, const H5L_info_t *li, void *data)
{
    (void)li;
    double t_keep = *(const double *)data;
    hsize_t keep;
    if (!gr_h5_is_group(g, name) || kept_rows(g, name, t_keep, &keep, NULL, NULL))
        return -1;
    const char *parts[] = {"step", "time", "value"};
    for (int k = 0; k < 3; k++) {
        char p[300];
        snprintf(p, sizeof p, "%s/%s", name, parts[k]);
        hid_t d = H5Dopen2(g, p, H5P_DEFAULT);
        int bad = d < 0 || shrink(d, keep);
        gr_h5_close(d);
        if (bad)
            return -1;
    }
    return 0;
}

/* The file must hold a run of this very scene, method and seed. */
static int check_same_run(hid_t f, const char *path, const gr_scene *sc, const gr_h5md_opts *o,
                          gr_err *err)
{
    hid_t g = gr_h5_is_group(f, "h5md/creator") ? H5Gopen2(f, "h5md/creator", H5P_DEFAULT) : -1;
    char *creator = g >= 0 ? gr_h5_read_attr_str(g, "name") : NULL;
    gr_h5_close(g);
    char *scene = gr_h5_read_dset_str(f, "parameters/scene");
    char *method = gr_h5_read_dset_str(f, "parameters/method");
    uint64_t seed = 0;
    int has_seed = gr_h5_read_dset_u64(f, "parameters/seed", &seed) == 0;
    int rc = GR_OK;
    if (!creator || strcmp(creator, "grano"))
        rc = gr_fail(err, GR_EINPUT, "%s is not a grano result file", path);
    else if (!scene || (!o->any_text && strcmp(scene, sc->text ? sc->text : "")))
        rc = gr_fail(err, GR_EINPUT, "%s holds a run of another scene (its parameters/scene differs); "
                     "continue into a new file", path);
    else if (!method || strcmp(method, o->method ? o->method : ""))
        rc = gr_fail(err, GR_EINPUT, "%s holds a run of method '%s', not '%s'", path,
                     method ? method : "?", o->method ? o->method : "");
    else if (!has_seed || seed != o->seed)
        rc = gr_fail(err, GR_EINPUT, "%s holds a run with seed %llu, not %llu", path,
                     (unsigned long long)seed, (unsigned long long)o->seed);
    free(creator);
    free(scene);
    free(method);
    return rc;
}

/* A failed reopen: the copy goes, the file stays as it was. */
static gr_h5md *unlink_release(gr_h5md *h)
{
    unlink(h->part);
    gr_h5md_release(h);
    return NULL;
}

static gr_h5md *reopen_impl(const char *path, const gr_scene *sc, const gr_h5md_opts *o,
                            double t_keep, gr_err *err)
{
    struct stat st;
    if (!path || stat(path, &st) != 0) {
        gr_fail(err, GR_EINPUT, "%s: %s", path ? path : "(no file)",
                errno == ENOENT ? "no such file to continue" : strerror(errno));
        return NULL;
    }
    if (H5Fis_hdf5(path) <= 0) {
        gr_fail(err, GR_EINPUT, "%s is not an HDF5 file, so not a grano result file", path);
        return NULL;
    }
    gr_h5md *h = gr_h5md_alloc();
    if (!h || !(h->path = strdup(path)) || (!o->no_xdmf && !(h->xdmf = gr_h5_catstr(path, ".xdmf")))) {
        gr_fail(err, GR_ERUN, "out of memory");
        if (h)
            gr_h5md_release(h);
        return NULL;
    }
    const char *slash = strrchr(path, '/');
    h->h5name = strdup(slash ? slash + 1 : path);
    h->owned = 1;
    gr_h5md_set_obs(h, o);
    /* Samples are dropped on a copy, published over the file once it holds
     * only whole ones: a kill meanwhile leaves the file as it was. */
    if (!(h->part = gr_h5_catstr(path, ".part")) || gr_h5_copy_file(path, h->part)) {
        gr_fail(err, GR_ERUN, "cannot copy %s to continue it: %s", path, strerror(errno));
        gr_h5md_release(h);
        return NULL;
    }
    h->file = gr_h5_open_rw(h->part);
    if (h->file < 0) {
        gr_h5_fail(err, GR_EINPUT, "cannot open %s to continue it", path);
        return unlink_release(h);
    }
    /* A run killed while HDF5 wrote a frame can leave chunks the index
     * points at past the end of allocation the superblock records, and
     * the continued run's next write there failed ("addr overflow": 2 of
     * 47 runs of fault_kill.py's 40 kills before, none of 80 since).
     * Allocation now starts past all the file holds. */
    if (H5Fincrement_filesize(h->file, 0) < 0) {
        gr_h5_fail(err, GR_ERUN, "cannot continue %s: its end of allocation cannot be set", path);
        return unlink_release(h);
    }
    if (check_same_run(h->file, path, sc, o, err))
        return unlink_release(h);
    h->width = sc->width;
    h->height = sc->height;
    h->traj = H5Gopen2(h->file, "particles/trajectory", H5P_DEFAULT);
    h->box = h->traj >= 0 ? H5Gopen2(h->traj, "box", H5P_DEFAULT) : -1;
    int bad = h->box < 0 || !h->h5name ||
              (gr_h5_is_group(h->traj, "position") && reopen_trajectory(h, t_keep)) ||
              (gr_h5_is_group(h->file, "observables") && reopen_observables(h, t_keep));
    if (!bad && gr_h5_is_group(h->file, "fields")) {
        hid_t g = H5Gopen2(h->file, "fields", H5P_DEFAULT);
        hsize_t idx = 0;
        bad = g < 0 || H5Literate(g, H5_INDEX_NAME, H5_ITER_INC, &idx, shrink_field, &t_keep) < 0;
        gr_h5_close(g);
    }
    if (!bad && gr_h5md_contacts_keep(h->file, t_keep))
        bad = 1;
    if (bad || H5Fflush(h->file, H5F_SCOPE_GLOBAL) < 0) {
        gr_h5_fail(err, GR_ERUN, "cannot continue %s: its trajectory, observables, fields or contacts are malformed",
                   path);
        return unlink_release(h);
    }
    if (gr_h5md_write_sidecar(h, err) || gr_h5md_publish(h, err))
        return unlink_release(h);
    return h;
}

gr_h5md *gr_h5md_reopen(const char *path, const gr_scene *sc, const gr_h5md_opts *o,
                        double t_keep, gr_err *err)
{
    gr_h5md_opts zero = {0};
    if (!sc) {
        gr_fail(err, GR_ERUN, "gr_h5md_reopen: no scene");
        return NULL;
    }
    gr_h5md *h = NULL;
    GR_H5_GUARD(err, !h, h = reopen_impl(path, sc, o ? o : &zero, t_keep, err));
    return h;
}
