/* Measurements against published numbers and exact identities: the
 * hard-disk equation of state, Haff's law against the Enskog cooling rate,
 * the fields on the cells, and bit-for-bit checkpoint restarts. */
#include "test.h"

#include <gsl/gsl_randist.h>
#include <stdlib.h>
#include <unistd.h>

#include "ckpt.h"
#include "edmd_int.h"
#include "edmd_test.h"

static gr_edmd *make(const gr_scene *sc, const gr_particles *p, const gr_edmd_params *prm)
{
    gr_err e = {0};
    gr_edmd *s = NULL;
    int rc = gr_edmd_create(sc, p, prm, NULL, &s, &e);
    if (rc)
        fprintf(stderr, "create: %s\n", e.msg);
    assert_int_equal(rc, GR_OK);
    return s;
}

/* Henderson, Mol. Phys. 30, 971 (1975): Z = (1 + eta^2/8) / (1 - eta)^2. */
static double z_henderson(double eta) { return (1 + eta * eta / 8) / ((1 - eta) * (1 - eta)); }
/* Luding, Phys. Rev. E 63, 042201 (2001): Henderson's contact value with a
 * correction, g4 = (1 - 7 eta/16) / (1 - eta)^2 - eta^3 / (128 (1 - eta)^4),
 * and Z = 1 + 2 eta g4. */
static double chi_luding(double eta)
{
    double u = 1 - eta;
    return (1 - 7 * eta / 16) / (u * u) - eta * eta * eta / (128 * u * u * u * u);
}
static double z_luding(double eta) { return 1 + 2 * eta * chi_luding(eta); }

/* Elastic disks in a periodic box: Z = P A / (N T) from the collisional
 * virial, at packing fractions 0.1 ... 0.6, within 1 % of Luding's equation
 * of state (Henderson's is printed beside it: it overestimates by 1 % at
 * 0.6, where the virial series of Clisby and McCoy gives Z = 6.45). */
static void equation_of_state(void **st)
{
    (void)st;
    double etas[6] = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6};
    long n = 2000;
    for (int k = 0; k < 6; k++) {
        double L = sqrt(n * M_PI / 4 / etas[k]);
        gr_scene sc = edmd_box(L, L, 1, 1.0);
        gr_particles *p = edmd_lattice(n, 0, 0, L, L, 1.0, 1, 30 + k);
        gr_edmd_params prm;
        gr_edmd_params_default(&prm);
        gr_edmd *s = make(&sc, p, &prm);
        gr_err e = {0};
        assert_int_equal(gr_edmd_advance(s, INFINITY, 50 * n, &e), GR_OK);
        gr_edmd_reset_averages(s);
        assert_int_equal(gr_edmd_advance(s, INFINITY, 400 * n, &e), GR_OK);
        gr_edmd_averages a;
        gr_edmd_get_averages(s, &a);
        double Z = a.virial_pressure * L * L / a.ekin;
        double Zh = z_henderson(etas[k]), Zl = z_luding(etas[k]);
        /* collision frequency per grain against Enskog, nu = 2 n sigma chi sqrt(pi T / m) */
        double T = a.ekin / n, nu = 2.0 * a.collision_rate / n;
        double nu_e = 2.0 * (n / (L * L)) * chi_luding(etas[k]) * sqrt(M_PI * T);
        printf("# eta %.1f: Z = %.5f, Luding %.5f (%+.2f %%), Henderson %.5f (%+.2f %%); collision frequency "
               "%.4f, Enskog %.4f (%+.2f %%)\n",
               etas[k], Z, Zl, 100 * (Z / Zl - 1), Zh, 100 * (Z / Zh - 1), nu, nu_e, 100 * (nu / nu_e - 1));
        assert_true(fabs(Z / Zl - 1) < 0.01);
        /* Z - 1 = (pi/2) n sigma^2 chi exactly, so Enskog's nu follows Z */
        gr_edmd_free(s);
        gr_particles_free(p);
    }
}

/* Maxwellian velocities (T = 1/2 per grain), zero mean. */
static void maxwell(gr_particles *p, unsigned long seed)
{
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(r, seed);
    double px = 0, py = 0;
    for (size_t i = 0; i < p->n; i++) {
        p->vx[i] = gsl_ran_gaussian(r, sqrt(0.5));
        p->vy[i] = gsl_ran_gaussian(r, sqrt(0.5));
        px += p->vx[i], py += p->vy[i];
    }
    for (size_t i = 0; i < p->n; i++)
        p->vx[i] -= px / p->n, p->vy[i] -= py / p->n;
    gsl_rng_free(r);
}

static double temperature(gr_edmd *s, gr_particles *p)
{
    gr_err e = {0};
    assert_int_equal(gr_edmd_snapshot(s, p, &e), GR_OK);
    double k = 0, px = 0, py = 0;
    for (size_t i = 0; i < p->n; i++) {
        k += 0.5 * (p->vx[i] * p->vx[i] + p->vy[i] * p->vy[i]);
        px += p->vx[i], py += p->vy[i];
    }
    return (k - 0.5 * (px * px + py * py) / p->n) / p->n;
}

/* Homogeneous cooling at low density (eta 0.05, 10000 disks): T against
 * collisions per grain follows T0 exp(-(1 - alpha^2) C / N) within 2 %, and
 * T(t) Haff's law T0 / (1 + t / tau)^2 with Enskog's tau within 5 %. */
static void haff_law(void **st)
{
    (void)st;
    double alphas[2] = {0.9, 0.8};
    long n = 10000;
    double eta = 0.05, L = sqrt(n * M_PI / 4 / eta);
    for (int a = 0; a < 2; a++) {
        gr_scene sc = edmd_box(L, L, 1, alphas[a]);
        gr_particles *p = edmd_lattice(n, 0, 0, L, L, 1.0, 1, 40 + a);
        maxwell(p, 50 + a);
        gr_edmd_params prm;
        gr_edmd_params_default(&prm);
        gr_edmd *s = make(&sc, p, &prm);
        gr_err e = {0};
        s->alpha = 1.0; /* elastic warm-up: equilibrium pair correlations */
        assert_int_equal(gr_edmd_advance(s, INFINITY, 3 * n, &e), GR_OK);
        s->alpha = alphas[a];
        s->alpha_w = alphas[a];
        double T0 = temperature(s, p), t0 = gr_edmd_time(s);
        uint64_t c0 = s->cnt.pair;
        double eps = 1 - alphas[a] * alphas[a];
        double tau = 2.0 / (eps * (n / (L * L)) * chi_luding(eta) * sqrt(M_PI * T0));
        double worst_c = 0, worst_t = 0;
        for (int k = 1; k <= 8; k++) {
            assert_int_equal(gr_edmd_advance(s, INFINITY, n / 2, &e), GR_OK);
            double T = temperature(s, p), C = (double)(s->cnt.pair - c0), t = gr_edmd_time(s) - t0;
            double Tc = T0 * exp(-eps * C / n), Tt = T0 / ((1 + t / tau) * (1 + t / tau));
            worst_c = fmax(worst_c, fabs(T / Tc - 1));
            worst_t = fmax(worst_t, fabs(T / Tt - 1));
            if (k % 2 == 0)
                printf("# alpha %.1f C/N = %.1f t = %7.3f: T/T0 = %.5f, exp law %.5f (%+.2f %%), Haff %.5f (%+.2f %%)\n",
                       alphas[a], C / n, t, T / T0, Tc / T0, 100 * (T / Tc - 1), Tt / T0, 100 * (T / Tt - 1));
        }
        assert_true(worst_c < 0.02);
        assert_true(worst_t < 0.05);
        gr_edmd_free(s);
        gr_particles_free(p);
    }
}

/* Fields on the cells: summed over the box they give exactly the density
 * N/A, the kinetic energy (thermal plus the cells' mean flow), the virial
 * pressure and the dissipation rate of the global exact averages. */
static void fields_consistency(void **st)
{
    (void)st;
    long n = 1000;
    double eta = 0.3, L = sqrt(n * M_PI / 4 / eta);
    gr_scene sc = edmd_box(L, L, 1, 0.95);
    gr_particles *p = edmd_lattice(n, 0, 0, L, L, 1.0, 1, 60);
    gr_edmd_params prm;
    gr_edmd_params_default(&prm);
    prm.fields = 1;
    gr_edmd *s = make(&sc, p, &prm);
    gr_err e = {0};
    assert_int_equal(gr_edmd_advance(s, INFINITY, 10 * n, &e), GR_OK);
    gr_edmd_reset_averages(s);
    assert_int_equal(gr_edmd_advance(s, INFINITY, 20 * n, &e), GR_OK);
    gr_edmd_averages a;
    gr_edmd_get_averages(s, &a);
    gr_edmd_fields f;
    assert_int_equal(gr_edmd_get_fields(s, &f, &e), GR_OK);
    int nc = f.nx * f.ny;
    double A = f.cx * f.cy, dens = 0, diss = 0, kin = 0, pres = 0;
    for (int c = 0; c < nc; c++) {
        dens += f.density[c] / nc;
        diss += f.dissipation[c] * A;
        double flow = f.density[c] > 0 ? 0.5 * f.density[c] * (f.ux[c] * f.ux[c] + f.uy[c] * f.uy[c]) : 0;
        if (f.density[c] > 0)
            kin += A * (f.density[c] * f.temperature[c] + flow);
        pres += A * (0.5 * (f.pxx[c] + f.pyy[c]) + flow) / (L * L);
    }
    double Kt = a.ekin - a.ekin_rot;
    printf("# fields: density %.9f (N/A %.9f), kinetic %.9g (<K> %.9g), pressure %.9f (virial %.9f), "
           "dissipation %.9g (global %.9g)\n",
           dens, n / (L * L), kin, Kt, pres, a.virial_pressure, diss, a.dissipation_rate);
    assert_true(fabs(dens / (n / (L * L)) - 1) < 1e-9);
    assert_true(fabs(kin / Kt - 1) < 1e-9);
    assert_true(fabs(pres / a.virial_pressure - 1) < 1e-9);
    assert_true(fabs(diss / a.dissipation_rate - 1) < 1e-9);
    gr_edmd_fields_free(&f);
    gr_edmd_free(s);
    gr_particles_free(p);
}

/* Save after some events, continue; a fresh state loads the file and
 * continues: the two runs agree bit for bit (vibrated bed with the random
 * high-frequency floor, and an elastic periodic gas with fields). */
static void checkpoint_restart(void **st)
{
    (void)st;
    for (int k = 0; k < 2; k++) {
        gr_scene sc;
        gr_particles *p;
        gr_edmd_params prm;
        gr_edmd_params_default(&prm);
        if (k == 0) {
            sc = edmd_box(15, 100, 0, 0.9);
            sc.gravity = 1.0;
            sc.floor.motion = GR_FLOOR_SINE_HF;
            sc.floor.amplitude = 1.0;
            sc.floor.omega = 2.0;
            sc.mat.tangential_restitution = 0.4;
            sc.mat.mu = 0.3;
            prm.collapse = GR_EDMD_COLLAPSE_TC;
            p = edmd_lattice(100, 0, 0.1, 15, 10, 1.0, 0, 70);
        } else {
            double L = 30;
            sc = edmd_box(L, L, 1, 1.0);
            prm.fields = 1;
            p = edmd_lattice(300, 0, 0, L, L, 1.0, 1, 71);
        }
        gr_err e = {0};
        char path[64];
        snprintf(path, sizeof path, "edmd_ckpt_%d_%d.h5", k, (int)getpid());
        gr_edmd *a = make(&sc, p, &prm);
        assert_int_equal(gr_edmd_advance(a, INFINITY, 20000, &e), GR_OK);
        gr_ckpt *ck = gr_ckpt_create(path, &e);
        assert_non_null(ck);
        assert_int_equal(gr_edmd_method.save(a, ck, &e), GR_OK);
        assert_int_equal(gr_ckpt_close(ck, &e), GR_OK);
        assert_int_equal(gr_edmd_advance(a, INFINITY, 30000, &e), GR_OK);
        gr_edmd *b = make(&sc, p, &prm);
        ck = gr_ckpt_open(path, &e);
        assert_non_null(ck);
        int rc = gr_edmd_method.load(b, ck, &e);
        if (rc)
            fprintf(stderr, "load: %s\n", e.msg);
        assert_int_equal(rc, GR_OK);
        gr_ckpt_close(ck, &e);
        assert_int_equal(gr_edmd_advance(b, INFINITY, 30000, &e), GR_OK);
        gr_particles *pa = gr_particles_create(0, &e), *pb = gr_particles_create(0, &e);
        assert_int_equal(gr_edmd_snapshot(a, pa, &e), GR_OK);
        assert_int_equal(gr_edmd_snapshot(b, pb, &e), GR_OK);
        assert_true(gr_edmd_time(a) == gr_edmd_time(b));
        assert_memory_equal(pa->x, pb->x, pa->n * sizeof(double));
        assert_memory_equal(pa->vy, pb->vy, pa->n * sizeof(double));
        assert_memory_equal(pa->omega, pb->omega, pa->n * sizeof(double));
        gr_edmd_averages aa, ab;
        gr_edmd_get_averages(a, &aa);
        gr_edmd_get_averages(b, &ab);
        assert_memory_equal(&aa, &ab, sizeof aa);
        printf("# checkpoint %d: t = %.10g after 5e4 collisions, identical state and averages\n", k,
               gr_edmd_time(a));
        unlink(path);
        gr_particles_free(pa);
        gr_particles_free(pb);
        gr_edmd_free(a);
        gr_edmd_free(b);
        gr_particles_free(p);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(equation_of_state),
        cmocka_unit_test(haff_law),
        cmocka_unit_test(fields_consistency),
        cmocka_unit_test(checkpoint_restart),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
