/* --set settings through gr_scene_load_set: applied as scene lines (a key
 * replaced, a key and a section added, a file without a final newline),
 * the file's line numbers kept, messages naming the flag. */
#include "test.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "scene.h"

static const char *const extra[] = {"dem", NULL};

/* A scene file without its final newline, so the settings must add one. */
static void write_scene(const char *path, int bogus)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs("[domain]\nwidth = 20\nheight = 20\n[material]\nmu = 0.5 ; friction\n"
          "[species]\ncount = 50", f);
    if (bogus)
        fputs("\nbogus_line_later = 1", f);
    fclose(f);
}

static gr_scene *load(const char *path, const char *const *sets, size_t n, gr_err *e)
{
    return gr_scene_load_set(path, extra, sets, n, e);
}

static void applied(void **s)
{
    (void)s;
    const char *path = "scene_set_a.ini";
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs("[domain]\nwidth = 20\nheight = 20\n[material]\nmu = 0.5 ; friction\n[species]\ncount = 50", f);
    fclose(f);
    const char *sets[] = {"material.mu=0.25", "species.count=7", "dem.dt=1e-4", "run.until=3"};
    gr_err e = {0};
    gr_scene *sc = load(path, sets, 4, &e);
    if (!sc)
        print_error("%s\n", e.msg);
    assert_non_null(sc);
    assert_true(sc->mat.mu == 0.25);
    assert_int_equal(gr_scene_count(sc), 7);
    assert_true(sc->run.until == 3);
    const gr_scene_entry *dt = gr_scene_find(sc, "dem", "dt");
    assert_non_null(dt);
    assert_string_equal(dt->value, "1e-4");
    assert_int_equal(sc->set_line0, 8);
    assert_non_null(strstr(sc->text, "\n; mu = 0.5 ; friction\n"));
    /* A later message about a setting's line names the flag. */
    snprintf(e.msg, sizeof e.msg, "%s:%d: [material] key 'mu': too rough", path, sc->set_line0 + 1);
    gr_scene_name_sets(sc, sets, 4, &e);
    assert_string_equal(e.msg, "--set material.mu: too rough");
    snprintf(e.msg, sizeof e.msg, "%s:2: [domain] key 'width': kept", path);
    gr_scene_name_sets(sc, sets, 4, &e);
    assert_string_equal(e.msg, "scene_set_a.ini:2: [domain] key 'width': kept");
    gr_scene_free(sc);
    unlink(path);
}

static void refused(void **s)
{
    (void)s;
    const char *path = "scene_set_b.ini";
    write_scene(path, 0);
    struct {
        const char *set, *want;
    } cases[] = {
        {"material.mu=-1", "--set material.mu: must be >= 0, got -1"},
        {"material.mux=1", "--set material.mux: unknown key 'mux' in [material]; did you mean 'mu'?"},
        {"mu=1", "--set 'mu=1': expected SECTION.KEY=VALUE"},
        {"material.m u=1", "--set 'material.m u=1': ' ' in a section or key name"},
        {"domain.width=abc", "--set domain.width: 'abc' is not a number"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        gr_err e = {0};
        gr_scene *sc = load(path, &cases[i].set, 1, &e);
        assert_null(sc);
        assert_int_equal(e.code, GR_EINPUT);
        if (strncmp(e.msg, cases[i].want, strlen(cases[i].want)))
            print_error("got \"%s\", wanted \"%s...\"\n", e.msg, cases[i].want);
        assert_int_equal(strncmp(e.msg, cases[i].want, strlen(cases[i].want)), 0);
    }
    /* The file's own bad line is still named by its line. */
    write_scene(path, 1);
    gr_err e = {0};
    const char *ok = "material.mu=0.1";
    assert_null(load(path, &ok, 1, &e));
    assert_non_null(strstr(e.msg, "scene_set_b.ini:8:"));
    unlink(path);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(applied), cmocka_unit_test(refused)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
