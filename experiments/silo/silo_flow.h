/* grano silo-flow (thesis chapter 4): the unit of work (one orifice size,
 * one realisation) and the report, shared by silo_flow.c and
 * silo_flow_report.c. */
#ifndef GR_SILO_FLOW_H
#define GR_SILO_FLOW_H

#include <stddef.h>
#include <stdint.h>

#include "silo_common.h"

#define SF_MAX_ORIF 48

/* The orifice closed during the filling; every orifice branches from that
 * settled state (silo_rebase). */
#define SF_FILL_D 6.0

typedef struct {
    silo_cfg base;
    int quick;
    double orifice[SF_MAX_ORIF];
    size_t norif;
    int nreal;
    uint64_t seed;
    long discard;       /* steps discarded after opening */
    long block;         /* steps per block */
    int nblocks;
    long sample_every;  /* steps between packing samples */
    double lift;        /* base of the D x D packing square above the silo base */
    double split;       /* small / large orifices for figs. 4.2-4.3 */
    const char *dir;
} sf_ctx;

/* The fillings: one unit per realisation, before the orifices' units. */
void sf_fill_label(size_t unit, void *ctx, char *buf, size_t n);
void sf_fill_key(size_t unit, void *ctx, char *buf, size_t n);
int sf_fill_unit(size_t unit, const char *part, const char *key, void *ctx, volatile double *progress,
                 gr_err *err);

/* The path of realisation r's filling part; whether it exists with the
 * key of c's filling. */
int sf_fill_path(const sf_ctx *c, size_t r, char *path, size_t n);
/* The settled silo of realisation r from its filling part, and the
 * filling's cost record. */
int sf_load_fill(const sf_ctx *c, size_t r, silo_settled *set, double *fill_cost, gr_err *err);

void sf_label(size_t unit, void *ctx, char *buf, size_t n);
void sf_key(size_t unit, void *ctx, char *buf, size_t n);
int sf_unit(size_t unit, const char *part, const char *key, void *ctx, volatile double *progress,
            gr_err *err);
int sf_report(const sf_ctx *c, char *const *parts, char *summary, size_t n, gr_err *err);

/* --peer lammps (silo_peer.c): the first orifice and seed, settled and
 * branched as the sweep does (its filling part reused when DIR holds
 * one), run without reinsertion by dem and by
 * LAMMPS's lmp from the same state; DIR/peer.dat and a summary. */
int sf_peer_lammps(const sf_ctx *c, char *summary, size_t n, gr_err *err);

#endif
