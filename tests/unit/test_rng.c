/* Random streams: reproducible from (seed, stream), independent across
 * streams and seeds, with the right moments. */
#include "test.h"

#include "rng.h"

#define N 200000

static void reproducible(void **s)
{
    (void)s;
    gr_err e = {0};
    gr_rng *a = gr_rng_create(42, 7, &e), *b = gr_rng_create(42, 7, &e);
    for (int i = 0; i < 1000; i++)
        assert_true(gr_rng_uniform(a) == gr_rng_uniform(b));
    gr_rng_free(a);
    gr_rng_free(b);
    gr_rng_free(NULL);
}

/* Pearson correlation of two streams' uniforms must be within 5 sigma of 0. */
static double correlation(gr_rng *a, gr_rng *b)
{
    double sa = 0, sb = 0, sab = 0, saa = 0, sbb = 0;
    for (int i = 0; i < N; i++) {
        double x = gr_rng_uniform(a), y = gr_rng_uniform(b);
        sa += x, sb += y, sab += x * y, saa += x * x, sbb += y * y;
    }
    double ca = saa / N - (sa / N) * (sa / N), cb = sbb / N - (sb / N) * (sb / N);
    return (sab / N - sa / N * sb / N) / sqrt(ca * cb);
}

static void independent(void **s)
{
    (void)s;
    gr_err e = {0};
    const uint64_t pairs[][4] = {{1, 0, 1, 1}, {1, 0, 2, 0}, {0, 0, 0, 1}, {123, 5, 124, 5}};
    for (int k = 0; k < 4; k++) {
        gr_rng *a = gr_rng_create(pairs[k][0], pairs[k][1], &e);
        gr_rng *b = gr_rng_create(pairs[k][2], pairs[k][3], &e);
        double c = correlation(a, b);
        assert_close(c, 0.0, 5.0 / sqrt(N));
        gr_rng_free(a);
        gr_rng_free(b);
    }
}

static void moments(void **s)
{
    (void)s;
    gr_err e = {0};
    gr_rng *r = gr_rng_create(9, 9, &e);
    double m = 0, v = 0;
    for (int i = 0; i < N; i++) {
        double x = gr_rng_gaussian(r, 2.0);
        m += x;
        v += x * x;
    }
    m /= N;
    v = v / N - m * m;
    assert_close(m, 0.0, 5 * 2.0 / sqrt(N));
    assert_rel(v, 4.0, 5 * sqrt(2.0 / N));
    double u = 0;
    for (int i = 0; i < N; i++) {
        double x = gr_rng_uniform(r);
        assert_true(x >= 0 && x < 1);
        u += x;
    }
    assert_close(u / N, 0.5, 5 * sqrt(1.0 / 12 / N));
    for (int i = 0; i < 1000; i++)
        assert_true(gr_rng_below(r, 7) < 7);
    gr_rng_free(r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(reproducible),
        cmocka_unit_test(independent),
        cmocka_unit_test(moments),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
