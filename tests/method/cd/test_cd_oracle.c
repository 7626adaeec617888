/* The Siconos oracle (tests/oracle/fc2d.h) against cd's own Gauss-Seidel on
 * the local problems cd meets, exported densely by gr_cd_local_export.
 *
 * 1. Random packings: 30 to 80 polydisperse disks (polydispersity 0.2) with
 *    mu from 0.2 to 0.8 settle in a box; at one step cd solves cold to
 *    tol 1e-10 and fc2d_nsgs_dense solves the exported problem to the same
 *    tol. Both residuals (gr_fc2d_residual, the solver-independent natural
 *    map) must be below 1e-6. Frictional packings are hyperstatic: their
 *    impulses r are not unique, so what is compared is what is unique: the
 *    local velocities u = W r + q (to 1e-6 of the velocity scale max |q|)
 *    and the total impulse on each body, H^T r (to 1e-6 of the largest).
 * 2. An isostatic case, the frictionless determinate pyramid of
 *    validation 3 (15 disks on 6 fixed): W is non-singular on the normal
 *    rows and r_t = 0, so r itself is unique and compared (to 1e-6 of the
 *    largest impulse).
 * The exported problem keeps the contacts whose predicted gap closes
 * (Jean's rule, docs/methods/cd.md): the others carry no impulse in cd and
 * are outside the velocity-level problem Siconos solves. Prints the
 * measured agreement (docs/methods/cd.md quotes it). */
#include "cd_test.h"

#include "fc2d.h"

#define TOL 1e-10
#define BOUND 1e-6

typedef struct {
    int nc;
    double res_cd, res_sic, du, dbody, dr;
    long sweeps;
    int sic_iter;
} agreement;

/* Total impulse (x, y, angular) on each grain from impulses r. */
static double *body_impulses(const gr_cd *d, const gr_cd_local *lp, const double *r)
{
    double *b = calloc(3 * d->n, sizeof *b);
    assert_non_null(b);
    for (int a = 0; a < lp->nc; a++) {
        const gr_cd_contact *c = &d->cur.c[lp->k[a]];
        double rn = r[2 * a], rt = r[2 * a + 1];
        double px = rn * c->nx - rt * c->ny, py = rn * c->ny + rt * c->nx;
        size_t i = (size_t)c->i, j = (size_t)c->j;
        b[3 * i] += px, b[3 * i + 1] += py, b[3 * i + 2] -= d->p->radius[i] * rt;
        if (j < d->n)
            b[3 * j] -= px, b[3 * j + 1] -= py, b[3 * j + 2] -= d->p->radius[j] * rt;
    }
    return b;
}

static double max_diff(size_t n, const double *a, const double *b, double *scale)
{
    double m = 0, s = 0;
    for (size_t k = 0; k < n; k++)
        m = fmax(m, fabs(a[k] - b[k])), s = fmax(s, fmax(fabs(a[k]), fabs(b[k])));
    if (scale)
        *scale = s;
    return m;
}

/* u = W r + q */
static void local_u(const gr_cd_local *lp, const double *r, double *u)
{
    size_t n2 = 2 * (size_t)lp->nc;
    for (size_t i = 0; i < n2; i++) {
        u[i] = lp->q[i];
        for (size_t j = 0; j < n2; j++)
            u[i] += lp->W[i * n2 + j] * r[j];
    }
}

/* One step's start, cd's cold solve, the export, Siconos, and the gaps. */
static agreement compare(gr_cd *d)
{
    gr_err e = {0};
    agreement ag = {0};
    gr_cd_solve_info si;
    d->par.tol = TOL;
    d->par.max_iter = 10000000;
    assert_int_equal(gr_cd_begin(d, &e), GR_OK);
    assert_int_equal(gr_cd_solve(d, &si, &e), GR_OK);
    assert_true(si.converged);
    gr_cd_local lp;
    assert_int_equal(gr_cd_local_export(d, 1, &lp, &e), GR_OK);
    int nc = lp.nc;
    size_t n2 = 2 * (size_t)nc;
    assert_true(nc > 0);
    double *rs = malloc(n2 * sizeof *rs), *us = malloc(n2 * sizeof *us), *uc = malloc(n2 * sizeof *uc);
    assert_true(rs && us && uc);
    gr_fc2d_stats st;
    if (gr_fc2d_solve(nc, lp.W, lp.q, lp.mu, TOL, 1000000, rs, us, &st, &e))
        fail_msg("siconos: %s", e.msg);
    gr_fc2d_res rc, rsic;
    assert_int_equal(gr_fc2d_residual(nc, lp.W, lp.q, lp.mu, lp.r, NULL, &rc, &e), GR_OK);
    assert_int_equal(gr_fc2d_residual(nc, lp.W, lp.q, lp.mu, rs, NULL, &rsic, &e), GR_OK);
    local_u(&lp, lp.r, uc);
    local_u(&lp, rs, us);
    double vscale = 0, bscale, rscale;
    for (size_t k = 0; k < n2; k++)
        vscale = fmax(vscale, fabs(lp.q[k]));
    double *bc = body_impulses(d, &lp, lp.r), *bs = body_impulses(d, &lp, rs);
    ag = (agreement){nc, rc.total, rsic.total, max_diff(n2, uc, us, NULL) / vscale,
                     max_diff(3 * d->n, bc, bs, &bscale), max_diff(n2, lp.r, rs, &rscale), si.sweeps,
                     st.iterations};
    ag.dbody /= bscale, ag.dr /= rscale;
    free(bc), free(bs), free(rs), free(us), free(uc);
    gr_cd_local_free(&lp);
    return ag;
}

static void random_packings(void **unused)
{
    (void)unused;
    static const int ns[] = {30, 45, 60, 80};
    static const double mus[] = {0.2, 0.4, 0.6, 0.8};
    for (int k = 0; k < 4; k++) {
        char text[768];
        double w = 8 + 0.05 * ns[k];
        snprintf(text, sizeof text,
                 "[scene]\nseed = %d\n[domain]\nwidth = %g\nheight = 40\ngravity = 1\n"
                 "[material]\ntangential = coulomb\nmu = %g\n"
                 "[species]\ncount = %d\npolydispersity = 0.2\n"
                 "[init]\nkind = random\nregion = 0 0 %g 30\n"
                 "[cd]\ndt = 2e-3\ntol = 1e-3\nmax_iter = 5000\n",
                 11 + k, w, mus[k], ns[k], w);
        gr_scene *sc = ct_scene(text);
        gr_sim *s = ct_sim(sc, NULL);
        gr_err e = {0};
        assert_int_equal(gr_sim_advance(s, 10.0, 0, &e), GR_OK);
        agreement ag = compare(ct_state(s));
        printf("# packing n = %d, mu = %.1f: %d closed contacts; residual cd %.2e (%ld sweeps), siconos %.2e "
               "(%d sweeps); max |du|/max|q| %.2e, max |d(H^T r)|/max %.2e, max |dr|/max %.2e (not unique)\n",
               ns[k], mus[k], ag.nc, ag.res_cd, ag.sweeps, ag.res_sic, ag.sic_iter, ag.du, ag.dbody, ag.dr);
        assert_true(ag.res_cd < BOUND && ag.res_sic < BOUND);
        assert_true(ag.du < BOUND);
        assert_true(ag.dbody < BOUND);
        gr_sim_free(s);
        gr_scene_free(sc);
    }
}

/* Validation 3's pyramid: rows of 5..1 disks, gaps 0.1 d, on 6 fixed. */
static void isostatic_pyramid(void **unused)
{
    (void)unused;
    gr_scene *sc = ct_scene("[domain]\nwidth = 60\nheight = 60\ngravity = 1\n[species]\ncount = 1\n"
                            "[cd]\ndt = 1e-3\nwarm_start = no\n");
    gr_err e = {0};
    gr_particles *p = gr_particles_create(64, &e);
    double s = 1.1, h = sqrt(1 - 0.25 * s * s);
    for (int r = 0; r < 6; r++)
        for (int k = 0; k < 6 - r; k++)
            assert_true(gr_particles_push(p, 25 + (k + 0.5 * r) * s, 0.5 + r * h, 0.5, 1.0,
                                          r ? 0 : GR_PF_FIXED, 0, &e) >= 0);
    gr_sim *sim = ct_sim(sc, p);
    agreement ag = compare(ct_state(sim));
    printf("# pyramid (isostatic, frictionless): %d contacts; residual cd %.2e (%ld sweeps), siconos %.2e "
           "(%d sweeps); max |dr|/max %.2e, max |du|/max|q| %.2e\n",
           ag.nc, ag.res_cd, ag.sweeps, ag.res_sic, ag.sic_iter, ag.dr, ag.du);
    assert_int_equal(ag.nc, 30);
    assert_true(ag.res_cd < BOUND && ag.res_sic < BOUND);
    assert_true(ag.dr < BOUND);
    gr_sim_free(sim);
    gr_particles_free(p);
    gr_scene_free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(random_packings), cmocka_unit_test(isostatic_pyramid)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
