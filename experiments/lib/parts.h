/* Part files: the checkpoint records a unit of a sweep leaves behind
 * (scalars, arrays, particle pictures, its key and its cost). */
#ifndef GR_EXP_PARTS_H
#define GR_EXP_PARTS_H

#include <stddef.h>
#include <stdint.h>

#include "ckpt.h"
#include "err.h"
#include "particles.h"

/* A hash of the running program's file (/proc/self/exe; 0 where it cannot
 * be read): parts made by another build of grano are not reused, since the
 * key of a unit names its settings but not the code that ran them. */
uint64_t exp_binary_hash(void);
/* key followed by " bin=<hash>": what a sweep stores in a part. */
void exp_key_seal(char *key, size_t n, uint64_t bin);
/* Whether the part at path exists, is complete and holds exactly sealed. */
int exp_part_key_is(const char *path, const char *sealed);
/* Whether the part at path exists, is complete and was made for key by
 * this build (key sealed with exp_binary_hash). */
int exp_part_key_matches(const char *path, const char *key);
/* x, y, vx, vy, radius and flags of every grain. */
int exp_put_particles(gr_ckpt *ck, const char *name, const gr_particles *p, gr_err *err);
int exp_get_particles(gr_ckpt *ck, const char *name, gr_particles *p, gr_err *err);
int exp_put_scalar(gr_ckpt *ck, const char *name, double v, gr_err *err);
/* NaN when absent. */
double exp_get_scalar(gr_ckpt *ck, const char *name);
/* A whole f64 array of unknown length (malloc'd). */
int exp_get_array(gr_ckpt *ck, const char *name, double **v, size_t *n, gr_err *err);

/* The "cost" record of a part: wall and CPU seconds of the filling, of the
 * run after opening, and the steps of that run (NaN when absent). */
void exp_get_cost(gr_ckpt *ck, double cost[5]);

#endif
