/* Settle once, branch many: the fillings that silo-flow and silo-start
 * share. One unit per realisation fills and settles the silo with an
 * orifice closed (silo-flow's SILO_FILL_D, silo-start's first) and keeps the settled grains in its part
 * (DIR/parts/fill-r<r>.part); every orifice's unit of that realisation
 * branches from it (silo_rebase), as does --peer lammps. */
#ifndef GR_SILO_FILL_H
#define GR_SILO_FILL_H

#include <stddef.h>
#include <stdint.h>

#include "silo_common.h"

/* The orifice closed during silo-flow's fillings. */
#define SILO_FILL_D 6.0

/* What the fillings of a sweep depend on: the silo (its orifice is
 * replaced by `orifice`, closed), realisation r's seed is seed + r, the
 * parts go to dir/parts. A branch to the filling's own orifice needs no
 * lift and settles at its first check. */
typedef struct {
    const silo_cfg *base;
    uint64_t seed;
    const char *dir;
    double orifice;
} silo_fills;

/* The pre-units of a sweep (silo_cli's pre_unit, pre_label, pre_key), ctx
 * a silo_fills. Realisation 0's part also keeps the picture of the filling
 * (thesis fig. 3.1). */
void silo_fill_label(size_t unit, void *ctx, char *buf, size_t n);
void silo_fill_key(size_t unit, void *ctx, char *buf, size_t n);
int silo_fill_unit(size_t unit, const char *part, const char *key, void *ctx, volatile double *progress,
                   gr_err *err);

/* The path of realisation r's filling part; whether it exists with the
 * key of f's filling. */
int silo_fill_path(const silo_fills *f, size_t r, char *path, size_t n);
/* The settled silo of realisation r from its part (with the picture of the
 * filling when the part has one), and the filling's cost record (wall and
 * CPU seconds first). */
int silo_fill_load(const silo_fills *f, size_t r, silo_settled *set, double *fill_cost, gr_err *err);

#endif
