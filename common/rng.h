/* Random streams on GSL: one generator per independent stream, derived
 * from an explicit (seed, stream) pair. No global generator. */
#ifndef GR_RNG_H
#define GR_RNG_H

#include <stddef.h>
#include <stdint.h>

#include <gsl/gsl_rng.h>

#include "ckpt.h"
#include "err.h"

typedef struct gr_rng gr_rng;

/* Streams with different (seed, stream) are statistically independent:
 * the pair is hashed (splitmix64) into the generator's seed. */
gr_rng *gr_rng_create(uint64_t seed, uint64_t stream, gr_err *err);
void gr_rng_free(gr_rng *r);
gsl_rng *gr_rng_gsl(gr_rng *r);       /* for gsl_ran_* */
double gr_rng_uniform(gr_rng *r);     /* [0, 1) */
double gr_rng_uniform_pos(gr_rng *r); /* (0, 1) */
double gr_rng_gaussian(gr_rng *r, double sigma);
unsigned long gr_rng_below(gr_rng *r, unsigned long n); /* [0, n) */
/* Generator state, for checkpoints (name is the dataset name). */
int gr_rng_save(const gr_rng *r, gr_ckpt *ck, const char *name, gr_err *err);
int gr_rng_load(gr_rng *r, gr_ckpt *ck, const char *name, gr_err *err);

#endif
