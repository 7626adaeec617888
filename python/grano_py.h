/* The flat C interface under the Python module grano (python/grano/_lib.py
 * declares it to ctypes): opaque handles, plain C types, and a gr_err to
 * fill, so that no Python binding needs a compiler or a struct layout
 * beyond gr_err's.
 *
 * A gp_sim is a gr_sim that stops where `grano run` stops: at every sample
 * time of the scene's [run] (observe_every, output_every, checkpoint_every,
 * counted from its start), observing there and starting a new measurement
 * window as the run loop does (experiments/lib/runio.c). Its trajectory,
 * its observables and its checkpoints are then the CLI's, bit for bit. */
#ifndef GP_GRANO_PY_H
#define GP_GRANO_PY_H

#include <stddef.h>
#include <stdint.h>

#include "method.h"

/* Once per process: GSL's aborting error handler off (grano checks every
 * status) and HDF5's exit handler off, as grano's main() does. */
void gp_init(void);
const char *gp_version(void);

/* ---- scenes (the caller frees with gp_scene_free) ---- */
/* A scene file with settings "section.key=value" applied as --set does. */
gr_scene *gp_scene_load(const char *path, const char *const *sets, size_t n, gr_err *err);
/* Scene text in memory; path names it in messages and results. */
gr_scene *gp_scene_parse(const char *text, const char *path, gr_err *err);
void gp_scene_free(gr_scene *sc);
const char *gp_scene_text(const gr_scene *sc);
const char *gp_scene_path(const gr_scene *sc);
const char *gp_scene_name(const gr_scene *sc);
uint64_t gp_scene_seed(const gr_scene *sc);
void gp_scene_set_seed(gr_scene *sc, uint64_t seed);
/* until, output_every, observe_every, checkpoint_every, width, height */
void gp_scene_numbers(const gr_scene *sc, double out[6]);
/* [measure] field_cells (0 0: none). */
void gp_scene_field_cells(const gr_scene *sc, int *nx, int *ny);
/* The value of section.key as written, or NULL when absent. */
const char *gp_scene_value(const gr_scene *sc, const char *section, const char *key);

/* ---- the registry, by index i < gp_method_count() ---- */
int gp_method_count(void);
const char *gp_method_name(int i);
const char *gp_method_summary(int i);
int gp_method_repr(int i);
unsigned gp_method_features(int i);
/* Operations of its own (GR_OP_*), not those given by a default. */
unsigned gp_method_ops(int i);
/* Bits below these counts name features and operations. */
int gp_feature_count(void);
int gp_op_count(void);
const char *gp_feature_name(unsigned bit);
int gp_feature_known(unsigned bit);
const char *gp_op_name(unsigned bit);
int gp_param_count(int i);
/* Parameter k: type (gr_param_type), v = default, min, max, min_open. */
const char *gp_param(int i, int k, int *type, double v[4], const char **unit, const char **doc);
/* Word c of a choice parameter, NULL past the last. */
const char *gp_param_choice(int i, int k, int c);
int gp_obs_count(int i);
/* Declared observable k: ncomp, integer (a count); key is the scene key
 * of a validity limit, else NULL. */
const char *gp_obs(int i, int k, const char **unit, int *ncomp, int *integer, const char **doc,
                   const char **key);

/* ---- simulations ---- */
typedef struct gp_sim gp_sim;
/* Takes sc (freed with the gp_sim, or here on failure), read with the n
 * settings sets (gp_scene_load), which messages name as --set does. init:
 * the grains to start from instead of the scene's [init] (NULL: the
 * scene's). */
gp_sim *gp_sim_create(const char *method, gr_scene *sc, const char *const *sets, size_t nsets,
                      const gr_particles *init, gr_err *err);
/* A checkpoint written by grano run or gp_sim_save. sc NULL: the scene,
 * method and seed stored in it; else sc (taken) with method (NULL: the
 * stored one), where [run] and [measure] may differ, and anything with
 * branch, as grano run --restart [--branch]; notes receives the
 * differences allowed. */
gp_sim *gp_sim_load(const char *ckpt, gr_scene *sc, const char *const *sets, size_t nsets, const char *method,
                    int branch, char *notes, size_t cap, gr_err *err);
void gp_sim_free(gp_sim *s);
const char *gp_sim_method(const gp_sim *s);
int gp_sim_method_index(const gp_sim *s);
const gr_scene *gp_sim_scene(const gp_sim *s);
double gp_sim_time(const gp_sim *s);
/* One stretch towards t_end: the samples due now, then an advance to the
 * next sample time or t_end, at most max_steps steps (0: no limit). *done
 * is 1, and nothing moved, once the time has reached t_end. */
int gp_sim_advance(gp_sim *s, double t_end, uint64_t max_steps, int *done, gr_err *err);
/* n times: the samples due now, then one step or event (off the sample
 * times: a sample time a step jumps over is not taken). */
int gp_sim_step(gp_sim *s, uint64_t n, gr_err *err);
/* The declared observables now: each k fills val[2k], val[2k+1] (a
 * scalar: the first) or, a count, ival[k]; bit k of *skip: observable k
 * does not exist in this scene. */
int gp_sim_observe(gp_sim *s, double *t, uint64_t *steps, double *val, int64_t *ival, uint64_t *skip,
                   gr_err *err);
/* Whether the observables' sample of the present time is still to be
 * taken (it is when the run moves on, or at gp_sim_save). */
int gp_sim_sample_due(const gp_sim *s);
/* Bit k: declared observable k does not exist in this scene. */
uint64_t gp_sim_obs_skip(const gp_sim *s);
/* The samples taken at the sample times so far, row r of each: dval[r *
 * 2 * nobs ...], ival[r * nobs ...], time[r], steps[r]. */
size_t gp_sim_history(const gp_sim *s, const double **time, const uint64_t **steps, const double **dval,
                      const int64_t **ival);
void gp_sim_history_clear(gp_sim *s);
/* A new snapshot (gp_particles_free), or NULL with err filled. */
gr_particles *gp_sim_snapshot(gp_sim *s, gr_err *err);
/* Coarse-grained fields now on nx x ny cells over the domain: phi[c],
 * v[2c + (x, y)], T[c], c = iy nx + ix. */
int gp_sim_fields(gp_sim *s, int nx, int ny, double *phi, double *v, double *T, gr_err *err);
size_t gp_sim_counters(const gp_sim *s, const char **names, uint64_t *values, size_t cap);
/* The validity limits newly broken since the last call, one message a
 * line (as grano run warns them), copied into buf; returns their length. */
size_t gp_sim_warnings(gp_sim *s, char *buf, size_t cap);
/* The samples due now, then the checkpoint as grano run writes it. */
int gp_sim_save(gp_sim *s, const char *path, gr_err *err);

/* ---- particles ---- */
size_t gp_particles_n(const gr_particles *p);
/* Array `which`: x y vx vy omega radius mass inertia (double), flags
 * (uint32), id (int64), species (int32), in that order 0 .. 10. */
void *gp_particles_data(const gr_particles *p, int which);
void gp_particles_free(gr_particles *p);

#endif
