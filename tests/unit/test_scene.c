/* Scene files: the examples load; every bad input fails with GR_EINPUT and
 * a message naming file, line and key. */
#include "test.h"

#include <stdlib.h>
#include <string.h>

#include "scene.h"

static const char *const extra[] = {"dem", "edmd", NULL};

#define BASE                                                                   \
    "[domain]\nwidth = 20\nheight = 20\ngravity = 1\n"                         \
    "[species]\ndiameter = 1\ncount = 50\n"

/* Parse text that must fail; the message must contain every fragment. */
static void expect_error(const char *text, const char *const *fragments)
{
    gr_err e = {0};
    gr_scene *sc = gr_scene_parse(text, "bad.ini", extra, &e);
    if (sc) {
        gr_scene_free(sc);
        print_error("parsed without error:\n%s\n", text);
        fail();
    }
    assert_int_equal(e.code, GR_EINPUT);
    for (int i = 0; fragments[i]; i++) {
        if (!strstr(e.msg, fragments[i])) {
            print_error("message \"%s\" lacks \"%s\"\n", e.msg, fragments[i]);
            fail();
        }
    }
}
#define EXPECT(text, ...) expect_error(text, (const char *const[]){__VA_ARGS__, NULL})

static void unknown_key_suggests_nearest(void **s)
{
    (void)s;
    EXPECT(BASE "[material]\nkn = 1e5\ngama_n = 10\n", "bad.ini:10:", "gama_n", "did you mean 'gamma_n'");
    EXPECT(BASE "[domian]\nwidth=3\n", "bad.ini:8:", "[domian]", "did you mean [domain]");
    EXPECT("[domain]\nwidht = 20\nheight = 20\n", "bad.ini:2:", "widht", "'width'");
}

static void wrong_types_and_non_finite(void **s)
{
    (void)s;
    EXPECT(BASE "[material]\nkn = stiff\n", "bad.ini:9:", "'kn'", "not a number");
    EXPECT(BASE "[material]\nmu = nan\n", "bad.ini:9:", "'mu'", "finite");
    EXPECT(BASE "[material]\nkn = inf\n", "bad.ini:9:", "'kn'", "finite");
    EXPECT(BASE "[material]\nkn = 1e999\n", "bad.ini:9:", "'kn'", "finite");
    EXPECT(BASE "[material]\nnormal = hertzz\n", "bad.ini:9:", "'normal'", "did you mean 'hertz'");
    EXPECT("[domain]\nwidth = 20\nheight = 20\n[species]\ncount = many\n", "bad.ini:5:", "'count'", "integer");
    EXPECT(BASE "[measure]\nwindow = 1 2 3\n", "bad.ini:9:", "'window'", "4 numbers");
}

static void non_positive_physical_values(void **s)
{
    (void)s;
    EXPECT("[domain]\nwidth = 20\nheight = 20\n[species]\ndiameter = -1\ncount = 5\n",
           "bad.ini:5:", "'diameter'", "> 0");
    EXPECT("[domain]\nwidth = 20\nheight = 20\n[species]\ndiameter = 0\ncount = 5\n",
           "bad.ini:5:", "'diameter'");
    EXPECT("[domain]\nwidth = 20\nheight = 20\n[species]\ndensity = 0\ncount = 5\n",
           "bad.ini:5:", "'density'", "> 0");
    EXPECT(BASE "[material]\nkn = -3\n", "bad.ini:9:", "'kn'", "> 0");
    EXPECT(BASE "[material]\nkn = 0\n", "bad.ini:9:", "'kn'");
    EXPECT(BASE "[material]\nrestitution = 1.5\n", "bad.ini:9:", "'restitution'", "[0, 1]");
    EXPECT("[domain]\nwidth = -20\nheight = 20\n", "bad.ini:2:", "'width'");
}

static void silo_geometry(void **s)
{
    (void)s;
    EXPECT(BASE "[silo]\nwidth = 10\nheight = 10\nbase = 2\norifice = 12\n",
           "bad.ini:12:", "'orifice'", "wider than the silo base");
    EXPECT(BASE "[silo]\nwidth = 30\nheight = 10\nbase = 2\norifice = 3\n",
           "bad.ini:9:", "'width'", "does not fit");
    EXPECT(BASE "[silo]\nwidth = 10\nheight = 10\nbase = 2\norifice = 3\norifice_center = 14.5\n",
           "bad.ini:13:", "'orifice_center'");
}

static void too_many_grains(void **s)
{
    (void)s;
    EXPECT("[domain]\nwidth = 10\nheight = 10\n[species]\ncount = 500\n", "bad.ini:5:", "'count'", "densest packing");
    EXPECT("[domain]\nwidth = 10\nheight = 10\n[species]\ncount = 95\n[init]\nspacing = 1.1\n",
           "bad.ini:5:", "'count'", "lattice sites");
    EXPECT("[domain]\nwidth = 10\nheight = 10\n[species]\ncount = 70\n[init]\nkind = random\n",
           "bad.ini:7:", "'kind'", "random placement");
    EXPECT("[domain]\nwidth = 100\nheight = 100\n[species]\ncount = 100\n[init]\nregion = 0 0 5 5\n",
           "bad.ini:7:", "'region'");
}

static void structure_errors(void **s)
{
    (void)s;
    EXPECT(BASE "[material]\nkn = 1\nkn = 2\n", "bad.ini:10:", "'kn'", "twice", "line 9");
    EXPECT("width = 3\n", "bad.ini:1:", "outside any [section]");
    EXPECT(BASE "[material\nkn = 1\n", "bad.ini:8:", "closing ']'");
    EXPECT("[domain]\nheight = 20\n", "bad.ini", "'width'");
    EXPECT(BASE "[domain.x]\n", "bad.ini");
    EXPECT("[domain]\nwidth = 20\nheight = 20\nleft = periodic\n", "bad.ini", "'right'", "periodic");
    EXPECT(BASE "[wall.a]\nfrom = 0 0\n", "bad.ini", "'to'");
    EXPECT(BASE "[init]\nkind = file\nfile = /nonexistent/grains.txt\n", "bad.ini:10:", "'file'", "cannot read");
    EXPECT(BASE "[floor]\nmotion = sine\n", "bad.ini:9:", "'motion'", "amplitude");
}

static void missing_file(void **s)
{
    (void)s;
    gr_err e = {0};
    assert_null(gr_scene_load("/nonexistent/scene.ini", extra, &e));
    assert_int_equal(e.code, GR_EINPUT);
    assert_non_null(strstr(e.msg, "/nonexistent/scene.ini"));
    assert_non_null(strstr(e.msg, "cannot read"));
}

static gr_scene *load_example(const char *name)
{
    char path[2048];
    const char *root = getenv("GRANO_SOURCE_ROOT");
    snprintf(path, sizeof path, "%s/experiments/scenes/%s", root ? root : "../../..", name);
    gr_err e = {0};
    gr_scene *sc = gr_scene_load(path, extra, &e);
    if (!sc)
        print_error("%s\n", e.msg);
    assert_non_null(sc);
    return sc;
}

static void examples_load(void **s)
{
    (void)s;
    gr_scene *sc = load_example("silo.ini");
    assert_close(sc->silo.width, 50, 0);
    assert_close(sc->silo.height, 100, 0);
    assert_int_equal(sc->silo.walls, GR_WALLS_GRAINS);
    assert_int_equal(gr_scene_count(sc), 5000);
    assert_int_equal(sc->mat.normal, GR_NORMAL_HERTZ);
    assert_int_equal(sc->mat.tangential, GR_TANG_REGULARISED);
    unsigned f = gr_scene_features(sc);
    assert_true(f & GR_FEAT_WALL_GRAINS);
    assert_true(f & GR_FEAT_ORIFICE);
    assert_true(f & GR_FEAT_GRAVITY);
    assert_false(f & GR_FEAT_PERIODIC);
    char where[512];
    gr_scene_feature_where(sc, GR_FEAT_ORIFICE, where, sizeof where);
    assert_non_null(strstr(where, "open_time"));
    assert_non_null(strstr(where, "silo.ini:"));
    gr_scene_free(sc);

    const char *names[] = {"box.ini", "silo-demo.ini", "vibrated.ini"};
    for (int i = 0; i < 3; i++)
        gr_scene_free(load_example(names[i]));
}

static void backend_getters(void **s)
{
    (void)s;
    gr_err e = {0};
    gr_scene *sc = gr_scene_parse(BASE "[dem]\ndt = 1e-4\nintegrator = gear\nsteps = 12\n", "ok.ini", extra, &e);
    assert_non_null(sc);
    double dt;
    long n;
    int k;
    static const char *const integ[] = {"verlet", "gear", "euler", NULL};
    assert_int_equal(gr_scene_get_double(sc, "dem", "dt", 1, &dt, &e), GR_OK);
    assert_close(dt, 1e-4, 0);
    assert_int_equal(gr_scene_get_long(sc, "dem", "steps", 0, &n, &e), GR_OK);
    assert_int_equal(n, 12);
    assert_int_equal(gr_scene_get_choice(sc, "dem", "integrator", integ, 0, &k, &e), GR_OK);
    assert_int_equal(k, 1);
    static const char *const valid[] = {"dt", "integrator", NULL};
    assert_int_equal(gr_scene_check_keys(sc, "dem", valid, &e), GR_EINPUT);
    assert_non_null(strstr(e.msg, "ok.ini:11:"));
    assert_non_null(strstr(e.msg, "'steps'"));
    gr_scene_free(sc);
}

/* A key replaced, added to its section, or added with a new section; the
 * result parses and every line of the text keeps its number. */
static void text_set(void **s)
{
    (void)s;
    gr_err e = {0};
    const char *text = BASE "[dem]\ndt = 1e-4 ; a comment\n[run]\nuntil = 3\n";
    char *a = gr_scene_text_set(text, "dem", "dt", "5e-5", &e);
    char *b = a ? gr_scene_text_set(a, "dem", "integrator", "gear", &e) : NULL;
    char *c = b ? gr_scene_text_set(b, "scene", "seed", "7", &e) : NULL;
    char *d = c ? gr_scene_text_set(c, "species", "count", "9", &e) : NULL;
    assert_non_null(d);
    assert_non_null(strstr(d, "[dem]\ndt = 5e-5\n[dem]\nintegrator = gear\n"));
    assert_non_null(strstr(d, "; dt = 1e-4"));
    assert_non_null(strstr(d, "[scene]\nseed = 7\n"));
    gr_scene *sc = gr_scene_parse(d, "set.ini", extra, &e);
    assert_non_null(sc);
    double dt;
    assert_int_equal(gr_scene_get_double(sc, "dem", "dt", 1, &dt, &e), GR_OK);
    assert_close(dt, 5e-5, 0);
    assert_int_equal(sc->seed, 7);
    assert_int_equal(gr_scene_count(sc), 9);
    assert_int_equal(gr_scene_find(sc, "run", "until")->line, 11);
    gr_scene_free(sc);
    free(a), free(b), free(c), free(d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(unknown_key_suggests_nearest),
        cmocka_unit_test(wrong_types_and_non_finite),
        cmocka_unit_test(non_positive_physical_values),
        cmocka_unit_test(silo_geometry),
        cmocka_unit_test(too_many_grains),
        cmocka_unit_test(structure_errors),
        cmocka_unit_test(missing_file),
        cmocka_unit_test(examples_load),
        cmocka_unit_test(backend_getters),
        cmocka_unit_test(text_set),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
