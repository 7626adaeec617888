/* The cases of grano compare and, for each, its rows: which method runs it,
 * over which knob, at which values. A method joins a case with one row.
 *
 * Values run from the coarsest setting to the finest: the --quick test
 * asserts that the error does not grow along them (beyond the error bars).
 * A row whose quick list is empty runs only in the full comparison.
 *
 * dsmc's cooling rows fix cells of 30 diameters, its validity limit of
 * 30 W sigma: in smaller cells the partners collide again while their
 * velocities are correlated and the gas cools too slowly (about 0.33 W
 * sigma / side; the Enskog mode's displacement thins pairs too), which the
 * dsmc-cell rows show (docs/methods/dsmc.md). The dsmc-weight row moves [species]
 * count and weight together ("count:weight", a knob of two keys) so the
 * represented grains stay the same: fewer particles per cell as the
 * weight grows.
 *
 * lgca (lattice gas) runs the silo-widths case on its own variant scene
 * (the row's scene: silo.ini's geometry without friction or restitution,
 * which the lattice refuses, and its own dissipation and wall roughness in
 * their place), over the lattice resolution; its time unit is its own, so
 * that case compares the shape Q(D) / Q(6 d), not the rate. In the column
 * and the dilute cooling it runs its own scenes and is held to its own
 * mean-field answers (CMP_OWN: the share of the weight its floor carries,
 * its movers' fall; cmp_lattice.c). It cannot model the vibrated bed (a
 * vibrating floor), and the other cases need a restitution, friction or
 * contact forces (docs/comparison.md).
 */
#include <stddef.h>

#include "cmp.h"

#define EDMD_AT_REST                                                                                       \
    "hard disks at rest exchange no impulse: the grains that come to rest (collapse = sleep) carry their " \
    "weight through no collision, so the floor's force from the stress is not the weight"

static const cmp_case cases[] = {
    {.name = "collision", .scene = "collision.ini", .quantity = "restitution", .aux = "contact time",
     .unit = "1", .aux_unit = "tau",
     .seeds_full = 16, .seeds_quick = 4, .tol_edmd = 1e-9, .tol = 0.01,
     .measure = cmp_measure_collision, .reference = cmp_ref_collision, .prepare = cmp_prepare_collision,
     .rows = {
         {"dem", "dem", "dem.dt", "2e-3,1e-3,5e-4,2.5e-4,1.25e-4,6.25e-5", "2e-3,5e-4,1.25e-4", NULL},
         {"dem", "dem-gear", "dem.dt", "2e-3,1e-3,5e-4,2.5e-4,1.25e-4", "2e-3,5e-4,1.25e-4", "dem.integrator=gear"},
         {"edmd", "edmd", NULL, "", "", NULL},
         {"cd", "cd", "cd.dt", "1e-2,1e-3,1e-4", "1e-2,1e-3", NULL},
         {"dsmc", "dsmc", "dsmc.dt", "1e-2,1e-3", "1e-2,1e-3", NULL, CMP_LIMIT, NULL,
          "a collision is drawn at random among the particles of a cell, not resolved where two disks "
          "touch: one pair is not a gas"},
     }},
    {.name = "cooling-dilute", .scene = "cooling-dilute.ini", .quantity = "T/T0 at Haff's time",
     .aux = "T/T0 at half Haff's time", .unit = "1", .aux_unit = "1",
     .quick_set = "species.count=256;domain.width=44.83992973118343;domain.height=44.83992973118343",
     .seeds_full = 16, .seeds_quick = 8, .tol_edmd = 0.1, .tol = 0.05,
     .measure = cmp_measure_cooling, .reference = cmp_ref_cooling, .prepare = cmp_prepare_cooling,
     .rows = {
         {"edmd", "edmd", NULL, "", "", NULL, CMP_REFERENCE},
         {"dem", "dem", "dem.dt", "5e-4,2.5e-4,1.25e-4", "5e-4,2.5e-4", NULL},
         {"cd", "cd", "cd.dt", "1e-2,5e-3,2.5e-3", "1e-2,2.5e-3", NULL},
         {"dsmc", "dsmc", "dsmc.dt", "0.4,0.2,0.1,0.05,0.02", "0.4,0.1", "dsmc.cell=30"},
         {"dsmc", "dsmc-cell", "dsmc.cell", "8,4,2,1", "", "dsmc.dt=0.1", CMP_BIAS},
         {"dsmc", "dsmc-weight", "species.count+species.weight", "64:16,256:4,1024:1", "64:4,256:1",
          "dsmc.dt=0.1;dsmc.cell=8"},
         /* knob: the lattice spacing in the case's box (--quick's smaller box too; no grains) */
         {"lgca", "lgca", "species.diameter", "1,0.5,0.25", "1,0.5", "species.count=0", CMP_OWN, "cooling-lgca.ini",
          .measure = cmp_measure_lattice_cooling, .own_label = "the Boltzmann map of its granular rules",
          .tol = 0.01},
     }},
    {.name = "cooling-dense", .scene = "cooling-dense.ini", .quantity = "T/T0 at Haff's time",
     .aux = "T/T0 at half Haff's time", .unit = "1", .aux_unit = "1",
     .quick_set = "species.count=256;domain.width=25.888345500742656;domain.height=25.888345500742656",
     .seeds_full = 16, .seeds_quick = 8, .tol_edmd = 0.1, .tol = 0.05,
     .measure = cmp_measure_cooling, .reference = cmp_ref_cooling, .prepare = cmp_prepare_cooling,
     .rows = {
         {"edmd", "edmd", NULL, "", "", NULL, CMP_REFERENCE},
         {"dem", "dem", "dem.dt", "5e-4,2.5e-4,1.25e-4", "5e-4,1.25e-4", NULL},
         {"cd", "cd", "cd.dt", "1e-2,5e-3,2.5e-3", "1e-2,2.5e-3", NULL},
         {"dsmc", "dsmc", "dsmc.dt", "0.2,0.1,0.05,0.02", "0.2,0.05", "dsmc.cell=30", CMP_LIMIT, NULL,
          "Enskog's kinetic theory, which dsmc solves, has no velocity correlations: at a packing of 0.3 the "
          "hard disks cool 7 % more slowly than Enskog-Sonine predicts, and dsmc follows the theory"},
         {"dsmc", "dsmc-cell", "dsmc.cell", "8,4,2,1", "", "dsmc.dt=0.05", CMP_BIAS},
     }},
    {.name = "column", .scene = "column.ini", .quantity = "base force / weight", .aux = "bulk packing fraction",
     .unit = "1", .aux_unit = "1",
     .seeds_full = 1, .seeds_quick = 1, .tol_edmd = 0, .tol = 1e-3,
     .measure = cmp_measure_column, .reference = cmp_ref_column,
     .rows = {
         {"dem", "dem", "dem.dt", "5e-4,2.5e-4,1.25e-4", "5e-4,1.25e-4", NULL},
         {"cd", "cd", "cd.tol", "1e-2,1e-3,1e-4,1e-5,1e-6", "1e-2,1e-4,1e-6", NULL},
         {"edmd", "edmd", NULL, "", "", NULL, CMP_LIMIT, NULL, EDMD_AT_REST},
         {"dsmc", "dsmc", "dsmc.dt", "1e-2,1e-3", "1e-2", NULL, CMP_LIMIT, NULL,
          "point particles with no excluded volume and no lasting contact: a column at rest is not a gas"},
         /* knob: lattice spacing : lgca.dt (spacing / 5) */
         {"lgca", "lgca", "species.diameter+lgca.dt", "1:0.2,0.5:0.1,0.25:0.05", "1:0.2,0.5:0.1", NULL, CMP_OWN,
          "column-lgca.ini", .measure = cmp_measure_lattice_column,
          .own_label = "the lattice's mean-field hydrostatics", .tol = 0.01},
     }},
    {.name = "janssen", .scene = "janssen.ini", .quantity = "base force / Janssen's", .aux = "bulk packing fraction",
     .unit = "1", .aux_unit = "1",
     .seeds_full = 4, .seeds_quick = 2, .tol_edmd = 0, .tol = 0.3,
     .measure = cmp_measure_column, .reference = cmp_ref_column,
     .rows = {
         /* first: the plan asks the methods about the scene with the first row's settings */
         {"cd", "cd", "cd.tol", "1e-2,1e-3", "1e-2", NULL},
         /* dem refuses dt above 3.69e-4 here, Verlet's bound in a dense packing */
         {"dem", "dem", "dem.dt", "2.5e-4,1.25e-4,6.25e-5", "1.25e-4", "material.tangential=spring"},
         {"dem", "dem-sliding", "dem.dt", "2.5e-4,1.25e-4", "", NULL, CMP_BIAS},
         {"edmd", "edmd", NULL, "", "", NULL, CMP_LIMIT, NULL,
          "the sinking floor keeps a dense packing of hard disks moving: no grain is held still long "
          "enough to sleep, the collisions come ever faster (inelastic collapse) and no force lasts"},
     }},
    {.name = "eos", .scene = "eos.ini", .quantity = "Z / Z_Luding(eta_bulk)", .aux = "eta_bulk",
     .unit = "1", .aux_unit = "1",
     .quick_set = "species.count=400;domain.width=33.36043187592832;domain.height=33.36043187592832;"
                  "run.until=25",
     .seeds_full = 6, .seeds_quick = 3, .tol_edmd = 0.05, .tol = 0.05,
     .measure = cmp_measure_eos, .reference = cmp_ref_eos,
     .rows = {
         {"edmd", "edmd", NULL, "", "", NULL},
         {"cd", "cd", "cd.dt", "1e-2,5e-3,2.5e-3", "1e-2,2.5e-3", NULL},
         {"dem", "dem", "dem.dt", "5e-4,2.5e-4,1.25e-4", "5e-4,2.5e-4", NULL},
         {"dsmc", "dsmc", "dsmc.dt", "0.1,0.05,0.02", "0.1,0.02", "dsmc.cell=8"},
     }},
    {.name = "vibrated", .scene = "vibrated.ini", .quantity = "mean height", .aux = "mean temperature",
     .unit = "d", .aux_unit = "m d+2 tau-2",
     .quick_set = "run.until=60", .seeds_full = 8, .seeds_quick = 4, .tol_edmd = 0, .tol = 0.05,
     .measure = cmp_measure_bed, .reference = NULL,
     .rows = {
         {"edmd", "edmd-long", "run.until", "2000", "300", NULL, CMP_REFERENCE},
         {"dem", "dem", "dem.dt", "1e-3,5e-4,2.5e-4", "1e-3,2.5e-4", NULL, 0},
         /* cd: 0.2 ms a step on this bed's 100 grains (its contact detection over the tall box) */
         {"cd", "cd", "cd.dt", "2e-3,1e-3", "2e-3", NULL, 0},
         {"dsmc", "dsmc", "dsmc.dt", "0.01,0.005,0.0025", "0.01,0.0025", "dsmc.cell=4", CMP_LIMIT, NULL,
          "a dilute-gas model under a bed whose lower layers are dense: the bed stands higher and hotter"},
     }},
    {.name = "silo", .scene = "silo.ini", .quantity = "outflow rate", .aux = "kinetic energy per grain",
     .unit = "tau-1", .aux_unit = "m d+2 tau-2",
     .quick_set = "run.until=20", .seeds_full = 3, .seeds_quick = 1, .tol_edmd = 0, .tol = 0.1,
     .measure = cmp_measure_silo, .reference = cmp_ref_silo,
     .rows = {
         {"dem", "dem-long", "run.until", "200", "40", "dem.dt=1.25e-4", CMP_REFERENCE},
         {"dem", "dem", "dem.dt", "5e-4,2.5e-4", "5e-4", NULL, 0},
         {"cd", "cd", "cd.tol", "1e-2,1e-3,1e-4", "1e-2,1e-3", "cd.dt=2e-3", 0},
         {"edmd", "edmd", "edmd.tc", "1e-3,1e-4,1e-5", "1e-3", NULL, 0},
     }},
    {.name = "silo-widths", .scene = "silo.ini", .quantity = "Q(4 d) / Q(6 d)", .aux = "Q(8 d) / Q(6 d)",
     .unit = "1", .aux_unit = "1",
     .quick_set = "run.until=20", .seeds_full = 3, .seeds_quick = 1, .tol_edmd = 0, .tol = 0.1,
     .measure = cmp_measure_silo_widths, .reference = cmp_ref_silo_widths,
     .rows = {
         {"dem", "dem-long", "dem.dt+run.until", "1.25e-4:100", "2.5e-4:40", NULL, CMP_REFERENCE},
         {"dem", "dem", "dem.dt", "5e-4,2.5e-4", "5e-4", NULL, 0},
         {"cd", "cd", "cd.tol", "1e-2,1e-3", "1e-2", "cd.dt=2e-3", 0},
         {"edmd", "edmd", "edmd.tc", "1e-3,1e-4", "1e-3", NULL, 0},
         /* knob: lattice spacing (species.diameter, in grain diameters) : lgca.dt */
         {"lgca", "lgca", "species.diameter+lgca.dt", "1:0.1,0.5:0.05,0.25:0.025,0.125:0.0125",
          "0.5:0.05,0.25:0.025,0.125:0.0125", NULL, CMP_MODEL, "silo-lgca.ini"},
     }},
    {.name = NULL},
};

const cmp_case *cmp_cases(void)
{
    return cases;
}

const char *cmp_ref_label(const cmp_case *c)
{
    for (const cmp_row *r = c->rows; r->method; r++)
        if (r->role == CMP_REFERENCE)
            return r->label;
    return NULL;
}

const char *cmp_role_name(int role)
{
    static const char *const names[] = {"sweep", "reference", "bias", "model", "limit", "own"};
    return role >= 0 && role <= CMP_OWN ? names[role] : "?";
}
