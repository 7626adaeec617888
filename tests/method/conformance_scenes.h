/* The conformance battery's scenes and its parameter-table tests
 * (test_conformance.c runs them over every registered backend). */
#ifndef GR_CONFORMANCE_SCENES_H
#define GR_CONFORMANCE_SCENES_H

#include <stddef.h>
#include <stdint.h>

typedef struct {
    const char *name;
    unsigned feature;   /* the GR_FEAT_* bit it exercises (0: none) */
    const char *text;
    double t_end;       /* run length */
    uint64_t save_after; /* steps (events) past 0.6 t_end: the restart point */
    long grains;        /* mobile grains at the start */
} conf_scene;

extern const conf_scene conf_scenes[];
extern const size_t conf_nscenes;

void conf_param_tables(void **unused);
void conf_param_checks_in_scenes(void **unused);
void conf_param_checkpoint(void **unused);
void conf_param_docs(void **unused);
void conf_optional_ops(void **unused);

#endif
