/* Random streams on GSL: one generator per independent stream, derived
 * from an explicit (seed, stream) pair. No global generator. */
#ifndef GR_RNG_H
#define GR_RNG_H

#include <stddef.h>
#include <stdint.h>

#include <gsl/gsl_rng.h>

#include "err.h"

typedef struct gr_rng gr_rng;

/* Streams with different (seed, stream) are statistically independent:
 * the pair is hashed (splitmix64) into the generator's seed. */
gr_rng *gr_rng_create(uint64_t seed, uint64_t stream, gr_err *err);
void gr_rng_free(gr_rng *r);
/* The 64-bit key of (seed, stream), hashed as for the generators above:
 * for counter-based generators (Random123) keyed by the stream. */
uint64_t gr_rng_key(uint64_t seed, uint64_t stream);
gsl_rng *gr_rng_gsl(gr_rng *r);       /* for gsl_ran_* */
double gr_rng_uniform(gr_rng *r);     /* [0, 1) */
double gr_rng_uniform_pos(gr_rng *r); /* (0, 1) */
double gr_rng_gaussian(gr_rng *r, double sigma);
unsigned long gr_rng_below(gr_rng *r, unsigned long n); /* [0, n) */
/* Its state in a checkpoint: gr_rng_save, gr_rng_load (io/ckpt.h). */

/* Every random stream id of the code, in one place so that no two draw
 * the same numbers: a stream is the pair (scene seed, id). A backend's own
 * streams are GR_STREAM_METHOD_BASE + k, handed out by gr_sim_stream. */
enum {
    GR_STREAM_INIT = 0x1417,           /* initial positions and velocities */
    GR_STREAM_DEM_REINSERT = 0xD3E1,   /* dem: reinsertion spots */
    GR_STREAM_EDMD = 0x65646d64,       /* edmd: high-frequency floor phases */
    GR_STREAM_SILO_START = 77,         /* silo-start: per-discharge seeds */
    GR_STREAM_METHOD_BASE = 0x10000    /* first of the streams a backend
                                          numbers itself (gr_sim_stream) */
};
#endif
