/* grano silo-flow (thesis chapter 4): the unit of work (one orifice size,
 * one realisation) and the report, shared by silo_flow.c and
 * silo_flow_report.c. */
#ifndef GR_SILO_FLOW_H
#define GR_SILO_FLOW_H

#include <stddef.h>
#include <stdint.h>

#include "silo_common.h"
#include "silo_fill.h"

#define SF_MAX_ORIF 48

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
    silo_fills fills;   /* one per realisation, before the orifices' units */
} sf_ctx;

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
