/* Independent units of work spread over MPI ranks (`mpirun -n K grano
 * silo-flow ...`): rank r runs the units r, r + K, r + 2K, ... of a sweep
 * into the shared parts directory; the ranks then agree on the outcome and
 * rank 0 alone writes the report from every part. Each unit draws from its
 * own seeds, so the numbers are those of the serial run. Built without
 * MPI (meson -Dmpi=disabled, or none found), or started without mpirun,
 * everything runs in the one process as before. */
#ifndef GR_EXP_DIST_H
#define GR_EXP_DIST_H

#include "err.h"
#include "sweep.h"

typedef struct {
    int rank, size;
    int mpi; /* MPI_Init was called here (MPI_Finalize in exp_dist_end) */
} exp_dist;

/* Join the MPI job when the program was launched by mpirun (its
 * environment says so); otherwise rank 0 of 1. */
void exp_dist_begin(exp_dist *d);
void exp_dist_end(exp_dist *d);
/* Whether the build has MPI (for --help and messages). */
int exp_dist_available(void);

/* Run this rank's share of the sweep (every unit with one rank), then
 * wait for every rank: the worst status of all of them. err names the
 * failure on the rank where it happened, else says which rank failed. */
int exp_dist_sweep(const exp_dist *d, const exp_sweep *sw, exp_unit_fn fn, exp_label_fn label,
                   exp_label_fn key, void *ctx, gr_err *err);

#endif
