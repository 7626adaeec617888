/* Conformance of every registered backend to methods/method.h, over a set
 * of scenes each exercising one scene feature (GSL's battery over every
 * step type is the model): a backend is held to the contract the moment it
 * is registered. On each scene the backend declares:
 *   determinism (two runs give the same bits), bit-exact restart from a
 *   checkpoint taken after an arbitrary number of steps, pure observation
 *   (observing twice gives the same numbers and does not change the run),
 *   snapshots in id order, monotone time, finite observables and fields
 *   (the packing field holds every grain's area); a window-averaged stress
 *   that restarts bit for bit, averages its cells and changes nothing;
 * on the scenes it does not declare: refusal naming the feature and file;
 * and its parameter table: consistent, enforced on scene files (range,
 * unknown key with a suggestion), compared by checkpoints, and documented
 * in docs/methods/<name>.md. */
#include "test.h"

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "conformance_scenes.h"
#include "init.h"
#include "method.h"

static const char *const sections[] = {"dem", "edmd", "cd", "dsmc", "lgca", NULL};

static gr_scene *parse(const char *text)
{
    gr_err e = {0};
    gr_scene *sc = gr_scene_parse(text, "conformance.ini", sections, &e);
    if (!sc)
        print_error("%s\n", e.msg);
    assert_non_null(sc);
    return sc;
}

static gr_sim *create(const gr_method_type *m, const gr_scene *sc)
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

/* Whether the backend takes the scene: a scene of declared features may
 * still ask for a model the backend has not (edmd takes rough collisions,
 * not a soft tangential law); it must say so, as an input error. */
static int accepts(const gr_method_type *m, const gr_scene *sc, const char *name)
{
    gr_err e = {0};
    gr_particles *p = gr_particles_create(0, &e);
    assert_int_equal(gr_init_particles(sc, p, &e), GR_OK);
    gr_sim *s = NULL;
    int rc = gr_sim_create(m, sc, p, &s, &e);
    gr_particles_free(p);
    gr_sim_free(s);
    if (rc) {
        printf("# %s refuses %s: %s\n", m->name, name, e.msg);
        assert_int_equal(rc, GR_EINPUT);
        assert_null(s);
        assert_non_null(strstr(e.msg, "conformance.ini:"));
    }
    return rc == GR_OK;
}

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

/* Everything a run shows: the snapshot (a lattice: its fields on a fine
 * grid), the observables, the counters. */
typedef struct {
    gr_particles *p;
    gr_field *f;      /* lattice backends */
    gr_contacts *net; /* methods that give contact networks */
    gr_obs o;
    size_t nc;
    gr_counter c[GR_MAX_COUNTERS];
} outcome;

static outcome look(gr_sim *s)
{
    gr_err e = {0};
    outcome r;
    memset(&r, 0, sizeof r);
    gr_obs_clear(&r.o);
    assert_int_equal(gr_sim_observe(s, &r.o, &e), GR_OK);
    r.nc = gr_sim_counters(s, r.c, GR_MAX_COUNTERS);
    if (gr_sim_type(s)->snapshot) {
        r.p = gr_particles_create(0, &e);
        assert_int_equal(gr_sim_snapshot(s, r.p, &e), GR_OK);
    }
    if (gr_sim_type(s)->repr == GR_REPR_LATTICE) {
        const gr_scene *sc = gr_sim_scene(s);
        r.f = gr_field_create(40, 40, 0, 0, sc->width / 40, sc->height / 40, &e);
        assert_non_null(r.f);
        assert_int_equal(gr_sim_fields(s, r.f, 1.0, &e), GR_OK);
    }
    if (gr_sim_type(s)->contacts) {
        r.net = gr_contacts_create(0, &e);
        assert_int_equal(gr_sim_contacts(s, r.net, &e), GR_OK);
    }
    return r;
}

static void same_outcome(const outcome *a, const outcome *b)
{
    assert_memory_equal(&a->o, &b->o, sizeof a->o);
    assert_int_equal(a->nc, b->nc);
    for (size_t k = 0; k < a->nc; k++)
        assert_true(a->c[k].value == b->c[k].value);
    if (a->net) {
        size_t m = a->net->n;
        assert_int_equal(m, b->net->n);
        assert_memory_equal(a->net->i, b->net->i, m * sizeof(int64_t));
        assert_memory_equal(a->net->j, b->net->j, m * sizeof(int64_t));
        assert_memory_equal(a->net->fn, b->net->fn, m * sizeof(double));
        assert_memory_equal(a->net->ft, b->net->ft, m * sizeof(double));
    }
    if (a->f) {
        size_t nc = gr_field_ncells(a->f);
        assert_memory_equal(a->f->num, b->f->num, nc * sizeof(double));
        assert_memory_equal(a->f->px, b->f->px, nc * sizeof(double));
        assert_memory_equal(a->f->py, b->f->py, nc * sizeof(double));
        assert_memory_equal(a->f->mv2, b->f->mv2, nc * sizeof(double));
    }
    if (!a->p)
        return;
    size_t n = a->p->n;
    assert_int_equal(n, b->p->n);
    assert_memory_equal(a->p->x, b->p->x, n * sizeof(double));
    assert_memory_equal(a->p->y, b->p->y, n * sizeof(double));
    assert_memory_equal(a->p->vx, b->p->vx, n * sizeof(double));
    assert_memory_equal(a->p->vy, b->p->vy, n * sizeof(double));
    assert_memory_equal(a->p->omega, b->p->omega, n * sizeof(double));
    assert_memory_equal(a->p->flags, b->p->flags, n * sizeof(uint32_t));
    assert_memory_equal(a->p->id, b->p->id, n * sizeof(int64_t));
}

static void outcome_free(outcome *r)
{
    gr_particles_free(r->p);
    gr_field_free(r->f);
    gr_contacts_free(r->net);
}

/* A run with observations on the way and one without end the same. */
static outcome run_plain(const gr_method_type *m, const gr_scene *sc, double t_end, int observe)
{
    gr_sim *s = create(m, sc);
    if (observe) {
        advance(s, 0.3 * t_end);
        outcome a = look(s), b = look(s);
        same_outcome(&a, &b); /* pure */
        outcome_free(&a), outcome_free(&b);
    }
    advance(s, t_end);
    outcome r = look(s);
    gr_sim_free(s);
    return r;
}

/* Save `steps` steps past 0.6 t_end (an arbitrary point, not a time boundary), run
 * on to t_end; a fresh instance loads the checkpoint and runs to t_end. */
static outcome run_restarted(const gr_method_type *m, const gr_scene *sc, double t_end,
                             uint64_t steps, const char *path, outcome *uninterrupted)
{
    gr_err e = {0};
    gr_sim *a = create(m, sc);
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
    *uninterrupted = look(a);
    gr_sim_free(a);

    gr_sim *b = create(m, sc);
    ck = gr_ckpt_open(path, &e);
    assert_non_null(ck);
    if (gr_sim_load(b, ck, &e))
        print_error("%s load: %s\n", m->name, e.msg);
    assert_int_equal(e.code, GR_OK);
    gr_ckpt_close(ck, &e);
    assert_true(gr_sim_time(b) == t_save);
    advance(b, t_end);
    outcome r = look(b);
    gr_sim_free(b);
    return r;
}

static void check_outcome(const gr_method_type *m, const conf_scene *cs, const outcome *r)
{
    assert_true(isfinite(r->o.ekin_trans) && isfinite(r->o.ekin_rot) && isfinite(r->o.temperature));
    assert_true(isfinite(r->o.px) && isfinite(r->o.py) && isfinite(r->o.epot_grav));
    assert_true(r->o.n_mobile <= (uint64_t)cs->grains);
    for (size_t k = 0; k < r->nc; k++) {
        assert_non_null(r->c[k].name);
        for (size_t j = 0; j < k; j++)
            assert_string_not_equal(r->c[k].name, r->c[j].name);
    }
    if (!r->p)
        return;
    /* a network names grains of the snapshot (or walls, j < 0), finite forces */
    for (size_t k = 0; r->net && k < r->net->n; k++) {
        int found_i = 0, found_j = r->net->j[k] < 0;
        for (size_t q = 0; q < r->p->n; q++) {
            found_i |= r->p->id[q] == r->net->i[k];
            found_j |= r->p->id[q] == r->net->j[k];
        }
        assert_true(found_i && found_j && r->net->i[k] != r->net->j[k]);
        assert_true(isfinite(r->net->fn[k]) && isfinite(r->net->ft[k]));
    }
    for (size_t i = 1; i < r->p->n; i++)
        assert_true(r->p->id[i] > r->p->id[i - 1]);
    for (size_t i = 0; i < r->p->n; i++)
        assert_true(isfinite(r->p->x[i]) && isfinite(r->p->y[i]) && isfinite(r->p->vx[i]) &&
                    isfinite(r->p->vy[i]) && isfinite(r->p->omega[i]));
    (void)m;
}

/* The packing field over the whole domain holds the area of every mobile
 * grain inside it, and every field value is finite where defined. */
static void check_fields(gr_sim *s, const gr_scene *sc)
{
    gr_err e = {0};
    gr_field *f = gr_field_create(7, 5, 0, 0, sc->width / 7, sc->height / 5, &e);
    assert_non_null(f);
    assert_int_equal(gr_sim_fields(s, f, 1.0, &e), GR_OK);
    size_t nc = gr_field_ncells(f);
    double *phi = malloc(nc * sizeof *phi), *T = malloc(nc * sizeof *T), area = 0;
    gr_field_packing(f, phi);
    gr_field_temperature(f, T);
    for (size_t c = 0; c < nc; c++) {
        assert_true(isfinite(phi[c]) && phi[c] >= 0 && phi[c] <= 1);
        assert_true(isnan(T[c]) || (isfinite(T[c]) && T[c] >= 0));
        area += phi[c] * f->cx * f->cy;
    }
    if (gr_sim_type(s)->repr == GR_REPR_LATTICE) {
        /* every particle counts once, in the cell of its node */
        double *num = malloc(nc * sizeof *num), total = 0;
        gr_field_number(f, num, NULL);
        for (size_t c = 0; c < nc; c++)
            total += num[c];
        gr_obs o;
        assert_int_equal(gr_sim_observe(s, &o, &e), GR_OK);
        assert_rel(total, (double)o.n_mobile, 1e-12);
        free(num), free(phi), free(T);
        gr_field_free(f);
        return;
    }
    gr_particles *p = gr_particles_create(0, &e);
    assert_int_equal(gr_sim_snapshot(s, p, &e), GR_OK);
    double want = 0;
    for (size_t i = 0; i < p->n; i++)
        if (!(p->flags[i] & (GR_PF_FIXED | GR_PF_GONE)))
            want += gr_disk_rect_area(p->x[i], p->y[i], p->radius[i], 0, sc->width, 0, sc->height);
    assert_rel(area, want, 1e-9);
    gr_particles_free(p);
    free(phi), free(T);
    gr_field_free(f);
}

/* A backend with a thread count gives the same bits on two threads. */
static void threads_change_nothing(const gr_method_type *m, const conf_scene *cs, const outcome *one)
{
    if (gr_param_index(m->params, "threads") < 0)
        return;
    char text[4096];
    snprintf(text, sizeof text, "%s\n[%s]\nthreads = 2\n", cs->text, m->name);
    gr_scene *sc = parse(text);
    outcome two = run_plain(m, sc, cs->t_end, 0);
    same_outcome(one, &two);
    outcome_free(&two);
    gr_scene_free(sc);
}

/* The window-averaged stress (a backend that gives one): opened at the
 * start, read at t_end: finite, its global value the mean of its cells,
 * the same bits after a restart from a checkpoint taken inside the window,
 * and the run itself the same as one that measured nothing (plain). */
static void stress_window(const gr_method_type *m, const conf_scene *cs, const gr_scene *sc, const char *path,
                          const outcome *plain)
{
    enum { NX = 7, NY = 5 };
    gr_err e = {0};
    double g[2][4], c[2][NX * NY * 4];
    gr_sim *a = create(m, sc);
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
    outcome o = look(a);
    same_outcome(&o, plain);
    outcome_free(&o);
    gr_sim_free(a);
    gr_sim *b = create(m, sc);
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

static void contract_on_scenes(void **unused)
{
    (void)unused;
    char path[] = "/tmp/grano-conformance-XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    const gr_method_type *const *all = gr_method_all();
    assert_non_null(all[0]);
    for (size_t k = 0; all[k]; k++) {
        const gr_method_type *m = all[k];
        int ran = 0;
        unsigned exercised = 0;
        for (size_t j = 0; j < conf_nscenes; j++) {
            const conf_scene *cs = &conf_scenes[j];
            gr_scene *sc = parse(cs->text);
            if ((gr_scene_features(sc) & ~m->features) || !accepts(m, sc, cs->name)) {
                gr_scene_free(sc);
                continue;
            }
            exercised |= cs->feature;
            printf("# %s on %s\n", m->name, cs->name);
            outcome a = run_plain(m, sc, cs->t_end, 1), b = run_plain(m, sc, cs->t_end, 0), u;
            same_outcome(&a, &b); /* deterministic, and observing changed nothing */
            check_outcome(m, cs, &a);
            outcome r = run_restarted(m, sc, cs->t_end, cs->save_after, path, &u);
            same_outcome(&u, &a);
            same_outcome(&r, &a);
            threads_change_nothing(m, cs, &a);
            if (m->stress)
                stress_window(m, cs, sc, path, &a);
            if (m->snapshot || m->fields) {
                gr_sim *s = create(m, sc);
                advance(s, 0.5 * cs->t_end);
                check_fields(s, sc);
                gr_sim_free(s);
            }
            outcome_free(&a), outcome_free(&b), outcome_free(&r), outcome_free(&u);
            gr_scene_free(sc);
            ran++;
        }
        assert_true(ran >= 3); /* every backend is held to several scenes */
        for (unsigned b = 0; b < GR_FEAT_COUNT; b++) {
            if (((m->features & ~exercised) & (1u << b)) && gr_feature_known(1u << b))
                print_error("%s declares %s but runs no scene of it\n", m->name, gr_feature_name(1u << b));
        }
        assert_int_equal(m->features & ~exercised, 0);
    }
    unlink(path);
}

static void unsupported_features_refused(void **unused)
{
    (void)unused;
    const gr_method_type *const *all = gr_method_all();
    for (unsigned b = 0; b < GR_FEAT_COUNT; b++) {
        if (!gr_feature_known(1u << b))
            continue; /* a reserved bit */
        int covered = 0;
        for (size_t j = 0; j < conf_nscenes; j++)
            covered |= conf_scenes[j].feature == 1u << b;
        if (!covered)
            print_error("no conformance scene uses %s\n", gr_feature_name(1u << b));
        assert_true(covered);
    }
    for (size_t k = 0; all[k]; k++) {
        const gr_method_type *m = all[k];
        for (size_t j = 0; j < conf_nscenes; j++) {
            gr_scene *sc = parse(conf_scenes[j].text);
            unsigned used = gr_scene_features(sc);
            assert_true(used & conf_scenes[j].feature || !conf_scenes[j].feature);
            if (used & ~m->features) {
                gr_err e = {0};
                gr_particles *p = gr_particles_create(0, &e);
                assert_int_equal(gr_init_particles(sc, p, &e), GR_OK);
                gr_sim *s = (gr_sim *)p; /* must come back NULL */
                assert_int_equal(gr_sim_create(m, sc, p, &s, &e), GR_EINPUT);
                assert_null(s);
                assert_non_null(strstr(e.msg, "does not support"));
                assert_non_null(strstr(e.msg, "conformance.ini:"));
                gr_particles_free(p);
            }
            gr_scene_free(sc);
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(contract_on_scenes),
        cmocka_unit_test(unsupported_features_refused),
        cmocka_unit_test(conf_param_tables),
        cmocka_unit_test(conf_param_checks_in_scenes),
        cmocka_unit_test(conf_param_checkpoint),
        cmocka_unit_test(conf_param_docs),
        cmocka_unit_test(conf_optional_ops),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
