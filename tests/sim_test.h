/* Helpers shared by the method tests that go through the interface: a
 * scene from INI text and an instance of a backend on it, each aborting the
 * test with the message on failure. Only tests linked with the methods
 * include it. */
#ifndef GR_SIM_TEST_H
#define GR_SIM_TEST_H

#include "test.h"

#include "init.h"
#include "method.h"

/* ext: the backend sections the text may hold (NULL ended); path names the
 * text in messages. */
static inline gr_scene *st_scene(const char *text, const char *path, const char *const *ext)
{
    gr_err e = {0};
    gr_scene *sc = gr_scene_parse(text, path, ext, &e);
    if (!sc)
        print_error("scene: %s\n", e.msg);
    assert_non_null(sc);
    return sc;
}

/* An instance of m from the grains p (NULL: the scene's own). */
static inline gr_sim *st_sim(const gr_method_type *m, const gr_scene *sc, const gr_particles *p)
{
    gr_err e = {0};
    gr_particles *q = (gr_particles *)p;
    if (!q) {
        q = gr_particles_create(0, &e);
        assert_int_equal(gr_init_particles(sc, q, &e), GR_OK);
    }
    gr_sim *s = NULL;
    if (gr_sim_create(m, sc, q, &s, &e))
        print_error("create: %s\n", e.msg);
    assert_non_null(s);
    if (!p)
        gr_particles_free(q);
    return s;
}

#endif
