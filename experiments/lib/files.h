/* Directories for results and part files. */
#ifndef GR_EXP_FILES_H
#define GR_EXP_FILES_H

#include "err.h"

/* Make a directory and its parents. */
int exp_mkdirs(const char *dir, gr_err *err);

/* May a writer create or replace path? GR_EINPUT naming the flag when path
 * is a directory or a device (never replaced, even with force), exists
 * and force is 0, or cannot be created (its folder missing or read-only). */
int exp_check_writable(const char *path, const char *flag, int force, gr_err *err);

/* Remove path if it exists (a partial file a killed run left behind);
 * 1 if something was removed. */
int exp_remove_stale(const char *path);

#endif
