/* The scene: what is simulated, independent of the method. Read from an INI
 * file (docs/scene-format.md); every key keeps its file and line so that any
 * later refusal (by a backend, by a check) can name them. */
#ifndef GR_SCENE_H
#define GR_SCENE_H

#include <stddef.h>
#include <stdint.h>

#include "err.h"
#include "scene_types.h"

/* Features a scene uses; a backend declares those it supports. */
enum {
    GR_FEAT_GRAVITY = 1u << 0,
    GR_FEAT_FRICTION = 1u << 1,       /* any tangential force / rough collisions */
    GR_FEAT_CONTACT_HISTORY = 1u << 2, /* tangential spring */
    GR_FEAT_PERIODIC = 1u << 3,
    GR_FEAT_OPEN_SIDE = 1u << 4,
    GR_FEAT_SEGMENTS = 1u << 5,
    GR_FEAT_WALL_GRAINS = 1u << 6,
    GR_FEAT_ORIFICE = 1u << 7,        /* a gate that opens at a time */
    GR_FEAT_VIBRATING_FLOOR = 1u << 8,
    GR_FEAT_REINSERT = 1u << 9,
    GR_FEAT_POLYDISPERSE = 1u << 10,
    GR_FEAT_MIXTURE = 1u << 11,
    GR_FEAT_HERTZ = 1u << 12,
    GR_FEAT_HF_FLOOR = 1u << 13,      /* high-frequency floor limits */
    GR_FEAT_WEIGHTS = 1u << 14,       /* a particle stands for several grains */
    GR_FEAT_RESTITUTION = 1u << 15,   /* a prescribed normal restitution */
    GR_FEAT_LATTICE = 1u << 16,       /* an initial state given as lattice occupations */
    GR_FEAT_SOFT_TANGENTIAL = 1u << 17 /* a viscous or regularised tangential force */
};
#define GR_FEAT_COUNT 18

/* Load and check a scene file. extra_sections lists the section names the
 * caller accepts besides the common ones (the backend names), NULL ended;
 * their keys are kept for the backend to read. */
gr_scene *gr_scene_load(const char *path, const char *const *extra_sections, gr_err *err);
/* The file's text (malloc'd, NUL ended; a NUL byte in it is refused). */
char *gr_scene_read_text(const char *path, gr_err *err);
/* gr_scene_load with the n settings "section.key=value" of --set applied
 * as if they were lines of the file (the same parser and checks): each
 * replaces the file's key or adds it. The scene's text is the text run. A
 * message about a setting names it ("--set material.mu: ...") instead of a
 * line; gr_scene_name_sets does that to a later message about the scene. */
gr_scene *gr_scene_load_set(const char *path, const char *const *extra_sections,
                            const char *const *sets, size_t n, gr_err *err);
void gr_scene_name_sets(const gr_scene *sc, const char *const *sets, size_t n, gr_err *err);
/* Same, from text in memory; path is used in messages. */
gr_scene *gr_scene_parse(const char *text, const char *path,
                         const char *const *extra_sections, gr_err *err);
void gr_scene_free(gr_scene *sc);
/* A copy of scene text (malloc'd) with key of section set to value, as
 * --set does it (scene_set.c): the key's line commented out and
 * "[section]\nkey = value" appended, so every other line keeps its number.
 * For sweeps over a scene's parameters. */
char *gr_scene_text_set(const char *text, const char *section, const char *key, const char *value,
                        gr_err *err);

unsigned gr_scene_features(const gr_scene *sc);
const char *gr_feature_name(unsigned feature_bit);
/* Whether the table has a row for the bit (bits below GR_FEAT_COUNT may be
 * reserved). */
int gr_feature_known(unsigned feature_bit);
/* The file line and key that brought in a feature, for messages:
 * writes "file:line: key 'k'" (or the file alone) into buf. */
void gr_scene_feature_where(const gr_scene *sc, unsigned feature_bit, char *buf, size_t n);
/* GR_EINPUT naming every feature of missing (the scene's features that
 * `who` lacks), each with its file, line and key, in one message. */
int gr_scene_refuse_features(const gr_scene *sc, unsigned missing, const char *who, gr_err *err);

/* Entry of the file, or NULL. */
const gr_scene_entry *gr_scene_find(const gr_scene *sc, const char *section, const char *key);
/* "file:line" of an entry, or "file" when absent. */
void gr_scene_where(const gr_scene *sc, const char *section, const char *key, char *buf, size_t n);
/* The same for a key written "section.key" (a validity limit's key). */
void gr_scene_where_key(const gr_scene *sc, const char *dotted, char *buf, size_t n);
/* GR_EINPUT for a particle method given no grains, naming where they would
 * come from: [init] kind when the file sets it, else [species] count. */
int gr_scene_no_grains(const gr_scene *sc, gr_err *err);

/* Backend sections: typed getters that default when the key is absent and
 * fail with file, line and key on a bad value. */
int gr_scene_get_double(const gr_scene *sc, const char *section, const char *key,
                        double def, double *out, gr_err *err);
int gr_scene_get_long(const gr_scene *sc, const char *section, const char *key,
                      long def, long *out, gr_err *err);
/* choices is NULL ended; *out is the index of the match. */
int gr_scene_get_choice(const gr_scene *sc, const char *section, const char *key,
                        const char *const *choices, int def, int *out, gr_err *err);
/* Fail on a key of section that is not in valid (NULL ended), suggesting the nearest. */
int gr_scene_check_keys(const gr_scene *sc, const char *section,
                        const char *const *valid, gr_err *err);

/* Total mobile grains. */
long gr_scene_count(const gr_scene *sc);
double gr_scene_max_diameter(const gr_scene *sc);

/* The nearest of candidates to word by edit distance (NULL ended list). */
const char *gr_nearest(const char *word, const char *const *candidates);

#endif
