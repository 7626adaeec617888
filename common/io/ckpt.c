/* Checkpoint store on HDF5: named typed arrays in /checkpoint. A checkpoint
 * is written to <path>.tmp and renamed over <path> only once it is complete
 * and synced, so a crash at any moment leaves the previous one intact. */
#include "ckpt.h"

#include <errno.h>
#include <fcntl.h>
#include <libgen.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "h5md_impl.h"
#include "scene_types.h"

struct gr_ckpt {
    hid_t file, group;
    int writing;
    int failed;       /* a store failed: close discards instead of publishing */
    int has_h5md;
    char *path, *tmp;
};

static const char *type_name(gr_h5_type t)
{
    static const char *const names[] = {"f64", "i64", "i32", "u32", "u64", "bytes"};
    return names[t];
}

static void ckpt_release(gr_ckpt *c)
{
    gr_h5_close(c->group);
    gr_h5_close(c->file);
    free(c->path);
    free(c->tmp);
    free(c);
}

static gr_ckpt *create_impl(const char *path, gr_err *err)
{
    gr_ckpt *c = calloc(1, sizeof *c);
    size_t len = path ? strlen(path) : 0;
    if (!len) {
        free(c);
        gr_fail(err, GR_EINPUT, "no checkpoint file given");
        return NULL;
    }
    if (!c || !(c->path = strdup(path)) || !(c->tmp = malloc(len + 5))) {
        if (c)
            free(c->path);
        free(c);
        gr_fail(err, GR_ERUN, "out of memory");
        return NULL;
    }
    memcpy(c->tmp, path, len);
    memcpy(c->tmp + len, ".tmp", 5);
    c->writing = 1;
    c->group = -1;
    hid_t fapl = gr_h5_fapl();
    hid_t fcpl = gr_h5_untimed(H5P_FILE_CREATE);
    c->file = fapl < 0 || fcpl < 0 ? -1 : H5Fcreate(c->tmp, H5F_ACC_TRUNC, fcpl, fapl);
    gr_h5_close(fapl);
    gr_h5_close(fcpl);
    if (c->file < 0) {
        gr_h5_fail(err, GR_EINPUT, "cannot create checkpoint %s", path);
        ckpt_release(c);
        return NULL;
    }
    c->group = gr_h5_mkgroup(c->file, "checkpoint");
    if (c->group < 0) {
        gr_h5_fail(err, GR_ERUN, "cannot write checkpoint %s", path);
        gr_h5_close(c->file);
        c->file = -1;
        unlink(c->tmp);
        ckpt_release(c);
        return NULL;
    }
    return c;
}

gr_ckpt *gr_ckpt_create(const char *path, gr_err *err)
{
    gr_ckpt *c = NULL;
    GR_H5_GUARD(err, !c, c = create_impl(path, err));
    return c;
}

static gr_ckpt *open_impl(const char *path, gr_err *err)
{
    struct stat st;
    if (!path || stat(path, &st) != 0) {
        gr_fail(err, GR_EINPUT, "checkpoint %s: %s", path ? path : "(none)",
                errno == ENOENT ? "no such file" : strerror(errno));
        return NULL;
    }
    if (H5Fis_hdf5(path) <= 0) {
        gr_fail(err, GR_EINPUT, "%s is not an HDF5 file, so not a grano checkpoint", path);
        return NULL;
    }
    gr_ckpt *c = calloc(1, sizeof *c);
    if (!c || !(c->path = strdup(path))) {
        free(c);
        gr_fail(err, GR_ERUN, "out of memory");
        return NULL;
    }
    c->group = -1;
    hid_t fapl = gr_h5_fapl();
    c->file = fapl < 0 ? -1 : H5Fopen(path, H5F_ACC_RDONLY, fapl);
    gr_h5_close(fapl);
    if (c->file < 0) {
        gr_h5_fail(err, GR_EINPUT, "cannot open checkpoint %s", path);
        ckpt_release(c);
        return NULL;
    }
    if (H5Lexists(c->file, "checkpoint", H5P_DEFAULT) <= 0 ||
        (c->group = H5Gopen2(c->file, "checkpoint", H5P_DEFAULT)) < 0) {
        H5Eclear2(H5E_DEFAULT);
        gr_fail(err, GR_EINPUT, "%s is not a grano checkpoint (no /checkpoint group)", path);
        ckpt_release(c);
        return NULL;
    }
    return c;
}

gr_ckpt *gr_ckpt_open(const char *path, gr_err *err)
{
    gr_ckpt *c = NULL;
    GR_H5_GUARD(err, !c, c = open_impl(path, err));
    return c;
}

static int valid_name(const char *s)
{
    return s && s[0] && s[0] != '/' && s[strlen(s) - 1] != '/' && !strstr(s, "//") &&
           strlen(s) < 256;
}

static int put(gr_ckpt *c, const char *name, gr_h5_type t, const void *v, size_t n, gr_err *err)
{
    if (!c->writing)
        return gr_fail(err, GR_ERUN, "checkpoint %s is open for reading", c->path);
    int rc = GR_OK;
    if (!valid_name(name)) {
        rc = gr_fail(err, GR_ERUN, "invalid checkpoint array name '%s'", name ? name : "");
    } else if (gr_h5_exists(c->group, name)) {
        rc = gr_fail(err, GR_ERUN, "checkpoint array '%s' stored twice", name);
    } else if (n && !v) {
        rc = gr_fail(err, GR_ERUN, "checkpoint array '%s': no data", name);
    } else {
        hsize_t dims[2] = {n, 0};
        hid_t d = gr_h5_fixed_create(c->group, name, t, dims, v);
        if (d < 0)
            rc = gr_h5_fail(err, GR_ERUN, "cannot store checkpoint array '%s' in %s", name, c->tmp);
        gr_h5_close(d);
    }
    if (rc)
        c->failed = 1;
    return rc;
}

/* Open name and check it is a 1-D array of type t; *len gets its length. */
static hid_t open_array(gr_ckpt *c, const char *name, gr_h5_type t, size_t *len, gr_err *err)
{
    if (!valid_name(name) || !gr_h5_exists(c->group, name)) {
        gr_fail(err, GR_ERUN, "checkpoint %s has no array '%s'", c->path, name ? name : "");
        return -1;
    }
    hid_t d = H5Dopen2(c->group, name, H5P_DEFAULT);
    if (d < 0) {
        gr_h5_fail(err, GR_ERUN, "checkpoint %s: '%s' is not an array", c->path, name);
        return -1;
    }
    hid_t ft = H5Dget_type(d), s = H5Dget_space(d);
    int same = ft >= 0 && H5Tequal(ft, gr_h5_ftype(t)) > 0;
    int rank = s >= 0 ? H5Sget_simple_extent_ndims(s) : -1;
    hssize_t np = rank == 1 ? H5Sget_simple_extent_npoints(s) : -1;
    gr_h5_close(ft);
    gr_h5_close(s);
    if (!same) {
        /* Name what is stored, to tell a format change from a wrong call. */
        const char *stored = "another type";
        for (int k = GR_T_F64; k <= GR_T_U8; k++) {
            hid_t ft2 = H5Dget_type(d);
            if (H5Tequal(ft2, gr_h5_ftype((gr_h5_type)k)) > 0)
                stored = type_name((gr_h5_type)k);
            H5Tclose(ft2);
        }
        H5Dclose(d);
        gr_fail(err, GR_ERUN, "checkpoint %s: array '%s' holds %s, not %s", c->path, name, stored,
                type_name(t));
        return -1;
    }
    if (np < 0) {
        H5Dclose(d);
        gr_fail(err, GR_ERUN, "checkpoint %s: '%s' is not a 1-D array", c->path, name);
        return -1;
    }
    *len = (size_t)np;
    return d;
}

static int get(gr_ckpt *c, const char *name, gr_h5_type t, void *v, size_t n, gr_err *err)
{
    size_t len;
    hid_t d = open_array(c, name, t, &len, err);
    if (d < 0)
        return err->code;
    int rc = GR_OK;
    if (len != n)
        rc = gr_fail(err, GR_ERUN, "checkpoint %s: array '%s' holds %zu elements, %zu expected",
                     c->path, name, len, n);
    else if (n && H5Dread(d, gr_h5_mtype(t), H5S_ALL, H5S_ALL, H5P_DEFAULT, v) < 0)
        rc = gr_h5_fail(err, GR_ERUN, "checkpoint %s: cannot read '%s'", c->path, name);
    H5Dclose(d);
    return rc;
}

#define CKPT_TYPE(suffix, ctype, code)                                                         \
    int gr_ckpt_put_##suffix(gr_ckpt *c, const char *name, const ctype *v, size_t n,           \
                             gr_err *err)                                                       \
    {                                                                                           \
        int rc;                                                                                 \
        GR_H5_GUARD(err, rc, rc = put(c, name, code, v, n, err));                                        \
        return rc;                                                                              \
    }                                                                                           \
    int gr_ckpt_get_##suffix(gr_ckpt *c, const char *name, ctype *v, size_t n, gr_err *err)  \
    {                                                                                           \
        int rc;                                                                                 \
        GR_H5_GUARD(err, rc, rc = get(c, name, code, v, n, err));                                        \
        return rc;                                                                              \
    }

CKPT_TYPE(f64, double, GR_T_F64)
CKPT_TYPE(i64, int64_t, GR_T_I64)
CKPT_TYPE(u64, uint64_t, GR_T_U64)
CKPT_TYPE(u32, uint32_t, GR_T_U32)
CKPT_TYPE(bytes, void, GR_T_U8)

int gr_ckpt_len(gr_ckpt *c, const char *name, size_t *n, gr_err *err)
{
    int rc = GR_OK;
    GR_H5_GUARD(err, rc, {
        if (!valid_name(name) || !gr_h5_exists(c->group, name)) {
            rc = gr_fail(err, GR_ERUN, "checkpoint %s has no array '%s'", c->path, name ? name : "");
        } else {
            hid_t d = H5Dopen2(c->group, name, H5P_DEFAULT);
            hid_t s = d >= 0 ? H5Dget_space(d) : -1;
            hssize_t np = s >= 0 && H5Sget_simple_extent_ndims(s) == 1 ? H5Sget_simple_extent_npoints(s) : -1;
            gr_h5_close(s);
            gr_h5_close(d);
            if (np < 0)
                rc = gr_h5_fail(err, GR_ERUN, "checkpoint %s: '%s' is not a 1-D array", c->path, name);
            else
                *n = (size_t)np;
        }
    });
    return rc;
}

int gr_ckpt_put_h5md(gr_ckpt *c, const struct gr_scene *sc, const struct gr_h5md_opts *o,
                     uint64_t step, double time, const gr_particles *p, gr_err *err)
{
    if (!c->writing)
        return gr_fail(err, GR_ERUN, "checkpoint %s is open for reading", c->path);
    if (c->has_h5md) {
        c->failed = 1;
        return gr_fail(err, GR_ERUN, "checkpoint %s already holds its frame", c->path);
    }
    gr_h5md_opts zero = {0};
    gr_h5md_opts oo = o ? *o : zero;
    oo.no_xdmf = 1;
    gr_h5md *h = gr_h5md_attach(c->file, sc, &oo, err);
    int rc = h ? gr_h5md_write_frame(h, step, time, p, err) : err->code;
    gr_h5md_free(h);
    if (rc) {
        c->failed = 1;
        return gr_err_prefix(err, "checkpoint %s: ", c->path);
    }
    c->has_h5md = 1;
    return GR_OK;
}

/* Make the bytes and the new directory entry durable before the old
 * checkpoint is replaced. */
static int sync_path(const char *path, int dir)
{
    int fd = open(path, dir ? O_RDONLY | O_DIRECTORY : O_RDONLY);
    if (fd < 0)
        return -1;
    int rc = fsync(fd);
    close(fd);
    return rc;
}

void gr_ckpt_discard(gr_ckpt *c)
{
    if (!c)
        return;
    GR_H5_QUIET({
        gr_h5_close(c->group);
        gr_h5_close(c->file);
    });
    c->group = c->file = -1;
    if (c->writing)
        unlink(c->tmp);
    ckpt_release(c);
}

int gr_ckpt_close(gr_ckpt *c, gr_err *err)
{
    if (!c)
        return GR_OK;
    if (!c->writing) {
        gr_ckpt_discard(c);
        return GR_OK;
    }
    if (c->failed) {
        int rc = gr_fail(err, GR_ERUN, "checkpoint %s not written: a store into it failed "
                         "(the previous checkpoint, if any, is kept)", c->path);
        gr_ckpt_discard(c);
        return rc;
    }
    int rc = GR_OK;
    GR_H5_GUARD(err, rc, {
        if (H5Fflush(c->file, H5F_SCOPE_GLOBAL) < 0)
            rc = gr_h5_fail(err, GR_ERUN, "cannot flush checkpoint %s", c->tmp);
        gr_h5_close(c->group);
        c->group = -1;
        if (H5Fclose(c->file) < 0 && !rc)
            rc = gr_h5_fail(err, GR_ERUN, "cannot close checkpoint %s", c->tmp);
        c->file = -1;
    });
    if (!rc && sync_path(c->tmp, 0) != 0)
        rc = gr_fail(err, GR_ERUN, "cannot sync checkpoint %s: %s", c->tmp, strerror(errno));
    if (!rc && rename(c->tmp, c->path) != 0)
        rc = gr_fail(err, GR_ERUN, "cannot move checkpoint %s to %s: %s", c->tmp, c->path,
                     strerror(errno));
    if (!rc) {
        char *d = strdup(c->path);
        if (d)
            sync_path(dirname(d), 1); /* best effort: some file systems refuse */
        free(d);
    } else {
        unlink(c->tmp);
    }
    c->writing = 0;
    ckpt_release(c);
    return rc;
}
