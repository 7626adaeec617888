/* The conformance battery (docs/interface.md, Conformance): every check of
 * methods/method.h's contract, run on a given NULL-ended list of backends
 * over a given list of scenes, each backend x scene and each per-backend
 * check its own cmocka test case, so that one failure hides no other.
 * test_conformance.c runs it on gr_method_all(); tests/method/toy/ on a
 * backend registered nowhere else. */
#ifndef GR_CONFORMANCE_H
#define GR_CONFORMANCE_H

#include <stddef.h>
#include <stdint.h>

#include "method.h"

typedef struct {
    const char *name;
    unsigned feature;   /* the GR_FEAT_* bit it exercises (0: none) */
    const char *text;
    double t_end;       /* run length */
    uint64_t save_after; /* steps (events) past 0.6 t_end: the restart point */
    long grains;        /* mobile grains at the start */
} conf_scene;

/* The shipped scenes: one per scene feature, plus a plain box (the first,
 * which every backend runs) and a second friction model. */
extern const conf_scene conf_scenes[];
extern const size_t conf_nscenes;

typedef struct {
    const char *group;                     /* the test group's name */
    const gr_method_type *const *methods;  /* NULL ended */
    const conf_scene *scenes;              /* scenes[0] a plain box every backend takes */
    size_t nscenes;
    const char *docs;                      /* the folder of the methods' <name>.md pages */
} conf_battery;

/* Run the battery; returns the number of failed cases (cmocka's). Scene
 * sections are read for the registered names and the battery's. */
int conf_run(const conf_battery *b);

/* ---- the cases (conformance_*.c), each handed a conf_case ---- */
typedef struct {
    const conf_battery *b;
    const char *const *sections; /* NULL ended: the scene sections read */
    const gr_method_type *m;     /* NULL: a case over the scenes alone */
    const conf_scene *cs;        /* the scene of a backend x scene case */
} conf_case;

/* conformance_util.c */
gr_scene *conf_parse(const conf_case *c, const char *text);
gr_sim *conf_create(const gr_method_type *m, const gr_scene *sc);
/* Whether the backend takes the scene; a refusal must be an input error
 * naming the file. */
int conf_accepts(const gr_method_type *m, const gr_scene *sc, const char *name);
/* msg as the rest of a TAP comment line (its line breaks made comments). */
void conf_print_comment(const char *msg);

/* conformance_outcome.c: everything a run shows (a lattice: its fields
 * on a fine grid instead of a snapshot). */
typedef struct {
    gr_particles *p;
    gr_field *f;      /* lattice backends */
    gr_contacts *net; /* methods that give contact networks */
    gr_obs o;
    size_t nc;
    gr_counter c[GR_MAX_COUNTERS];
} conf_outcome;
conf_outcome conf_look(gr_sim *s);
void conf_same(const conf_outcome *a, const conf_outcome *b); /* bit for bit */
void conf_outcome_free(conf_outcome *r);
/* Finite observables, distinct counter names, snapshots in id order, a
 * network naming grains of the snapshot. */
void conf_check_outcome(const gr_method_type *m, const conf_scene *cs, const conf_outcome *r);
/* The packing field holds every mobile grain's area (a lattice: the
 * number field every particle). */
void conf_check_fields(gr_sim *s, const gr_scene *sc);

/* conformance_contract.c */
void conf_scene_case(void **state);
void conf_features_run(void **state);
void conf_features_covered(void **state);

/* conformance_observables.c: the declared table (per backend), and on a
 * scene every counter declared, every quantity the scene has finite after
 * a window, observing pure (per backend x scene) */
void conf_obs_table(void **state);
void conf_obs_scene(void **state);

/* conformance_params.c */
void conf_param_tables(void **state);
void conf_param_checks_in_scenes(void **state);
void conf_param_checkpoint(void **state);
void conf_param_docs(void **state);
void conf_optional_ops(void **state);

#endif
