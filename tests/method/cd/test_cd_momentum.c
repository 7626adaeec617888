/* The sweeps' momentum (accel = momentum) against plain Gauss-Seidel on
 * tall packings solved cold in one step, where Gauss-Seidel carries the
 * load about one contact row per sweep:
 * 1. validation 2's column of 40 frictionless disks: the same impulses
 *    (k m g dt below the k-th disk from the top, relative 1e-6 at
 *    tol 1e-10) in at most a fifth of the sweeps;
 * 2. a hyperstatic pile of 8 x 30 frictional disks (mu = 0.5) in touching
 *    hexagonal order, periodic sides: the floor carries the weight and no
 *    disk moves (relative 1e-6, |v| < 1e-6 dt at tol 1e-10), in at most
 *    a fifth of the sweeps. Individual impulses of a hyperstatic pile are
 *    not unique, so they are not compared. */
#include "cd_test.h"

/* One cold step of the grains p, with friction mu = 0.5 or none. */
static gr_sim *one_step(const char *accel, int friction, const gr_particles *p, gr_scene **sc)
{
    char text[1024];
    snprintf(text, sizeof text,
             "[domain]\nwidth = 8\nheight = 60\nleft = periodic\nright = periodic\ngravity = 1\n"
             "%s[species]\ncount = 1\n"
             "[cd]\ndt = 1e-3\ntol = 1e-10\nmax_iter = 10000000\nstrict = yes\nwarm_start = no\n"
             "gap = 0.01\naccel = %s\n",
             friction ? "[material]\ntangential = coulomb\nmu = 0.5\n" : "", accel);
    *sc = ct_scene(text);
    gr_sim *s = ct_sim(*sc, p);
    ct_steps(s, 1);
    return s;
}

static long column(int N, const char *accel)
{
    gr_err e = {0};
    gr_particles *p = gr_particles_create((size_t)N, &e);
    for (int k = 0; k < N; k++)
        gr_particles_push(p, 4, 0.5 + k, 0.5, 1.0, 0, 0, &e);
    gr_scene *sc;
    gr_sim *s = one_step(accel, 0, p, &sc);
    /* the floor is wall 0, after the N disks */
    double worst = ct_column_error(ct_state(s), N, N, 1);
    long sweeps = (long)ct_counter(s, "iterations");
    printf("# column N = %d, accel = %s: %ld sweeps, largest relative impulse error %.2e\n", N, accel, sweeps, worst);
    gr_particles_free(p);
    gr_sim_free(s);
    gr_scene_free(sc);
    return sweeps;
}

static void column_of_disks(void **unused)
{
    (void)unused;
    long plain = column(40, "none"), fast = column(40, "momentum");
    assert_true(5 * fast <= plain);
}

#define NX 8
#define NY 30

static long pile(const char *accel)
{
    gr_particles *p = ct_hex_pile(NX, NY);
    gr_scene *sc;
    gr_sim *s = one_step(accel, 1, p, &sc);
    gr_cd *d = ct_state(s);
    double dt = d->par.dt, base = 0, vmax = 0;
    size_t n = d->n;
    for (size_t k = 0; k < d->prev.n; k++)
        if ((size_t)d->prev.c[k].j == n)
            base += d->prev.c[k].rn;
    for (size_t i = 0; i < n; i++)
        vmax = fmax(vmax, fmax(fmax(fabs(d->p->vx[i]), fabs(d->p->vy[i])), fabs(d->p->omega[i]) * 0.5));
    long sweeps = (long)ct_counter(s, "iterations");
    printf("# pile %d x %d, mu = 0.5, accel = %s: %zu contacts, %ld sweeps; floor impulse / (weight dt) %.12f;"
           " largest |v| after the step %.2e\n",
           NX, NY, accel, d->prev.n, sweeps, base / (NX * NY * dt), vmax);
    assert_rel(base, NX * NY * dt, 1e-6);
    assert_true(vmax < 1e-6 * dt);
    gr_particles_free(p);
    gr_sim_free(s);
    gr_scene_free(sc);
    return sweeps;
}

static void tall_pile(void **unused)
{
    (void)unused;
    long plain = pile("none"), fast = pile("momentum");
    assert_true(5 * fast <= plain);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(column_of_disks), cmocka_unit_test(tall_pile)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
