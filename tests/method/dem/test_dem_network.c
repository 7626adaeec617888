/* The contact network of the soft DEM backend (gr_dem_contacts, the
 * method's contacts operation): a resting column of N disks carries the
 * statics, (1..N) m g from the top down, on a floor segment and on a floor
 * grain; a pair across a periodic side is found by minimum image with the
 * law's force; friction: a disk resting on an incline (rotation locked)
 * has ft = m g sin(theta) up the slope, and in a collapsing frictional
 * pile every row obeys |ft| <= mu |fn|; asking for the network changes no
 * bit of the run. */
#include "dem_test.h"

#include <string.h>

static gr_contacts *network(gr_dem *d)
{
    gr_err e = {0};
    gr_contacts *c = gr_contacts_create(0, &e);
    assert_non_null(c);
    if (gr_dem_contacts(d, c, &e))
        print_error("contacts: %s\n", e.msg);
    assert_int_equal(e.code, GR_OK);
    return c;
}

/* N disks of diameter 1 and mass 1 stacked at x = 0.65 from y0 up (on a
 * fixed floor grain, id 0, when floor_grain) settle to t = 30, where the
 * kinetic energy is ~1e-22: speeds ~1e-11 bound the damping terms
 * gamma_n v by ~2e-9 m g, whence tol = 1e-8 (measured: 2e-16, the springs
 * alone). The network: fn sorted is (1..N) m g, every disk joined, ft = 0. */
static void column(const char *domain, double y0, int floor_grain, double tol)
{
    enum { N = 10 };
    char text[1024];
    snprintf(text, sizeof text,
             "[domain]\nwidth = 1.3\nheight = 14\ngravity = 1\n%s"
             "[material]\nnormal = linear\nkn = 1e5\ngamma_n = 200\n[species]\ncount = 1\n",
             domain);
    gr_scene *sc = dt_scene(text);
    gr_err e = {0};
    gr_particles *p = gr_particles_create(N + 1, &e);
    if (floor_grain)
        gr_particles_push(p, 0.65, y0 - 1.0, 0.5, 1.0, GR_PF_FIXED, 0, &e);
    for (int k = 0; k < N; k++)
        gr_particles_push(p, 0.65, y0 + k, 0.5, 1.0, 0, 0, &e);
    gr_dem *d = dt_create(sc, p);
    dt_advance(d, 30.0);
    gr_contacts *c = network(d);
    double fn[N + 1], err_max = 0.0, ft_max = 0.0;
    int seen[N + 1] = {0}, nwall = 0;
    assert_int_equal(c->n, N);
    for (size_t k = 0; k < c->n; k++) {
        fn[k] = c->fn[k];
        ft_max = fmax(ft_max, fabs(c->ft[k]));
        seen[c->i[k]] = 1;
        if (c->j[k] >= 0)
            seen[c->j[k]] = 1;
        nwall += c->j[k] < 0;
        /* the floor, whether segment or grain, holds all N */
        if (c->j[k] < 0 || (floor_grain && c->i[k] == 0))
            assert_true(fabs(c->fn[k] / N - 1) < tol);
    }
    for (size_t a = 0; a < c->n; a++)
        for (size_t b = a + 1; b < c->n; b++)
            if (fn[b] < fn[a]) {
                double t = fn[a];
                fn[a] = fn[b], fn[b] = t;
            }
    for (int k = 0; k < N; k++)
        err_max = fmax(err_max, fabs(fn[k] / (k + 1) - 1));
    double ek;
    gr_dem_energy(d, &ek, NULL);
    printf("# column of %d on a floor %s at t = %g: fn = (1..%d) m g within %.2e (bound %.0e), |ft| <= %.1e, kinetic energy %.1e\n",
           N, floor_grain ? "grain" : "segment", d->t, N, err_max, tol, ft_max, ek);
    assert_true(err_max < tol);
    assert_true(ft_max == 0.0);
    assert_int_equal(nwall, floor_grain ? 0 : 1);
    for (int k = 0; k < N + floor_grain; k++)
        assert_true(seen[k]);
    gr_contacts_free(c);
    gr_dem_free(d);
    gr_particles_free(p);
    gr_scene_free(sc);
}

static void column_on_segment(void **state)
{
    (void)state;
    column("", 0.5, 0, 1e-8);
}

static void column_on_wall_grain(void **state)
{
    (void)state;
    column("bottom = open\n", 1.5, 1, 1e-8);
}

/* Two disks overlapping by 0.02 across the periodic side x = 0 = 6, at
 * rest: one row, fn = kn xi, the same whichever of them is on which side. */
static void periodic_pair_by_minimum_image(void **state)
{
    (void)state;
    gr_scene *sc = dt_scene("[domain]\nwidth = 6\nheight = 6\ngravity = 0\nleft = periodic\nright = periodic\n"
                            "[material]\nnormal = linear\nkn = 1e5\ngamma_n = 50\n[species]\ncount = 1\n");
    gr_err e = {0};
    gr_particles *p = gr_particles_create(2, &e);
    gr_particles_push(p, 6 - 0.49, 3, 0.5, 1.0, 0, 0, &e);
    gr_particles_push(p, 0.49, 3, 0.5, 1.0, 0, 0, &e);
    gr_dem *d = dt_create(sc, p);
    gr_contacts *c = network(d);
    assert_int_equal(c->n, 1);
    printf("# periodic pair: rows (%lld, %lld), fn = %.12g for kn xi = %.12g\n", (long long)c->i[0],
           (long long)c->j[0], c->fn[0], 1e5 * 0.02);
    assert_true(c->i[0] == 0 && c->j[0] == 1);
    assert_true(fabs(c->fn[0] / (1e5 * 0.02) - 1) < 1e-9);
    assert_true(c->ft[0] == 0.0);
    gr_contacts_free(c);
    gr_dem_free(d);
    gr_particles_free(p);
    gr_scene_free(sc);
}

#define FRICTION                                                               \
    "[material]\nnormal = linear\ntangential = spring\nkn = 1e5\ngamma_n = 50\n" \
    "kt = 2e4\ngamma_t = 20\nmu = 0.5\n"

/* A disk (rotation locked) resting on a slope of 15 degrees, tan = 0.27 <
 * mu: statics give fn = m g cos, ft = m g sin, and the row's t (n, from the
 * wall to the disk, turned +90 degrees) points up the slope. */
static void incline_holds_by_friction(void **state)
{
    (void)state;
    double th = 15 * M_PI / 180, cs = cos(th), sn = sin(th);
    double ax = 1, ay = 20, L = 25;
    char text[1024];
    snprintf(text, sizeof text,
             "[domain]\nwidth = 30\nheight = 30\ngravity = 1\n" FRICTION
             "[species]\ncount = 1\n[dem]\ndt = 2e-5\n[wall.slope]\nfrom = %.17g %.17g\nto = %.17g %.17g\n",
             ax, ay, ax + L * cs, ay - L * sn);
    gr_scene *sc = dt_scene(text);
    gr_err e = {0};
    gr_particles *p = gr_particles_create(1, &e);
    double xi0 = cs / 1e5;
    gr_particles_push(p, ax + 5 * cs + (0.5 - xi0) * sn, ay - 5 * sn + (0.5 - xi0) * cs, 0.5, 1.0, 0, 0, &e);
    gr_dem *d = dt_create(sc, p);
    gr_dem_lock_rotation(d, 0);
    dt_advance(d, 3.0);
    gr_contacts *c = network(d);
    assert_int_equal(c->n, 1);
    printf("# incline 15 deg: fn = %.9f (m g cos %.9f), ft = %.9f (m g sin %.9f), ft/fn = %.9f, wall %lld of %d\n",
           c->fn[0], cs, c->ft[0], sn, c->ft[0] / c->fn[0], (long long)c->j[0], d->nseg);
    assert_true(c->i[0] == 0 && c->j[0] == -1 - (d->nseg - 1));
    assert_true(fabs(c->fn[0] / cs - 1) < 1e-6);
    assert_true(fabs(c->ft[0] / sn - 1) < 1e-6);
    gr_contacts_free(c);
    gr_dem_free(d);
    gr_particles_free(p);
    gr_scene_free(sc);
}

#define PILE                                                                   \
    "[scene]\nseed = 5\n[domain]\nwidth = 16\nheight = 40\ngravity = 1\n" FRICTION \
    "[species]\ncount = 150\npolydispersity = 0.2\n"                           \
    "[init]\nkind = lattice\nregion = 0.5 0.5 15.5 39.5\nvelocity = gaussian\nv0 = 0.5\n[dem]\ndt = 1e-4\n"

static int same_state(const gr_dem *a, const gr_dem *b)
{
    size_t n = a->n;
    int same = a->n == b->n && a->step == b->step;
    for (int f = F_X; same && f <= F_W; f++)
        same = !memcmp(a->f[f][a->cur], b->f[f][b->cur], n * sizeof(double));
    size_t h = n * (size_t)a->hist.cap;
    return same && !memcmp(a->hist.z, b->hist.z, h * sizeof(double)) &&
           !memcmp(a->hist.partner, b->hist.partner, h * sizeof(int32_t)) &&
           !memcmp(a->hist.stamp, b->hist.stamp, h * sizeof(uint64_t));
}

/* A pile collapsing with the spring law: Coulomb's bound on every row,
 * sliding contacts at it; and a twin run that never asks for the network
 * ends with the same bits. */
static void pile_obeys_coulomb(void **state)
{
    (void)state;
    gr_scene *sc = dt_scene(PILE);
    gr_dem *d = dt_create(sc, NULL), *twin = dt_create(sc, NULL);
    double ratio = 0.0, ft_max = 0.0;
    size_t rows = 0, at_limit = 0;
    for (int k = 0; k < 40; k++) {
        dt_step(d, 2500);
        gr_contacts *c = network(d);
        for (size_t r = 0; r < c->n; r++) {
            double lim = 0.5 * fabs(c->fn[r]);
            assert_true(fabs(c->ft[r]) <= lim * (1 + 1e-12));
            ratio = fmax(ratio, lim > 0 ? fabs(c->ft[r]) / lim : 0.0);
            ft_max = fmax(ft_max, fabs(c->ft[r]));
            at_limit += lim > 0 && fabs(c->ft[r]) >= lim * (1 - 1e-12);
        }
        rows += c->n;
        gr_contacts_free(c);
    }
    dt_step(twin, 100000);
    printf("# pile of 150 (spring, mu = 0.5) to t = %g: %zu rows in 40 networks, max |ft| = %.3g, "
           "max |ft|/(mu |fn|) = %.15f, %zu at the limit; twin run without networks bit-identical: %s\n",
           d->t, rows, ft_max, ratio, at_limit, same_state(d, twin) ? "yes" : "no");
    assert_true(ft_max > 0.0 && at_limit > 0);
    assert_true(same_state(d, twin));
    gr_dem_free(d);
    gr_dem_free(twin);
    gr_scene_free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(column_on_segment),
        cmocka_unit_test(column_on_wall_grain),
        cmocka_unit_test(periodic_pair_by_minimum_image),
        cmocka_unit_test(incline_holds_by_friction),
        cmocka_unit_test(pile_obeys_coulomb),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
