/* The backend interface: a backend is a const table of functions, chosen
 * by name at run time from the registry (methods/registry.c). */
#ifndef GR_METHOD_H
#define GR_METHOD_H

#include <stdint.h>

#include "ckpt.h"
#include "err.h"
#include "observe.h"
#include "particles.h"
#include "scene.h"

typedef struct gr_method_type {
    const char *name;     /* "dem", "edmd", ... also its scene section */
    const char *summary;  /* one line for --help */
    unsigned features;    /* GR_FEAT_* the backend supports */
    const char *const *param_keys; /* keys of its scene section, NULL ended */

    /* Build a state from the scene and its initial particles (the backend
     * copies what it needs). Features outside `features` were already
     * refused by gr_method_create; parameters are read from the scene
     * section named after the backend. */
    int (*create)(const gr_scene *sc, const gr_particles *init, void **state, gr_err *err);
    /* Advance until the simulated time reaches t_end or max_steps steps
     * (events) were done, whichever is first; max_steps 0 = no limit. */
    int (*advance)(void *state, double t_end, uint64_t max_steps, gr_err *err);
    double (*time)(const void *state);
    /* Current state of every grain in id order, synchronised to time(). */
    int (*snapshot)(void *state, gr_particles *out, gr_err *err);
    int (*observe)(void *state, gr_obs *obs, gr_err *err);
    /* Full state: a load on a state created from the same scene continues
     * bit for bit as the uninterrupted run. */
    int (*save)(const void *state, gr_ckpt *ck, gr_err *err);
    int (*load)(void *state, gr_ckpt *ck, gr_err *err);
    void (*free)(void *state);
} gr_method_type;

/* Registry. */
const gr_method_type *gr_method_find(const char *name);
/* NULL-ended list of registered backends. */
const gr_method_type *const *gr_method_all(void);
/* Their names, NULL ended, for gr_scene_load's extra sections: fills at
 * most cap entries including the NULL. */
void gr_method_names(const char **names, size_t cap);
#define GR_MAX_METHODS 16

/* Refuse scene features the backend lacks (naming the feature, the file
 * and line that asked for it), check its section's keys, then create. */
int gr_method_create(const gr_method_type *m, const gr_scene *sc,
                     const gr_particles *init, void **state, gr_err *err);

#endif
