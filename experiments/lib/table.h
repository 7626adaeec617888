/* Result tables: to the HDF5 result file and as plain .dat text. */
#ifndef GR_EXP_TABLE_H
#define GR_EXP_TABLE_H

#include <stddef.h>

#include "err.h"
#include "h5md.h"

/* To the HDF5 file, columns named by cols_csv (comma separated) or NULL. */
int exp_put_result(gr_h5md *h, const char *name, size_t rows, size_t cols, const char *cols_csv,
                   const char *desc, const double *v, gr_err *err);
/* A plain .dat with a '# header' line, then rows of cols numbers. */
int exp_write_dat(const char *path, const char *header, const double *v, size_t rows, size_t cols,
                  gr_err *err);

#endif
