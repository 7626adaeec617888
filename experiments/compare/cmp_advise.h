/* The cheapest method for a scene at an accepted error, from a
 * comparison's results (cmp_advise.c): grano advise, grano run --method
 * auto. */
#ifndef GR_CMP_ADVISE_H
#define GR_CMP_ADVISE_H

#include "err.h"
#include "method.h"
#include "scene.h"

typedef struct {
    char method[32];     /* the method chosen */
    char case_name[32];  /* the nearest case of grano compare */
    char row[64], knob[64], value[64]; /* the compare row relied on ("" when none was needed) */
    double error, error_sem, wall;     /* its relative error, error bar, wall s per run */
    int setting;         /* the knob is one key of the method's own section ("dem.dt"): a
                            setting to run with (grano run --method auto applies it) */
    char why[2048];      /* the choice and why, one sentence */
} cmp_advice;

/* The advice for sc at relative error tol (0: the nearest case's own
 * tolerance) from the comparison file `from` (compare.h5). GR_EINPUT with the reason when no method models the scene,
 * the file cannot be read, or no row reaches tol (naming --tolerance). */
int cmp_advise(const gr_scene *sc, const char *from, double tol, cmp_advice *a, gr_err *err);

/* A tolerance as "5%" or "0.05" (GR_EINPUT naming flag otherwise). */
int cmp_parse_tolerance(const char *flag, const char *s, double *tol, gr_err *err);

#endif
