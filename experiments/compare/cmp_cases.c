/* The cases of grano compare and, for each, its rows: which method runs it,
 * over which knob, at which values. A method joins a case with one row.
 *
 * lgca (lattice gas, fields only) is not in any row yet: its rows (knob:
 * the lattice resolution) go into the vibrated-bed and silo cases when
 * those cases and the backend land (docs/comparison.md). */
#include <stddef.h>

#include "cmp.h"

static const cmp_case cases[] = {
    {.name = "collision", .scene = "collision.ini", .quantity = "restitution", .aux = "contact time",
     .seeds_full = 16, .seeds_quick = 4, .tol_edmd = 1e-9,
     .measure = cmp_measure_collision, .reference = cmp_ref_collision, .prepare = cmp_prepare_collision,
     .rows = {
         {"dem", "dem", "dem.dt", "2e-3,1e-3,5e-4,2.5e-4,1.25e-4,6.25e-5", "2e-3,5e-4,1.25e-4", NULL},
         {"dem", "dem-gear", "dem.dt", "2e-3,1e-3,5e-4,2.5e-4,1.25e-4", "2e-3,5e-4,1.25e-4", "dem.integrator=gear"},
         {"edmd", "edmd", NULL, "", "", NULL},
         {"cd", "cd", "cd.dt", "1e-2,1e-3,1e-4", "1e-2,1e-3", NULL},
     }},
    {.name = "cooling-dilute", .scene = "cooling-dilute.ini", .quantity = "T/T0 at Haff's time",
     .aux = "T/T0 at half Haff's time",
     .quick_set = "species.count=256;domain.width=44.83992973118343;domain.height=44.83992973118343",
     .seeds_full = 8, .seeds_quick = 3, .tol_edmd = 0.04,
     .measure = cmp_measure_cooling, .reference = cmp_ref_cooling, .prepare = cmp_prepare_cooling,
     .rows = {
         {"edmd", "edmd", NULL, "", "", NULL},
         {"dem", "dem", "dem.dt", "2e-3,1e-3,5e-4", "2e-3,5e-4", NULL},
         {"dsmc", "dsmc", "dsmc.dt", "0.4,0.2,0.1,0.05", "0.4,0.1", NULL},
     }},
    {.name = "cooling-dense", .scene = "cooling-dense.ini", .quantity = "T/T0 at Haff's time",
     .aux = "T/T0 at half Haff's time",
     .quick_set = "species.count=256;domain.width=25.888345500742656;domain.height=25.888345500742656",
     .seeds_full = 8, .seeds_quick = 3, .tol_edmd = 0.06,
     .measure = cmp_measure_cooling, .reference = cmp_ref_cooling, .prepare = cmp_prepare_cooling,
     .rows = {
         {"edmd", "edmd", NULL, "", "", NULL},
         {"dem", "dem", "dem.dt", "2e-3,1e-3,5e-4", "2e-3,5e-4", NULL},
         {"dsmc", "dsmc", "dsmc.dt", "0.2,0.1,0.05,0.02", "0.2,0.05", NULL},
     }},
    {.name = "column", .scene = "column.ini", .quantity = "wall force / weight", .aux = "top height",
     .seeds_full = 1, .seeds_quick = 1, .tol_edmd = 0,
     .measure = cmp_measure_column, .reference = cmp_ref_column,
     .rows = {
         {"dem", "dem", "dem.dt", "5e-4,2.5e-4,1.25e-4", "5e-4,1.25e-4", NULL},
         {"cd", "cd", "cd.tol", "1e-2,1e-3,1e-4,1e-5,1e-6", "1e-2,1e-4,1e-6", NULL},
     }},
    {.name = "eos", .scene = "eos.ini", .quantity = "Z = PA/(NT)", .aux = "T/T0",
     .quick_set = "species.count=144;domain.width=20.416259125556994;domain.height=20.416259125556994;"
                  "run.until=15",
     .seeds_full = 4, .seeds_quick = 2, .tol_edmd = 0.05,
     .measure = cmp_measure_eos, .reference = cmp_ref_eos,
     .rows = {
         {"edmd", "edmd", NULL, "", "", NULL},
         {"dem", "dem", "dem.dt", "5e-4,2.5e-4,1.25e-4", "5e-4,2.5e-4", NULL},
         {"dsmc", "dsmc", "dsmc.dt", "0.1,0.05,0.02", "0.1,0.02", NULL},
     }},
    {.name = NULL},
};

const cmp_case *cmp_cases(void)
{
    return cases;
}
