/* Settle once, branch many: what may differ between the scene a checkpoint
 * was written with and the scene of its restart. */
#ifndef GR_RESTART_H
#define GR_RESTART_H

#include <stddef.h>

#include "scene.h"

/* The scene text stored in the checkpoint ckpt against the scene now.
 * [run] (until, intervals, contacts), [measure] (windows, field cells) and
 * [scene] name may differ: they are listed in notes. Any other key differs
 * only with branch (a new output from the checkpoint's state); without it,
 * GR_EINPUT naming the first such key, its line and both values. *old_run
 * receives the checkpoint's [run] (for intervals that changed). */
int gr_restart_compare(const gr_scene *now, const char *old_text, const char *ckpt, int branch,
                       char *notes, size_t cap, gr_runctl *old_run, gr_err *err);

#endif
