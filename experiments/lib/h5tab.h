/* Result files of typed tables (HDF5, not H5MD: no trajectory). A table is
 * a group holding one dataset per column, in the order written, each with a
 * `unit` and a `description` attribute: h5py and pandas read a column by
 * name. Strings are variable-length UTF-8, counts 64-bit integers, the
 * rest float64. The file is written as <path>.part and renamed on a clean
 * close, so a failed report leaves nothing that looks like a result. */
#ifndef GR_EXP_H5TAB_H
#define GR_EXP_H5TAB_H

#include <stddef.h>

#include "err.h"

typedef struct exp_tab_file exp_tab_file;

enum {
    EXP_F64 = 0, /* v: const double *, stored as float64 */
    EXP_INT = 1, /* v: const double * holding whole numbers, stored as int64 */
    EXP_STR = 2  /* v: const char *const *, stored as UTF-8 strings */
};

typedef struct {
    const char *name;
    const char *unit;  /* "1" for a pure number; "" for strings */
    const char *desc;  /* a short line */
    int type;
    const void *v;     /* rows values, the k-th at v[k * stride] */
    size_t stride;     /* 0 or 1: contiguous */
} exp_col;

/* Create path (replacing it at close); kind goes to the root's `kind`
 * attribute, with `creator` (grano and its version). */
exp_tab_file *exp_tab_create(const char *path, const char *kind, gr_err *err);

/* The table `group` ('/'-separated; parents are made) of rows rows, with
 * description desc on the group. */
int exp_tab_write(exp_tab_file *f, const char *group, const char *desc, size_t rows, const exp_col *cols,
                  size_t ncols, gr_err *err);

/* A float64 array of rank dimensions dims at `name` (parents are made),
 * with its unit and description. */
int exp_tab_array(exp_tab_file *f, const char *name, int rank, const size_t *dims, const double *v,
                  const char *unit, const char *desc, gr_err *err);

/* A string attribute on the existing object obj ("/" for the root). */
int exp_tab_attr(exp_tab_file *f, const char *obj, const char *name, const char *value, gr_err *err);

/* Close and rename into place; f is freed whatever the status. */
int exp_tab_close(exp_tab_file *f, gr_err *err);
/* Close and remove the unfinished file; accepts NULL. */
void exp_tab_free(exp_tab_file *f);

/* Column col of table group in the file at path, read back: numbers
 * (*v malloc'd, n of them) or text (*v and each string malloc'd; free
 * with exp_tab_strs_free). GR_EINPUT naming the file and column if it
 * cannot be read. */
int exp_tab_read_f64(const char *path, const char *group, const char *col, double **v, size_t *n, gr_err *err);
int exp_tab_read_str(const char *path, const char *group, const char *col, char ***v, size_t *n, gr_err *err);
void exp_tab_strs_free(char **v, size_t n);
/* Text attribute name of object obj (a table's group) into out. */
int exp_tab_read_attr(const char *path, const char *obj, const char *name, char *out, size_t n, gr_err *err);

#endif
