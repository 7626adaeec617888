/* Conformance of every registered backend to methods/method.h: a run saved
 * and restarted continues bit for bit; runs are deterministic; snapshots
 * come in id order; observables are finite; every scene feature outside the
 * backend's declared set is refused by name. */
#include "test.h"

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "init.h"
#include "method.h"

static const char *const names_ext[] = {"dem", "edmd", "cd", "dsmc", "lgca", NULL};

/* A small frictionless gas in a closed box: every backend supports it. */
#define BOX                                                                    \
    "[scene]\nname = conformance\nseed = 11\n"                                 \
    "[domain]\nwidth = 14\nheight = 14\n"                                      \
    "[material]\nrestitution = 0.9\nkn = 1e4\ngamma_n = 5\n"                   \
    "[species]\ncount = 40\n"                                                  \
    "[init]\nkind = random\nvelocity = gaussian\nv0 = 1\n"

static gr_scene *parse(const char *text)
{
    gr_err e = {0};
    gr_scene *sc = gr_scene_parse(text, "conformance.ini", names_ext, &e);
    if (!sc)
        print_error("%s\n", e.msg);
    assert_non_null(sc);
    return sc;
}

static void *create(const gr_method_type *m, const gr_scene *sc)
{
    gr_err e = {0};
    gr_particles *p = gr_particles_create(0, &e);
    assert_int_equal(gr_init_particles(sc, p, &e), GR_OK);
    void *st = NULL;
    if (gr_method_create(m, sc, p, &st, &e))
        print_error("%s: %s\n", m->name, e.msg);
    assert_non_null(st);
    gr_particles_free(p);
    return st;
}

static void advance(const gr_method_type *m, void *st, double t)
{
    gr_err e = {0};
    if (m->advance(st, t, 0, &e))
        print_error("%s: %s\n", m->name, e.msg);
    assert_int_equal(e.code, GR_OK);
    assert_true(m->time(st) >= t - 1e-9);
}

static gr_particles *snap(const gr_method_type *m, void *st)
{
    gr_err e = {0};
    gr_particles *p = gr_particles_create(0, &e);
    assert_int_equal(m->snapshot(st, p, &e), GR_OK);
    return p;
}

static void assert_same_state(const gr_particles *a, const gr_particles *b)
{
    assert_int_equal(a->n, b->n);
    assert_memory_equal(a->x, b->x, a->n * sizeof(double));
    assert_memory_equal(a->y, b->y, a->n * sizeof(double));
    assert_memory_equal(a->vx, b->vx, a->n * sizeof(double));
    assert_memory_equal(a->vy, b->vy, a->n * sizeof(double));
    assert_memory_equal(a->omega, b->omega, a->n * sizeof(double));
    assert_memory_equal(a->id, b->id, a->n * sizeof(int64_t));
}

static void restart_bit_for_bit(void **s)
{
    (void)s;
    const gr_method_type *const *all = gr_method_all();
    assert_non_null(all[0]); /* at least one backend is registered */
    char path[] = "/tmp/grano-conformance-XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    for (size_t k = 0; all[k]; k++) {
        const gr_method_type *m = all[k];
        gr_scene *sc = parse(BOX);
        gr_err e = {0};
        void *a = create(m, sc);
        advance(m, a, 0.5);
        unlink(path);
        gr_ckpt *ck = gr_ckpt_create(path, &e);
        assert_non_null(ck);
        if (m->save(a, ck, &e))
            print_error("%s save: %s\n", m->name, e.msg);
        assert_int_equal(e.code, GR_OK);
        assert_int_equal(gr_ckpt_close(ck, &e), GR_OK);
        advance(m, a, 1.5);
        gr_particles *pa = snap(m, a);

        void *b = create(m, sc);
        ck = gr_ckpt_open(path, &e);
        assert_non_null(ck);
        if (m->load(b, ck, &e))
            print_error("%s load: %s\n", m->name, e.msg);
        assert_int_equal(e.code, GR_OK);
        gr_ckpt_close(ck, &e);
        assert_close(m->time(b), 0.5, 1e-9);
        advance(m, b, 1.5);
        gr_particles *pb = snap(m, b);
        assert_same_state(pa, pb);

        /* A fresh run without the checkpoint is the same bits too. */
        void *c = create(m, sc);
        advance(m, c, 1.5);
        gr_particles *pc = snap(m, c);
        assert_same_state(pa, pc);

        for (size_t i = 1; i < pa->n; i++)
            assert_true(pa->id[i] > pa->id[i - 1]);
        gr_obs o;
        gr_obs_clear(&o);
        assert_int_equal(m->observe(a, &o, &e), GR_OK);
        assert_true(isfinite(o.ekin_trans) && isfinite(o.ekin_rot) && isfinite(o.temperature));
        assert_true(o.ekin_trans > 0);
        assert_int_equal(o.n_mobile, 40);
        assert_close(o.t, m->time(a), 1e-12);

        gr_particles_free(pa);
        gr_particles_free(pb);
        gr_particles_free(pc);
        m->free(a);
        m->free(b);
        m->free(c);
        m->free(NULL);
        gr_scene_free(sc);
    }
    unlink(path);
}

/* A scene that uses exactly one feature beyond the plain box (plus what
 * that feature needs). */
typedef struct {
    unsigned bit;
    const char *text;
} feature_scene;

#define DOM "[scene]\nseed = 3\n[domain]\nwidth = 20\nheight = 20\n"
#define MAT "[material]\nrestitution = 0.9\n"
#define SP "[species]\ncount = 20\n"
static const feature_scene feature_scenes[] = {
    {GR_FEAT_GRAVITY, DOM "gravity = 1\n" MAT SP},
    {GR_FEAT_FRICTION, DOM "[material]\nrestitution = 0.9\ntangential = regularised\ngamma_t = 10\n" SP},
    {GR_FEAT_CONTACT_HISTORY, DOM "[material]\nrestitution = 0.9\ntangential = spring\n" SP},
    {GR_FEAT_PERIODIC, DOM "left = periodic\nright = periodic\n" MAT SP},
    {GR_FEAT_OPEN_SIDE, DOM "top = open\n" MAT SP},
    {GR_FEAT_SEGMENTS, DOM MAT SP "[wall.a]\nfrom = 1 1\nto = 19 1\n"},
    {GR_FEAT_WALL_GRAINS, DOM MAT SP "[silo]\nheight = 15\nbase = 2\norifice = 3\nwalls = grains\n"},
    {GR_FEAT_ORIFICE, DOM MAT SP "[wall.gate]\nfrom = 1 1\nto = 19 1\nopen_time = 2\n"},
    {GR_FEAT_VIBRATING_FLOOR, DOM MAT SP "[floor]\nmotion = sine\namplitude = 0.1\nomega = 10\n"},
    {GR_FEAT_REINSERT, DOM MAT SP "[silo]\nheight = 15\nbase = 3\norifice = 3\nreinsert = yes\n"},
    {GR_FEAT_POLYDISPERSE, DOM MAT "[species]\ncount = 20\npolydispersity = 0.1\n"},
    {GR_FEAT_MIXTURE, DOM MAT "[species.a]\ncount = 10\n[species.b]\ncount = 10\ndiameter = 0.8\n"},
    {GR_FEAT_HERTZ, DOM "[material]\nrestitution = 0.9\nnormal = hertz\n" SP},
    {GR_FEAT_HF_FLOOR, DOM MAT SP "[floor]\nmotion = sine-hf\namplitude = 0.01\nomega = 100\n"},
};

static void unsupported_features_refused(void **s)
{
    (void)s;
    const gr_method_type *const *all = gr_method_all();
    size_t nf = sizeof feature_scenes / sizeof feature_scenes[0];
    assert_int_equal(nf, GR_FEAT_COUNT);
    for (size_t k = 0; all[k]; k++) {
        const gr_method_type *m = all[k];
        for (size_t f = 0; f < nf; f++) {
            gr_scene *sc = parse(feature_scenes[f].text);
            unsigned used = gr_scene_features(sc);
            assert_true(used & feature_scenes[f].bit);
            if (used & ~m->features) {
                gr_err e = {0};
                gr_particles *p = gr_particles_create(0, &e);
                assert_int_equal(gr_init_particles(sc, p, &e), GR_OK);
                void *st = (void *)1;
                assert_int_equal(gr_method_create(m, sc, p, &st, &e), GR_EINPUT);
                assert_null(st);
                assert_non_null(strstr(e.msg, "does not support"));
                assert_non_null(strstr(e.msg, "conformance.ini"));
                gr_particles_free(p);
            }
            gr_scene_free(sc);
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(restart_bit_for_bit),
        cmocka_unit_test(unsupported_features_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
