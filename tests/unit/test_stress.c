/* The window-averaged stress accumulator (common/stress.h, gr_stress_acc):
 * hand-computed cells (kinetic part about the cell's mean velocity,
 * collisional shares, periodic wrap and clamping), NaN for an empty
 * window, the reset on read, and the checkpoint round trip. */
#include "test.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "stress.h"

/* Two cells of 2 x 2 over [0, 4] x [0, 2]; a window of T = 2 from t = 1. */
static gr_stress_acc *fill(int periodic)
{
    gr_err e = {0};
    gr_stress_acc *a = gr_stress_acc_create(4, 2, periodic, 0, 2, 1, 1.0, &e);
    assert_non_null(a);
    /* cell 0: two grains of m = 1 over the window, vx = +1 and -1: no mean
     * flow, int sum m vx vx dt = 4; cell 1: one grain at vx = vy = 3, a
     * mean flow, which leaves nothing */
    const double g1[6] = {2, 2, 0, 2, 0, 0}, g2[6] = {2, -2, 0, 2, 0, 0}, g3[6] = {2, 6, 6, 18, 18, 18};
    gr_stress_acc_kinetic(a, 1, 1, g1);
    gr_stress_acc_kinetic(a, 1.5, 0.5, g2);
    gr_stress_acc_kinetic(a, periodic ? -0.5 : 9, 5, g3); /* wrapped, or clamped, into cell 1 */
    /* a collision across the cells: l = (1, 2), J = (2, 0), a quarter in cell 0 */
    gr_stress_acc_collision(a, 1.9, 1, 2.1, 1, 0.25, 1, 2, 2, 0);
    /* a wall: l = (0, 0.5), J = (0, 4), all in cell 0 (below the domain: clamped) */
    gr_stress_acc_collision(a, 0.5, -0.1, 0, 0, 1.0, 0, 0.5, 0, 4);
    return a;
}

static void cells_by_hand(void **st)
{
    (void)st;
    for (int periodic = 0; periodic < 2; periodic++) {
        gr_stress_acc *a = fill(periodic);
        double g[4], c[8];
        gr_stress_acc_read(a, 3.0, g, c);
        const double At = 4 * 2; /* cell area 4, T = 2 */
        const double want[8] = {(4 + 0.25 * 2) / At, 0, (0.25 * 4) / At, (0.5 * 4) / At,
                                (0.75 * 2) / At, 0, (0.75 * 4) / At, 0};
        for (int k = 0; k < 8; k++)
            assert_close(c[k], want[k], 1e-15);
        for (int q = 0; q < 4; q++)
            assert_close(g[q], 0.5 * (c[q] + c[4 + q]), 1e-15);
        /* reset on read: the next window starts at 3 and is empty */
        assert_true(a->t0 == 3.0);
        gr_stress_acc_read(a, 3.0, g, c);
        for (int k = 0; k < 8; k++)
            assert_true(isnan(c[k]));
        assert_true(isnan(g[0]) && isnan(g[3]));
        gr_stress_acc_free(a);
    }
}

static void checkpoint(void **st)
{
    (void)st;
    char path[] = "/tmp/grano-stress-XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    unlink(path);
    gr_err e = {0};
    gr_stress_acc *a = fill(1), *b = NULL;
    gr_ckpt *ck = gr_ckpt_create(path, &e);
    assert_non_null(ck);
    assert_int_equal(gr_stress_acc_save(a, ck, "s", &e), GR_OK);
    assert_int_equal(gr_ckpt_close(ck, &e), GR_OK);
    ck = gr_ckpt_open(path, &e);
    assert_non_null(ck);
    assert_int_equal(gr_stress_acc_load(&b, ck, "absent", 4, 2, 1, 0, &e), GR_OK);
    assert_null(b);
    assert_int_equal(gr_stress_acc_load(&b, ck, "s", 4, 2, 1, 0, &e), GR_OK);
    gr_ckpt_close(ck, &e);
    assert_non_null(b);
    assert_int_equal(b->nx, 2);
    assert_int_equal(b->ny, 1);
    double ga[4], gb[4], ca[8], cb[8];
    gr_stress_acc_read(a, 3.0, ga, ca);
    gr_stress_acc_read(b, 3.0, gb, cb);
    assert_memory_equal(ca, cb, sizeof ca);
    assert_memory_equal(ga, gb, sizeof ga);
    gr_stress_acc_free(a);
    gr_stress_acc_free(b);
    unlink(path);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(cells_by_hand),
        cmocka_unit_test(checkpoint),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
