/* Segment distance, disk-segment contact and floor motion. */
#include "test.h"

#include "geom.h"

static void segment_distance(void **s)
{
    (void)s;
    gr_v2 a = {0, 0}, b = {4, 0};
    double t;
    gr_v2 q = gr_seg_closest(a, b, (gr_v2){1, 3}, &t);
    assert_close(q.x, 1, 1e-15);
    assert_close(q.y, 0, 1e-15);
    assert_close(t, 0.25, 1e-15);
    assert_close(gr_seg_distance(a, b, (gr_v2){1, 3}), 3, 1e-15);
    /* Beyond an end the nearest point is the end itself. */
    assert_close(gr_seg_distance(a, b, (gr_v2){7, 4}), 5, 1e-15);
    assert_close(gr_seg_distance(a, b, (gr_v2){-3, -4}), 5, 1e-15);
    /* A slanted segment: distance from the origin to x + y = 2. */
    assert_close(gr_seg_distance((gr_v2){2, 0}, (gr_v2){0, 2}, (gr_v2){0, 0}), sqrt(2.0), 1e-15);
    /* Degenerate segment is a point. */
    assert_close(gr_seg_distance(a, a, (gr_v2){3, 4}), 5, 1e-15);
}

static void disk_contact(void **s)
{
    (void)s;
    gr_v2 a = {0, 0}, b = {10, 0}, n, p;
    double ov;
    assert_true(gr_disk_segment_contact(a, b, (gr_v2){3, 0.4}, 0.5, &ov, &n, &p));
    assert_close(ov, 0.1, 1e-15);
    assert_close(n.x, 0, 1e-15);
    assert_close(n.y, 1, 1e-15);
    assert_close(p.x, 3, 1e-15);
    /* From below the normal points down, towards the disk. */
    assert_true(gr_disk_segment_contact(a, b, (gr_v2){3, -0.3}, 0.5, &ov, &n, &p));
    assert_close(n.y, -1, 1e-15);
    assert_close(ov, 0.2, 1e-15);
    /* Touching an end: normal along the line from the end to the centre. */
    assert_true(gr_disk_segment_contact(a, b, (gr_v2){10.3, 0.4}, 0.6, &ov, &n, &p));
    assert_close(ov, 0.1, 1e-14);
    assert_close(n.x, 0.6, 1e-14);
    assert_close(n.y, 0.8, 1e-14);
    assert_close(p.x, 10, 0);
    assert_false(gr_disk_segment_contact(a, b, (gr_v2){3, 0.5}, 0.5, &ov, &n, &p));
}

static void floor_motion(void **s)
{
    (void)s;
    gr_floor f = {GR_FLOOR_SINE, 0.1, 30.0};
    for (double t = 0; t < 1; t += 0.013) {
        assert_close(gr_floor_offset(&f, t), 0.1 * cos(30 * t), 1e-15);
        /* velocity is the derivative of the offset (central difference) */
        double h = 1e-6, dv = (gr_floor_offset(&f, t + h) - gr_floor_offset(&f, t - h)) / (2 * h);
        assert_close(gr_floor_velocity(&f, t), dv, 1e-6);
    }
    gr_floor saw = {GR_FLOOR_SAWTOOTH, 0.2, 2 * M_PI};  /* period 1 */
    assert_close(gr_floor_offset(&saw, 0.0), -0.2, 1e-15);
    assert_close(gr_floor_offset(&saw, 0.5), 0.0, 1e-15);
    assert_close(gr_floor_offset(&saw, 1.25), -0.1, 1e-12);
    assert_close(gr_floor_velocity(&saw, 0.3), 0.4, 1e-15); /* 2A per period */
    gr_floor hf = {GR_FLOOR_SINE_HF, 0.01, 100};
    assert_close(gr_floor_offset(&hf, 0.7), 0, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(segment_distance),
        cmocka_unit_test(disk_contact),
        cmocka_unit_test(floor_motion),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
