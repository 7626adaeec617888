/* Validation 6: Janssen saturation in a narrow silo. Polydisperse disks
 * (mu = 0.5 between grains and on the walls, e = 0) settle in a column of
 * width W between vertical walls. With F(y) the vertical force across the
 * level y (the grain-grain contacts with one centre above y and the other
 * below, averaged over a window of steps) and M(y) the mass above it,
 * Janssen in 2D gives, at fill height z = M / (rho W) above the level
 * (rho the areal mass density of the packing),
 *
 *   F = rho g W lambda (1 - exp(-z / lambda)) = g M_l (1 - exp(-M / M_l)),
 *   lambda = W / (2 mu_w K),  M_l = rho W lambda,
 *
 * so a fit of F = A (1 - exp(-M / B)) gives lambda = B / (rho W) and K
 * (A = g B is Janssen's premise that a shallow fill is carried by its base,
 * printed as a check). The floor is lowered by 0.05 d first, so the
 * walls' friction is mobilised upwards. Asserted: the fit converges, the
 * base of the tall column (mean over the seeds) carries less than 0.7 of
 * the weight with friction, and all of it (to 1e-3, the window's momentum
 * change) without friction, across every level too. The quick variant
 * (suite 'method') is one column of 6 d with 150 grains; the slow one
 * (suite 'slow') four seeds of a 10 d column of 600 grains.
 */
#include "cd_test.h"

#include <math.h>
#include <time.h>

#include "stats.h"

#define NLEV 24
#define WINDOW 100

static gr_scene *column_scene(double W, long n, double mu, int seed)
{
    double hfill = 2.5 * (double)n / W; /* loose random spots: packing ~0.3 */
    char text[1024];
    snprintf(text, sizeof text,
             "[scene]\nseed = %d\n[domain]\nwidth = %g\nheight = %g\ngravity = 1\n"
             "[material]\n%s\nmu = %g\nrestitution = 0\n"
             "[species]\ncount = %ld\npolydispersity = 0.2\n"
             "[init]\nkind = random\nregion = 0 0 %g %g\n"
             "[cd]\ndt = 2e-3\ntol = 1e-3\nmax_iter = 5000\n",
             seed, W, hfill + 5, mu > 0 ? "tangential = coulomb" : "; frictionless", mu, n, W, hfill);
    return ct_scene(text);
}

/* Lower the floor (wall 2) by `depth` over `steps` steps and let the
 * column follow: every grain then slides down along the walls, so their
 * friction is mobilised upwards as Janssen assumes. A packing of rigid
 * grains settled from a pour leaves it indeterminate (in a first try the
 * walls pulled the middle of the column down by 17% of its weight). */
static void lower_floor(gr_sim *s, double depth, long steps)
{
    gr_cd *d = ct_state(s);
    for (long k = 0; k < steps; k++) {
        d->wall[2].y0 -= depth / (double)steps, d->wall[2].y1 -= depth / (double)steps;
        ct_steps(s, 1);
    }
    ct_steps(s, 250);
}

/* Settled: advanced until the kinetic energy per grain is below 1e-8
 * (checked every tau), then the floor lowered at tol 1e-5. */
static void settle(gr_sim *s)
{
    gr_err e = {0};
    gr_obs o;
    double t = 0;
    do {
        t += 1.0;
        assert_int_equal(gr_sim_advance(s, t, 0, &e), GR_OK);
        assert_int_equal(gr_sim_observe(s, &o, &e), GR_OK);
    } while ((o.ekin_trans + o.ekin_rot) / o.n_mobile > 1e-8 && t < 200);
    assert_true(t < 200);
    ct_state(s)->par.tol = 1e-5;
    /* without friction the walls carry nothing: no need to mobilise it */
    if (ct_state(s)->mu > 0)
        lower_floor(s, 0.05, 500);
    else
        ct_steps(s, 250);
}

/* The vertical force on the grains above each level across it (F), and the
 * base force (floor: wall 2), summed over this step's contacts. */
static void add_forces(const gr_cd *d, const double *lev, double *F, double *Fw, double *base)
{
    const gr_particles *p = d->p;
    for (size_t k = 0; k < d->prev.n; k++) {
        const gr_cd_contact *c = &d->prev.c[k];
        double fy = (c->rn * c->ny + c->rt * c->nx) / d->par.dt; /* on i */
        if ((size_t)c->j == d->n + 2)
            *base += fy;
        if ((size_t)c->j >= d->n) {
            for (int l = 0; l < NLEV; l++)
                Fw[l] += p->y[c->i] > lev[l] ? fy : 0.0;
            continue;
        }
        double yi = p->y[c->i], yj = p->y[c->j];
        for (int l = 0; l < NLEV; l++)
            F[l] += yi > lev[l] && yj <= lev[l] ? fy : yj > lev[l] && yi <= lev[l] ? -fy : 0.0;
    }
}

typedef struct {
    double weight, base;   /* total weight, base force */
    double M[NLEV], F[NLEV], Fw[NLEV];
    double rho, top;       /* areal mass density in the bulk, highest centre */
} column_res;

static void measure(gr_sim *s, double W, column_res *r)
{
    gr_cd *d = ct_state(s);
    const gr_particles *p = d->p;
    *r = (column_res){0};
    double lev[NLEV], bulk = 0;
    for (size_t i = 0; i < p->n; i++)
        r->top = fmax(r->top, p->y[i]), r->weight += p->mass[i] * d->g;
    for (int l = 0; l < NLEV; l++)
        lev[l] = 1.0 + (r->top - 3.0) * l / (NLEV - 1);
    for (size_t i = 0; i < p->n; i++) {
        for (int l = 0; l < NLEV; l++)
            r->M[l] += p->y[i] > lev[l] ? p->mass[i] : 0.0;
        bulk += p->y[i] > 2 && p->y[i] < r->top - 3 ? p->mass[i] : 0.0;
    }
    r->rho = bulk / (W * (r->top - 5));
    for (int k = 0; k < WINDOW; k++) {
        ct_steps(s, 1);
        add_forces(d, lev, r->F, r->Fw, &r->base);
    }
    for (int l = 0; l < NLEV; l++)
        r->F[l] /= WINDOW, r->Fw[l] /= WINDOW;
    r->base /= WINDOW;
}

static double sat_model(double x, const double *p, double *dydp, void *user)
{
    (void)dydp, (void)user;
    return p[0] * (1 - exp(-x / p[1]));
}

/* Fit F = A (1 - exp(-M / B)); lambda and K from B. */
static void janssen_fit(const double *M, const double *F, size_t n, double W, double rho, double mu,
                        double *lambda, double *K)
{
    gr_model m = {"Janssen saturation", 2, sat_model, 0, NULL, {"A", "B"}};
    double p0[2] = {F[0], M[0] / 2};
    gr_fit f;
    gr_err e = {0};
    if (gr_fit_nlin(&m, M, F, NULL, n, p0, NULL, &f, &e))
        print_error("fit: %s\n", e.msg);
    assert_int_equal(e.code, GR_OK);
    *lambda = f.p[1] / (rho * W);
    *K = W / (2 * mu * *lambda);
    printf("# fit F = A (1 - exp(-M/B)): A = %.4g +- %.2g, B = %.4g +- %.2g (A/(g B) = %.3f), chi2/dof %.3g\n",
           f.p[0], f.err[0], f.p[1], f.err[1], f.p[0] / f.p[1], f.chi2_dof);
    printf("# lambda = B / (rho W) = %.3f d = %.3f W;  K = W / (2 mu lambda) = %.3f\n", *lambda, *lambda / W, *K);
}

/* One settled column per seed, the forces averaged over the seeds. */
static void run_columns(double W, long n, double mu, int nseed, column_res *r)
{
    column_res one;
    for (int k = 0; k < nseed; k++) {
        gr_scene *sc = column_scene(W, n, mu, 3 + k);
        gr_sim *s = ct_sim(sc, NULL);
        settle(s);
        measure(s, W, &one);
        printf("# column W = %g, %ld grains, mu = %g, seed %d: fill height %.2f d, rho %.4f, base force / weight %.5f\n",
               W, n, mu, 3 + k, one.top, one.rho, one.base / one.weight);
        if (mu == 0) {
            /* all the weight on the base, and across every level */
            assert_rel(one.base, one.weight, 1e-3);
            for (int l = 0; l < NLEV; l++)
                assert_rel(one.F[l], one.M[l], 1e-3);
        }
        double *acc = (double *)r, *add = (double *)&one;
        for (size_t i = 0; i < sizeof *r / sizeof(double); i++)
            acc[i] = k ? acc[i] + add[i] / nseed : add[i] / nseed;
        gr_sim_free(s);
        gr_scene_free(sc);
    }
}

static void column(double W, long n, int nseed)
{
    clock_t t0 = clock();
    column_res r;
    run_columns(W, n, 0.0, 1, &r);
    run_columns(W, n, 0.5, nseed, &r);
    printf("# mean of %d: base force / weight %.4f\n", nseed, r.base / r.weight);
    for (int l = 0; l < NLEV; l++)
        printf("#   z = %6.2f  M = %8.3f  F = %8.3f  F/(gM) = %.4f  walls %.4f\n", r.M[l] / (r.rho * W), r.M[l],
               r.F[l], r.F[l] / r.M[l], r.Fw[l] / r.M[l]);
    double lambda, K;
    janssen_fit(r.M, r.F, NLEV, W, r.rho, 0.5, &lambda, &K);
    assert_true(lambda > 0 && K > 0 && isfinite(K));
    assert_true(r.base < 0.7 * r.weight);
    printf("# %.1f s CPU\n", (double)(clock() - t0) / CLOCKS_PER_SEC);
}

static void janssen_quick(void **unused)
{
    (void)unused;
    column(6, 150, 1);
}

static void janssen_slow(void **unused)
{
    (void)unused;
    column(10, 600, 4);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest quick[] = {cmocka_unit_test(janssen_quick)};
    const struct CMUnitTest slow[] = {cmocka_unit_test(janssen_slow)};
    if (argc > 1 && !strcmp(argv[1], "slow"))
        return cmocka_run_group_tests(slow, NULL, NULL);
    return cmocka_run_group_tests(quick, NULL, NULL);
}
