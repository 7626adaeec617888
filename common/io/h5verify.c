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

/* Dataset d read slice by slice along its first dimension, as bytes of
 * its own stored type (no conversion: the check is of the stored bytes). */
static int read_all(hid_t d, walk *w)
{
    hid_t s = H5Dget_space(d), t = H5Dget_type(d);
    int rc = s < 0 || t < 0 ? -1 : 0;
    int rank = rc ? -1 : H5Sget_simple_extent_ndims(s);
    size_t el = rc ? 0 : H5Tget_size(t);
    hsize_t dims[32];
    if (!rc && (rank < 0 || rank > 32 || el == 0 || H5Tis_variable_str(t) > 0 || H5Tget_class(t) == H5T_VLEN))
        rank = rank == 0 ? 0 : -2; /* variable-length: read through a string type below */
    if (rank == -2 || rank == 0) {
        /* a scalar or variable-length dataset: small, read whole */
        hid_t mt = H5Tis_variable_str(t) > 0 ? H5Tcopy(t) : H5Tget_native_type(t, H5T_DIR_DEFAULT);
        hssize_t np = H5Sget_simple_extent_npoints(s);
        size_t msz = mt >= 0 ? H5Tget_size(mt) : 0;
        void *b = np >= 0 && msz ? calloc((size_t)np + 1, msz) : NULL;
        rc = !b || H5Dread(d, mt, H5S_ALL, H5S_ALL, H5P_DEFAULT, b) < 0 ? -1 : 0;
        if (!rc && H5Tis_variable_str(t) > 0)
            H5Dvlen_reclaim(mt, s, H5P_DEFAULT, b);
        w->bytes += (unsigned long long)(np > 0 ? np : 0) * msz;
        free(b);
        if (mt >= 0)
            H5Tclose(mt);
    } else if (!rc) {
        H5Sget_simple_extent_dims(s, dims, NULL);
        size_t row = el;
        for (int k = 1; k < rank; k++)
            row *= (size_t)dims[k];
        hsize_t per = row ? SLICE / row : 1, start[32] = {0}, count[32];
        per = per < 1 ? 1 : per;
        for (int k = 1; k < rank; k++)
            count[k] = dims[k];
        for (hsize_t r = 0; !rc && r < dims[0]; r += per) {
            start[0] = r, count[0] = r + per <= dims[0] ? per : dims[0] - r;
            hid_t ms = H5Screate_simple(rank, count, NULL);
            void *b = count[0] * row <= SLICE || !w->buf ? realloc(w->buf, count[0] * row + 1) : w->buf;
            if (b)
                w->buf = b;
            rc = ms < 0 || !b || H5Sselect_hyperslab(s, H5S_SELECT_SET, start, NULL, count, NULL) < 0 ||
                         H5Dread(d, t, ms, s, H5P_DEFAULT, b) < 0
                     ? -1
                     : 0;
            w->bytes += count[0] * row;
            if (ms >= 0)
                H5Sclose(ms);
        }
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
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
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
