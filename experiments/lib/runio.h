/* The run loop shared by `grano run` and the experiments: advance a method
 * through a scene, writing observables, frames, fields and checkpoints as
 * it goes; restart from a checkpoint; keep the last good state on failure. */
#ifndef GR_RUNIO_H
#define GR_RUNIO_H

#include <stddef.h>

#include "method.h"
#include "scene.h"

typedef struct {
    const char *out;      /* H5MD result file */
    const char *ckpt;     /* checkpoint file (NULL: none) */
    const char *restart;  /* checkpoint to continue from (NULL: fresh start) */
    const char *snapshot; /* PNG of the final state (NULL: none) */
    int force;            /* replace existing files */
    int progress;         /* progress line on a terminal */
    int branch;           /* restart into a new output, physical changes allowed */
    char *notes;          /* receives the scene differences a restart allowed */
    size_t notes_cap;
    /* Told each validity limit the run breaks, once when it first happens,
     * and again in the summary at the end (NULL: not told). */
    void (*warn)(void *ctx, const char *msg);
    void *warn_ctx;
    /* Told once what the method derived from the scene (gr_sim_notes), when
     * it derived anything (NULL: not told; the result keeps it anyway). */
    void (*note)(void *ctx, const char *msg);
} gr_run_opts;

/* "<out minus .h5>.ckpt" */
void gr_run_ckpt_path(const char *out, char *buf, size_t n);

/* Samples of any one kind a run may ask for ([run] until / *_every). */
#define GR_RUN_MAX_SAMPLES 1e8

/* The [run] intervals: GR_EINPUT naming file:line:key beyond the limit. */
int gr_run_check(const gr_scene *sc, gr_err *err);

/* Returns GR_OK, GR_EINPUT (scene refused, bad restart) or GR_ERUN (the run
 * failed; the checkpoint then holds the last good state). */
int gr_run_scene(gr_scene *sc, const gr_method_type *m, const gr_run_opts *o, gr_err *err);

/* The sample times of a run are t0 + k * every (k = 0, 1, ...; every one
 * of [run] observe_every, output_every, checkpoint_every): the first k
 * whose time lies after t + eps. */
uint64_t gr_run_next_index(double t, double t0, double every, double eps);
/* The sample indices k[3] after a restart at time t (the checkpoint's
 * [run] was `was`), as gr_run_scene resumes them. */
void gr_run_resume_counters(const gr_scene *sc, const gr_runctl *was, double t, double t0, int branch,
                            uint64_t k[3]);

/* Save / restore a method's full state and the run counters. */
int gr_run_save(const char *path, gr_sim *sim, const uint64_t counters[3], gr_err *err);
/* Load: the scene may differ from the checkpoint's as restart.h allows
 * (o->branch, o->notes); *old_run receives the checkpoint's [run]. */
int gr_run_load(const char *path, gr_sim *sim, uint64_t counters[3], const gr_run_opts *o, gr_runctl *old_run,
                gr_err *err);

#endif
