/* The drift done ahead (dem_flow.c: the fused kick also drifts each strip
 * for the next step) changes no bit: a flowing silo with reinsertion, run
 * by gr_dem_advance (which drifts ahead) and by gr_dem_step one step at a
 * time (which never does), ends in the same state, bit for bit, after
 * grains left, were reinserted and the lists were rebuilt. (Two threads
 * against one: test_dem_restart.c; the threaded step drifts ahead too.)
 * And on 2 and 3 threads, where a run of strips that starts at an even
 * strip kicks that strip itself (dem_flow.c), the same bits as one
 * thread's steps, with such runs met. The buffers are compared whole, so
 * they start zeroed: the grains fill only their first 5 ntag doubles, and
 * with the rest uninitialised the comparison depended on what the heap
 * held (it failed with the tests in another order, and at times in this
 * one). */
#include "dem_test.h"
#include "dem/dem_eval.h"

#include <string.h>


static const char *silo(void)
{
    static char text[2048];
    snprintf(text, sizeof text,
             "[scene]\nseed = 3\n[domain]\nwidth = 16\nheight = 44\nbottom = open\ngravity = 4\n"
             "[material]\nnormal = hertz\ntangential = regularised\nkn = 1e5\ngamma_n = 100\n"
             "gamma_t = 300\nmu = 0.5\n[species]\ndiameter = 1\ncount = 200\npolydispersity = 0.1\n"
             "[silo]\nwidth = 12\nheight = 36\nbase = 5\norifice = 6\nopen_time = 0\n"
             "walls = grains\nexit_below = 4.8\nreinsert = yes\n"
             "[init]\nkind = lattice\nregion = 2.6 5.6 13.4 40\nspacing = 1.1\nvelocity = gaussian\nv0 = 1\n"
             "[dem]\ndt = 1.25e-4\nskin = 0.2\nmax_overlap = 0.25\n");
    return text;
}

/* The mobile state in tag order, with the outflow and list builds. */
static void run(int by_steps, long steps, double *out, uint64_t *outflow, uint64_t *builds)
{
    gr_scene *sc = dt_scene(silo());
    gr_dem *d = dt_create(sc, NULL);
    gr_err e = {0};
    if (by_steps)
        dt_step(d, steps);
    else if (gr_dem_advance(d, INFINITY, (uint64_t)steps, &e))
        print_error("advance: %s\n", e.msg);
    assert_int_equal(e.code, GR_OK);
    for (size_t k = 0; k < 5 * d->ntag; k++)
        out[k] = NAN;
    for (size_t i = 0; i < d->n; i++) {
        size_t t = (size_t)d->tag[i];
        double v[5] = {d->f[F_X][d->cur][i], d->f[F_Y][d->cur][i], d->f[F_VX][d->cur][i],
                       d->f[F_VY][d->cur][i], d->f[F_W][d->cur][i]};
        memcpy(out + 5 * t, v, sizeof v);
    }
    *outflow = d->outflow;
    *builds = d->builds;
    gr_dem_free(d);
    gr_scene_free(sc);
}

static void same_bits_as_steps(void **state)
{
    (void)state;
    const long steps = 8000; /* 1 tau */
    size_t cap = 5 * 4096;
    double *a = calloc(cap, sizeof *a), *b = calloc(cap, sizeof *b); /* compared whole */
    assert_true(a && b);
    uint64_t oa, ob, ba, bb;
    run(1, steps, a, &oa, &ba);
    run(0, steps, b, &ob, &bb);
    printf("# %ld steps: %llu grains left and were reinserted, %llu list builds\n", steps,
           (unsigned long long)oa, (unsigned long long)ba);
    assert_true(oa >= 5 && ba >= 10); /* the cases that must drop a drift done ahead */
    assert_true(oa == ob && ba == bb);
    assert_memory_equal(a, b, cap * sizeof *a);
    free(a), free(b);
}

/* The silo advanced one step at a time on T threads (each call one
 * one-barrier step): its state as run() gives it, and in how many steps a
 * run of strips started at an even strip. */
static void run_threads(int T, long steps, double *out, long *even)
{
    gr_scene *sc = dt_scene(silo());
    gr_dem *d = dt_create(sc, NULL);
    gr_err e = {0};
    d->par.threads = T;
    *even = 0;
    for (long k = 0; k < steps && e.code == GR_OK; k++) {
        gr_dem_advance(d, INFINITY, 1, &e);
        const struct gr_dem_eval *ev = d->ev;
        const int *S = ev->split + 3 * (T + 1);
        int hit = 0;
        for (int t = 1; ev->tred_on && t < T; t++)
            hit |= S[t] > 0 && S[t] < ev->ns && S[t] % 2 == 0;
        *even += hit;
    }
    assert_int_equal(e.code, GR_OK);
    for (size_t k = 0; k < 5 * d->ntag; k++)
        out[k] = NAN;
    for (size_t i = 0; i < d->n; i++) {
        double v[5] = {d->f[F_X][d->cur][i], d->f[F_Y][d->cur][i], d->f[F_VX][d->cur][i],
                       d->f[F_VY][d->cur][i], d->f[F_W][d->cur][i]};
        memcpy(out + 5 * (size_t)d->tag[i], v, sizeof v);
    }
    gr_dem_free(d);
    gr_scene_free(sc);
}

static void threads_kick_their_first_strip(void **state)
{
    (void)state;
    const long steps = 2000;
    size_t cap = 5 * 4096;
    double *a = calloc(cap, sizeof *a), *b = calloc(cap, sizeof *b); /* compared whole */
    assert_true(a && b);
    uint64_t oa, ba;
    run(1, steps, a, &oa, &ba);
    for (int T = 2; T <= 3; T++) {
        long even;
        run_threads(T, steps, b, &even);
        printf("# %d threads: %ld of %ld steps with a run starting at an even strip\n", T, even, steps);
        assert_true(even >= 100);
        assert_memory_equal(a, b, cap * sizeof *a);
    }
    free(a), free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(same_bits_as_steps),
        cmocka_unit_test(threads_kick_their_first_strip),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
