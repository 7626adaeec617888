/* Internal to the scene reader: the range-checked getters and errors of
 * scene_get.c, used by scene_geom.c (floor, walls, silo) and scene.c (the
 * rest and the whole). */
#ifndef GR_SCENE_GET_H
#define GR_SCENE_GET_H

#include "scene.h"

/* A number of [s] k (def when absent) within lo (open or closed) and hi,
 * else an error naming file, line and key. */
int gr_scene_get_num(const gr_scene *sc, const char *s, const char *k, double def, double lo, int lo_open, double hi,
                     double *out, gr_err *err);
#define POSITIVE(s, k, def, out) gr_scene_get_num(sc, s, k, def, 0.0, 1, INFINITY, out, err)
#define NONNEG(s, k, def, out) gr_scene_get_num(sc, s, k, def, 0.0, 0, INFINITY, out, err)
#define ANYNUM(s, k, def, out) gr_scene_get_num(sc, s, k, def, -INFINITY, 0, INFINITY, out, err)
int gr_scene_get_yesno(const gr_scene *sc, const char *s, const char *k, int def, int *out, gr_err *err);
/* GR_EINPUT "<file>:<line>: [s] key 'k': what" (the section's line when k is absent). */
int gr_scene_entry_fail(const gr_scene *sc, const char *s, const char *k, gr_err *err, const char *what);
/* The kind of a section name: "species.big" -> "species", "wall.a" -> "wall". */
const char *gr_scene_section_kind(const char *name);
/* [floor], [wall.*] and [silo] into sc (silo segments added to the walls). */
int gr_scene_read_geometry(gr_scene *sc, gr_err *err);

#endif
