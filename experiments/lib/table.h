/* Result tables: to the HDF5 result file and as plain .dat text. */
#ifndef GR_EXP_TABLE_H
#define GR_EXP_TABLE_H

#include <stddef.h>

#include <stdio.h>

#include "err.h"
#include "h5md.h"

/* To the HDF5 file, columns named by cols_csv (comma separated) or NULL. */
int exp_put_result(gr_h5md *h, const char *name, size_t rows, size_t cols, const char *cols_csv,
                   const char *desc, const double *v, gr_err *err);
/* A plain .dat with a '# header' line, then rows of cols numbers. */
/* A text file written whole or not at all: exp_dat_open opens path.part,
 * exp_dat_close closes it and renames it to path (on failure, removes it),
 * so that a reader never meets a half-written table under path. */
FILE *exp_dat_open(const char *path, gr_err *err);
int exp_dat_close(FILE *f, const char *path, gr_err *err);
int exp_write_dat(const char *path, const char *header, const double *v, size_t rows, size_t cols,
                  gr_err *err);

#endif
