/* The battery's helpers: scenes parsed with the sections of the backends
 * under test, instances made from them. */
#include "test.h"

#include <string.h>

#include "conformance.h"
#include "init.h"

gr_scene *conf_parse(const conf_case *c, const char *text)
{
    gr_err e = {0};
    gr_scene *sc = gr_scene_parse(text, "conformance.ini", c->sections, &e);
    if (!sc)
        print_error("%s\n", e.msg);
    assert_non_null(sc);
    return sc;
}

gr_sim *conf_create(const gr_method_type *m, const gr_scene *sc)
{
    gr_err e = {0};
    gr_particles *p = gr_particles_create(0, &e);
    assert_int_equal(gr_init_particles(sc, p, &e), GR_OK);
    gr_sim *s = NULL;
    if (gr_sim_create(m, sc, p, &s, &e))
        print_error("%s on %s: %s\n", m->name, sc->name, e.msg);
    assert_non_null(s);
    gr_particles_free(p);
    return s;
}

/* A scene of declared features may still ask for a model the backend has
 * not (edmd takes rough collisions, not a soft tangential law); it must say
 * so, as an input error. */
/* msg as the rest of a TAP comment: a refusal of several features spans
 * lines, each then a comment of its own. */
void conf_print_comment(const char *msg)
{
    for (const char *c = msg; *c; c++)
        if (*c == '\n')
            fputs("\n#   ", stdout);
        else
            putchar(*c);
    putchar('\n');
}

int conf_accepts(const gr_method_type *m, const gr_scene *sc, const char *name)
{
    gr_err e = {0};
    gr_particles *p = gr_particles_create(0, &e);
    assert_int_equal(gr_init_particles(sc, p, &e), GR_OK);
    gr_sim *s = NULL;
    int rc = gr_sim_create(m, sc, p, &s, &e);
    gr_particles_free(p);
    gr_sim_free(s);
    if (rc) {
        printf("# %s refuses %s: ", m->name, name);
        conf_print_comment(e.msg);
        assert_int_equal(rc, GR_EINPUT);
        assert_null(s);
        assert_non_null(strstr(e.msg, "conformance.ini:"));
    }
    return rc == GR_OK;
}
