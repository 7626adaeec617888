/* [init] kind = file readers (common/init_file.c): a LAMMPS data file of
 * style atomic with ids out of order and no velocities, one of style sphere
 * with velocities, an extxyz frame with momenta and masses, and the
 * messages for bad files. */
#include "test.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "init.h"
#include "scene.h"

static const gr_species sp = {.diameter = 1.0, .density = 4 / M_PI};

static gr_particles *read_text(const char *text, gr_err *e)
{
    const char *path = "init_file_test.txt";
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
    gr_particles *p = gr_particles_create(0, e);
    assert_non_null(p);
    int rc = gr_init_read_file(path, &sp, p, e);
    unlink(path);
    if (rc) {
        gr_particles_free(p);
        return NULL;
    }
    return p;
}

static void lammps_atomic_in_id_order(void **s)
{
    (void)s;
    gr_err e = {0};
    gr_particles *p = read_text("title\n\n2 atoms\n1 atom types\n0 10 xlo xhi\n0 10 ylo yhi\n-1 1 zlo zhi\n\n"
                                "Masses\n\n1 1.0\n\nAtoms # atomic\n\n7 1 3 4 0\n2 1 1 2 0\n", &e);
    if (!p)
        print_error("%s\n", e.msg);
    assert_non_null(p);
    assert_int_equal(p->n, 2);
    assert_true(p->x[0] == 1 && p->y[0] == 2 && p->x[1] == 3 && p->y[1] == 4);
    assert_true(p->vx[0] == 0 && p->radius[0] == 0.5 && fabs(p->mass[0] - 1) < 1e-15);
    gr_particles_free(p);
}

static void lammps_sphere_velocities(void **s)
{
    (void)s;
    gr_err e = {0};
    gr_particles *p = read_text("t\n2 atoms\nAtoms # sphere\n\n1 1 2 1 5 6 0\n2 1 1 1 7 8 0\n\n"
                                "Velocities\n\n2 0.5 0.25 0 0 0 3\n1 -1 -2 0 0 0 -4\n", &e);
    assert_non_null(p);
    assert_true(p->radius[0] == 1 && p->vx[0] == -1 && p->vy[0] == -2 && p->omega[0] == -4);
    assert_true(p->x[1] == 7 && p->vx[1] == 0.5 && p->omega[1] == 3);
    assert_true(fabs(p->mass[0] - 4) < 1e-14); /* the scene's density, not the file's */
    gr_particles_free(p);
}

static void extxyz_momenta(void **s)
{
    (void)s;
    gr_err e = {0};
    gr_particles *p = read_text("2\nLattice=\"9 0 0 0 9 0 0 0 1\" Properties=species:S:1:pos:R:3:momenta:R:3:"
                                "masses:R:1:radius:R:1 pbc=\"F F F\"\nH 1 2 0 2 4 0 2 0.6\nH 3 4 0 0 0 0 1 0.5\n", &e);
    assert_non_null(p);
    assert_true(p->x[0] == 1 && p->vx[0] == 1 && p->vy[0] == 2 && p->radius[0] == 0.6);
    assert_true(p->x[1] == 3 && p->y[1] == 4);
    gr_particles_free(p);
}

static void bad_files(void **s)
{
    (void)s;
    struct {
        const char *text, *want;
    } c[] = {
        {"t\n2 atoms\nAtoms # sphere\n\n1 1 1 1 5 6\n", "init_file_test.txt:5: expected atom style sphere"},
        {"t\n2 atoms\nAtoms\n\n1 1 5 6 0\n", "2 atoms announced, 1 in the Atoms section"},
        {"t\n2 atoms\nAtoms\n\n1 1 5 6 0\n1 1 7 8 0\n", "atom id 1 appears twice"},
        {"t\n1 atoms\nAtoms\n\n1 1 5 6 0\nVelocities\n\n3 0 0 0\n", "Velocities names atom 3"},
        {"2\nLattice=\"1 0 0 0 1 0 0 0 1\"\nH 0 0 0\n", "init_file_test.txt:2: extended XYZ without Properties="},
        {"2\nProperties=species:S:1:pos:R:3\nH 0 0 0\n", "2 atoms announced, 1 found"},
        {"1 2\n3 4 5\n", "init_file_test.txt:2: expected 'x y'"},
        {"# nothing\n", "no grains in the file"},
    };
    for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
        gr_err e = {0};
        assert_null(read_text(c[i].text, &e));
        if (!strstr(e.msg, c[i].want))
            print_error("case %zu: \"%s\" lacks \"%s\"\n", i, e.msg, c[i].want);
        assert_non_null(strstr(e.msg, c[i].want));
        assert_int_equal(e.code, GR_EINPUT);
    }
}

/* [init] overlap = push on the simplest soft overlaps: two grains 0.02
 * into each other move 0.01 apart each, a grain 0.01 into the left wall
 * moves 0.01 in; nothing overlaps after, no grain moved more than the
 * largest overlap, and the report says so. */
static void push_apart_pair_and_wall(void **s)
{
    (void)s;
    gr_err e = {0};
    gr_scene *sc = gr_scene_parse("[domain]\nwidth = 10\nheight = 10\n[init]\nkind = lattice\noverlap = push\n",
                                  "push.ini", NULL, &e);
    assert_non_null(sc);
    gr_particles *p = gr_particles_create(0, &e);
    gr_particles_push(p, 5.0, 5.0, 0.5, 1.0, 0, 0, &e);
    gr_particles_push(p, 5.98, 5.0, 0.5, 1.0, 0, 0, &e);
    gr_particles_push(p, 0.49, 3.0, 0.5, 1.0, 0, 0, &e);
    gr_init_relax_report r;
    assert_int_equal(gr_init_push_apart(sc, p, &r, &e), GR_OK);
    printf("# largest overlap %.6g (%s), %d sweeps, largest displacement %.9g; pair at %.9g, %.9g, wall grain %.9g\n",
           r.overlap, r.where, r.sweeps, r.max_displacement, p->x[0], p->x[1], p->x[2]);
    assert_true(fabs(r.overlap - 0.02) < 1e-12 && !strcmp(r.where, "grains 1 and 2"));
    assert_true(p->x[1] - p->x[0] >= 1.0 && p->x[1] - p->x[0] < 1.0 + 1e-5 && p->x[2] >= 0.5);
    assert_true(fabs(p->x[0] - 4.99) < 1e-5 && fabs(p->x[1] - 5.99) < 1e-5 && fabs(p->x[2] - 0.5) < 1e-5);
    assert_true(r.max_displacement <= r.overlap && fabs(r.max_displacement - 0.01) < 1e-5);
    gr_particles_free(p);
    gr_scene_free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(lammps_atomic_in_id_order),
                                       cmocka_unit_test(lammps_sphere_velocities),
                                       cmocka_unit_test(extxyz_momenta), cmocka_unit_test(bad_files),
                                       cmocka_unit_test(push_apart_pair_and_wall)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
