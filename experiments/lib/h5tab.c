/* Result files of typed tables (h5tab.h). */
#include "h5tab.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <hdf5.h>

#ifndef GRANO_VERSION
#define GRANO_VERSION "unknown"
#endif

struct exp_tab_file {
    hid_t file;
    char path[1200], part[1210];
};

/* HDF5 prints its error stack unless told not to; the status says enough. */
typedef struct {
    H5E_auto2_t fn;
    void *data;
} quiet;

static void quiet_on(quiet *q)
{
    H5Eget_auto2(H5E_DEFAULT, &q->fn, &q->data);
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
}

static void quiet_off(const quiet *q)
{
    H5Eset_auto2(H5E_DEFAULT, q->fn, q->data);
}

static hid_t utf8_type(void)
{
    hid_t t = H5Tcopy(H5T_C_S1);
    if (t >= 0 && (H5Tset_size(t, H5T_VARIABLE) < 0 || H5Tset_cset(t, H5T_CSET_UTF8) < 0)) {
        H5Tclose(t);
        return -1;
    }
    return t;
}

static int put_attr(hid_t obj, const char *name, const char *value)
{
    hid_t t = utf8_type(), s = H5Screate(H5S_SCALAR);
    hid_t a = t >= 0 && s >= 0 ? H5Acreate2(obj, name, t, s, H5P_DEFAULT, H5P_DEFAULT) : -1;
    const char *v = value ? value : "";
    int bad = a < 0 || H5Awrite(a, t, &v) < 0;
    if (a >= 0)
        H5Aclose(a);
    if (s >= 0)
        H5Sclose(s);
    if (t >= 0)
        H5Tclose(t);
    return bad;
}

exp_tab_file *exp_tab_create(const char *path, const char *kind, gr_err *err)
{
    exp_tab_file *f = calloc(1, sizeof *f);
    if (!f) {
        gr_fail(err, GR_ERUN, "out of memory");
        return NULL;
    }
    snprintf(f->path, sizeof f->path, "%s", path);
    snprintf(f->part, sizeof f->part, "%s.part", path);
    quiet q;
    quiet_on(&q);
    /* no modification times recorded: the same tables, the same bytes */
    hid_t fcpl = H5Pcreate(H5P_FILE_CREATE);
    f->file = fcpl >= 0 && H5Pset_obj_track_times(fcpl, 0) >= 0
                  ? H5Fcreate(f->part, H5F_ACC_TRUNC, fcpl, H5P_DEFAULT)
                  : -1;
    if (fcpl >= 0)
        H5Pclose(fcpl);
    int bad = f->file < 0 || put_attr(f->file, "kind", kind) || put_attr(f->file, "creator", "grano " GRANO_VERSION);
    quiet_off(&q);
    if (bad) {
        gr_fail(err, GR_ERUN, "%s: cannot write", f->part);
        exp_tab_free(f);
        return NULL;
    }
    return f;
}

/* A group at path whose links keep their creation order (the columns'),
 * its missing parents made one by one (HDF5's intermediate groups would
 * record their modification times). */
static hid_t make_group(hid_t file, const char *path)
{
    hid_t gcpl = H5Pcreate(H5P_GROUP_CREATE), g = -1;
    char buf[1024];
    size_t n = strlen(path);
    if (gcpl < 0 || n >= sizeof buf || H5Pset_obj_track_times(gcpl, 0) < 0 ||
        H5Pset_link_creation_order(gcpl, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED) < 0) {
        if (gcpl >= 0)
            H5Pclose(gcpl);
        return -1;
    }
    memcpy(buf, path, n + 1);
    for (size_t i = 1; i <= n; i++) {
        if (buf[i] != '/' && buf[i] != '\0')
            continue;
        char c = buf[i];
        buf[i] = '\0';
        if (g >= 0)
            H5Gclose(g);
        g = H5Lexists(file, buf, H5P_DEFAULT) > 0 ? H5Gopen2(file, buf, H5P_DEFAULT)
                                                  : H5Gcreate2(file, buf, H5P_DEFAULT, gcpl, H5P_DEFAULT);
        buf[i] = c;
        if (g < 0)
            break;
    }
    H5Pclose(gcpl);
    return g;
}

/* A column's creation list: no modification time; numbers (rows > 0)
 * in one chunk with HDF5's Fletcher-32 checksum, as the result files'
 * datasets (strings are stored as references to a heap, which the filter
 * would not cover). */
static hid_t numbers_dcpl(size_t rows)
{
    hid_t p = H5Pcreate(H5P_DATASET_CREATE);
    hsize_t chunk = rows;
    if (p >= 0 && (H5Pset_obj_track_times(p, 0) < 0 ||
                   (rows && (H5Pset_chunk(p, 1, &chunk) < 0 || H5Pset_fletcher32(p) < 0)))) {
        H5Pclose(p);
        return -1;
    }
    return p;
}

static int put_column(hid_t g, size_t rows, const exp_col *c)
{
    size_t st = c->stride ? c->stride : 1, n = rows ? rows : 1;
    hsize_t dim = rows;
    hid_t s = H5Screate_simple(1, &dim, NULL);
    hid_t t = c->type == EXP_STR ? utf8_type() : H5Tcopy(c->type == EXP_INT ? H5T_STD_I64LE : H5T_IEEE_F64LE);
    hid_t mt = c->type == EXP_STR ? t : c->type == EXP_INT ? H5T_NATIVE_INT64 : H5T_NATIVE_DOUBLE;
    hid_t dcpl = numbers_dcpl(c->type == EXP_STR ? 0 : rows);
    hid_t d = s >= 0 && t >= 0 && dcpl >= 0 ? H5Dcreate2(g, c->name, t, s, H5P_DEFAULT, dcpl, H5P_DEFAULT) : -1;
    if (dcpl >= 0)
        H5Pclose(dcpl);
    void *buf = malloc(n * (c->type == EXP_STR ? sizeof(char *) : 8));
    int bad = d < 0 || !buf;
    for (size_t k = 0; !bad && k < rows; k++) {
        if (c->type == EXP_STR) {
            const char *v = ((const char *const *)c->v)[k * st];
            ((const char **)buf)[k] = v ? v : "";
        } else if (c->type == EXP_INT) {
            double v = ((const double *)c->v)[k * st];
            ((int64_t *)buf)[k] = isfinite(v) ? (int64_t)llround(v) : -1;
        } else
            ((double *)buf)[k] = ((const double *)c->v)[k * st];
    }
    bad = bad || (rows && H5Dwrite(d, mt, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) < 0) ||
          put_attr(d, "unit", c->unit) || put_attr(d, "description", c->desc);
    free(buf);
    if (d >= 0)
        H5Dclose(d);
    if (t >= 0)
        H5Tclose(t);
    if (s >= 0)
        H5Sclose(s);
    return bad;
}

int exp_tab_write(exp_tab_file *f, const char *group, const char *desc, size_t rows, const exp_col *cols,
                  size_t ncols, gr_err *err)
{
    quiet q;
    quiet_on(&q);
    hid_t g = make_group(f->file, group);
    int bad = g < 0 || put_attr(g, "description", desc);
    size_t k = 0;
    for (; !bad && k < ncols; k++)
        bad = put_column(g, rows, &cols[k]);
    if (g >= 0)
        H5Gclose(g);
    bad = bad || H5Fflush(f->file, H5F_SCOPE_GLOBAL) < 0;
    quiet_off(&q);
    if (bad)
        return gr_fail(err, GR_ERUN, "%s: cannot write the table %s%s%s", f->part, group, k ? ", column " : "",
                       k ? cols[k - 1].name : "");
    return GR_OK;
}

int exp_tab_array(exp_tab_file *f, const char *name, int rank, const size_t *dims, const double *v,
                  const char *unit, const char *desc, gr_err *err)
{
    hsize_t hd[8];
    for (int k = 0; k < rank && k < 8; k++)
        hd[k] = dims[k];
    quiet q;
    quiet_on(&q);
    /* the parents made untimed first (make_group), then the array */
    const char *slash = strrchr(name, '/');
    if (slash && slash > name) {
        char parent[1024];
        snprintf(parent, sizeof parent, "%.*s", (int)(slash - name), name);
        hid_t g = make_group(f->file, parent);
        if (g >= 0)
            H5Gclose(g);
    }
    hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    hid_t s = rank > 0 && rank <= 8 ? H5Screate_simple(rank, hd, NULL) : -1;
    int ok = dcpl >= 0 && s >= 0 && H5Pset_obj_track_times(dcpl, 0) >= 0;
    hssize_t np = s >= 0 ? H5Sget_simple_extent_npoints(s) : 0;
    if (ok && np > 0)
        ok = H5Pset_chunk(dcpl, rank, hd) >= 0 && H5Pset_fletcher32(dcpl) >= 0;
    hid_t d = ok ? H5Dcreate2(f->file, name, H5T_IEEE_F64LE, s, H5P_DEFAULT, dcpl, H5P_DEFAULT) : -1;
    if (dcpl >= 0)
        H5Pclose(dcpl);
    int bad = d < 0 || H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) < 0 ||
              put_attr(d, "unit", unit) || put_attr(d, "description", desc) ||
              H5Fflush(f->file, H5F_SCOPE_GLOBAL) < 0;
    if (d >= 0)
        H5Dclose(d);
    if (s >= 0)
        H5Sclose(s);
    quiet_off(&q);
    return bad ? gr_fail(err, GR_ERUN, "%s: cannot write the array %s", f->part, name) : GR_OK;
}

int exp_tab_attr(exp_tab_file *f, const char *obj, const char *name, const char *value, gr_err *err)
{
    quiet q;
    quiet_on(&q);
    hid_t o = H5Oopen(f->file, obj, H5P_DEFAULT);
    int bad = o < 0 || put_attr(o, name, value);
    if (o >= 0)
        H5Oclose(o);
    quiet_off(&q);
    return bad ? gr_fail(err, GR_ERUN, "%s: cannot write the attribute %s of %s", f->part, name, obj) : GR_OK;
}

int exp_tab_close(exp_tab_file *f, gr_err *err)
{
    quiet q;
    quiet_on(&q);
    int bad = H5Fclose(f->file) < 0;
    quiet_off(&q);
    f->file = -1;
    if (bad || rename(f->part, f->path)) {
        gr_fail(err, GR_ERUN, "%s: cannot finish the file", f->path);
        remove(f->part);
        free(f);
        return GR_ERUN;
    }
    free(f);
    return GR_OK;
}

void exp_tab_free(exp_tab_file *f)
{
    if (!f)
        return;
    if (f->file >= 0) {
        quiet q;
        quiet_on(&q);
        H5Fclose(f->file);
        quiet_off(&q);
    }
    remove(f->part);
    free(f);
}
