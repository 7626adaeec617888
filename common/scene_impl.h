/* Internal to the scene reader (scene_parse.c, scene.c). */
#ifndef GR_SCENE_IMPL_H
#define GR_SCENE_IMPL_H

#include "scene.h"

int gr_scene_read_entries(gr_scene *sc, const char *text, gr_err *err);
int gr_scene_parse_double(const gr_scene *sc, const gr_scene_entry *e, double *out, gr_err *err);
int gr_scene_get_vec(const gr_scene *sc, const char *section, const char *key,
                     int n, double *out, int *found, gr_err *err);

#endif
