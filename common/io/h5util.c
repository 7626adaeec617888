/* Small HDF5 helpers for the H5MD writer, reader and checkpoint store. */
#include "h5md_impl.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Walked from the innermost frame outwards: keep the first description,
 * where HDF5 saw the problem. */
static herr_t first_error(unsigned n, const H5E_error2_t *e, void *data)
{
    (void)n;
    gr_h5_guard *g = data;
    if (!g->set && e->desc && e->desc[0]) {
        snprintf(g->text, sizeof g->text, "%s", e->desc);
        g->set = 1;
    }
    return 0;
}

static herr_t record(hid_t estack, void *data)
{
    gr_h5_guard *g = data;
    if (!g->set)
        H5Ewalk2(estack, H5E_WALK_UPWARD, first_error, g);
    return 0;
}

void gr_h5_guard_begin(gr_h5_guard *g)
{
    g->fn = NULL;
    g->data = NULL;
    g->text[0] = '\0';
    g->set = 0;
    H5Eget_auto2(H5E_DEFAULT, &g->fn, &g->data);
    H5Eset_auto2(H5E_DEFAULT, record, g);
}

void gr_h5_guard_end(gr_h5_guard *g, gr_err *err)
{
    H5Eset_auto2(H5E_DEFAULT, g->fn, g->data);
    if (err && err->code && g->set) {
        size_t len = strlen(err->msg);
        snprintf(err->msg + len, sizeof err->msg - len, " (HDF5: %s)", g->text);
    }
}

int gr_h5_fail(gr_err *err, int code, const char *fmt, ...)
{
    if (!err)
        return code;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->msg, sizeof err->msg, fmt, ap);
    va_end(ap);
    err->code = code;
    return code;
}

void gr_h5_no_exit_handler(void)
{
    H5dont_atexit();
}

hid_t gr_h5_fapl(void)
{
    hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
    if (fapl < 0)
        return -1;
    if (H5Pset_fclose_degree(fapl, H5F_CLOSE_STRONG) < 0 ||
        H5Pset_libver_bounds(fapl, H5F_LIBVER_V110, H5F_LIBVER_V110) < 0) {
        H5Pclose(fapl);
        return -1;
    }
    return fapl;
}

hid_t gr_h5_untimed(hid_t cls)
{
    hid_t p = H5Pcreate(cls);
    if (p >= 0 && H5Pset_obj_track_times(p, 0) < 0) {
        H5Pclose(p);
        return -1;
    }
    return p;
}

void gr_h5_close(hid_t id)
{
    if (id <= 0)
        return;
    switch (H5Iget_type(id)) {
    case H5I_FILE: H5Fclose(id); break;
    case H5I_GROUP: H5Gclose(id); break;
    case H5I_DATASET: H5Dclose(id); break;
    case H5I_DATASPACE: H5Sclose(id); break;
    case H5I_DATATYPE: H5Tclose(id); break;
    case H5I_ATTR: H5Aclose(id); break;
    case H5I_GENPROP_LST: H5Pclose(id); break;
    default: break;
    }
}

static hid_t str_type(size_t len, int vlen, int utf8)
{
    hid_t t = H5Tcopy(H5T_C_S1);
    if (t < 0)
        return -1;
    herr_t s = vlen ? H5Tset_size(t, H5T_VARIABLE) : H5Tset_size(t, len ? len : 1);
    if (s >= 0 && !vlen)
        s = H5Tset_strpad(t, H5T_STR_NULLPAD);
    if (s >= 0)
        s = H5Tset_cset(t, utf8 ? H5T_CSET_UTF8 : H5T_CSET_ASCII);
    if (s < 0) {
        H5Tclose(t);
        return -1;
    }
    return t;
}

static int write_attr(hid_t obj, const char *name, hid_t type, hid_t space, const void *buf)
{
    if (H5Aexists(obj, name) > 0)
        H5Adelete(obj, name);
    hid_t a = H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
    int rc = a >= 0 && H5Awrite(a, type, buf) >= 0 ? 0 : -1;
    if (a >= 0)
        H5Aclose(a);
    return rc;
}

int gr_h5_attr_strs(hid_t obj, const char *name, const char *const *v, size_t n, int vlen)
{
    size_t maxlen = 1;
    for (size_t i = 0; i < n; i++)
        if (strlen(v[i]) > maxlen)
            maxlen = strlen(v[i]);
    hid_t t = str_type(maxlen, vlen, 0);
    hsize_t dim = n;
    hid_t s = H5Screate_simple(1, &dim, NULL);
    int rc = -1;
    if (t >= 0 && s >= 0) {
        if (vlen) {
            rc = write_attr(obj, name, t, s, v);
        } else {
            char *buf = calloc(n ? n : 1, maxlen);
            if (buf) {
                for (size_t i = 0; i < n; i++)
                    memcpy(buf + i * maxlen, v[i], strlen(v[i]));
                rc = write_attr(obj, name, t, s, buf);
                free(buf);
            }
        }
    }
    gr_h5_close(t);
    gr_h5_close(s);
    return rc;
}

int gr_h5_attr_str(hid_t obj, const char *name, const char *value, int vlen)
{
    hid_t t = str_type(strlen(value), vlen, 0);
    hid_t s = H5Screate(H5S_SCALAR);
    int rc = -1;
    if (t >= 0 && s >= 0)
        rc = write_attr(obj, name, t, s, vlen ? (const void *)&value : (const void *)value);
    gr_h5_close(t);
    gr_h5_close(s);
    return rc;
}

/* H5MD 1.1's units module: a unit is a fixed-length string. */
int gr_h5_unit(hid_t obj, const char *unit)
{
    return gr_h5_attr_str(obj, "unit", unit, 0);
}

int gr_h5_attr_int(hid_t obj, const char *name, const int *v, size_t n)
{
    hsize_t dim = n;
    hid_t s = n ? H5Screate_simple(1, &dim, NULL) : H5Screate(H5S_SCALAR);
    if (s < 0)
        return -1;
    hid_t a;
    if (H5Aexists(obj, name) > 0)
        H5Adelete(obj, name);
    a = H5Acreate2(obj, name, H5T_STD_I32LE, s, H5P_DEFAULT, H5P_DEFAULT);
    int rc = a >= 0 && H5Awrite(a, H5T_NATIVE_INT, v) >= 0 ? 0 : -1;
    gr_h5_close(a);
    H5Sclose(s);
    return rc;
}

int gr_h5_attr_f64(hid_t obj, const char *name, const double *v, size_t n)
{
    hsize_t dim = n;
    hid_t s = n ? H5Screate_simple(1, &dim, NULL) : H5Screate(H5S_SCALAR);
    if (s < 0)
        return -1;
    if (H5Aexists(obj, name) > 0)
        H5Adelete(obj, name);
    hid_t a = H5Acreate2(obj, name, H5T_IEEE_F64LE, s, H5P_DEFAULT, H5P_DEFAULT);
    int rc = a >= 0 && H5Awrite(a, H5T_NATIVE_DOUBLE, v) >= 0 ? 0 : -1;
    gr_h5_close(a);
    H5Sclose(s);
    return rc;
}

/* Read a string of type ft (fixed or variable) from an attribute or dataset. */
static char *read_str(hid_t obj, int is_attr)
{
    hid_t ft = is_attr ? H5Aget_type(obj) : H5Dget_type(obj);
    if (ft < 0)
        return NULL;
    char *out = NULL;
    /* One string: a damaged file whose dataspace holds more would have
     * the library write past the single pointer or buffer read into. */
    hid_t sp = is_attr ? H5Aget_space(obj) : H5Dget_space(obj);
    hssize_t np = sp >= 0 ? H5Sget_simple_extent_npoints(sp) : -1;
    if (sp >= 0)
        H5Sclose(sp);
    if (H5Tget_class(ft) != H5T_STRING || np != 1)
        goto done;
    hid_t mt = H5Tcopy(H5T_C_S1);
    if (H5Tis_variable_str(ft) > 0) {
        H5Tset_size(mt, H5T_VARIABLE);
        H5Tset_cset(mt, H5Tget_cset(ft));
        char *s = NULL;
        herr_t st = is_attr ? H5Aread(obj, mt, &s) : H5Dread(obj, mt, H5S_ALL, H5S_ALL, H5P_DEFAULT, &s);
        if (st >= 0 && s) {
            out = strdup(s);
            /* Memory of a variable-length read belongs to the HDF5 library. */
            H5free_memory(s);
        } else if (st >= 0) {
            out = strdup("");
        }
    } else {
        size_t len = H5Tget_size(ft);
        H5Tset_size(mt, len + 1);
        H5Tset_strpad(mt, H5T_STR_NULLTERM);
        H5Tset_cset(mt, H5Tget_cset(ft));
        out = calloc(len + 1, 1);
        herr_t st = -1;
        if (out)
            st = is_attr ? H5Aread(obj, mt, out) : H5Dread(obj, mt, H5S_ALL, H5S_ALL, H5P_DEFAULT, out);
        if (st < 0) {
            free(out);
            out = NULL;
        }
    }
    H5Tclose(mt);
done:
    H5Tclose(ft);
    return out;
}

char *gr_h5_read_attr_str(hid_t obj, const char *name)
{
    if (H5Aexists(obj, name) <= 0)
        return NULL;
    hid_t a = H5Aopen(obj, name, H5P_DEFAULT);
    if (a < 0)
        return NULL;
    char *s = read_str(a, 1);
    H5Aclose(a);
    return s;
}

static int read_attr_num(hid_t obj, const char *name, hid_t mt, void *v, size_t n)
{
    if (H5Aexists(obj, name) <= 0)
        return -1;
    hid_t a = H5Aopen(obj, name, H5P_DEFAULT);
    if (a < 0)
        return -1;
    hid_t s = H5Aget_space(a);
    hssize_t np = H5Sget_simple_extent_npoints(s);
    int rc = np == (hssize_t)(n ? n : 1) && H5Aread(a, mt, v) >= 0 ? 0 : -1;
    H5Sclose(s);
    H5Aclose(a);
    return rc;
}

int gr_h5_read_attr_int(hid_t obj, const char *name, int *v, size_t n)
{
    return read_attr_num(obj, name, H5T_NATIVE_INT, v, n);
}

int gr_h5_read_attr_f64(hid_t obj, const char *name, double *v, size_t n)
{
    return read_attr_num(obj, name, H5T_NATIVE_DOUBLE, v, n);
}

int gr_h5_dset_str(hid_t loc, const char *name, const char *text)
{
    hid_t t = str_type(0, 1, 1);
    hid_t s = H5Screate(H5S_SCALAR), dcpl = gr_h5_untimed(H5P_DATASET_CREATE);
    hid_t d = -1;
    int rc = -1;
    if (t >= 0 && s >= 0 && dcpl >= 0)
        d = H5Dcreate2(loc, name, t, s, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    if (d >= 0 && H5Dwrite(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, &text) >= 0)
        rc = 0;
    gr_h5_close(dcpl);
    gr_h5_close(d);
    gr_h5_close(t);
    gr_h5_close(s);
    return rc;
}

int gr_h5_dset_u64(hid_t loc, const char *name, uint64_t v)
{
    hid_t s = H5Screate(H5S_SCALAR), dcpl = gr_h5_untimed(H5P_DATASET_CREATE);
    hid_t d = s >= 0 && dcpl >= 0 ? H5Dcreate2(loc, name, H5T_STD_U64LE, s, H5P_DEFAULT, dcpl, H5P_DEFAULT) : -1;
    int rc = d >= 0 && H5Dwrite(d, H5T_NATIVE_UINT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, &v) >= 0 ? 0 : -1;
    gr_h5_close(dcpl);
    gr_h5_close(d);
    gr_h5_close(s);
    return rc;
}

char *gr_h5_read_dset_str(hid_t loc, const char *name)
{
    if (!gr_h5_exists(loc, name))
        return NULL;
    hid_t d = H5Dopen2(loc, name, H5P_DEFAULT);
    if (d < 0)
        return NULL;
    char *s = read_str(d, 0);
    H5Dclose(d);
    return s;
}

int gr_h5_read_dset_u64(hid_t loc, const char *name, uint64_t *v)
{
    if (!gr_h5_exists(loc, name))
        return -1;
    hid_t d = H5Dopen2(loc, name, H5P_DEFAULT);
    if (d < 0)
        return -1;
    hid_t s = H5Dget_space(d);
    int rc = H5Sget_simple_extent_npoints(s) == 1 &&
             H5Dread(d, H5T_NATIVE_UINT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) >= 0 ? 0 : -1;
    H5Sclose(s);
    H5Dclose(d);
    return rc;
}

hid_t gr_h5_ftype(gr_h5_type t)
{
    switch (t) {
    case GR_T_F64: return H5T_IEEE_F64LE;
    case GR_T_I64: return H5T_STD_I64LE;
    case GR_T_I32: return H5T_STD_I32LE;
    case GR_T_U32: return H5T_STD_U32LE;
    case GR_T_U64: return H5T_STD_U64LE;
    case GR_T_U8: return H5T_STD_U8LE;
    }
    return -1;
}

hid_t gr_h5_mtype(gr_h5_type t)
{
    switch (t) {
    case GR_T_F64: return H5T_NATIVE_DOUBLE;
    case GR_T_I64: return H5T_NATIVE_INT64;
    case GR_T_I32: return H5T_NATIVE_INT32;
    case GR_T_U32: return H5T_NATIVE_UINT32;
    case GR_T_U64: return H5T_NATIVE_UINT64;
    case GR_T_U8: return H5T_NATIVE_UINT8;
    }
    return -1;
}

size_t gr_h5_tsize(gr_h5_type t)
{
    static const size_t sz[] = {8, 8, 4, 4, 8, 1};
    return sz[t];
}

hid_t gr_h5_ext_create(hid_t loc, const char *name, gr_h5_type t, int item_rank,
                       const hsize_t *item_dims)
{
    hsize_t dims[4] = {0}, maxd[4] = {H5S_UNLIMITED}, chunk[4];
    size_t rowbytes = gr_h5_tsize(t);
    for (int k = 0; k < item_rank; k++) {
        dims[k + 1] = maxd[k + 1] = chunk[k + 1] = item_dims[k];
        rowbytes *= item_dims[k];
    }
    /* Small rows share a chunk of one page (4 KiB with its checksum, on a
     * page of the file: gr_h5_paged_fcpl), rewritten in place as rows arrive: a
     * kill cannot tear a write within one page, and a torn chunk would
     * fail its checksum, taking the rows before with it. A row larger than
     * that (a frame of many grains) is a chunk of its own, written once. */
    size_t rows = rowbytes ? GR_H5_PAGE_DATA / rowbytes : 1;
    chunk[0] = rows < 1 ? 1 : rows;
    hid_t s = H5Screate_simple(item_rank + 1, dims, maxd);
    hid_t p = H5Pcreate(H5P_DATASET_CREATE);
    hid_t d = -1;
    /* each chunk checksummed: a flipped byte fails its read, named */
    if (s >= 0 && p >= 0 && H5Pset_chunk(p, item_rank + 1, chunk) >= 0 && H5Pset_fletcher32(p) >= 0 &&
        H5Pset_obj_track_times(p, 0) >= 0)
        d = H5Dcreate2(loc, name, gr_h5_ftype(t), s, H5P_DEFAULT, p, H5P_DEFAULT);
    gr_h5_close(p);
    gr_h5_close(s);
    return d;
}

static int little_endian(void)
{
    static const uint16_t one = 1;
    return *(const uint8_t *)&one == 1;
}

/* Fletcher's partial reduction modulo 65535, as HDF5 applies it. */
static uint32_t fold(uint32_t x)
{
    return (x & 0xffff) + (x >> 16);
}

uint32_t gr_h5_fletcher32(const void *data, size_t len)
{
    /* HDF5's own sums (H5_checksum_fletcher32: big-endian 16-bit words,
     * folded every 360), each block summed at once, sum2 as the weighted
     * sum it is, n s1 - sum of i w_i (below 2^32 for 360 words): the same
     * bits, about three times faster (the loop vectorises). */
    const int swap = little_endian();
    const uint8_t *d = data;
    size_t words = len / 2;
    uint32_t sum1 = 0, sum2 = 0;
    while (words) {
        uint32_t n = words > 360 ? 360 : (uint32_t)words, s1 = 0, iw = 0;
        for (uint32_t i = 0; i < n; i++) {
            uint16_t v;
            memcpy(&v, d + 2 * i, 2);
            uint32_t w = swap ? (uint16_t)(v << 8 | v >> 8) : v;
            s1 += w;
            iw += i * w;
        }
        sum2 = (uint32_t)(sum2 + (uint64_t)n * sum1 + (uint64_t)n * s1 - iw);
        sum1 += s1;
        d += 2 * (size_t)n;
        words -= n;
        sum1 = fold(sum1);
        sum2 = fold(sum2);
    }
    if (len % 2) {
        sum1 += (uint32_t)*d << 8;
        sum2 += sum1;
        sum1 = fold(sum1);
        sum2 = fold(sum2);
    }
    return fold(sum2) << 16 | fold(sum1);
}

/* A row that is a chunk of its own (a frame of many grains) and a dataset
 * whose only filter is the checksum: the chunk as the filter would write
 * it, data then its checksum (little-endian), without the library's copy
 * through its filter pipeline. Our file types are little-endian, so this
 * holds on a little-endian host only; 1 when it does not apply. */
static int append_chunk(hid_t dset, int rank, const hsize_t *start, size_t bytes, const void *row)
{
    if (!little_endian() || bytes <= GR_H5_PAGE_DATA)
        return 1;
    hid_t p = H5Dget_create_plist(dset);
    hsize_t chunk[4] = {0};
    unsigned flags, cd[4];
    size_t ncd = 4;
    int direct = p >= 0 && H5Pget_chunk(p, 4, chunk) == rank && chunk[0] == 1 && H5Pget_nfilters(p) == 1 &&
                 H5Pget_filter2(p, 0, &flags, &ncd, cd, 0, NULL, NULL) == H5Z_FILTER_FLETCHER32;
    gr_h5_close(p);
    uint8_t *buf = direct ? malloc(bytes + 4) : NULL;
    if (!buf)
        return direct ? -1 : 1;
    memcpy(buf, row, bytes);
    uint32_t c = gr_h5_fletcher32(buf, bytes);
    for (int k = 0; k < 4; k++)
        buf[bytes + (size_t)k] = (uint8_t)(c >> 8 * k);
    int rc = H5Dwrite_chunk(dset, H5P_DEFAULT, 0, start, bytes + 4, buf) < 0 ? -1 : 0;
    free(buf);
    return rc;
}

int gr_h5_ext_append(hid_t dset, gr_h5_type t, const void *row)
{
    hsize_t dims[4], start[4] = {0}, count[4];
    hid_t fs = H5Dget_space(dset);
    if (fs < 0)
        return -1;
    int rank = H5Sget_simple_extent_ndims(fs);
    H5Sget_simple_extent_dims(fs, dims, NULL);
    H5Sclose(fs);
    if (rank < 1 || rank > 4)
        return -1;
    start[0] = dims[0];
    dims[0] += 1;
    if (H5Dset_extent(dset, dims) < 0)
        return -1;
    count[0] = 1;
    size_t bytes = gr_h5_tsize(t);
    for (int k = 1; k < rank; k++)
        bytes *= count[k] = dims[k];
    int direct = append_chunk(dset, rank, start, bytes, row);
    if (direct <= 0)
        return direct;
    fs = H5Dget_space(dset);
    hid_t ms = H5Screate_simple(rank, count, NULL);
    int rc = -1;
    if (fs >= 0 && ms >= 0 &&
        H5Sselect_hyperslab(fs, H5S_SELECT_SET, start, NULL, count, NULL) >= 0 &&
        H5Dwrite(dset, gr_h5_mtype(t), ms, fs, H5P_DEFAULT, row) >= 0)
        rc = 0;
    gr_h5_close(ms);
    gr_h5_close(fs);
    return rc;
}

hsize_t gr_h5_rows(hid_t dset)
{
    hsize_t dims[8] = {0};
    hid_t fs = H5Dget_space(dset);
    if (fs < 0)
        return 0;
    int rank = H5Sget_simple_extent_ndims(fs);
    if (rank >= 1 && rank <= 8)
        H5Sget_simple_extent_dims(fs, dims, NULL);
    H5Sclose(fs);
    return rank >= 1 ? dims[0] : 0;
}

int gr_h5_read_rows(hid_t dset, gr_h5_type t, hsize_t first, hsize_t count, void *buf)
{
    hsize_t dims[4], start[4] = {0}, cnt[4];
    hid_t fs = H5Dget_space(dset);
    if (fs < 0)
        return -1;
    int rank = H5Sget_simple_extent_ndims(fs);
    int rc = -1;
    if (rank >= 1 && rank <= 4) {
        H5Sget_simple_extent_dims(fs, dims, NULL);
        if (first + count <= dims[0]) {
            start[0] = first;
            cnt[0] = count;
            for (int k = 1; k < rank; k++)
                cnt[k] = dims[k];
            hid_t ms = H5Screate_simple(rank, cnt, NULL);
            if (count == 0)
                rc = 0;
            else if (ms >= 0 &&
                     H5Sselect_hyperslab(fs, H5S_SELECT_SET, start, NULL, cnt, NULL) >= 0 &&
                     H5Dread(dset, gr_h5_mtype(t), ms, fs, H5P_DEFAULT, buf) >= 0)
                rc = 0;
            gr_h5_close(ms);
        }
    }
    H5Sclose(fs);
    return rc;
}

/* Each missing group of path, made one by one with no modification time
 * (HDF5's intermediate groups would record theirs). n: how much of path
 * to make. Returns the last group, open. */
static hid_t groups_along(hid_t loc, const char *path, size_t n)
{
    char buf[1024];
    if (n >= sizeof buf)
        return -1;
    memcpy(buf, path, n);
    buf[n] = '\0';
    hid_t gcpl = gr_h5_untimed(H5P_GROUP_CREATE), g = -1;
    for (size_t i = 1; gcpl >= 0 && i <= n; i++) {
        if (buf[i] != '/' && buf[i] != '\0')
            continue;
        char c = buf[i];
        buf[i] = '\0';
        gr_h5_close(g);
        g = H5Lexists(loc, buf, H5P_DEFAULT) > 0 ? H5Gopen2(loc, buf, H5P_DEFAULT)
                                                 : H5Gcreate2(loc, buf, H5P_DEFAULT, gcpl, H5P_DEFAULT);
        buf[i] = c;
        if (g < 0)
            break;
    }
    gr_h5_close(gcpl);
    return g;
}

static void make_parents(hid_t loc, const char *name)
{
    const char *slash = strrchr(name, '/');
    if (slash && slash > name)
        gr_h5_close(groups_along(loc, name, (size_t)(slash - name)));
}

hid_t gr_h5_fixed_create(hid_t loc, const char *name, gr_h5_type t, const hsize_t dims[2],
                         const void *data)
{
    int rank = dims[1] ? 2 : 1;
    hid_t s = H5Screate_simple(rank, dims, NULL);
    hid_t dcpl = gr_h5_checked_dcpl(rank, dims, gr_h5_tsize(t));
    hid_t d = -1;
    /* the parents made here, untimed, not as HDF5's intermediate groups */
    make_parents(loc, name);
    if (s >= 0 && dcpl >= 0)
        d = H5Dcreate2(loc, name, gr_h5_ftype(t), s, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    gr_h5_close(dcpl);
    hsize_t total = dims[0] * (dims[1] ? dims[1] : 1);
    if (d >= 0 && total > 0 &&
        H5Dwrite(d, gr_h5_mtype(t), H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) {
        H5Dclose(d);
        H5Ldelete(loc, name, H5P_DEFAULT);
        d = -1;
    }
    gr_h5_close(s);
    return d;
}

hid_t gr_h5_checked_dcpl(int rank, const hsize_t *dims, size_t elsize)
{
    hsize_t chunk[8], rowbytes = elsize;
    if (rank < 1 || rank > 8)
        return gr_h5_untimed(H5P_DATASET_CREATE);
    for (int k = 0; k < rank; k++) {
        if (dims[k] == 0)
            return gr_h5_untimed(H5P_DATASET_CREATE);
        chunk[k] = dims[k];
        if (k)
            rowbytes *= dims[k];
    }
    hsize_t rows = (1u << 20) / (rowbytes ? rowbytes : 1);
    chunk[0] = rows < 1 ? 1 : rows < dims[0] ? rows : dims[0];
    hid_t p = gr_h5_untimed(H5P_DATASET_CREATE);
    if (p >= 0 && (H5Pset_chunk(p, rank, chunk) < 0 || H5Pset_fletcher32(p) < 0)) {
        H5Pclose(p);
        return -1;
    }
    return p;
}

int gr_h5_exists(hid_t loc, const char *path)
{
    /* H5Lexists needs every intermediate component to exist. */
    char buf[1024];
    size_t len = strlen(path);
    if (len >= sizeof buf)
        return 0;
    memcpy(buf, path, len + 1);
    for (size_t i = 1; i <= len; i++) {
        if (buf[i] == '/' || buf[i] == '\0') {
            char c = buf[i];
            buf[i] = '\0';
            if (H5Lexists(loc, buf, H5P_DEFAULT) <= 0)
                return 0;
            buf[i] = c;
        }
    }
    return 1;
}

hid_t gr_h5_mkgroup(hid_t loc, const char *name)
{
    return groups_along(loc, name, strlen(name));
}

int gr_h5_is_group(hid_t loc, const char *path)
{
    if (!gr_h5_exists(loc, path))
        return 0;
    H5O_info_t oi;
    if (H5Oget_info_by_name(loc, path, &oi, H5P_DEFAULT) < 0)
        return 0;
    return oi.type == H5O_TYPE_GROUP;
}

static hsize_t rows_at(hid_t loc, const char *path)
{
    if (!gr_h5_exists(loc, path))
        return 0;
    hid_t d = H5Dopen2(loc, path, H5P_DEFAULT);
    if (d < 0)
        return 0;
    hsize_t r = gr_h5_rows(d);
    H5Dclose(d);
    return r;
}

hsize_t gr_h5_series_rows(hid_t loc, const char *group)
{
    char p[512];
    hsize_t r = (hsize_t)-1;
    const char *parts[] = {"step", "time", "value"};
    for (int k = 0; k < 3; k++) {
        snprintf(p, sizeof p, "%s/%s", group, parts[k]);
        if (k == 1 && !gr_h5_exists(loc, p))
            continue; /* time is optional in H5MD */
        hsize_t n = rows_at(loc, p);
        if (n < r)
            r = n;
    }
    return r == (hsize_t)-1 ? 0 : r;
}

int gr_h5_read_path(hid_t f, const char *path, gr_h5_type t, hsize_t first, hsize_t count,
                    void *buf)
{
    hid_t d = H5Dopen2(f, path, H5P_DEFAULT);
    if (d < 0)
        return -1;
    int rc = gr_h5_read_rows(d, t, first, count, buf);
    H5Dclose(d);
    return rc;
}

int gr_h5_valid_name(const char *s)
{
    /* Names end up in HDF5 paths and in the XML of the sidecar. */
    return s && s[0] && s[0] != '/' && s[strlen(s) - 1] != '/' && !strstr(s, "//") &&
           !strstr(s, "..") && !strpbrk(s, "\"<>&") && strlen(s) < 200;
}
