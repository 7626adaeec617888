/* Read a whole HDF5 file back: every group and every dataset, each read to
 * its end in slices of about 4 MiB, so that a checksum that fails
 * (Fletcher-32 on grano's datasets, HDF5's own on its metadata) names the
 * first damaged object. */
#include <stdlib.h>
#include <string.h>

#include "h5md.h"
#include "h5md_impl.h"

#define SLICE (4u << 20)

typedef struct {
    size_t dsets;
    unsigned long long bytes;
    char bad[512]; /* the first damaged object */
    void *buf;
} walk;

/* A scalar or variable-length dataset (small: scene text, names), read
 * whole; strings through their own type, then their memory given back. */
static int read_whole(hid_t d, hid_t s, hid_t t, walk *w)
{
    int vstr = H5Tis_variable_str(t) > 0;
    hid_t mt = vstr ? H5Tcopy(t) : H5Tget_native_type(t, H5T_DIR_DEFAULT);
    hssize_t np = H5Sget_simple_extent_npoints(s);
    size_t msz = mt >= 0 ? H5Tget_size(mt) : 0;
    void *b = np >= 0 && msz ? calloc((size_t)np + 1, msz) : NULL;
    int rc = !b || H5Dread(d, mt, H5S_ALL, H5S_ALL, H5P_DEFAULT, b) < 0 ? -1 : 0;
    if (!rc && vstr)
        H5Dvlen_reclaim(mt, s, H5P_DEFAULT, b);
    w->bytes += (unsigned long long)(np > 0 ? np : 0) * msz;
    free(b);
    if (mt >= 0)
        H5Tclose(mt);
    return rc;
}

/* A fixed-size dataset read slice by slice along its first dimension, as
 * its stored bytes (no conversion: the check is of what is stored). */
static int read_slices(hid_t d, hid_t s, hid_t t, int rank, walk *w)
{
    hsize_t dims[32], start[32] = {0}, count[32];
    H5Sget_simple_extent_dims(s, dims, NULL);
    size_t row = H5Tget_size(t);
    for (int k = 1; k < rank; k++)
        row *= (size_t)dims[k], count[k] = dims[k];
    hsize_t per = row && row < SLICE ? SLICE / row : 1;
    if (!w->buf && !(w->buf = malloc(per * row > SLICE ? per * row : SLICE)))
        return -1;
    if (per * row > SLICE) {
        void *b = realloc(w->buf, per * row);
        if (!b)
            return -1;
        w->buf = b;
    }
    int rc = 0;
    for (hsize_t r = 0; !rc && r < dims[0]; r += per) {
        start[0] = r, count[0] = r + per <= dims[0] ? per : dims[0] - r;
        hid_t ms = H5Screate_simple(rank, count, NULL);
        rc = ms < 0 || H5Sselect_hyperslab(s, H5S_SELECT_SET, start, NULL, count, NULL) < 0 ||
                     H5Dread(d, t, ms, s, H5P_DEFAULT, w->buf) < 0
                 ? -1
                 : 0;
        w->bytes += count[0] * row;
        if (ms >= 0)
            H5Sclose(ms);
    }
    return rc;
}

static int read_all(hid_t d, walk *w)
{
    hid_t s = H5Dget_space(d), t = H5Dget_type(d);
    int rank = s >= 0 ? H5Sget_simple_extent_ndims(s) : -1, rc = -1;
    if (t >= 0 && rank >= 0) {
        int whole = rank == 0 || rank > 32 || H5Tis_variable_str(t) > 0 || H5Tget_class(t) == H5T_VLEN;
        rc = whole ? read_whole(d, s, t, w) : read_slices(d, s, t, rank, w);
    }
    if (t >= 0)
        H5Tclose(t);
    if (s >= 0)
        H5Sclose(s);
    return rc;
}

static herr_t visit(hid_t loc, const char *name, const H5L_info_t *info, void *data)
{
    walk *w = data;
    (void)info;
    H5O_info_t oi;
    if (H5Oget_info_by_name(loc, name, &oi, H5P_DEFAULT) < 0) {
        snprintf(w->bad, sizeof w->bad, "/%s (its object header)", name);
        return 1;
    }
    if (oi.type != H5O_TYPE_DATASET)
        return 0;
    hid_t d = H5Dopen2(loc, name, H5P_DEFAULT);
    int rc = d < 0 || read_all(d, w);
    if (d >= 0)
        H5Dclose(d);
    if (rc) {
        snprintf(w->bad, sizeof w->bad, "/%s", name);
        return 1;
    }
    w->dsets++;
    return 0;
}

static int verify_impl(const char *path, size_t *ndsets, unsigned long long *bytes, gr_err *err)
{
    walk w = {0};
    hid_t f = gr_h5_open_ro(path);
    if (f < 0)
        return gr_h5_fail(err, GR_ERUN, "%s: damaged: the file's metadata (superblock or root) does not read", path);
    herr_t st = H5Lvisit(f, H5_INDEX_NAME, H5_ITER_INC, visit, &w);
    H5Fclose(f);
    free(w.buf);
    *ndsets = w.dsets, *bytes = w.bytes;
    if (st != 0)
        return gr_h5_fail(err, GR_ERUN, "%s: damaged: %s does not read back%s", path,
                          w.bad[0] ? w.bad : "a link", w.bad[0] ? "" : " (the group structure)");
    return GR_OK;
}

int gr_h5_verify(const char *path, size_t *ndsets, unsigned long long *bytes, gr_err *err)
{
    int rc;
    GR_H5_GUARD(err, rc, rc = verify_impl(path, ndsets, bytes, err));
    return rc;
}
