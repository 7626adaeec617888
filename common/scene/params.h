/* A method's parameters as a table (name, type, default, range, unit, one
 * line of doc): the one description from which its scene section is
 * checked, its values read, checkpoints compared, `grano methods` prints,
 * and its docs page is tested. */
#ifndef GR_PARAMS_H
#define GR_PARAMS_H

#include <stddef.h>
#include <stdio.h>

#include "err.h"
#include "scene.h"

typedef enum { GR_PARAM_REAL = 0, GR_PARAM_INT, GR_PARAM_CHOICE } gr_param_type;

typedef struct {
    const char *name;
    gr_param_type type;
    /* Default; for a choice, the index of its word. NaN: derived from the
     * scene when absent (doc says how). */
    double def;
    /* Allowed range, inclusive; min_open: the value must exceed min. */
    double min, max;
    int min_open;
    const char *const *choices; /* NULL ended; GR_PARAM_CHOICE only */
    const char *unit;           /* "tau", "d", "1"; "" for choices */
    const char *doc;
} gr_param;

/* Tables end with an entry whose name is NULL. */
#define GR_MAX_PARAMS 32

/* The values of a section, table order; v is the default where absent. */
typedef struct {
    const gr_param *table;
    int n;
    double v[GR_MAX_PARAMS];
} gr_param_values;

/* Every key of [section] must be in the table (else file:line, the key and
 * the nearest name); every value must parse as its type and lie in its
 * range (else file:line, the key and the range). */
int gr_params_read(const gr_scene *sc, const char *section, const gr_param *table,
                   gr_param_values *pv, gr_err *err);
int gr_params_count(const gr_param *table);
/* Index of name in the table, or -1. */
int gr_param_index(const gr_param *table, const char *name);
/* Value of a parameter the table must hold: asking for a name outside it
 * is a programming error and aborts. */
double gr_param_get(const gr_param_values *pv, const char *name);
/* A table that contradicts itself (default outside its range, unnamed or
 * repeated names, a choice without words, no doc): GR_EINPUT naming it. */
int gr_params_check_table(const char *section, const gr_param *table, gr_err *err);
/* "value" as the scene would write it: a choice's word, an integer, %.17g. */
void gr_param_format(const gr_param *p, double v, char *buf, size_t n);
/* The table as aligned text, one parameter a line (for `grano methods`). */
void gr_params_print(FILE *f, const gr_param *table);

#endif
