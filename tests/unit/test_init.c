/* Initial particles: counts, no overlaps, silo wall grains and orifice. */
#include "test.h"

#include <stdlib.h>
#include <string.h>

#include "geom.h"
#include "init.h"
#include "rng.h"

static gr_scene *parse(const char *text)
{
    gr_err e = {0};
    gr_scene *sc = gr_scene_parse(text, "init.ini", NULL, &e);
    if (!sc)
        print_error("%s\n", e.msg);
    assert_non_null(sc);
    return sc;
}

static gr_particles *make(const gr_scene *sc)
{
    gr_err e = {0};
    gr_particles *p = gr_particles_create(0, &e);
    if (gr_init_particles(sc, p, &e))
        print_error("%s\n", e.msg);
    assert_int_equal(e.code, GR_OK);
    return p;
}

static double min_gap(const gr_particles *p, double Lx, double Ly)
{
    double g = INFINITY;
    for (size_t i = 0; i < p->n; i++)
        for (size_t j = i + 1; j < p->n; j++) {
            if ((p->flags[i] & GR_PF_FIXED) && (p->flags[j] & GR_PF_FIXED))
                continue;
            double dx = gr_min_image(p->x[j] - p->x[i], Lx), dy = gr_min_image(p->y[j] - p->y[i], Ly);
            double gap = sqrt(dx * dx + dy * dy) - p->radius[i] - p->radius[j];
            g = gap < g ? gap : g;
        }
    return g;
}

static void lattice_and_velocities(void **s)
{
    (void)s;
    gr_scene *sc = parse("[domain]\nwidth = 40\nheight = 40\n[species]\ncount = 1000\n"
                         "[init]\nvelocity = gaussian\nv0 = 2\n");
    gr_particles *p = make(sc);
    assert_int_equal(p->n, 1000);
    double v2 = 0;
    for (size_t i = 0; i < p->n; i++) {
        assert_true(p->x[i] - p->radius[i] >= 0 && p->x[i] + p->radius[i] <= 40);
        assert_true(p->y[i] - p->radius[i] >= 0 && p->y[i] + p->radius[i] <= 40);
        assert_close(p->mass[i], 1.0, 1e-15); /* d = 1, default density 4/pi */
        assert_int_equal(p->id[i], (int64_t)i);
        v2 += p->vx[i] * p->vx[i] + p->vy[i] * p->vy[i];
    }
    assert_true(min_gap(p, 0, 0) >= 0.05 - 1e-12);
    /* <vx^2 + vy^2> = 2 v0^2 within 5 sigma (sigma of the mean: 2 v0^2 / sqrt(N)) */
    assert_close(v2 / 1000, 8.0, 5 * 8.0 / sqrt(1000));
    /* Same seed, same bits. */
    gr_particles *q = make(sc);
    assert_memory_equal(p->x, q->x, p->n * sizeof(double));
    assert_memory_equal(p->vy, q->vy, p->n * sizeof(double));
    gr_particles_free(p);
    gr_particles_free(q);
    gr_scene_free(sc);
}

static void random_without_overlap(void **s)
{
    (void)s;
    gr_scene *sc = parse("[domain]\nwidth = 30\nheight = 20\nleft = periodic\nright = periodic\n"
                         "[species]\ncount = 250\npolydispersity = 0.2\n[init]\nkind = random\n");
    gr_particles *p = make(sc);
    assert_int_equal(p->n, 250);
    assert_true(min_gap(p, 30, 0) >= 0);
    double dmin = 1, dmax = 1;
    for (size_t i = 0; i < p->n; i++) {
        double d = 2 * p->radius[i];
        dmin = d < dmin ? d : dmin;
        dmax = d > dmax ? d : dmax;
        assert_close(p->mass[i], d * d, 1e-12); /* mass scales as area */
    }
    assert_true(dmin >= 0.8 && dmax <= 1.2 && dmax - dmin > 0.3);
    gr_particles_free(p);
    gr_scene_free(sc);
}

static void silo_walls_of_grains(void **s)
{
    (void)s;
    gr_scene *sc = parse("[domain]\nwidth = 22\nheight = 40\nbottom = open\n[species]\ncount = 300\n"
                         "[silo]\nwidth = 20\nheight = 30\nbase = 3\norifice = 3.8\nopen_time = 5\nwalls = grains\n");
    gr_particles *p = make(sc);
    size_t mobile = gr_particles_count_mobile(p);
    assert_int_equal(mobile, 300);
    /* Base grains: the two bordering the orifice leave a gap of exactly D. */
    double left_edge = -INFINITY, right_edge = INFINITY;
    int gates = 0;
    for (size_t i = 0; i < p->n; i++) {
        if (!(p->flags[i] & GR_PF_FIXED))
            continue;
        if (p->flags[i] & GR_PF_GATE) {
            gates++;
            continue;
        }
        if (fabs(p->y[i] - 2.5) > 1e-12)
            continue;
        if (p->x[i] < 11 && p->x[i] + 0.5 > left_edge)
            left_edge = p->x[i] + 0.5;
        if (p->x[i] > 11 && p->x[i] - 0.5 < right_edge)
            right_edge = p->x[i] - 0.5;
    }
    assert_close(right_edge - left_edge, 3.8, 1e-12);
    assert_close(0.5 * (left_edge + right_edge), 11.0, 1e-12);
    assert_true(gates >= 3);
    /* Walls close: consecutive wall grains along a side touch or overlap. */
    for (size_t i = 0; i < p->n; i++) {
        if (!(p->flags[i] & GR_PF_FIXED) || fabs(p->x[i] - 0.5) > 1e-12)
            continue;
        double nearest = INFINITY;
        for (size_t j = 0; j < p->n; j++)
            if (j != i && (p->flags[j] & GR_PF_FIXED) && !(p->flags[j] & GR_PF_GATE)) {
                double d = hypot(p->x[j] - p->x[i], p->y[j] - p->y[i]);
                nearest = d < nearest ? d : nearest;
            }
        assert_true(nearest <= 1.0 + 1e-12);
    }
    /* Mobile grains start inside the silo, clear of the wall grains. */
    assert_true(min_gap(p, 0, 0) >= -1e-12);
    gr_particles_free(p);
    gr_scene_free(sc);
}

/* The hopper's slopes continue past the domain's sides: the topmost fixed
 * grains lie outside the container's walls, on the slopes' lines, so that
 * no grain can come to rest balanced on an end grain against a side. */
static void hopper_without_perch(void **s)
{
    (void)s;
    gr_scene *sc = parse("[domain]\nwidth = 22\nheight = 60\nbottom = open\n[species]\ncount = 100\n"
                         "[silo]\nwidth = 20\nheight = 30\nbase = 3\norifice = 3.8\nwalls = grains\n"
                         "hopper = yes\nhopper_outlet = 6\nhopper_bottom = 36\nhopper_top = 41\n");
    gr_particles *p = make(sc);
    const gr_silo *h = &sc->silo;
    double top = -INFINITY;
    for (size_t i = 0; i < p->n; i++)
        if (p->flags[i] & GR_PF_FIXED)
            top = p->y[i] > top ? p->y[i] : top;
    assert_true(top > h->hopper_top + 0.1);
    int ends = 0;
    for (size_t i = 0; i < p->n; i++) {
        if (!(p->flags[i] & GR_PF_FIXED) || p->y[i] < top - 1e-12)
            continue;
        ends++;
        int left = p->x[i] < h->orifice_center;
        /* the slope from the outlet's edge grain to the rim's over the wall */
        double ax = h->orifice_center + (left ? -1 : 1) * (0.5 * h->hopper_outlet + 0.5), ay = h->hopper_bottom;
        double bx = left ? h->x0 - 0.5 : h->x0 + h->width + 0.5, by = h->hopper_top;
        double cross = (bx - ax) * (p->y[i] - ay) - (by - ay) * (p->x[i] - ax);
        assert_true(fabs(cross) / hypot(bx - ax, by - ay) < 1e-9);
        assert_true(left ? p->x[i] < bx - 0.5 : p->x[i] > bx + 0.5);
    }
    assert_int_equal(ends, 2);
    assert_true(min_gap(p, 0, 0) >= -1e-12);
    gr_particles_free(p);
    gr_scene_free(sc);
}

/* The spot for a reinserted grain: the same as trying each random spot
 * against every grain (the search bins the grains near the band), over
 * bands from sparse to full (where no spot is found), grains of several
 * radii, some of them gone. */
static void reinsert_spot_as_brute_force(void **s)
{
    (void)s;
    gr_scene *sc = parse("[domain]\nwidth = 22\nheight = 40\nbottom = open\n[species]\ncount = 10\n"
                         "[silo]\nwidth = 20\nheight = 30\nbase = 3\norifice = 3.8\nreinsert = yes\n");
    const gr_silo *si = &sc->silo;
    gr_err e = {0};
    int found_some = 0, missed_some = 0;
    for (int n = 0; n <= 600; n += 40) {
        gr_particles *p = gr_particles_create(0, &e);
        gr_rng *place = gr_rng_create(7, (uint64_t)n, &e);
        for (int k = 0; k < n; k++) {
            double r = 0.3 + 0.3 * gr_rng_uniform(place);
            double x = si->x0 - 1.0 + (si->width + 2.0) * gr_rng_uniform(place);
            double y = si->reinsert_bottom - 1.5 + (si->reinsert_top - si->reinsert_bottom + 3.0) * gr_rng_uniform(place);
            long i = gr_particles_push(p, x, y, r, 1.0, k % 7 == 3 ? GR_PF_GONE : 0, 0, &e);
            assert_true(i >= 0);
        }
        for (int trial = 0; trial < 4; trial++) {
            double r = 0.25 + 0.1 * trial, x = NAN, y = NAN, bx = NAN, by = NAN;
            gr_rng *a = gr_rng_create(11, (uint64_t)(n * 4 + trial), &e), *b = gr_rng_create(11, (uint64_t)(n * 4 + trial), &e);
            int got = gr_reinsert_spot(sc, p, r, a, 300, &x, &y), want = 0;
            for (int t = 0; t < 300 && !want; t++) {
                double cx = si->x0 + r + (si->width - 2 * r) * gr_rng_uniform(b);
                double cy = si->reinsert_bottom + r + (si->reinsert_top - si->reinsert_bottom - 2 * r) * gr_rng_uniform(b);
                int ok = 1;
                for (size_t j = 0; j < p->n && ok; j++) {
                    double dx = cx - p->x[j], dy = cy - p->y[j], rr = r + p->radius[j];
                    ok = (p->flags[j] & GR_PF_GONE) || dx * dx + dy * dy >= rr * rr;
                }
                if (ok)
                    want = 1, bx = cx, by = cy;
            }
            assert_int_equal(got, want);
            if (want)
                assert_true(x == bx && y == by);
            found_some |= want, missed_some |= !want;
            gr_rng_free(a), gr_rng_free(b);
        }
        gr_rng_free(place);
        gr_particles_free(p);
    }
    /* both outcomes met */
    assert_true(found_some && missed_some);
    gr_scene_free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(lattice_and_velocities),
        cmocka_unit_test(random_without_overlap),
        cmocka_unit_test(silo_walls_of_grains),
        cmocka_unit_test(hopper_without_perch),
        cmocka_unit_test(reinsert_spot_as_brute_force),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
