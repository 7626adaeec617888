/* Fields on a grid (fields/<name>) and experiment results (results/<name>):
 * written through a gr_h5md, read through a gr_h5md_reader. The grid of a
 * field is kept in the file's attributes, which every later sample must
 * match. */
#include "h5md_impl.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int create_field(hid_t file, const char *path, const gr_field_desc *f)
{
    hid_t g = gr_h5_mkgroup(file, path);
    int grid[2] = {f->nx, f->ny}, nc = f->ncomp;
    double origin[2] = {f->x0, f->y0}, cell[2] = {f->dx, f->dy};
    hsize_t item[3] = {(hsize_t)f->ny, (hsize_t)f->nx, (hsize_t)f->ncomp};
    hid_t step = -1, time = -1, value = -1;
    int bad = g < 0 || gr_h5_attr_int(g, "grid", grid, 2) || gr_h5_attr_f64(g, "origin", origin, 2) ||
              gr_h5_attr_f64(g, "cell", cell, 2) || gr_h5_attr_int(g, "components", &nc, 0) ||
              (step = gr_h5_ext_create(g, "step", GR_T_I64, 0, NULL)) < 0 ||
              (time = gr_h5_ext_create(g, "time", GR_T_F64, 0, NULL)) < 0 || gr_h5_unit(time, "tau") ||
              (value = gr_h5_ext_create(g, "value", GR_T_F64, f->ncomp > 1 ? 3 : 2, item)) < 0 ||
              gr_h5_unit(value, f->unit ? f->unit : "1");
    gr_h5_close(value);
    gr_h5_close(time);
    gr_h5_close(step);
    gr_h5_close(g);
    return bad ? -1 : 0;
}

static int read_grid(hid_t file, const char *path, gr_field_desc *f)
{
    hid_t g = H5Gopen2(file, path, H5P_DEFAULT);
    int grid[2], nc = 1;
    double origin[2], cell[2];
    int bad = g < 0 || gr_h5_read_attr_int(g, "grid", grid, 2) ||
              gr_h5_read_attr_f64(g, "origin", origin, 2) || gr_h5_read_attr_f64(g, "cell", cell, 2) ||
              gr_h5_read_attr_int(g, "components", &nc, 0);
    gr_h5_close(g);
    if (bad)
        return -1;
    f->nx = grid[0];
    f->ny = grid[1];
    f->ncomp = nc;
    f->x0 = origin[0];
    f->y0 = origin[1];
    f->dx = cell[0];
    f->dy = cell[1];
    return 0;
}

static int append_at(hid_t file, const char *group, const char *name, gr_h5_type t, const void *row)
{
    char p[300];
    snprintf(p, sizeof p, "%s/%s", group, name);
    hid_t d = H5Dopen2(file, p, H5P_DEFAULT);
    int rc = d < 0 ? -1 : gr_h5_ext_append(d, t, row);
    gr_h5_close(d);
    return rc;
}

static int field_impl(gr_h5md *h, const gr_field_desc *f, uint64_t step, double time,
                      const double *values, gr_err *err)
{
    if (!gr_h5_valid_name(f->name) || strchr(f->name, '/'))
        return gr_fail(err, GR_ERUN, "invalid field name '%s'", f->name ? f->name : "");
    if (f->nx < 1 || f->ny < 1 || f->ncomp < 1 || f->ncomp > 4 || !(f->dx > 0) || !(f->dy > 0) ||
        !isfinite(f->dx) || !isfinite(f->dy) || !isfinite(f->x0) || !isfinite(f->y0))
        return gr_fail(err, GR_ERUN, "field '%s': invalid grid %dx%d (ncomp %d, cell %g x %g)",
                       f->name, f->nx, f->ny, f->ncomp, f->dx, f->dy);
    if (!isfinite(time))
        return gr_fail(err, GR_ERUN, "field '%s': non-finite time", f->name);
    char path[256];
    snprintf(path, sizeof path, "fields/%s", f->name);
    int fresh = !gr_h5_exists(gr_h5md_file_of(h), path);
    if (fresh && gr_h5md_edit(h))
        return gr_h5_fail(err, GR_ERUN, "cannot copy %s to add %s", gr_h5md_path_of(h), path);
    hid_t file = gr_h5md_file_of(h);
    if (fresh) {
        if (create_field(file, path, f))
            return gr_h5_fail(err, GR_ERUN, "cannot create %s in %s", path, gr_h5md_path_of(h));
    } else {
        gr_field_desc old;
        if (read_grid(file, path, &old))
            return gr_h5_fail(err, GR_ERUN, "%s in %s is malformed", path, gr_h5md_path_of(h));
        if (old.nx != f->nx || old.ny != f->ny || old.ncomp != f->ncomp || old.x0 != f->x0 ||
            old.y0 != f->y0 || old.dx != f->dx || old.dy != f->dy)
            return gr_fail(err, GR_ERUN,
                           "field '%s': grid %dx%d (ncomp %d) differs from its first sample (%dx%d, ncomp %d)",
                           f->name, f->nx, f->ny, f->ncomp, old.nx, old.ny, old.ncomp);
    }
    int64_t s = (int64_t)step;
    if (append_at(file, path, "value", GR_T_F64, values) || append_at(file, path, "step", GR_T_I64, &s) ||
        append_at(file, path, "time", GR_T_F64, &time))
        return gr_h5_fail(err, GR_ERUN, "cannot append to %s in %s", path, gr_h5md_path_of(h));
    if (H5Fflush(file, H5F_SCOPE_GLOBAL) < 0)
        return gr_h5_fail(err, GR_ERUN, "cannot flush %s", gr_h5md_path_of(h));
    return gr_h5md_edited(h, err);
}

int gr_h5md_write_field(gr_h5md *h, const gr_field_desc *f, uint64_t step, double time,
                        const double *values, gr_err *err)
{
    int rc;
    GR_H5_GUARD(err, rc, rc = field_impl(h, f, step, time, values, err));
    return rc;
}

static int result_impl(gr_h5md *h, const gr_result_desc *d, const double *v, gr_err *err)
{
    if (!gr_h5_valid_name(d->name))
        return gr_fail(err, GR_ERUN, "invalid result name '%s'", d->name ? d->name : "");
    char path[256];
    snprintf(path, sizeof path, "results/%s", d->name);
    if (gr_h5md_edit(h))
        return gr_h5_fail(err, GR_ERUN, "cannot copy %s to add %s", gr_h5md_path_of(h), path);
    hid_t file = gr_h5md_file_of(h);
    if (gr_h5_exists(file, path) && H5Ldelete(file, path, H5P_DEFAULT) < 0)
        return gr_h5_fail(err, GR_ERUN, "cannot replace %s in %s", path, gr_h5md_path_of(h));
    hsize_t dims[2] = {d->rows, d->cols};
    hid_t ds = gr_h5_fixed_create(file, path, GR_T_F64, dims, v);
    int bad = ds < 0;
    if (!bad && d->columns && d->cols)
        bad = gr_h5_attr_strs(ds, "columns", d->columns, d->cols, 1);
    if (!bad && d->units)
        bad = d->cols ? gr_h5_attr_strs(ds, "units", d->units, d->cols, 0) : gr_h5_unit(ds, d->units[0]);
    if (!bad && d->description)
        bad = gr_h5_attr_str(ds, "description", d->description, 1);
    gr_h5_close(ds);
    if (bad)
        return gr_h5_fail(err, GR_ERUN, "cannot write %s in %s", path, gr_h5md_path_of(h));
    if (H5Fflush(file, H5F_SCOPE_GLOBAL) < 0)
        return gr_h5_fail(err, GR_ERUN, "cannot flush %s", gr_h5md_path_of(h));
    return gr_h5md_edited(h, err);
}

int gr_h5md_write_result(gr_h5md *h, const gr_result_desc *d, const double *v, gr_err *err)
{
    int rc;
    GR_H5_GUARD(err, rc, rc = result_impl(h, d, v, err));
    return rc;
}

static int field_info_impl(gr_h5md_reader *r, const char *name, gr_field_desc *f, size_t *samples,
                           gr_err *err)
{
    hid_t file = gr_h5md_reader_file(r);
    const char *fp = gr_h5md_info_of(r)->path;
    char p[256];
    snprintf(p, sizeof p, "fields/%s", name);
    if (!gr_h5_valid_name(name) || !gr_h5_is_group(file, p))
        return gr_fail(err, GR_EINPUT, "%s has no field '%s'", fp, name);
    if (read_grid(file, p, f))
        return gr_h5_fail(err, GR_ERUN, "%s: malformed field %s", fp, p);
    if (samples)
        *samples = gr_h5_series_rows(file, p);
    return GR_OK;
}

int gr_h5md_field_info(gr_h5md_reader *r, const char *name, gr_field_desc *f, size_t *samples,
                       gr_err *err)
{
    int rc;
    GR_H5_GUARD(err, rc, rc = field_info_impl(r, name, f, samples, err));
    return rc;
}

static int read_field_impl(gr_h5md_reader *r, const char *name, size_t sample, double *values,
                           uint64_t *step, double *time, gr_err *err)
{
    gr_field_desc f;
    size_t n;
    if (field_info_impl(r, name, &f, &n, err))
        return err->code;
    hid_t file = gr_h5md_reader_file(r);
    const char *fp = gr_h5md_info_of(r)->path;
    if (sample >= n)
        return gr_fail(err, GR_EINPUT, "field '%s' of %s has %zu samples; there is no sample %zu",
                       name, fp, n, sample);
    char p[256];
    int64_t s = 0;
    snprintf(p, sizeof p, "fields/%s/value", name);
    int bad = gr_h5_read_path(file, p, GR_T_F64, sample, 1, values);
    snprintf(p, sizeof p, "fields/%s/step", name);
    bad = bad || (step && gr_h5_read_path(file, p, GR_T_I64, sample, 1, &s));
    snprintf(p, sizeof p, "fields/%s/time", name);
    bad = bad || (time && gr_h5_read_path(file, p, GR_T_F64, sample, 1, time));
    if (bad)
        return gr_h5_fail(err, GR_ERUN, "%s: cannot read field '%s'", fp, name);
    if (step)
        *step = (uint64_t)s;
    return GR_OK;
}

int gr_h5md_read_field(gr_h5md_reader *r, const char *name, size_t sample, double *values,
                       uint64_t *step, double *time, gr_err *err)
{
    int rc;
    GR_H5_GUARD(err, rc, rc = read_field_impl(r, name, sample, values, step, time, err));
    return rc;
}

static int result_read_impl(gr_h5md_reader *r, const char *name, size_t *rows, size_t *cols,
                            double **v, gr_err *err)
{
    hid_t file = gr_h5md_reader_file(r);
    const char *fp = gr_h5md_info_of(r)->path;
    char p[256];
    snprintf(p, sizeof p, "results/%s", name);
    if (!gr_h5_valid_name(name) || !gr_h5_exists(file, p) || gr_h5_is_group(file, p))
        return gr_fail(err, GR_EINPUT, "%s has no result array '%s'", fp, name);
    hid_t d = H5Dopen2(file, p, H5P_DEFAULT);
    hid_t s = d >= 0 ? H5Dget_space(d) : -1;
    hsize_t dims[2] = {0, 0};
    int rank = s >= 0 ? H5Sget_simple_extent_ndims(s) : -1;
    if (rank == 1 || rank == 2)
        H5Sget_simple_extent_dims(s, dims, NULL);
    gr_h5_close(s);
    int rc = GR_OK;
    if (rank != 1 && rank != 2) {
        rc = gr_h5_fail(err, GR_ERUN, "%s: %s is not a table", fp, p);
    } else {
        *rows = dims[0];
        *cols = rank == 2 ? dims[1] : 0;
        size_t total = dims[0] * (rank == 2 ? dims[1] : 1);
        if (v && !(*v = malloc((total ? total : 1) * sizeof **v))) {
            rc = gr_fail(err, GR_ERUN, "out of memory");
        } else if (v && total && H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, *v) < 0) {
            free(*v);
            *v = NULL;
            rc = gr_h5_fail(err, GR_ERUN, "%s: cannot read %s", fp, p);
        }
    }
    gr_h5_close(d);
    return rc;
}

int gr_h5md_read_result(gr_h5md_reader *r, const char *name, size_t *rows, size_t *cols,
                        double **v, gr_err *err)
{
    int rc;
    GR_H5_GUARD(err, rc, rc = result_read_impl(r, name, rows, cols, v, err));
    return rc;
}

/* The "columns" attribute (variable-length strings), joined by ", ". */
static void read_columns(hid_t d, char *cols, size_t m)
{
    hid_t a = H5Aopen(d, "columns", H5P_DEFAULT);
    hid_t s = a >= 0 ? H5Aget_space(a) : -1;
    hssize_t n = s >= 0 ? H5Sget_simple_extent_npoints(s) : 0;
    hid_t t = H5Tcopy(H5T_C_S1);
    H5Tset_size(t, H5T_VARIABLE);
    char **v = n > 0 ? calloc((size_t)n, sizeof *v) : NULL;
    if (v && H5Aread(a, t, v) >= 0) {
        size_t k = 0;
        for (hssize_t i = 0; i < n && k + 1 < m; i++)
            k += (size_t)snprintf(cols + k, m - k, "%s%s", i ? ", " : "", v[i] ? v[i] : "?");
        H5Dvlen_reclaim(t, s, H5P_DEFAULT, v);
    }
    free(v);
    H5Tclose(t);
    gr_h5_close(s);
    gr_h5_close(a);
}

static int result_text_impl(gr_h5md_reader *r, const char *name, char *desc, size_t n, char *cols, size_t m,
                            gr_err *err)
{
    hid_t file = gr_h5md_reader_file(r);
    char p[256];
    snprintf(p, sizeof p, "results/%s", name);
    desc[0] = cols[0] = '\0';
    if (!gr_h5_valid_name(name) || !gr_h5_exists(file, p) || gr_h5_is_group(file, p))
        return gr_fail(err, GR_EINPUT, "%s has no result array '%s'", gr_h5md_info_of(r)->path, name);
    hid_t d = H5Dopen2(file, p, H5P_DEFAULT);
    if (d < 0)
        return gr_h5_fail(err, GR_ERUN, "cannot open %s", p);
    char *s = H5Aexists(d, "description") > 0 ? gr_h5_read_attr_str(d, "description") : NULL;
    if (s)
        snprintf(desc, n, "%s", s);
    free(s);
    if (H5Aexists(d, "columns") > 0)
        read_columns(d, cols, m);
    gr_h5_close(d);
    return GR_OK;
}

int gr_h5md_result_text(gr_h5md_reader *r, const char *name, char *desc, size_t n, char *cols, size_t m,
                        gr_err *err)
{
    int rc;
    GR_H5_GUARD(err, rc, rc = result_text_impl(r, name, desc, n, cols, m, err));
    return rc;
}
