/* The Siconos oracle against analytic one-contact solutions, then on
 * random dense disk packings judged by the solver-independent residual. */
#include "test.h"

#include <stdint.h>
#include <stdlib.h>

#include "fc2d.h"

/* One contact, W = diag(A, B), MU: every regime has a closed form. */
#define A 2.0
#define B 0.5
#define MU 0.4

static void solve1(double qn, double qt, double *r, double *u)
{
    double W[4] = {A, 0, 0, B}, q[2] = {qn, qt}, mu[1] = {MU};
    gr_fc2d_stats st;
    gr_err e = {0};
    assert_int_equal(gr_fc2d_solve(1, W, q, mu, 1e-12, 100, r, u, &st, &e), GR_OK);
    /* One local solve is exact, so the first sweep already satisfies
     * W r + q = v. */
    assert_int_equal(st.iterations, 1);
    assert_true(st.nsgs_error <= 1e-15);
    assert_true(st.siconos_error <= 1e-15);
    gr_fc2d_res res;
    assert_int_equal(gr_fc2d_residual(1, W, q, mu, r, u, &res, &e), GR_OK);
    assert_true(res.total <= 1e-15);
}

/* Exact up to one rounding of values of order 1. */
#define assert_pair(x, a, b)            \
    do {                                \
        assert_close((x)[0], (a), 1e-15); \
        assert_close((x)[1], (b), 1e-15); \
    } while (0)

static void one_contact_regimes(void **s)
{
    (void)s;
    double r[2], u[2];
    solve1(0.3, -1.2, r, u); /* open: q_n >= 0 */
    assert_pair(r, 0, 0);
    assert_pair(u, 0.3, -1.2);
    solve1(-1, 0.05, r, u); /* stick: |q_t / B| = 0.1 <= MU (-q_n / A) = 0.2 */
    assert_pair(r, 0.5, -0.1);
    assert_pair(u, 0, 0);
    solve1(-1, 2, r, u); /* slides forward: r_t = -MU r_n */
    assert_pair(r, 0.5, -MU * 0.5);
    assert_pair(u, 0, 2 - B * MU * 0.5);
    solve1(-1, -2, r, u); /* slides backward: r_t = +MU r_n */
    assert_pair(r, 0.5, MU * 0.5);
    assert_pair(u, 0, -2 + B * MU * 0.5);
}

/* The residual must see wrong answers: the stick impulse where the contact
 * slides, friction with the wrong sign, an impulse on an open contact. */
static void residual_rejects(void **s)
{
    (void)s;
    double W[4] = {A, 0, 0, B}, mu[1] = {MU};
    double q[2] = {-1, 2}, stick[2] = {0.5, -4}, flip[2] = {0.5, 0.2}, good[2] = {0.5, -0.2};
    gr_fc2d_res res;
    gr_err e = {0};
    assert_int_equal(gr_fc2d_residual(1, W, q, mu, good, NULL, &res, &e), GR_OK);
    assert_true(res.total <= 1e-15);
    assert_int_equal(gr_fc2d_residual(1, W, q, mu, stick, NULL, &res, &e), GR_OK);
    assert_true(res.cone > 0.1);
    assert_int_equal(gr_fc2d_residual(1, W, q, mu, flip, NULL, &res, &e), GR_OK);
    assert_true(res.cone > 0.1);
    double qo[2] = {0.3, 0}, push[2] = {0.2, 0};
    assert_int_equal(gr_fc2d_residual(1, W, qo, mu, push, NULL, &res, &e), GR_OK);
    assert_true(res.cone > 0.1);
    /* A u inconsistent with W r + q counts too. */
    double ubad[2] = {0.1, 1.9};
    assert_int_equal(gr_fc2d_residual(1, W, q, mu, good, ubad, &res, &e), GR_OK);
    assert_close(res.eq, (0.1 / A) / (sqrt(5.0) / A), 1e-15); /* s = ||rho q|| here */
    double Wa[4] = {A, 0.1, 0, B};
    assert_int_equal(gr_fc2d_residual(1, Wa, q, mu, good, NULL, &res, &e), GR_EINPUT);
}

/* splitmix64: the test owns its stream, independent of common's table. */
static uint64_t sm_state;
static double unif(void)
{
    uint64_t z = (sm_state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return (double)((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
}

typedef struct {
    int nc;
    double *W, *q, *mu;
} problem;

#define SIDE 6
#define ND (SIDE * SIDE)

/* Disks of radius ~1 on a jittered triangular lattice of spacing 2: about
 * half the neighbour pairs overlap and are contacts.  H maps the disks'
 * (vx, vy, w) to the contacts' (u_n, u_t); W = H M^-1 H^T couples contacts
 * sharing a disk while each 2x2 diagonal block stays diagonal (W_nt = 0).
 * q = H v for random velocities plus a uniform compression. */
static problem disk_problem(uint64_t seed)
{
    sm_state = seed;
    double x[ND][2], rad[ND], v[3 * ND];
    for (int k = 0; k < ND; k++) {
        int i = k % SIDE, j = k / SIDE;
        x[k][0] = 2.0 * i + (j % 2) + 0.08 * (unif() - 0.5);
        x[k][1] = sqrt(3.0) * j + 0.08 * (unif() - 0.5);
        rad[k] = 1 + 0.02 * (unif() - 0.5);
    }
    for (int k = 0; k < ND; k++) {
        v[3 * k] = unif() - 0.5 - 0.3 * (x[k][0] - SIDE);
        v[3 * k + 1] = unif() - 0.5 - 0.3 * (x[k][1] - SIDE * 0.85);
        v[3 * k + 2] = (unif() - 0.5) / rad[k];
    }
    int cap = 3 * ND, nc = 0, pair[3 * ND][2];
    for (int a = 0; a < ND; a++)
        for (int b = a + 1; b < ND && nc < cap; b++)
            if (hypot(x[b][0] - x[a][0], x[b][1] - x[a][1]) < rad[a] + rad[b]) {
                pair[nc][0] = a;
                pair[nc][1] = b;
                nc++;
            }
    size_t n = 2 * (size_t)nc, m = 3 * ND;
    double *H = calloc(n * m, sizeof *H);
    problem p = {nc, calloc(n * n, sizeof(double)), calloc(n, sizeof(double)),
                 calloc((size_t)nc, sizeof(double))};
    assert_non_null(H);
    assert_non_null(p.W);
    for (int c = 0; c < nc; c++) {
        int a = pair[c][0], b = pair[c][1];
        double dx = x[b][0] - x[a][0], dy = x[b][1] - x[a][1], d = hypot(dx, dy);
        double nx = dx / d, ny = dy / d, tx = -ny, ty = nx;
        double *hn = H + 2 * c * m, *ht = hn + m;
        hn[3 * a] = -nx, hn[3 * a + 1] = -ny, hn[3 * b] = nx, hn[3 * b + 1] = ny;
        ht[3 * a] = -tx, ht[3 * a + 1] = -ty, ht[3 * a + 2] = -rad[a];
        ht[3 * b] = tx, ht[3 * b + 1] = ty, ht[3 * b + 2] = -rad[b];
        p.mu[c] = 0.1 + 0.7 * unif();
    }
    for (size_t i = 0; i < n; i++) {
        for (size_t k = 0; k < m; k++)
            p.q[i] += H[i * m + k] * v[k];
        for (size_t j = 0; j < n; j++)
            for (size_t k = 0; k < m; k++) {
                double r = rad[k / 3], mass = M_PI * r * r;
                double inv = k % 3 == 2 ? 2 / (mass * r * r) : 1 / mass;
                p.W[i * n + j] += H[i * m + k] * inv * H[j * m + k];
            }
    }
    free(H);
    return p;
}

static void random_packings(void **s)
{
    (void)s;
    const double tol = 1e-10;
    for (uint64_t seed = 1; seed <= 3; seed++) {
        problem p = disk_problem(seed);
        assert_in_range(p.nc, 20, 50);
        size_t n = 2 * (size_t)p.nc;
        double *r = malloc(n * sizeof *r), *u = malloc(n * sizeof *u);
        gr_fc2d_stats st;
        gr_fc2d_res res;
        gr_err e = {0};
        int rc = gr_fc2d_solve(p.nc, p.W, p.q, p.mu, tol, 100000, r, u, &st, &e);
        if (rc)
            print_error("%s\n", e.msg);
        assert_int_equal(rc, GR_OK);
        assert_int_equal(gr_fc2d_residual(p.nc, p.W, p.q, p.mu, r, u, &res, &e), GR_OK);
        int open = 0, stick = 0, slide = 0;
        for (int c = 0; c < p.nc; c++) {
            double rn = r[2 * c], rt = r[2 * c + 1];
            open += rn <= 0;
            slide += rn > 0 && fabs(fabs(rt) - p.mu[c] * rn) <= 1e-9 * rn;
            stick += rn > 0 && fabs(fabs(rt) - p.mu[c] * rn) > 1e-9 * rn;
        }
        print_message("# seed %d: %d contacts (%d open, %d stick, %d slide), %d sweeps, %.3f ms, "
                      "nsgs error %.2e, fc2d_compute_error %.2e, residual cone %.2e eq %.2e\n",
                      (int)seed, p.nc, open, stick, slide, st.iterations, 1e3 * st.seconds,
                      st.nsgs_error, st.siconos_error, res.cone, res.eq);
        assert_true(st.nsgs_error <= tol);
        /* Not a theorem: NSGS stops on ||W r + q - v|| / ||q||, which bounds
         * the natural map only up to a factor of order (1 + mu) rho ||q|| / s;
         * measured 0.5-0.6 tol on these seeds. */
        assert_true(res.total <= tol);
        free(r);
        free(u);
        free(p.W);
        free(p.q);
        free(p.mu);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(one_contact_regimes),
        cmocka_unit_test(residual_rejects),
        cmocka_unit_test(random_packings),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
