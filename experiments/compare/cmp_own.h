/* grano compare SCENE.ini: a user's scene as a case of its own
 * (cmp_own.c). */
#ifndef GR_CMP_OWN_H
#define GR_CMP_OWN_H

#include "cmp.h"

typedef struct {
    const char *scene;      /* the scene file */
    const char *methods;    /* comma-separated, NULL: all */
    const char *observable; /* NULL: epot_grav under gravity, else temperature */
    const char *reference;  /* method whose finest run is the reference, NULL: chosen */
    double until;           /* > 0: [run] until for every run */
    double tolerance;       /* the outcome's tolerance (0: none) */
    int seeds;              /* realisations (0: 3) */
} cmp_own_opts;

/* The case and the storage its strings point into. */
typedef struct {
    cmp_case c[2];          /* the case, then the NULL-name end */
    char dir[2048], file[512], name[128], quantity[64], unit[32], fixed[64];
    char values[CMP_MAXROWS][2][64]; /* a row's knob values: coarse ones, the finest */
    char labels[CMP_MAXROWS][64];
    char notes[2048];       /* the methods left out and why */
} cmp_own;

/* Build the case of o->scene: GR_EINPUT naming the file or the flag. */
int cmp_own_build(const cmp_own_opts *o, cmp_own *own, gr_err *err);

#endif
