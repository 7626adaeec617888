/* The Enskog mode (rate times Henderson's chi, partners drawn where they
 * touch: Montanero and Santos' Enskog simulation Monte Carlo) against the
 * equation of state of hard disks, Henderson's Z = (1 + eta^2/8)/(1 - eta)^2:
 * in a periodic box from the collisional transfer (the virial of the
 * collisions), and in a closed box from the momentum the walls receive,
 * which only the partners drawn across cell boundaries bring to Z (with
 * enskog = no the walls see the ideal gas, n T). Tolerances in each test
 * and docs/methods/dsmc.md. */
#include "dsmc_test.h"

#define BOX                                                                                                            \
    "[scene]\nseed = %d\n[domain]\nwidth = %.17g\nheight = %.17g\nleft = %s\nright = %s\nbottom = %s\ntop = %s\n"      \
    "[material]\nrestitution = 1\n[species]\ncount = %d\n[init]\nkind = random\nvelocity = gaussian\nv0 = 1\n"         \
    "[dsmc]\ndt = 0.05\ncell = %g\nenskog = %s\n"

static double cell_side = 10.0; /* `scan CELL` sets it */

static gr_sim *box(int n, double eta, const char *side, const char *enskog, gr_scene **sc)
{
    char text[1024];
    double L = sqrt(n * M_PI / 4 / eta);
    snprintf(text, sizeof text, BOX, 3, L, L, side, side, side, side, n, cell_side, enskog);
    return ds_make(text, sc);
}

/* p = n T + W sum(sigma J) / (2 A t) over 40 time units after 10, against
 * Henderson within 2 % (the statistics give 0.3 %). Cells of 10 d; with
 * 3, 5, 10, 20 d Z is 0.5 %, 0.5 %, 0.2 % low and 0.03 % high
 * (docs/methods/dsmc.md; `scan CELL` prints it). */
static void test_eos_virial(void **st)
{
    (void)st;
    const double eta = 0.3;
    gr_scene *sc;
    gr_sim *s = box(4000, eta, "periodic", "yes", &sc);
    gr_dsmc *d = gr_sim_state(s);
    ds_run_to(s, 10);
    gr_sim_reset_window(s);
    double Tsum = 0;
    for (int k = 1; k <= 40; k++) {
        ds_run_to(s, 10 + k);
        Tsum += ds_temp(s);
    }
    double A = d->Lx * d->Ly, n = d->n * d->W / A, T = Tsum / 40; /* grains per area */
    double Z = 1 + d->W * d->virial / (2 * A * d->wall_time * n * T);
    print_message("# EOS from the collisional transfer, eta %.2f: Z %.4f, Henderson %.4f, ratio %.4f\n", eta, Z,
                  exp_z_henderson(eta), Z / exp_z_henderson(eta));
    assert_true(fabs(Z / exp_z_henderson(eta) - 1) < 0.02);
    gr_sim_free(s);
    gr_scene_free(sc);
}

/* Closed box: the virial theorem of hard disks in a container,
 * p A = N T + sum(sigma J) / (2 t), A = (L - sigma)^2 the area the
 * centres reach and p the force on a wall over the length L - sigma its
 * contacts cover (wall_pressure L / (L - sigma): the observable divides by
 * the whole side), holds when the collisional transfer reaches the walls,
 * across the cells' boundaries: within 2 % (statistics 0.5 % over
 * 300 time units).
 * With the rate alone (enskog = no) the walls must see the ideal gas,
 * p A = N T, within 2 %, however many collisions. No density is
 * estimated (the slow sound modes of a closed box make a bulk count noisy
 * at the percent level). */
static double wall_ratio(const char *enskog, double *z)
{
    gr_scene *sc;
    gr_sim *s = box(4000, 0.3, "wall", enskog, &sc);
    gr_dsmc *d = gr_sim_state(s);
    ds_run_to(s, 20);
    gr_sim_reset_window(s);
    double Tsum = 0;
    int K = 300;
    for (int k = 1; k <= K; k++) {
        ds_run_to(s, 20 + k);
        Tsum += ds_temp(s);
    }
    double A = (d->Lx - d->sigma) * (d->Ly - d->sigma), NT = d->n * d->W * Tsum / K;
    double pw = ds_observe(s).wall_pressure * d->Lx / (d->Lx - d->sigma), vir = d->W * d->virial / (2 * d->wall_time);
    *z = pw * A / NT;
    gr_sim_free(s);
    gr_scene_free(sc);
    return strcmp(enskog, "yes") ? pw * A / NT : pw * A / (NT + vir);
}

static void test_eos_walls(void **st)
{
    (void)st;
    double z, z0;
    double r = wall_ratio("yes", &z), r0 = wall_ratio("no", &z0);
    double eta = 4000 * M_PI / 4 / (4000 * M_PI / 4 / 0.3 + 1 - 2 * sqrt(4000 * M_PI / 4 / 0.3));
    print_message("# closed box, Enskog: p A / (N T + virial) %.4f; p A / (N T) %.4f (Henderson at "
                  "N / A: %.4f)\n",
                  r, z, exp_z_henderson(eta));
    print_message("# closed box, rate alone (enskog = no): p A / (N T) %.4f (ideal gas 1)\n", r0);
    assert_true(fabs(r - 1) < 0.02);
    assert_true(fabs(r0 - 1) < 0.02);
}

int main(int argc, char **argv)
{
    if (argc > 2 && !strcmp(argv[1], "scan")) { /* `scan CELL`: the periodic box's Z with that cell side */
        cell_side = atof(argv[2]);
        const struct CMUnitTest one[] = {cmocka_unit_test(test_eos_virial)};
        return cmocka_run_group_tests(one, NULL, NULL);
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_eos_virial),
        cmocka_unit_test(test_eos_walls),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
