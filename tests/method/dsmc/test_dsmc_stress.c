/* The window-averaged stress of DSMC (the method table's stress op) in a
 * periodic box of elastic disks, against the hard-disk equation of state:
 * in the Enskog mode the collisional part is the momentum the partners'
 * displacement carries, and Z = P / (n T) with P = (sigma_xx + sigma_yy)/2
 * must meet Henderson's within the 2 % test_dsmc_enskog established; in
 * the Boltzmann mode (enskog = no) the collisional part is the hard disks'
 * sigma n (x) J that each collision stands for, and at eta = 0.01 Z must be
 * the second-virial value 1 + 2 eta within a tenth of the 2 eta (the
 * standard error is 1e-4, so the ideal gas, 1, is far outside). In both, the trace is the collisional virial the existing
 * tests read (`virial`, sigma J per collision) plus n T, to rounding. */
#include "dsmc_test.h"

#define BOX                                                                                                            \
    "[scene]\nseed = 5\n[domain]\nwidth = %.17g\nheight = %.17g\nleft = periodic\nright = periodic\n"                  \
    "bottom = periodic\ntop = periodic\n[material]\nrestitution = 1\n[species]\ncount = %d\n"                         \
    "[init]\nkind = random\nvelocity = gaussian\nv0 = 1\n[dsmc]\ndt = %g\ncell = %g\nenskog = %s\n"

/* Z over `blocks` windows of `len` after t0 on nx x nx cells, with its
 * standard error; *dv the largest relative difference of P from the
 * virial's. The domain's value (one cell) is the one to compare: each
 * cell's kinetic part is taken about the cell's mean velocity over the
 * window, which removes about T per cell and component (the sample mean's
 * degree of freedom; docs/output-format.md). With one cell that mean is the
 * centre of mass's, which the collisions keep exactly. */
static double z_of(const char *text, int nx, double t0, double len, int blocks, double *ez, double *dv)
{
    enum { NX = 4, NY = 4 };
    gr_scene *sc;
    gr_sim *s = ds_make(text, &sc);
    gr_dsmc *d = gr_sim_state(s);
    gr_err e = {0};
    double g[4], cells[NX * NY * 4], z[64], zs = 0, A = d->Lx * d->Ly;
    assert_true(nx <= NX);
    ds_run_to(s, t0);
    assert_int_equal(gr_sim_stress(s, nx, nx, g, cells, &e), GR_OK);
    *dv = 0;
    for (int b = 0; b < blocks; b++) {
        gr_sim_reset_window(s);
        double nT = (double)d->n * d->W * ds_temp(s) / A; /* elastic: the energy stays */
        ds_run_to(s, t0 + (b + 1) * len);
        assert_int_equal(gr_sim_stress(s, nx, nx, g, cells, &e), GR_OK);
        double P = 0.5 * (g[0] + g[3]), mean = 0;
        for (int c = 0; c < nx * nx; c++)
            mean += 0.5 * (cells[4 * c] + cells[4 * c + 3]) / (nx * nx);
        assert_true(fabs(mean - P) <= 1e-12 * P);
        z[b] = P / nT, zs += z[b] / blocks;
        double Pv = nT + d->W * d->virial / (2 * A * d->wall_time);
        *dv = fmax(*dv, fabs(P / Pv - 1));
    }
    double v = 0;
    for (int b = 0; b < blocks; b++)
        v += (z[b] - zs) * (z[b] - zs);
    *ez = sqrt(v / (blocks - 1) / blocks);
    gr_sim_free(s);
    gr_scene_free(sc);
    return zs;
}

/* 4000 particles at packing fraction eta. */
static void box_text(char *text, size_t size, double eta, double dt, double cell, const char *enskog)
{
    int n = 4000;
    double L = sqrt(n * M_PI / 4 / eta);
    snprintf(text, size, BOX, L, L, n, dt, cell, enskog);
}

static void enskog(void **st)
{
    (void)st;
    char text[1024];
    double eta = 0.3, ez, dv;
    box_text(text, sizeof text, eta, 0.05, 10.0, "yes");
    double Z = z_of(text, 1, 10, 4, 10, &ez, &dv), Zh = exp_z_henderson(eta);
    print_message("# Enskog mode, eta %.2f: Z from the stress %.4f +- %.4f, Henderson %.4f (%+.2f %%); largest "
                  "|P / (n T + virial) - 1| %.2g\n",
                  eta, Z, ez, Zh, 100 * (Z / Zh - 1), dv);
    assert_true(fabs(Z / Zh - 1) < 0.02);
    assert_true(dv < 1e-9);
}

static void boltzmann(void **st)
{
    (void)st;
    char text[1024];
    double eta = 0.01, ez, dv;
    box_text(text, sizeof text, eta, 0.5, 0.0, "no");
    double ez4, dv4, Z4 = z_of(text, 4, 20, 40, 10, &ez4, &dv4);
    double Z = z_of(text, 1, 20, 40, 10, &ez, &dv);
    print_message("# Boltzmann mode, eta %.2f, 4 x 4 cells: Z %.5f +- %.5f (the cells' mean flows taken out)\n", eta,
                  Z4, ez4);
    print_message("# Boltzmann mode, eta %.2f: Z from the stress %.5f +- %.5f, 1 + 2 eta %.5f; (Z - 1) / (2 eta) "
                  "%.3f; largest |P / (n T + virial) - 1| %.2g\n",
                  eta, Z, ez, 1 + 2 * eta, (Z - 1) / (2 * eta), dv);
    assert_true(fabs((Z - 1) / (2 * eta) - 1) < 0.1);
    assert_true(ez < 0.1 * 2 * eta);
    assert_true(dv < 1e-9);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(enskog),
        cmocka_unit_test(boltzmann),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
