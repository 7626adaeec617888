/* Directories for results and part files. */
#ifndef GR_EXP_FILES_H
#define GR_EXP_FILES_H

#include "err.h"

/* Make a directory and its parents. */
int exp_mkdirs(const char *dir, gr_err *err);

#endif
