/* Validations 2 and 3: statics solved in one step from a cold start.
 * 2. A column of N frictionless disks (unit mass and diameter, g = 1) on
 *    the floor: the impulse of the contact below the k-th disk from the
 *    top is k m g dt (relative 1e-6 at tol = 1e-10); the sweeps to
 *    converge against N are printed for tol = 1e-6 and 1e-10.
 * 3. A determinate pyramid: frictionless disks in rows with gaps of 0.1 d
 *    (no two disks of a row touch) on a base row of fixed grains lying on
 *    the floor; every contact force matches the recursive static solution
 *    (relative 1e-6) and the base forces sum to the total weight. */
#include "cd_test.h"

static const char *scene_text(double tol)
{
    static char text[512];
    snprintf(text, sizeof text,
             "[domain]\nwidth = 60\nheight = 60\ngravity = 1\n[species]\ncount = 1\n"
             "[cd]\ndt = 1e-3\ntol = %g\nmax_iter = 10000000\nstrict = yes\nwarm_start = no\n", tol);
    return text;
}

static long column(int N, double tol, int check)
{
    gr_scene *sc = ct_scene(scene_text(tol));
    gr_err e = {0};
    gr_particles *p = gr_particles_create((size_t)N, &e);
    for (int k = 0; k < N; k++)
        gr_particles_push(p, 30, 0.5 + k, 0.5, 1.0, 0, 0, &e);
    gr_sim *s = ct_sim(sc, p);
    ct_steps(s, 1);
    /* the floor is wall 2, after the N disks */
    double worst = ct_column_error(ct_state(s), N, N + 2, check);
    long sweeps = (long)ct_counter(s, "iterations");
    printf("# column N = %2d, tol %g: %6ld sweeps, largest relative impulse error %.2e\n", N, tol, sweeps, worst);
    gr_particles_free(p);
    gr_sim_free(s);
    gr_scene_free(sc);
    return sweeps;
}

static void column_of_disks(void **unused)
{
    (void)unused;
    static const int Ns[] = {5, 10, 20, 40};
    for (int k = 0; k < 4; k++) {
        column(Ns[k], 1e-6, 0);
        column(Ns[k], 1e-10, 1);
    }
}

#define ROWS 6
/* Recursive static solution, top down: each disk carries its weight and
 * the pushes of the disks above, balanced by the two normal forces of the
 * disks below (along the lines of centres). f[r][k][0..1]: the forces
 * from its lower-left and lower-right supports. */
static void statics(const double *x, const double *y, int idx[ROWS][ROWS], double f[ROWS][ROWS][2])
{
    double load[ROWS][ROWS][2] = {{{0}}};
    for (int r = ROWS - 1; r >= 1; r--) {
        for (int k = 0; k < ROWS - r; k++) {
            int i = idx[r][k], a = idx[r - 1][k], b = idx[r - 1][k + 1];
            double ax = x[i] - x[a], ay = y[i] - y[a], bx = x[i] - x[b], by = y[i] - y[b];
            double na = hypot(ax, ay), nb = hypot(bx, by);
            ax /= na, ay /= na, bx /= nb, by /= nb;
            double Lx = load[r][k][0], Ly = load[r][k][1] - 1.0; /* weight m g = 1 */
            /* Fa (ax, ay) + Fb (bx, by) = -(Lx, Ly) */
            double det = ax * by - ay * bx;
            double Fa = (-Lx * by + Ly * bx) / det, Fb = (-ax * Ly + ay * Lx) / det;
            f[r][k][0] = Fa, f[r][k][1] = Fb;
            load[r - 1][k][0] -= Fa * ax, load[r - 1][k][1] -= Fa * ay;
            load[r - 1][k + 1][0] -= Fb * bx, load[r - 1][k + 1][1] -= Fb * by;
        }
    }
}

static void pyramid(void **unused)
{
    (void)unused;
    gr_scene *sc = ct_scene(scene_text(1e-10));
    gr_err e = {0};
    gr_particles *p = gr_particles_create(64, &e);
    int idx[ROWS][ROWS];
    double s = 1.1, h = sqrt(1 - 0.25 * s * s);
    for (int r = 0; r < ROWS; r++)
        for (int k = 0; k < ROWS - r; k++)
            idx[r][k] = (int)gr_particles_push(p, 25 + (k + 0.5 * r) * s, 0.5 + r * h, 0.5, 1.0,
                                               r ? 0 : GR_PF_FIXED, 0, &e);
    gr_sim *sim = ct_sim(sc, p);
    ct_steps(sim, 1);
    gr_cd *d = ct_state(sim);
    double f[ROWS][ROWS][2], base = 0, dt = d->par.dt, worst = 0;
    statics(p->x, p->y, idx, f);
    for (int r = 1; r < ROWS; r++) {
        for (int k = 0; k < ROWS - r; k++) {
            for (int side = 0; side < 2; side++) {
                const gr_cd_contact *c = ct_contact(d, idx[r - 1][k + side], idx[r][k]);
                assert_non_null(c);
                assert_rel(c->rn / dt, f[r][k][side], 1e-6);
                worst = fmax(worst, fabs(c->rn / dt / f[r][k][side] - 1));
                if (r == 1)
                    base += -c->rn * c->ny / dt;
            }
        }
    }
    double weight = ROWS * (ROWS - 1) / 2;
    printf("# pyramid of %g disks on %d fixed: base forces sum %.12g (weight %g), largest relative "
           "force error %.2e, %llu sweeps\n",
           weight, ROWS, base, weight, worst, (unsigned long long)ct_counter(sim, "iterations"));
    assert_rel(base, weight, 1e-6);
    gr_particles_free(p);
    gr_sim_free(sim);
    gr_scene_free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(column_of_disks), cmocka_unit_test(pyramid)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
