#include "rng.h"

#include <stdlib.h>

#include <gsl/gsl_randist.h>

struct gr_rng {
    gsl_rng *g;
};

/* splitmix64: a bijective mixer, so distinct (seed, stream) pairs give
 * well-separated generator seeds. */
static uint64_t mix64(uint64_t z)
{
    z += 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

uint64_t gr_rng_key(uint64_t seed, uint64_t stream)
{
    return mix64(mix64(seed) ^ mix64(stream + 0x632be59bd9b4e019ULL));
}

gr_rng *gr_rng_create(uint64_t seed, uint64_t stream, gr_err *err)
{
    gr_rng *r = malloc(sizeof *r);
    if (!r || !(r->g = gsl_rng_alloc(gsl_rng_mt19937))) {
        free(r);
        gr_fail(err, GR_ERUN, "out of memory for a random stream");
        return NULL;
    }
    /* mt19937 takes 32 bits of seed; 0 would select GSL's default seed. */
    uint64_t h = gr_rng_key(seed, stream);
    unsigned long s = (unsigned long)((h ^ (h >> 32)) & 0xffffffffUL);
    gsl_rng_set(r->g, s ? s : 0x5eed);
    return r;
}

void gr_rng_free(gr_rng *r)
{
    if (!r)
        return;
    gsl_rng_free(r->g);
    free(r);
}

gsl_rng *gr_rng_gsl(gr_rng *r) { return r->g; }
double gr_rng_uniform(gr_rng *r) { return gsl_rng_uniform(r->g); }
double gr_rng_uniform_pos(gr_rng *r) { return gsl_rng_uniform_pos(r->g); }
double gr_rng_gaussian(gr_rng *r, double sigma) { return gsl_ran_gaussian_ziggurat(r->g, sigma); }
unsigned long gr_rng_below(gr_rng *r, unsigned long n) { return gsl_rng_uniform_int(r->g, n); }
