/* Linked cells against brute force on random configurations, with walls
 * and with periodic sides. */
#include "test.h"

#include <stdlib.h>

#include "geom.h"
#include "grid.h"
#include "rng.h"

typedef struct {
    size_t n;
    unsigned char *seen; /* n*n matrix */
    long count;
    int dup;
} pair_log;

static int record(size_t i, size_t j, double dx, double dy, void *user)
{
    (void)dx;
    (void)dy;
    pair_log *l = user;
    assert_true(i < j);
    if (l->seen[i * l->n + j])
        l->dup = 1;
    l->seen[i * l->n + j] = 1;
    l->count++;
    return 0;
}

static void check_config(int px, int py, double lx, double ly, size_t n, double rcut, uint64_t seed)
{
    gr_err e = {0};
    gr_rng *r = gr_rng_create(seed, 3, &e);
    double *x = malloc(n * sizeof *x), *y = malloc(n * sizeof *y);
    for (size_t i = 0; i < n; i++) {
        x[i] = lx * gr_rng_uniform(r);
        y[i] = ly * gr_rng_uniform(r);
    }
    gr_grid *g = gr_grid_create(0, 0, lx, ly, rcut, px, py, &e);
    assert_non_null(g);
    assert_true(g->cx >= rcut && g->cy >= rcut);
    assert_int_equal(gr_grid_build(g, x, y, n, NULL, &e), GR_OK);
    pair_log l = {n, calloc(n * n, 1), 0, 0};
    gr_grid_pairs(g, x, y, rcut, record, &l);
    assert_false(l.dup);
    long brute = 0;
    for (size_t i = 0; i < n; i++) {
        for (size_t j = i + 1; j < n; j++) {
            double dx = gr_min_image(x[j] - x[i], px ? lx : 0), dy = gr_min_image(y[j] - y[i], py ? ly : 0);
            int close = dx * dx + dy * dy < rcut * rcut;
            brute += close;
            if (close != l.seen[i * n + j]) {
                print_error("pair %zu %zu: brute %d grid %d (px %d py %d)\n", i, j, close, l.seen[i * n + j], px, py);
                fail();
            }
        }
    }
    assert_int_equal(brute, l.count);
    assert_true(brute > 0);
    free(l.seen);
    free(x);
    free(y);
    gr_grid_free(g);
    gr_rng_free(r);
}

static void grid_equals_brute_force(void **s)
{
    (void)s;
    for (uint64_t seed = 1; seed <= 3; seed++) {
        check_config(0, 0, 20.0, 13.0, 600, 1.0, seed);
        check_config(1, 0, 20.0, 13.0, 600, 1.0, seed);
        check_config(0, 1, 20.0, 13.0, 600, 1.3, seed);
        check_config(1, 1, 20.0, 13.0, 600, 1.0, seed);
        /* Few cells per side: periodic neighbours must not repeat. */
        check_config(1, 1, 3.1, 2.7, 40, 1.0, seed);
    }
}

static void cell_clamps_and_wraps(void **s)
{
    (void)s;
    gr_err e = {0};
    gr_grid *g = gr_grid_create(0, 0, 10, 10, 1, 1, 0, &e);
    assert_int_equal(g->nx, 10);
    assert_int_equal(gr_grid_cell(g, -0.5, 5.5), 5 * 10 + 9);  /* wraps in x */
    assert_int_equal(gr_grid_cell(g, 10.5, 5.5), 5 * 10 + 0);
    assert_int_equal(gr_grid_cell(g, 3.5, -4.0), 3);             /* clamps in y */
    assert_int_equal(gr_grid_cell(g, 3.5, 40.0), 9 * 10 + 3);
    long nb[9];
    assert_int_equal(gr_grid_neighbours(g, 0, nb), 6);  /* bottom row, wrapping in x */
    gr_grid_free(g);
    assert_null(gr_grid_create(0, 0, -1, 10, 1, 0, 0, &e));
    assert_int_equal(e.code, GR_EINPUT);
    gr_grid_free(NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(grid_equals_brute_force),
        cmocka_unit_test(cell_clamps_and_wraps),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
