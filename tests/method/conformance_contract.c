/* The contract on one scene, for one backend: determinism, bit-exact
 * restart from a checkpoint taken after an arbitrary number of steps, pure
 * observation (observing twice gives the same numbers and does not change
 * the run), snapshots in id order, monotone time, finite observables and
 * fields (the packing field holds every grain's area); a window-averaged
 * stress that restarts bit for bit, averages its cells and changes nothing;
 * the same bits when a caller's OpenMP team runs two instances at once;
 * on a scene it does not declare: refusal naming the feature and file. */
#include "test.h"

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "conformance.h"
#include "init.h"

/* Advance in chunks, time never going back, to t_end exactly reached. */
static void advance(gr_sim *s, double t_end)
{
    gr_err e = {0};
    double t = gr_sim_time(s);
    for (int k = 1; k <= 4; k++) {
        double target = t + (t_end - t) * k / 4.0;
        if (gr_sim_advance(s, target, 0, &e))
            print_error("%s: %s\n", gr_sim_type(s)->name, e.msg);
        assert_int_equal(e.code, GR_OK);
        double now = gr_sim_time(s);
        assert_true(now >= t);
        assert_true(now >= target - 1e-9 * (1 + fabs(target)));
        t = now;
    }
}


/* A run with observations on the way and one without end the same. */
static conf_outcome run_plain(const gr_method_type *m, const gr_scene *sc, double t_end, int observe)
{
    gr_sim *s = conf_create(m, sc);
    if (observe) {
        advance(s, 0.3 * t_end);
        conf_outcome a = conf_look(s), b = conf_look(s);
        conf_same(&a, &b); /* pure */
        conf_outcome_free(&a), conf_outcome_free(&b);
    }
    advance(s, t_end);
    conf_outcome r = conf_look(s);
    gr_sim_free(s);
    return r;
}

/* Save `steps` steps past 0.6 t_end (an arbitrary point, not a time boundary), run
 * on to t_end; a fresh instance loads the checkpoint and runs to t_end. */
static conf_outcome run_restarted(const gr_method_type *m, const gr_scene *sc, double t_end,
                             uint64_t steps, const char *path, conf_outcome *uninterrupted)
{
    gr_err e = {0};
    gr_sim *a = conf_create(m, sc);
    advance(a, 0.6 * t_end);
    assert_int_equal(gr_sim_advance(a, t_end, steps, &e), GR_OK);
    double t_save = gr_sim_time(a);
    assert_true(t_save < t_end); /* the checkpoint is taken mid-run */
    unlink(path);
    gr_ckpt *ck = gr_ckpt_create(path, &e);
    assert_non_null(ck);
    if (gr_sim_save(a, ck, &e))
        print_error("%s save: %s\n", m->name, e.msg);
    assert_int_equal(gr_ckpt_close(ck, &e), GR_OK);
    advance(a, t_end);
    *uninterrupted = conf_look(a);
    gr_sim_free(a);

    gr_sim *b = conf_create(m, sc);
    ck = gr_ckpt_open(path, &e);
    assert_non_null(ck);
    if (gr_sim_load(b, ck, &e))
        print_error("%s load: %s\n", m->name, e.msg);
    assert_int_equal(e.code, GR_OK);
    gr_ckpt_close(ck, &e);
    assert_true(gr_sim_time(b) == t_save);
    advance(b, t_end);
    conf_outcome r = conf_look(b);
    gr_sim_free(b);
    return r;
}


/* A backend with a thread count gives the same bits on two threads. */
static void threads_change_nothing(const conf_case *c, const conf_outcome *one)
{
    const gr_method_type *m = c->m;
    const conf_scene *cs = c->cs;
    if (gr_param_index(m->params, "threads") < 0)
        return;
    char text[4096];
    snprintf(text, sizeof text, "%s\n[%s]\nthreads = 2\n", cs->text, m->name);
    gr_scene *sc = conf_parse(c, text);
    conf_outcome two = run_plain(m, sc, cs->t_end, 0);
    conf_same(one, &two);
    conf_outcome_free(&two);
    gr_scene_free(sc);
}

/* Two instances advanced at once by the threads of a caller's OpenMP team
 * (a program running several scenes in parallel) end as one alone: a
 * backend's barrier or single construct must not bind to the caller's
 * team. */
static void inside_a_team(const gr_method_type *m, const gr_scene *sc, double t_end, const conf_outcome *alone)
{
    conf_outcome o[2];
#pragma omp parallel for num_threads(2) schedule(static, 1)
    for (int k = 0; k < 2; k++) {
        gr_sim *s = conf_create(m, sc);
        advance(s, t_end);
        o[k] = conf_look(s);
        gr_sim_free(s);
    }
    for (int k = 0; k < 2; k++)
        conf_same(&o[k], alone), conf_outcome_free(&o[k]);
}

/* The window-averaged stress (a backend that gives one): opened at the
 * start, read at t_end: finite, its global value the mean of its cells,
 * the same bits after a restart from a checkpoint taken inside the window,
 * and the run itself the same as one that measured nothing (plain). */
static void stress_window(const gr_method_type *m, const conf_scene *cs, const gr_scene *sc, const char *path,
                          const conf_outcome *plain)
{
    enum { NX = 7, NY = 5 };
    gr_err e = {0};
    double g[2][4], c[2][NX * NY * 4];
    gr_sim *a = conf_create(m, sc);
    assert_int_equal(gr_sim_stress(a, NX, NY, g[0], c[0], &e), GR_OK);
    assert_true(isnan(g[0][0]) && isnan(c[0][0])); /* an empty window */
    advance(a, 0.6 * cs->t_end);
    assert_int_equal(gr_sim_advance(a, cs->t_end, cs->save_after, &e), GR_OK);
    unlink(path);
    gr_ckpt *ck = gr_ckpt_create(path, &e);
    assert_int_equal(gr_sim_save(a, ck, &e), GR_OK);
    assert_int_equal(gr_ckpt_close(ck, &e), GR_OK);
    advance(a, cs->t_end);
    assert_int_equal(gr_sim_stress(a, NX, NY, g[0], c[0], &e), GR_OK);
    conf_outcome o = conf_look(a);
    conf_same(&o, plain);
    conf_outcome_free(&o);
    gr_sim_free(a);
    gr_sim *b = conf_create(m, sc);
    ck = gr_ckpt_open(path, &e);
    assert_int_equal(gr_sim_load(b, ck, &e), GR_OK);
    gr_ckpt_close(ck, &e);
    advance(b, cs->t_end);
    assert_int_equal(gr_sim_stress(b, NX, NY, g[1], c[1], &e), GR_OK);
    gr_sim_free(b);
    assert_memory_equal(g[0], g[1], sizeof g[0]);
    assert_memory_equal(c[0], c[1], sizeof c[0]);
    for (int q = 0; q < 4; q++) {
        double mean = 0, scale = 0;
        for (int k = 0; k < NX * NY; k++) {
            assert_true(isfinite(c[0][k * 4 + q]));
            mean += c[0][k * 4 + q] / (NX * NY), scale += fabs(c[0][k * 4 + q]) / (NX * NY);
        }
        assert_true(isfinite(g[0][q]) && fabs(mean - g[0][q]) <= 1e-12 * scale);
    }
    printf("# %s on %s: stress over the window %.6g %.6g %.6g %.6g\n", m->name, cs->name, g[0][0], g[0][1],
           g[0][2], g[0][3]);
}


/* A scene whose features the backend lacks is refused by gr_sim_create as
 * an input error naming the feature and the file. */
static void refused_by_features(const gr_method_type *m, const gr_scene *sc)
{
    gr_err e = {0};
    gr_particles *p = gr_particles_create(0, &e);
    assert_int_equal(gr_init_particles(sc, p, &e), GR_OK);
    gr_sim *s = (gr_sim *)p; /* must come back NULL */
    assert_int_equal(gr_sim_create(m, sc, p, &s, &e), GR_EINPUT);
    assert_null(s);
    printf("# %s refuses %s by its features: ", m->name, sc->name);
    conf_print_comment(e.msg);
    assert_non_null(strstr(e.msg, "does not support"));
    assert_non_null(strstr(e.msg, "conformance.ini:"));
    gr_particles_free(p);
}

/* The whole contract on a scene the backend takes. */
static void contract(const conf_case *c, const gr_scene *sc)
{
    const gr_method_type *m = c->m;
    const conf_scene *cs = c->cs;
    char path[] = "/tmp/grano-conformance-XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    conf_outcome a = run_plain(m, sc, cs->t_end, 1), b = run_plain(m, sc, cs->t_end, 0), u;
    conf_same(&a, &b); /* deterministic, and observing changed nothing */
    conf_check_outcome(m, cs, &a);
    conf_outcome r = run_restarted(m, sc, cs->t_end, cs->save_after, path, &u);
    conf_same(&u, &a);
    conf_same(&r, &a);
    threads_change_nothing(c, &a);
    inside_a_team(m, sc, cs->t_end, &a);
    if (m->stress)
        stress_window(m, cs, sc, path, &a);
    if (m->snapshot || m->fields) {
        gr_sim *s = conf_create(m, sc);
        advance(s, 0.5 * cs->t_end);
        conf_check_fields(s, sc);
        gr_sim_free(s);
    }
    conf_outcome_free(&a), conf_outcome_free(&b), conf_outcome_free(&r), conf_outcome_free(&u);
    unlink(path);
}

void conf_scene_case(void **state)
{
    const conf_case *c = *state;
    gr_scene *sc = conf_parse(c, c->cs->text);
    unsigned used = gr_scene_features(sc);
    assert_true(used & c->cs->feature || !c->cs->feature);
    if (used & ~c->m->features)
        refused_by_features(c->m, sc);
    else if (conf_accepts(c->m, sc, c->cs->name))
        contract(c, sc);
    gr_scene_free(sc);
}

/* Every feature the backend declares is run by a scene it takes, and it
 * takes several. */
void conf_features_run(void **state)
{
    const conf_case *c = *state;
    const gr_method_type *m = c->m;
    unsigned exercised = 0;
    int ran = 0;
    for (size_t j = 0; j < c->b->nscenes; j++) {
        const conf_scene *cs = &c->b->scenes[j];
        gr_scene *sc = conf_parse(c, cs->text);
        if (!(gr_scene_features(sc) & ~m->features) && conf_accepts(m, sc, cs->name))
            exercised |= cs->feature, ran++;
        gr_scene_free(sc);
    }
    if (ran < 3)
        print_error("%s takes %d scenes of the battery\n", m->name, ran);
    assert_true(ran >= 3);
    for (unsigned b = 0; b < GR_FEAT_COUNT; b++) {
        if (((m->features & ~exercised) & (1u << b)) && gr_feature_known(1u << b))
            print_error("%s declares %s but runs no scene of it\n", m->name, gr_feature_name(1u << b));
    }
    assert_int_equal(m->features & ~exercised, 0);
}

/* Every scene feature of the table has a scene that uses it. */
void conf_features_covered(void **state)
{
    const conf_case *c = *state;
    for (unsigned b = 0; b < GR_FEAT_COUNT; b++) {
        if (!gr_feature_known(1u << b))
            continue; /* a reserved bit */
        int covered = 0;
        for (size_t j = 0; j < c->b->nscenes; j++)
            covered |= c->b->scenes[j].feature == 1u << b;
        if (!covered)
            print_error("no conformance scene uses %s\n", gr_feature_name(1u << b));
        assert_true(covered);
    }
}
