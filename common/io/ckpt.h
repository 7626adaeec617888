/* Checkpoint store: named arrays in one HDF5 group, so a backend saves its
 * full state (contact history, event clocks, RNG) without knowing HDF5. */
#ifndef GR_CKPT_H
#define GR_CKPT_H

#include <stddef.h>
#include <stdint.h>

#include "err.h"
#include "particles.h"
#include "rng.h"

typedef struct gr_ckpt gr_ckpt;

int gr_ckpt_put_f64(gr_ckpt *c, const char *name, const double *v, size_t n, gr_err *err);
int gr_ckpt_put_i64(gr_ckpt *c, const char *name, const int64_t *v, size_t n, gr_err *err);
int gr_ckpt_put_u64(gr_ckpt *c, const char *name, const uint64_t *v, size_t n, gr_err *err);
int gr_ckpt_put_u32(gr_ckpt *c, const char *name, const uint32_t *v, size_t n, gr_err *err);
int gr_ckpt_put_bytes(gr_ckpt *c, const char *name, const void *v, size_t n, gr_err *err);
/* Number of elements stored under name; fails if absent. */
int gr_ckpt_len(gr_ckpt *c, const char *name, size_t *n, gr_err *err);
/* Read exactly n elements; fails if the stored length or type differs. */
int gr_ckpt_get_f64(gr_ckpt *c, const char *name, double *v, size_t n, gr_err *err);
int gr_ckpt_get_i64(gr_ckpt *c, const char *name, int64_t *v, size_t n, gr_err *err);
int gr_ckpt_get_u64(gr_ckpt *c, const char *name, uint64_t *v, size_t n, gr_err *err);
int gr_ckpt_get_u32(gr_ckpt *c, const char *name, uint32_t *v, size_t n, gr_err *err);
int gr_ckpt_get_bytes(gr_ckpt *c, const char *name, void *v, size_t n, gr_err *err);

/* Open a checkpoint file for writing (a fresh file) or reading; the store
 * is the file's /checkpoint group. */
gr_ckpt *gr_ckpt_create(const char *path, gr_err *err);
gr_ckpt *gr_ckpt_open(const char *path, gr_err *err);
/* Flush and close; returns the status of the final flush. */
int gr_ckpt_close(gr_ckpt *c, gr_err *err);
/* Abandon a checkpoint being written (its temporary file is removed, the
 * previous checkpoint stays); closes one opened for reading. Accepts NULL. */
void gr_ckpt_discard(gr_ckpt *c);

/* A random stream's generator state (name is the dataset name);
 * io/rng_ckpt.c. */
int gr_rng_save(const gr_rng *r, gr_ckpt *ck, const char *name, gr_err *err);
int gr_rng_load(gr_rng *r, gr_ckpt *ck, const char *name, gr_err *err);

/* Make the checkpoint an H5MD file too (h5md/, parameters/ with the scene,
 * one frame at step/time), so gr_h5md_open reads its scene and particles. */
struct gr_scene;
struct gr_h5md_opts;
int gr_ckpt_put_h5md(gr_ckpt *c, const struct gr_scene *sc, const struct gr_h5md_opts *o,
                     uint64_t step, double time, const gr_particles *p, gr_err *err);

#endif
