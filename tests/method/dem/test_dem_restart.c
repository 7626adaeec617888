/* Validation 8 of docs/methods/dem.md (beyond the shared conformance test): a run saved
 * and restarted continues bit for bit, with contact history, gates opening,
 * grains leaving and being reinserted (the generator's state), the Gear
 * integrator and linked cells; and runs are bit-identical for any number
 * of threads. */
#include "dem_test.h"

#include <string.h>
#include <unistd.h>

#include "method.h"

static const char *silo(const char *dem)
{
    static char text[2048];
    snprintf(text, sizeof text,
             "[scene]\nseed = 21\n"
             "[domain]\nwidth = 16\nheight = 34\ngravity = 1\n"
             "left = open\nright = open\nbottom = open\ntop = open\n"
             "[material]\nnormal = hertz\ntangential = spring\nkn = 1e5\ngamma_n = 100\n"
             "kt = 3e4\ngamma_t = 300\nmu = 0.5\n"
             "[silo]\nwalls = grains\nwidth = 12\nheight = 30\nbase = 2\norifice = 5\nopen_time = 0.2\n"
             "reinsert = yes\nreinsert_bottom = 26\nreinsert_top = 31\nexit_below = 1\n"
             "[species]\ncount = 150\npolydispersity = 0.1\n"
             "[init]\nkind = lattice\nregion = 2 2.2 14 30\nvelocity = gaussian\nv0 = 0.3\n"
             "[dem]\ndt = 1.25e-4\n%s", dem);
    return text;
}

static const char *gas_gear(const char *dem)
{
    static char text[2048];
    snprintf(text, sizeof text,
             "[scene]\nseed = 8\n"
             "[domain]\nwidth = 15\nheight = 15\nleft = periodic\nright = periodic\n"
             "bottom = periodic\ntop = periodic\n"
             "[material]\nnormal = linear\ntangential = regularised\nkn = 1e4\ngamma_n = 10\n"
             "gamma_t = 30\nmu = 0.4\n"
             "[species]\ncount = 90\n"
             "[init]\nkind = random\nvelocity = gaussian\nv0 = 1\n"
             "[dem]\nintegrator = gear\nneighbour = cells\nsort_every = 7\n%s", dem);
    return text;
}

static gr_particles *run(const char *text, double t_save, double t_end, const char *ck_path,
                         int load, uint64_t *outflow)
{
    const gr_method_type *m = gr_method_find("dem");
    assert_non_null(m);
    gr_scene *sc = dt_scene(text);
    gr_err e = {0};
    gr_particles *init = gr_particles_create(0, &e);
    assert_int_equal(gr_init_particles(sc, init, &e), GR_OK);
    gr_sim *st = NULL;
    if (gr_sim_create(m, sc, init, &st, &e))
        print_error("%s\n", e.msg);
    assert_non_null(st);
    if (load) {
        gr_ckpt *ck = gr_ckpt_open(ck_path, &e);
        assert_non_null(ck);
        if (gr_sim_load(st, ck, &e))
            print_error("load: %s\n", e.msg);
        assert_int_equal(e.code, GR_OK);
        gr_ckpt_close(ck, &e);
        assert_true(fabs(gr_sim_time(st) - t_save) < 1e-9);
    } else if (ck_path) {
        assert_int_equal(gr_sim_advance(st, t_save, 0, &e), GR_OK);
        unlink(ck_path);
        gr_ckpt *ck = gr_ckpt_create(ck_path, &e);
        assert_non_null(ck);
        if (gr_sim_save(st, ck, &e))
            print_error("save: %s\n", e.msg);
        assert_int_equal(e.code, GR_OK);
        assert_int_equal(gr_ckpt_close(ck, &e), GR_OK);
    }
    if (gr_sim_advance(st, t_end, 0, &e))
        print_error("advance: %s\n", e.msg);
    assert_int_equal(e.code, GR_OK);
    gr_particles *p = gr_particles_create(0, &e);
    assert_int_equal(gr_sim_snapshot(st, p, &e), GR_OK);
    *outflow = ((gr_dem *)gr_sim_state(st))->outflow;
    gr_sim_free(st);
    gr_particles_free(init);
    gr_scene_free(sc);
    return p;
}

static void same(const gr_particles *a, const gr_particles *b)
{
    assert_int_equal(a->n, b->n);
    assert_memory_equal(a->x, b->x, a->n * sizeof(double));
    assert_memory_equal(a->y, b->y, a->n * sizeof(double));
    assert_memory_equal(a->vx, b->vx, a->n * sizeof(double));
    assert_memory_equal(a->vy, b->vy, a->n * sizeof(double));
    assert_memory_equal(a->omega, b->omega, a->n * sizeof(double));
    assert_memory_equal(a->flags, b->flags, a->n * sizeof(uint32_t));
}

static void restart(const char *text, double t_save, double t_end, const char *what)
{
    char path[] = "/tmp/grano-dem-restart-XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    uint64_t oa, ob, oc;
    gr_particles *a = run(text, t_save, t_end, path, 0, &oa);
    gr_particles *b = run(text, t_save, t_end, path, 1, &ob);
    gr_particles *c = run(text, t_save, t_end, NULL, 0, &oc);
    printf("# %s: restarted at t = %g, compared at t = %g: %zu grains, outflow %llu\n", what, t_save, t_end,
           a->n, (unsigned long long)oa);
    same(a, b);
    same(a, c);
    assert_int_equal(oa, ob);
    assert_int_equal(oa, oc);
    unlink(path);
    gr_particles_free(a);
    gr_particles_free(b);
    gr_particles_free(c);
}

static void silo_with_springs_gates_and_reinsertion(void **state)
{
    (void)state;
    char path[] = "/tmp/grano-dem-restart-XXXXXX";
    (void)path;
    uint64_t out;
    gr_particles *p = run(silo(""), 0, 3.5, NULL, 0, &out);
    printf("# the silo lets %llu grains out by t = 3.5\n", (unsigned long long)out);
    assert_true(out > 5);
    gr_particles_free(p);
    restart(silo(""), 2.5, 3.5, "silo, spring friction, gate at 0.2, reinsertion");
}

static void gear_cells_periodic(void **state)
{
    (void)state;
    restart(gas_gear(""), 0.5, 1.0, "periodic gas, Gear, linked cells");
}

static void threads_give_the_same_bits(void **state)
{
    (void)state;
    uint64_t o1, o2;
    gr_particles *a = run(silo("threads = 1\n"), 0, 1.5, NULL, 0, &o1);
    gr_particles *b = run(silo("threads = 2\n"), 0, 1.5, NULL, 0, &o2);
    same(a, b);
    assert_int_equal(o1, o2);
    gr_particles_free(a);
    gr_particles_free(b);
    a = run(silo("threads = 1\nneighbour = cells\n"), 0, 1.0, NULL, 0, &o1);
    b = run(silo("threads = 2\nneighbour = cells\n"), 0, 1.0, NULL, 0, &o2);
    same(a, b);
    gr_particles_free(a);
    gr_particles_free(b);
    /* periodic in y: three colours */
    a = run(gas_gear("threads = 1\n"), 0, 0.5, NULL, 0, &o1);
    b = run(gas_gear("threads = 2\n"), 0, 0.5, NULL, 0, &o2);
    same(a, b);
    gr_particles_free(a);
    gr_particles_free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(silo_with_springs_gates_and_reinsertion),
        cmocka_unit_test(gear_cells_periodic),
        cmocka_unit_test(threads_give_the_same_bits),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
