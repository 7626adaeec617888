/* Shared by the exercises of `grano course` (docs/course.md): their
 * options, the instance on a scene text, collision counting and the result
 * file. Each exercise is one file. */
#ifndef GR_COURSE_H
#define GR_COURSE_H

#include <stdint.h>

#include "err.h"
#include "h5md.h"
#include "method.h"
#include "particles.h"
#include "progress.h"
#include "scene.h"

typedef struct {
    const char *out;
    int quick;
    int naive;     /* [edmd] algorithm = naive (v1.0 of the slides) instead of the tree */
    double alpha;  /* cooling */
    unsigned long seed;
    int force;     /* replace existing result files */
    const gr_method_type *m;
    gr_progress *pg; /* the exercise's progress line on a terminal (NULL: none) */
} course_opts;

/* The scene of text (the keys of a scene file) with the method's section,
 * and an instance on it starting from init (NULL: the scene's [init]). The
 * scene outlives the instance: free it after. */
int course_sim(const char *text, const course_opts *o, const gr_particles *init, gr_scene **psc,
               gr_sim **ps, gr_err *err);

/* Disk-disk collisions so far (the counter "pair_collisions"); GR_EINPUT
 * naming the counter and `who` when the method does not count them. */
int course_pairs(const gr_sim *s, const char *who, uint64_t *pairs, gr_err *err);
/* Run until `target` disk-disk collisions have happened. */
int course_advance_pairs(gr_sim *s, uint64_t target, gr_err *err);

/* How the method runs, for the first line of an exercise's report:
 * "algorithm tree" for edmd, the method's name for the others. */
const char *course_how(const course_opts *o);

/* The exercise's HDF5 result file at <out>/<name>, labelled with the method. */
gr_h5md *course_h5(const course_opts *o, const char *name, const gr_scene *sc, gr_err *err);

int course_maxwell(const course_opts *o, gr_err *err);
int course_pressure(const course_opts *o, gr_err *err);
int course_cooling(const course_opts *o, gr_err *err);

#endif
