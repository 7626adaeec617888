#include "test.h"

#include "particles.h"

static void push_grows_and_keeps_fields(void **state)
{
    (void)state;
    gr_err e = {0};
    gr_particles *p = gr_particles_create(1, &e);
    assert_non_null(p);
    for (int i = 0; i < 1000; i++)
        assert_int_equal(gr_particles_push(p, i, -i, 0.5, 1.0, i % 3 == 0 ? GR_PF_FIXED : 0, 0, &e), i);
    assert_int_equal(p->n, 1000);
    assert_true(p->cap >= 1000);
    assert_close(p->x[999], 999.0, 0.0);
    assert_close(p->y[500], -500.0, 0.0);
    assert_close(p->inertia[7], 0.5 * 1.0 * 0.25, 1e-15);
    assert_int_equal(p->id[123], 123);
    /* 334 of 1000 indices are multiples of 3 */
    assert_int_equal(gr_particles_count_mobile(p), 666);

    gr_particles *q = gr_particles_create(0, &e);
    assert_int_equal(gr_particles_copy(q, p, &e), GR_OK);
    assert_int_equal(q->n, p->n);
    assert_memory_equal(q->x, p->x, p->n * sizeof(double));
    assert_memory_equal(q->flags, p->flags, p->n * sizeof(uint32_t));
    gr_particles_free(q);
    gr_particles_free(p);
    gr_particles_free(NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(push_grows_and_keeps_fields),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
