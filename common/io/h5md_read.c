/* H5MD reader for the files gr_h5md writes (and checkpoints): used by
 * `grano info` and restarts. A file whose writer died is read up to its
 * last complete frame: the count is the shortest of all the series. */
#include "h5md_impl.h"

#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

struct gr_h5md_reader {
    hid_t file;
    gr_h5md_info info;
};

static const char *const traj_elems[] = {"position", "velocity", "omega", "flags", "radius",
                                         "mass", "inertia", "species", "id"};
#define NTRAJ (sizeof traj_elems / sizeof traj_elems[0])

static void free_info(gr_h5md_info *in)
{
    free(in->path);
    free(in->creator);
    free(in->creator_version);
    free(in->author);
    free(in->scene_text);
    free(in->scene_name);
    free(in->scene_path);
    free(in->method);
    free(in->grano_version);
    free(in->derived);
}

static char *dup_or_empty(char *s)
{
    return s ? s : strdup("");
}

static int count_frames(gr_h5md_reader *r)
{
    gr_h5md_info *in = &r->info;
    hid_t f = r->file;
    if (!gr_h5_is_group(f, "particles/trajectory/position"))
        return 0;
    hsize_t frames = gr_h5_series_rows(f, "particles/trajectory/position");
    char p[256];
    for (size_t k = 1; k < NTRAJ; k++) {
        snprintf(p, sizeof p, "particles/trajectory/%s", traj_elems[k]);
        if (gr_h5_is_group(f, p)) {
            hsize_t n = gr_h5_series_rows(f, p);
            if (n < frames)
                frames = n;
        }
    }
    if (gr_h5_is_group(f, "particles/trajectory/box/edges")) {
        hsize_t n = gr_h5_series_rows(f, "particles/trajectory/box/edges");
        if (n < frames)
            frames = n;
    }
    in->nframes = frames;
    hid_t d = H5Dopen2(f, "particles/trajectory/position/value", H5P_DEFAULT);
    if (d < 0)
        return -1;
    hid_t s = H5Dget_space(d);
    hsize_t dims[3] = {0};
    int rank = H5Sget_simple_extent_ndims(s);
    if (rank == 3)
        H5Sget_simple_extent_dims(s, dims, NULL);
    H5Sclose(s);
    H5Dclose(d);
    if (rank != 3 || dims[2] != 2)
        return -1;
    in->nparticles = dims[1];
    return 0;
}


typedef struct {
    char **names;
    size_t n, cap;
    int failed;
} name_list;

static herr_t collect(hid_t g, const char *name, const H5L_info_t *li, void *data)
{
    (void)g;
    (void)li;
    name_list *l = data;
    if (l->n == l->cap) {
        size_t cap = l->cap ? 2 * l->cap : 16;
        char **q = realloc(l->names, cap * sizeof *q);
        if (!q) {
            l->failed = 1;
            return -1;
        }
        l->names = q;
        l->cap = cap;
    }
    if (!(l->names[l->n] = strdup(name))) {
        l->failed = 1;
        return -1;
    }
    l->n++;
    return 0;
}

static int list_impl(hid_t f, const char *group, char ***names, size_t *n)
{
    *names = NULL;
    *n = 0;
    if (!gr_h5_is_group(f, group))
        return 0;
    hid_t g = H5Gopen2(f, group, H5P_DEFAULT);
    if (g < 0)
        return -1;
    name_list l = {NULL, 0, 0, 0};
    hsize_t idx = 0;
    herr_t st = H5Literate(g, H5_INDEX_NAME, H5_ITER_INC, &idx, collect, &l);
    H5Gclose(g);
    if (st < 0 || l.failed) {
        gr_h5md_names_free(l.names, l.n);
        return -1;
    }
    *names = l.names;
    *n = l.n;
    return 0;
}

void gr_h5md_names_free(char **names, size_t n)
{
    for (size_t i = 0; i < n; i++)
        free(names[i]);
    free(names);
}

static int count_obs(gr_h5md_reader *r)
{
    char **names;
    size_t n;
    if (list_impl(r->file, "observables", &names, &n))
        return -1;
    hsize_t rows = (hsize_t)-1;
    char p[512];
    for (size_t i = 0; i < n; i++) {
        snprintf(p, sizeof p, "observables/%s", names[i]);
        if (gr_h5_is_group(r->file, p)) {
            hsize_t k = gr_h5_series_rows(r->file, p);
            if (k < rows)
                rows = k;
        }
    }
    r->info.nobs = rows == (hsize_t)-1 ? 0 : rows;
    gr_h5md_names_free(names, n);
    return 0;
}

/* The plain-file checks, so that a wrong path gets a message that says
 * what it is rather than an HDF5 error stack. */
static int check_hdf5_file(const char *path, gr_err *err)
{
    struct stat st;
    if (stat(path, &st) != 0)
        return gr_fail(err, GR_EINPUT, "%s: %s", path,
                       errno == ENOENT ? "no such file" : strerror(errno));
    if (S_ISDIR(st.st_mode))
        return gr_fail(err, GR_EINPUT, "%s is a directory, not a grano result file", path);
    if (H5Fis_hdf5(path) <= 0) {
        H5Eclear2(H5E_DEFAULT);
        return gr_fail(err, GR_EINPUT, "%s is not an HDF5 file, so not a grano result file",
                       path);
    }
    return GR_OK;
}

static gr_h5md_reader *open_file(const char *path, gr_err *err)
{
    gr_h5md_reader *r = calloc(1, sizeof *r);
    if (!r) {
        gr_fail(err, GR_ERUN, "out of memory");
        return NULL;
    }
    r->file = gr_h5_open_ro(path);
    if (r->file < 0) {
        gr_h5_fail(err, GR_EINPUT, "cannot open %s", path);
        free(r);
        return NULL;
    }
    return r;
}

/* Reads h5md/creator into in; fails unless it names grano. */
static int read_creator(hid_t file, gr_h5md_info *in, const char *path, gr_err *err)
{
    hid_t g = gr_h5_is_group(file, "h5md/creator") ? H5Gopen2(file, "h5md/creator", H5P_DEFAULT) : -1;
    in->creator = g >= 0 ? gr_h5_read_attr_str(g, "name") : NULL;
    in->creator_version = g >= 0 ? gr_h5_read_attr_str(g, "version") : NULL;
    gr_h5_close(g);
    if (in->creator && strcmp(in->creator, "grano") == 0)
        return GR_OK;
    if (in->creator)
        return gr_fail(err, GR_EINPUT, "%s was written by '%s', not by grano", path, in->creator);
    return gr_fail(err, GR_EINPUT, "%s is an HDF5 file but not a grano result file (no h5md/creator)", path);
}

static void read_parameters(hid_t file, gr_h5md_info *in)
{
    hid_t g = H5Gopen2(file, "h5md", H5P_DEFAULT);
    if (g >= 0)
        gr_h5_read_attr_int(g, "version", in->h5md_version, 2);
    gr_h5_close(g);
    g = gr_h5_is_group(file, "h5md/author") ? H5Gopen2(file, "h5md/author", H5P_DEFAULT) : -1;
    in->author = dup_or_empty(g >= 0 ? gr_h5_read_attr_str(g, "name") : NULL);
    gr_h5_close(g);
    in->creator_version = dup_or_empty(in->creator_version);
    in->scene_text = dup_or_empty(gr_h5_read_dset_str(file, "parameters/scene"));
    in->scene_name = dup_or_empty(gr_h5_read_dset_str(file, "parameters/scene_name"));
    in->scene_path = dup_or_empty(gr_h5_read_dset_str(file, "parameters/scene_path"));
    in->method = dup_or_empty(gr_h5_read_dset_str(file, "parameters/method"));
    in->grano_version = dup_or_empty(gr_h5_read_dset_str(file, "parameters/grano_version"));
    in->derived = dup_or_empty(gr_h5_read_dset_str(file, "parameters/derived"));
    gr_h5_read_dset_u64(file, "parameters/seed", &in->seed);
    in->has_checkpoint = gr_h5_is_group(file, "checkpoint");
    unsigned intent = 0;
    in->writing = H5Fget_intent(file, &intent) >= 0 && (intent & H5F_ACC_SWMR_READ);
}

/* The box's boundary attribute into in->periodic (left 0 if absent). */
static void read_boundary(hid_t file, gr_h5md_info *in)
{
    hid_t g = gr_h5_is_group(file, "particles/trajectory/box")
                  ? H5Gopen2(file, "particles/trajectory/box", H5P_DEFAULT) : -1;
    if (g < 0)
        return;
    char *b = NULL;
    /* boundary is a fixed-length string array: read it as one block. */
    hid_t a = H5Aexists(g, "boundary") > 0 ? H5Aopen(g, "boundary", H5P_DEFAULT) : -1;
    if (a >= 0) {
        hid_t t = H5Aget_type(a);
        size_t len = H5Tget_size(t);
        if (H5Tis_variable_str(t) <= 0 && (b = calloc(2 * len + 1, 1)) &&
            H5Aread(a, t, b) >= 0) {
            in->periodic[0] = !strncmp(b, "periodic", len < 8 ? len : 8);
            in->periodic[1] = !strncmp(b + len, "periodic", len < 8 ? len : 8);
        }
        free(b);
        H5Tclose(t);
        H5Aclose(a);
    }
    gr_h5_close(g);
}

static gr_h5md_reader *open_impl(const char *path, gr_err *err)
{
    if (check_hdf5_file(path, err))
        return NULL;
    gr_h5md_reader *r = open_file(path, err);
    if (!r)
        return NULL;
    gr_h5md_info *in = &r->info;
    in->path = strdup(path);
    if (read_creator(r->file, in, path, err)) {
        gr_h5md_reader_free(r);
        return NULL;
    }
    read_parameters(r->file, in);
    in->box[0] = in->box[1] = NAN;
    read_boundary(r->file, in);
    if (!in->path || count_frames(r) || count_obs(r)) {
        gr_h5_fail(err, GR_EINPUT, "%s: malformed grano trajectory", path);
        gr_h5md_reader_free(r);
        return NULL;
    }
    if (in->nframes) {
        hid_t d = H5Dopen2(r->file, "particles/trajectory/box/edges/value", H5P_DEFAULT);
        if (d >= 0)
            gr_h5_read_rows(d, GR_T_F64, 0, 1, in->box);
        gr_h5_close(d);
    }
    H5Eclear2(H5E_DEFAULT);
    return r;
}

gr_h5md_reader *gr_h5md_open(const char *path, gr_err *err)
{
    gr_h5md_reader *r = NULL;
    GR_H5_GUARD(err, !r, r = open_impl(path, err));
    if (!r && err && strstr(err->msg, "unable to lock file")) {
        size_t len = strlen(err->msg);
        snprintf(err->msg + len, sizeof err->msg - len,
                 "; is a run still writing it? (HDF5_USE_FILE_LOCKING=FALSE reads it anyway)");
    }
    return r;
}

void gr_h5md_reader_free(gr_h5md_reader *r)
{
    if (!r)
        return;
    GR_H5_QUIET(gr_h5_close(r->file));
    free_info(&r->info);
    free(r);
}

const gr_h5md_info *gr_h5md_info_of(const gr_h5md_reader *r)
{
    return &r->info;
}

static int times_impl(gr_h5md_reader *r, double *time, uint64_t *step, gr_err *err)
{
    size_t n = r->info.nframes;
    if (!n)
        return GR_OK;
    int64_t *s = step ? malloc(n * sizeof *s) : NULL;
    if (step && !s)
        return gr_fail(err, GR_ERUN, "out of memory");
    int bad = (time && gr_h5_read_path(r->file, "particles/trajectory/position/time", GR_T_F64, 0, n, time)) ||
              (s && gr_h5_read_path(r->file, "particles/trajectory/position/step", GR_T_I64, 0, n, s));
    for (size_t i = 0; s && !bad && i < n; i++)
        step[i] = (uint64_t)s[i];
    free(s);
    return bad ? gr_h5_fail(err, GR_ERUN, "%s: cannot read the frame times", r->info.path) : GR_OK;
}

int gr_h5md_read_times(gr_h5md_reader *r, double *time, uint64_t *step, gr_err *err)
{
    int rc;
    GR_H5_GUARD(err, rc, rc = times_impl(r, time, step, err));
    return rc;
}

/* Element k of frame into dst: from value[frame] if time-dependent, else
 * the dataset itself. Returns 1 if absent, -1 on error. */
static int read_elem(hid_t f, size_t k, size_t frame, gr_h5_type t, void *dst)
{
    char p[256];
    snprintf(p, sizeof p, "particles/trajectory/%s", traj_elems[k]);
    if (!gr_h5_exists(f, p))
        return 1;
    if (gr_h5_is_group(f, p)) {
        snprintf(p, sizeof p, "particles/trajectory/%s/value", traj_elems[k]);
        return gr_h5_read_path(f, p, t, frame, 1, dst);
    }
    hid_t d = H5Dopen2(f, p, H5P_DEFAULT);
    if (d < 0)
        return -1;
    int rc = H5Dread(d, gr_h5_mtype(t), H5S_ALL, H5S_ALL, H5P_DEFAULT, dst) < 0 ? -1 : 0;
    H5Dclose(d);
    return rc;
}

static int frame_impl(gr_h5md_reader *r, size_t frame, gr_particles *p, uint64_t *step,
                      double *time, gr_err *err)
{
    const gr_h5md_info *in = &r->info;
    if (frame >= in->nframes)
        return gr_fail(err, GR_EINPUT, "%s has %zu frames; there is no frame %zu", in->path,
                       in->nframes, frame);
    size_t n = in->nparticles;
    if (gr_particles_reserve(p, n, err))
        return err->code;
    double *buf = malloc(2 * n * sizeof *buf);
    if (!buf)
        return gr_fail(err, GR_ERUN, "out of memory");
    p->n = n;
    int bad = read_elem(r->file, 0, frame, GR_T_F64, buf) != 0;
    for (size_t i = 0; !bad && i < n; i++) {
        p->x[i] = buf[2 * i];
        p->y[i] = buf[2 * i + 1];
    }
    int st = bad ? -1 : read_elem(r->file, 1, frame, GR_T_F64, buf);
    bad = st < 0;
    for (size_t i = 0; !bad && i < n; i++) {
        p->vx[i] = st ? 0.0 : buf[2 * i];
        p->vy[i] = st ? 0.0 : buf[2 * i + 1];
    }
    free(buf);
    struct { void *dst; gr_h5_type t; } cols[] = {
        {p->omega, GR_T_F64}, {p->flags, GR_T_U32}, {p->radius, GR_T_F64}, {p->mass, GR_T_F64},
        {p->inertia, GR_T_F64}, {p->species, GR_T_I32}, {p->id, GR_T_I64}};
    int absent[NTRAJ] = {0};
    for (size_t k = 2; !bad && k < NTRAJ; k++) {
        st = read_elem(r->file, k, frame, cols[k - 2].t, cols[k - 2].dst);
        bad = st < 0;
        absent[k] = st == 1;
    }
    if (bad)
        return gr_h5_fail(err, GR_ERUN, "%s: cannot read frame %zu", in->path, frame);
    /* Defaults for elements another H5MD writer may not have stored. */
    for (size_t i = 0; i < n; i++) {
        if (absent[2]) p->omega[i] = 0.0;
        if (absent[3]) p->flags[i] = 0;
        if (absent[4]) p->radius[i] = 0.5;
        if (absent[5]) p->mass[i] = 1.0;
        if (absent[6]) p->inertia[i] = gr_disk_inertia(p->mass[i], p->radius[i]);
        if (absent[7]) p->species[i] = 0;
        if (absent[8]) p->id[i] = (int64_t)i;
    }
    int64_t s = 0;
    if ((step && gr_h5_read_path(r->file, "particles/trajectory/position/step", GR_T_I64, frame, 1, &s)) ||
        (time && gr_h5_read_path(r->file, "particles/trajectory/position/time", GR_T_F64, frame, 1, time)))
        return gr_h5_fail(err, GR_ERUN, "%s: cannot read the time of frame %zu", in->path, frame);
    if (step)
        *step = (uint64_t)s;
    return GR_OK;
}

int gr_h5md_read_frame(gr_h5md_reader *r, size_t frame, gr_particles *p, uint64_t *step,
                       double *time, gr_err *err)
{
    int rc;
    GR_H5_GUARD(err, rc, rc = frame_impl(r, frame, p, step, time, err));
    return rc;
}

static int obs_impl(gr_h5md_reader *r, gr_obs *obs, gr_err *err)
{
    size_t n = r->info.nobs;
    if (!n)
        return GR_OK;
    double *d = malloc(2 * n * sizeof *d);
    int64_t *iv = malloc(n * sizeof *iv);
    if (!d || !iv) {
        free(d);
        free(iv);
        return gr_fail(err, GR_ERUN, "out of memory");
    }
    for (size_t i = 0; i < n; i++) {
        memset(&obs[i], 0, sizeof obs[i]);
        obs[i].ekin_trans = obs[i].ekin_rot = obs[i].epot_grav = obs[i].temperature = NAN;
        obs[i].px = obs[i].py = obs[i].wall_pressure = obs[i].max_overlap = NAN;
    }
    static const char *const fnames[] = {"ekin_trans", "ekin_rot", "epot_grav", "temperature",
                                         "wall_pressure", "max_overlap"};
    const size_t foff[] = {offsetof(gr_obs, ekin_trans), offsetof(gr_obs, ekin_rot),
                           offsetof(gr_obs, epot_grav), offsetof(gr_obs, temperature),
                           offsetof(gr_obs, wall_pressure), offsetof(gr_obs, max_overlap)};
    char p[128];
    int bad = 0;
    const char *time_src = NULL;
    for (size_t k = 0; k < 6 && !bad; k++) {
        snprintf(p, sizeof p, "observables/%s/value", fnames[k]);
        if (!gr_h5_exists(r->file, p))
            continue;
        bad = gr_h5_read_path(r->file, p, GR_T_F64, 0, n, d) != 0;
        for (size_t i = 0; !bad && i < n; i++)
            *(double *)((char *)&obs[i] + foff[k]) = d[i];
        time_src = fnames[k];
    }
    if (!bad && gr_h5_exists(r->file, "observables/momentum/value")) {
        bad = gr_h5_read_path(r->file, "observables/momentum/value", GR_T_F64, 0, n, d) != 0;
        for (size_t i = 0; !bad && i < n; i++) {
            obs[i].px = d[2 * i];
            obs[i].py = d[2 * i + 1];
        }
        time_src = "momentum";
    }
    static const char *const inames[] = {"n_mobile", "outflow"};
    for (size_t k = 0; k < 2 && !bad; k++) {
        snprintf(p, sizeof p, "observables/%s/value", inames[k]);
        if (!gr_h5_exists(r->file, p))
            continue;
        bad = gr_h5_read_path(r->file, p, GR_T_I64, 0, n, iv) != 0;
        for (size_t i = 0; !bad && i < n; i++)
            *(k ? &obs[i].outflow : &obs[i].n_mobile) = (uint64_t)iv[i];
        time_src = inames[k];
    }
    if (!bad && time_src) {
        snprintf(p, sizeof p, "observables/%s/time", time_src);
        bad = gr_h5_read_path(r->file, p, GR_T_F64, 0, n, d) != 0;
        for (size_t i = 0; !bad && i < n; i++)
            obs[i].t = d[i];
        snprintf(p, sizeof p, "observables/%s/step", time_src);
        bad = bad || gr_h5_read_path(r->file, p, GR_T_I64, 0, n, iv) != 0;
        for (size_t i = 0; !bad && i < n; i++)
            obs[i].steps = (uint64_t)iv[i];
    }
    free(d);
    free(iv);
    return bad ? gr_h5_fail(err, GR_ERUN, "%s: cannot read the observables", r->info.path) : GR_OK;
}

int gr_h5md_read_obs(gr_h5md_reader *r, gr_obs *obs, gr_err *err)
{
    int rc;
    GR_H5_GUARD(err, rc, rc = obs_impl(r, obs, err));
    return rc;
}

int gr_h5md_list(gr_h5md_reader *r, const char *group, char ***names, size_t *n, gr_err *err)
{
    int rc;
    GR_H5_GUARD(err, rc, rc = list_impl(r->file, group, names, n));
    return rc ? gr_fail(err, GR_ERUN, "%s: cannot list %s", r->info.path, group) : GR_OK;
}

static int series_impl(gr_h5md_reader *r, const char *path, size_t *samples, double *t0,
                       double *t1, gr_err *err)
{
    if (!gr_h5_is_group(r->file, path))
        return gr_fail(err, GR_EINPUT, "%s has no time series %s", r->info.path, path);
    hsize_t n = gr_h5_series_rows(r->file, path);
    *samples = n;
    *t0 = *t1 = NAN;
    char p[512];
    snprintf(p, sizeof p, "%s/time", path);
    if (n && gr_h5_exists(r->file, p) &&
        (gr_h5_read_path(r->file, p, GR_T_F64, 0, 1, t0) || gr_h5_read_path(r->file, p, GR_T_F64, n - 1, 1, t1)))
        return gr_h5_fail(err, GR_ERUN, "%s: cannot read %s", r->info.path, p);
    return GR_OK;
}

int gr_h5md_series_info(gr_h5md_reader *r, const char *path, size_t *samples, double *t0,
                        double *t1, gr_err *err)
{
    int rc;
    GR_H5_GUARD(err, rc, rc = series_impl(r, path, samples, t0, t1, err));
    return rc;
}

static int series_times_impl(gr_h5md_reader *r, const char *path, size_t n, double *time, gr_err *err)
{
    char p[512];
    snprintf(p, sizeof p, "%s/time", path);
    if (!gr_h5_exists(r->file, p))
        return gr_fail(err, GR_EINPUT, "%s has no time series %s", r->info.path, path);
    if (n && gr_h5_read_path(r->file, p, GR_T_F64, 0, n, time))
        return gr_h5_fail(err, GR_ERUN, "%s: cannot read %zu times of %s", r->info.path, n, p);
    return GR_OK;
}

int gr_h5md_series_times(gr_h5md_reader *r, const char *path, size_t n, double *time, gr_err *err)
{
    int rc;
    GR_H5_GUARD(err, rc, rc = series_times_impl(r, path, n, time, err));
    return rc;
}

hid_t gr_h5md_reader_file(const gr_h5md_reader *r)
{
    return r->file;
}

static int xdmf_impl(gr_h5md_reader *r, gr_err *err)
{
    const gr_h5md_info *in = &r->info;
    double *t = malloc((in->nframes ? in->nframes : 1) * sizeof *t);
    size_t len = strlen(in->path);
    char *x = malloc(len + 6);
    if (!t || !x) {
        free(t);
        free(x);
        return gr_fail(err, GR_ERUN, "out of memory");
    }
    memcpy(x, in->path, len);
    memcpy(x + len, ".xdmf", 6);
    static const gr_h5_type types[NTRAJ] = {GR_T_F64, GR_T_F64, GR_T_F64, GR_T_U32, GR_T_F64,
                                            GR_T_F64, GR_T_F64, GR_T_I32, GR_T_I64};
    gr_xdmf_attr a[NTRAJ];
    size_t na = 0;
    char p[128];
    for (size_t k = 1; k < NTRAJ; k++) {
        if (k == 5 || k == 6) /* mass, inertia: as the writer, left out */
            continue;
        snprintf(p, sizeof p, "particles/trajectory/%s", traj_elems[k]);
        if (gr_h5_exists(r->file, p))
            a[na++] = (gr_xdmf_attr){traj_elems[k], gr_h5_is_group(r->file, p), k == 1 ? 2 : 1,
                                     types[k]};
    }
    const char *slash = strrchr(in->path, '/');
    int rc = times_impl(r, t, NULL, err);
    if (!rc)
        rc = gr_xdmf_write(x, slash ? slash + 1 : in->path, r->file, in->nparticles, in->nframes, t, a, na, err);
    free(t);
    free(x);
    return rc;
}

int gr_h5md_write_xdmf(gr_h5md_reader *r, gr_err *err)
{
    int rc;
    GR_H5_GUARD(err, rc, rc = xdmf_impl(r, err));
    return rc;
}

static int obs_last_impl(gr_h5md_reader *r, const char *name, double v[2], int *ncomp, char *key, size_t keyn,
                         gr_err *err)
{
    char p[300];
    snprintf(p, sizeof p, "observables/%s/value", name);
    hid_t d = H5Dopen2(r->file, p, H5P_DEFAULT);
    if (d < 0)
        return gr_h5_fail(err, GR_EINPUT, "%s: no %s", r->info.path, p);
    hid_t s = H5Dget_space(d);
    hsize_t dims[2] = {0, 1};
    int rank = s < 0 ? -1 : H5Sget_simple_extent_ndims(s);
    if (rank == 1 || rank == 2)
        H5Sget_simple_extent_dims(s, dims, NULL);
    gr_h5_close(s);
    *ncomp = rank == 2 ? (int)dims[1] : 1;
    int bad = rank < 1 || rank > 2 || *ncomp > 2 || !dims[0] ||
              gr_h5_read_rows(d, GR_T_F64, dims[0] - 1, 1, v);
    char *k = bad ? NULL : gr_h5_read_attr_str(d, "validity_key");
    snprintf(key, keyn, "%s", k ? k : "");
    free(k);
    H5Dclose(d);
    return bad ? gr_h5_fail(err, GR_EINPUT, "%s: cannot read the last sample of %s", r->info.path, p) : GR_OK;
}

int gr_h5md_obs_last(gr_h5md_reader *r, const char *name, double v[2], int *ncomp, char *key, size_t keyn,
                     gr_err *err)
{
    int rc;
    GR_H5_GUARD(err, rc, rc = obs_last_impl(r, name, v, ncomp, key, keyn, err));
    return rc;
}
