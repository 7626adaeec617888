/* Internal to the scene reader: scene_parse.c's entries and typed lookups,
 * for scene_get.c, scene_geom.c and scene.c (scene_get.h). */
#ifndef GR_SCENE_IMPL_H
#define GR_SCENE_IMPL_H

#include "scene.h"

int gr_scene_read_entries(gr_scene *sc, const char *text, gr_err *err);
int gr_scene_parse_double(const gr_scene *sc, const gr_scene_entry *e, double *out, gr_err *err);
int gr_scene_get_vec(const gr_scene *sc, const char *section, const char *key,
                     int n, double *out, int *found, gr_err *err);

#endif
