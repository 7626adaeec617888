/* Physics of lgca against exact and analytic results (fast variants; the
 * slow suite repeats the viscosity at more densities):
 *  - p = g = 0, periodic: mass and momentum exact at every step, both rule
 *    sets, 1 and 2 threads;
 *  - granular, p > 0: the moving population decays, mass and momentum exact;
 *  - equilibrium: from movers only, every channel (rest included) relaxes
 *    to the same Fermi-Dirac occupation d = mass / 7 per node, within 1.5 %;
 *  - sound speed sqrt(3/7) from a standing density wave, within 2 %;
 *  - shear viscosity from the decay of a shear wave against Frisch et al.'s
 *    FHP-III Boltzmann formula, within 3 % at d = 1/2; the slow suite
 *    (test_lgca_viscosity) covers other densities, wavelengths and the
 *    Poiseuille flow;
 *  - the pipe's density waves appear with dissipation (short run). */
#include "lgca_pipe.h"
#include "lgca_visc.h"

#include <stdlib.h>
#include <string.h>

static double uniform(int k, double x, double y, void *ctx)
{
    (void)x, (void)y;
    const double *d = ctx;
    return k == LGCA_REST ? d[1] : d[0];
}

/* A periodic nx x ny lattice with uniform occupations. */
static gr_sim *uniform_lattice(int nx, int ny, const char *extra, double moving, double rest,
                               uint64_t seed, gr_scene **sc, lgca **L)
{
    char text[1024];
    lgca_periodic_text(text, sizeof text, nx, ny, extra);
    gr_sim *s = lgca_make(text, sc);
    *L = gr_sim_state(s);
    double d[2] = {moving, rest};
    lgca_fill(*L, uniform, d, seed);
    return s;
}

/* One step, after which mass and momentum are what they were. */
static void step_exactly(gr_sim *s, const lgca *L)
{
    int64_t m0, x0, y0, m, x, y;
    gr_err e = {0};
    lgca_totals(L, &m0, &x0, &y0);
    assert_int_equal(gr_sim_step(s, &e), GR_OK);
    lgca_totals(L, &m, &x, &y);
    assert_true(m == m0 && x == x0 && y == y0);
}

static void conservation_exact(void **unused)
{
    (void)unused;
    const char *variants[] = {"rules = fhp3\n", "rules = granular\n", "rules = fhp3\nthreads = 2\n",
                              "rules = granular\nthreads = 2\n", "rules = granular\np = 0.3\nstop = 0.5\nthreads = 2\n"};
    for (size_t v = 0; v < sizeof variants / sizeof variants[0]; v++) {
        gr_scene *sc;
        lgca *L;
        gr_sim *s = uniform_lattice(96, 70, variants[v], 0.35, 0.2, 3 + v, &sc, &L);
        /* a net flow, so that momentum is not zero by symmetry */
        for (int j = 0; j < L->nj; j++)
            for (int i = 0; i < L->ni; i += 3)
                lgca_put(L, i, j, 1, 1);
        int64_t m0, x0, y0;
        lgca_totals(L, &m0, &x0, &y0);
        assert_true(x0 != 0 && y0 != 0);
        for (int k = 0; k < 60; k++)
            step_exactly(s, L);
        lgca_drop(s, sc);
    }
}

static void granular_decay(void **unused)
{
    (void)unused;
    gr_scene *sc;
    lgca *L;
    gr_sim *s = uniform_lattice(96, 96, "rules = granular\np = 0.5\n", 0.3, 0, 9, &sc, &L);
    int64_t m0, x0, y0;
    lgca_totals(L, &m0, &x0, &y0);
    uint64_t mov0, rest0, mov, rest, prev;
    lgca_populations(L, &mov0, &rest0);
    prev = mov0;
    for (int k = 0; k < 200; k++) {
        step_exactly(s, L);
        lgca_populations(L, &mov, &rest);
        assert_true(mov <= prev); /* nothing sets a rest particle moving */
        prev = mov;
    }
    printf("# granular p = 0.5: moving %llu -> %llu of %lld\n", (unsigned long long)mov0,
           (unsigned long long)mov, (long long)m0);
    assert_true(mov < mov0 / 2);
    lgca_drop(s, sc);
}

static void fermi_dirac_equilibrium(void **unused)
{
    (void)unused;
    gr_scene *sc;
    lgca *L;
    gr_sim *s = uniform_lattice(256, 256, "rules = fhp3\n", 0.3, 0, 4, &sc, &L);
    int64_t m0, x0, y0;
    lgca_totals(L, &m0, &x0, &y0);
    double nodes = (double)L->ni * L->nj, want = (double)m0 / (7 * nodes), occ[LGCA_CH] = {0};
    gr_err e = {0};
    assert_int_equal(gr_sim_advance(s, 100, 0, &e), GR_OK);
    for (int k = 0; k < 50; k++) {
        assert_int_equal(gr_sim_step(s, &e), GR_OK);
        for (int c = 0; c < LGCA_CH; c++)
            for (int j = 0; j < L->nj; j++)
                for (int w = 0; w < L->nw; w++)
                    occ[c] += __builtin_popcountll(L->lane[j][(size_t)c * L->nw + w]) / (50 * nodes);
    }
    for (int c = 0; c < LGCA_CH; c++) {
        printf("# channel %d: occupation %.5f, Fermi-Dirac at zero flow %.5f\n", c, occ[c], want);
        assert_rel(occ[c], want, 0.015);
    }
    lgca_drop(s, sc);
}

typedef struct {
    double d, eps, k;
} wave;

static double density_wave(int c, double x, double y, void *ctx)
{
    (void)c, (void)x;
    const wave *w = ctx;
    return w->d * (1 + w->eps * cos(w->k * y));
}

/* Projection of the density on cos(k y). */
static double mode_cos(const lgca *L, double k)
{
    double a = 0;
    for (int j = 0; j < L->nj; j++)
        for (int i = 0; i < L->ni; i++) {
            int n = 0;
            for (int c = 0; c < LGCA_CH; c++)
                n += lgca_get(L, i, j, c);
            double x, y;
            lgca_node_xy(L, i, j, &x, &y);
            a += n * cos(k * y);
        }
    return a;
}

static void sound_speed(void **unused)
{
    (void)unused;
    char text[1024];
    int ny = 128;
    lgca_periodic_text(text, sizeof text, 256, ny, "rules = fhp3\n");
    gr_scene *sc;
    gr_sim *s = lgca_make(text, &sc);
    lgca *L = gr_sim_state(s);
    wave w = {0.25, 0.3, 2 * M_PI / ny};
    lgca_fill(L, density_wave, &w, 6);
    gr_err e = {0};
    double prev = mode_cos(L, w.k), first = NAN, last = NAN;
    int crossings = 0;
    for (int t = 1; t <= 420; t++) {
        assert_int_equal(gr_sim_step(s, &e), GR_OK);
        double a = mode_cos(L, w.k);
        if ((a < 0) != (prev < 0)) {
            double tc = t - 1 + prev / (prev - a);
            if (!crossings)
                first = tc;
            last = tc;
            crossings++;
        }
        prev = a;
    }
    /* zero crossings every half period T/2 = pi / (c_s k) */
    double half = (last - first) / (crossings - 1), cs = M_PI / (half * w.k);
    printf("# %d zero crossings, half period %.3f steps: c_s = %.5f, sqrt(3/7) = %.5f\n", crossings, half,
           cs, sqrt(3.0 / 7));
    assert_true(crossings >= 3);
    assert_rel(cs, sqrt(3.0 / 7), 0.02);
    lgca_drop(s, sc);
}

/* The Boltzmann formula holds at d = 1/2, where the model's nonlinear
 * coupling g(rho) vanishes; elsewhere the 2D long-time tail adds a term
 * growing with ln(wavelength) (suite slow, test_lgca_viscosity). */
static void shear_viscosity(void **unused)
{
    (void)unused;
    double d = 0.5, nu = lgca_shear_viscosity(d, 16384, 32, 0.1, 12, 250, 1);
    printf("# d = %.2f, wavelength 32 a: nu = %.5f, Frisch et al. %.5f (%+.1f %%)\n", d, nu, lgca_frisch_nu(d),
           100 * (nu / lgca_frisch_nu(d) - 1));
    assert_rel(nu, lgca_frisch_nu(d), 0.03);
}

/* The pipe's density waves, short (test_lgca_pipe has the long runs):
 * with the rest collision the long-wave contrast of the density is large,
 * without dissipation it stays near 1. */
static void pipe_waves(void **unused)
{
    (void)unused;
    lgca_pipe q = {0.2, 0.005, 0.3, 1, 0.3, 16, 1024, 1500, 4096};
    double on = lgca_pipe_run(&q, NULL);
    q.p = q.stop = 0;
    double off = lgca_pipe_run(&q, NULL);
    printf("# pipe: long-wave contrast %.1f with p = stop = 0.3, %.2f without\n", on, off);
    assert_true(on > 30 && off < 3);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(conservation_exact), cmocka_unit_test(granular_decay),
        cmocka_unit_test(fermi_dirac_equilibrium), cmocka_unit_test(sound_speed),
        cmocka_unit_test(shear_viscosity), cmocka_unit_test(pipe_waves),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
