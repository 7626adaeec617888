/* The lattice-Boltzmann equation of the FHP-III automaton (McNamara and
 * Zanetti, Phys. Rev. Lett. 61, 2332 (1988)): the same lattice, the same
 * collision table (lgca_table_build), but real mean occupations f_k in
 * [0, 1] instead of bits, and the collision replaced by its average over
 * the uncorrelated (Boltzmann) distribution of the node's states:
 *   f'_k = sum_s P(s) <t(s)>_k,  P(s) = prod_j f_j^s_j (1 - f_j)^(1 - s_j),
 * <.> over both chiralities. This is the kinetic equation whose viscosity
 * Frisch et al.'s formula is, so a shear wave must decay at it exactly,
 * up to the wavelength's own O(k^2) correction: the test that decides
 * whether the automaton's excess away from d = 1/2 (docs/methods/lgca.md,
 * Viscosity) is the model (correlations the Boltzmann average leaves out)
 * or a fault of the table or the wavelength. Asserted: at d = 0.2, 0.3,
 * 0.5, 0.7 the decay rate of a shear wave of wavelength 32 a (the
 * automaton test's) and 64 a gives nu within 1 % of Frisch's, and the
 * rate converges as the wavelength grows (64 a within 0.2 % of 128 a). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lgca_test.h"

enum { NY = 2 }; /* rows: the wave runs along x and is uniform in y */

typedef struct {
    int nx;
    double *f, *g; /* LGCA_CH occupations per node, node (x, y) at (y nx + x) LGCA_CH */
    double avg[128][LGCA_CH]; /* <t(s)>_k over the two chiralities */
} lb;

static const double CY[6] = {0, 0.8660254037844386, 0.8660254037844386, 0, -0.8660254037844386,
                             -0.8660254037844386};

/* The neighbour of (x, y) along direction k on the brick layout the
 * automaton uses (odd rows half a spacing to the right). */
static void neighbour(int nx, int x, int y, int k, int *ox, int *oy)
{
    int odd = y & 1, dx[6] = {1, odd, odd - 1, -1, odd - 1, odd}, dy[6] = {0, 1, 1, 0, -1, -1};
    *ox = ((x + dx[k]) % nx + nx) % nx;
    *oy = ((y + dy[k]) % NY + NY) % NY;
}

/* f'_k = sum_s P(s) <t(s)>_k at one node. */
static void collide(const lb *L, const double *f, double *out)
{
    double q[LGCA_CH] = {0};
    for (unsigned s = 0; s < 128; s++) {
        double P = 1;
        for (int j = 0; j < LGCA_CH; j++)
            P *= (s >> j & 1u) ? f[j] : 1 - f[j];
        for (int k = 0; k < LGCA_CH; k++)
            q[k] += P * L->avg[s][k];
    }
    memcpy(out, q, sizeof q);
}

/* One step: collide every node, then stream along the six directions. */
static void step(lb *L)
{
    int n = L->nx * NY;
    for (int c = 0; c < n; c++)
        collide(L, L->f + (size_t)c * LGCA_CH, L->g + (size_t)c * LGCA_CH);
    for (int y = 0; y < NY; y++)
        for (int x = 0; x < L->nx; x++) {
            const double *src = L->g + ((size_t)y * L->nx + x) * LGCA_CH;
            for (int k = 0; k < 6; k++) {
                int ox, oy;
                neighbour(L->nx, x, y, k, &ox, &oy);
                L->f[((size_t)oy * L->nx + ox) * LGCA_CH + k] = src[k];
            }
            L->f[((size_t)y * L->nx + x) * LGCA_CH + 6] = src[6];
        }
}

/* The shear mode's amplitude: the projection of j_y on sin(k x). */
static double amplitude(const lb *L)
{
    double a = 0, kw = 2 * M_PI / L->nx;
    for (int y = 0; y < NY; y++)
        for (int x = 0; x < L->nx; x++) {
            const double *f = L->f + ((size_t)y * L->nx + x) * LGCA_CH;
            double jy = 0;
            for (int k = 0; k < 6; k++)
                jy += CY[k] * f[k];
            a += jy * sin(kw * (x + 0.5 * (y & 1)));
        }
    return a;
}

/* nu from the decay of a shear wave of wavelength nx at density d:
 * f_k = d + (c_k . j)/3 with j_y = U sin(k x) (the linearised
 * equilibrium; its transient dies in a few steps), then
 * nu = ln(A(t0) / A(t1)) / ((t1 - t0) k^2). */
static double lb_viscosity(int nx, double d)
{
    lb L = {.nx = nx};
    uint8_t t[LGCA_TABLE_SIZE];
    lgca_table_build(LGCA_RULES_FHP3, t);
    for (unsigned s = 0; s < 128; s++)
        for (unsigned ch = 0; ch < 2; ch++)
            for (int k = 0; k < LGCA_CH; k++)
                L.avg[s][k] += 0.5 * (t[s | ch << 7] >> k & 1u);
    L.f = malloc((size_t)nx * NY * LGCA_CH * sizeof *L.f);
    L.g = malloc((size_t)nx * NY * LGCA_CH * sizeof *L.g);
    assert_non_null(L.f);
    assert_non_null(L.g);
    double kw = 2 * M_PI / nx, U = 1e-4;
    for (int y = 0; y < NY; y++)
        for (int x = 0; x < nx; x++) {
            double *f = L.f + ((size_t)y * nx + x) * LGCA_CH, jy = U * sin(kw * (x + 0.5 * (y & 1)));
            for (int k = 0; k < 6; k++)
                f[k] = d + CY[k] * jy / 3;
            f[6] = d;
        }
    double nu0 = 1 / (28 * d * (1 - d) * (1 - 8 * d * (1 - d) / 7)) - 0.125;
    /* from 20 steps (the transient) over a tenth of the decay time */
    int t0 = 20, t1 = t0 + (int)ceil(0.1 / (nu0 * kw * kw));
    for (int s = 0; s < t0; s++)
        step(&L);
    double a0 = amplitude(&L);
    for (int s = t0; s < t1; s++)
        step(&L);
    double a1 = amplitude(&L);
    free(L.f);
    free(L.g);
    return log(a0 / a1) / ((t1 - t0) * kw * kw);
}

static void lb_is_frisch(void **unused)
{
    (void)unused;
    const double ds[] = {0.2, 0.3, 0.5, 0.7};
    for (size_t i = 0; i < sizeof ds / sizeof ds[0]; i++) {
        double d = ds[i], frisch = 1 / (28 * d * (1 - d) * (1 - 8 * d * (1 - d) / 7)) - 0.125;
        double n32 = lb_viscosity(32, d), n64 = lb_viscosity(64, d), n128 = lb_viscosity(128, d);
        printf("# d = %.2f: lattice Boltzmann nu = %.6f (32 a), %.6f (64 a), %.6f (128 a); Frisch et al. %.6f "
               "(%+.3f %%, %+.3f %%, %+.3f %%)\n",
               d, n32, n64, n128, frisch, 100 * (n32 / frisch - 1), 100 * (n64 / frisch - 1),
               100 * (n128 / frisch - 1));
        assert_true(fabs(n32 / frisch - 1) < 0.01);
        assert_true(fabs(n64 / frisch - 1) < 0.01);
        assert_true(fabs(n64 / n128 - 1) < 0.002);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(lb_is_frisch)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
