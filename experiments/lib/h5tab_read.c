/* Reading back a column of a typed table (h5tab.h): what a command that
 * answers from an earlier study's file (grano advise from compare.h5)
 * needs. */
#include "h5tab.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <hdf5.h>

/* The file opened read-only with HDF5's error printing off (the status
 * says enough), and closed with it restored. */
typedef struct {
    hid_t f;
    H5E_auto2_t fn;
    void *data;
} reader;

static int reader_open(reader *r, const char *path, gr_err *err)
{
    H5Eget_auto2(H5E_DEFAULT, &r->fn, &r->data);
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    r->f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    return r->f < 0 ? gr_fail(err, GR_EINPUT, "%s: cannot open it as HDF5", path) : GR_OK;
}

static void reader_close(reader *r)
{
    if (r->f >= 0)
        H5Fclose(r->f);
    H5Eset_auto2(H5E_DEFAULT, r->fn, r->data);
}

/* A variable-length UTF-8 string type. */
static hid_t utf8(void)
{
    hid_t t = H5Tcopy(H5T_C_S1);
    H5Tset_size(t, H5T_VARIABLE);
    H5Tset_cset(t, H5T_CSET_UTF8);
    return t;
}

/* The column's dataset and its length; -1 and err set if absent. */
static hid_t column(hid_t file, const char *path, const char *group, const char *col, size_t *n, gr_err *err)
{
    char name[512];
    snprintf(name, sizeof name, "%s/%s", group, col);
    hid_t d = H5Lexists(file, group, H5P_DEFAULT) > 0 && H5Lexists(file, name, H5P_DEFAULT) > 0
                  ? H5Dopen2(file, name, H5P_DEFAULT)
                  : -1;
    hid_t s = d >= 0 ? H5Dget_space(d) : -1;
    hssize_t k = s >= 0 ? H5Sget_simple_extent_npoints(s) : -1;
    if (s >= 0)
        H5Sclose(s);
    if (k < 0) {
        if (d >= 0)
            H5Dclose(d);
        gr_fail(err, GR_EINPUT, "%s: no table column %s", path, name);
        return -1;
    }
    *n = (size_t)k;
    return d;
}

int exp_tab_read_f64(const char *path, const char *group, const char *col, double **v, size_t *n, gr_err *err)
{
    *v = NULL;
    reader rd;
    int rc = reader_open(&rd, path, err);
    hid_t d = rc ? -1 : column(rd.f, path, group, col, n, err);
    rc = rc || d < 0;
    if (!rc && !(*v = malloc((*n ? *n : 1) * sizeof **v)))
        rc = gr_fail(err, GR_ERUN, "out of memory");
    if (!rc && *n && H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, *v) < 0)
        rc = gr_fail(err, GR_EINPUT, "%s: cannot read %s/%s as numbers", path, group, col);
    if (d >= 0)
        H5Dclose(d);
    reader_close(&rd);
    if (rc) {
        free(*v);
        *v = NULL;
        return err->code ? err->code : GR_EINPUT;
    }
    return GR_OK;
}

int exp_tab_read_str(const char *path, const char *group, const char *col, char ***v, size_t *n, gr_err *err)
{
    *v = NULL;
    reader rd;
    int rc = reader_open(&rd, path, err);
    hid_t d = rc ? -1 : column(rd.f, path, group, col, n, err);
    rc = rc || d < 0;
    hid_t t = utf8();
    char **raw = rc ? NULL : calloc(*n ? *n : 1, sizeof *raw);
    if (!rc && (!raw || !(*v = calloc(*n ? *n : 1, sizeof **v))))
        rc = gr_fail(err, GR_ERUN, "out of memory");
    if (!rc && *n && H5Dread(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, raw) < 0)
        rc = gr_fail(err, GR_EINPUT, "%s: cannot read %s/%s as text", path, group, col);
    for (size_t i = 0; !rc && i < *n; i++)
        if (!((*v)[i] = strdup(raw[i] ? raw[i] : "")))
            rc = gr_fail(err, GR_ERUN, "out of memory");
    if (raw && d >= 0 && *n) {
        hid_t s = H5Dget_space(d);
        H5Dvlen_reclaim(t, s, H5P_DEFAULT, raw);
        H5Sclose(s);
    }
    free(raw);
    H5Tclose(t);
    if (d >= 0)
        H5Dclose(d);
    reader_close(&rd);
    if (rc) {
        exp_tab_strs_free(*v, *v ? *n : 0);
        *v = NULL;
        return err->code ? err->code : GR_EINPUT;
    }
    return GR_OK;
}

void exp_tab_strs_free(char **v, size_t n)
{
    for (size_t i = 0; v && i < n; i++)
        free(v[i]);
    free(v);
}

int exp_tab_read_attr(const char *path, const char *obj, const char *name, char *out, size_t n, gr_err *err)
{
    reader rd;
    int rc = reader_open(&rd, path, err);
    hid_t a = !rc && H5Aexists_by_name(rd.f, obj, name, H5P_DEFAULT) > 0
                  ? H5Aopen_by_name(rd.f, obj, name, H5P_DEFAULT, H5P_DEFAULT)
                  : -1;
    hid_t t = utf8();
    char *v = NULL;
    rc = rc || a < 0 || H5Aread(a, t, &v) < 0 || !v;
    if (!rc)
        snprintf(out, n, "%s", v);
    if (v) {
        hid_t s = H5Screate(H5S_SCALAR);
        H5Dvlen_reclaim(t, s, H5P_DEFAULT, &v);
        H5Sclose(s);
    }
    H5Tclose(t);
    if (a >= 0)
        H5Aclose(a);
    reader_close(&rd);
    return rc ? gr_fail(err, GR_EINPUT, "%s: no attribute %s of %s", path, name, obj) : GR_OK;
}
