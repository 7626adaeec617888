/* The collisions' random numbers: Philox2x64-10 (Random123) keyed by the
 * run's key, counted by (step, cell, draw), so that a cell's draws depend
 * on nothing but its contents and its place in the run: no generator
 * state to save, cells in any order or on any thread
 * (docs/methods/dsmc.md: generator). */
#ifndef GR_DSMC_RNG_H
#define GR_DSMC_RNG_H

#include <stddef.h>
#include <stdint.h>

#include <Random123/philox.h>

/* The counter of the grid's shift: no cell has this index. */
#define GR_DSMC_RNG_GRID 0xffffffffu

typedef struct {
    philox2x64_key_t key;
    philox2x64_ctr_t ctr;
    uint64_t buf[2];
    int left;
} gr_dsmc_rng;

static inline void gr_dsmc_rng_init(gr_dsmc_rng *r, uint64_t key, uint64_t step, size_t cell)
{
    r->key.v[0] = key;
    r->ctr.v[0] = step, r->ctr.v[1] = (uint64_t)cell << 32;
    r->left = 0;
}

static inline uint64_t gr_dsmc_next64(gr_dsmc_rng *r)
{
    if (!r->left) {
        philox2x64_ctr_t o = philox2x64(r->ctr, r->key);
        r->ctr.v[1]++;
        r->buf[0] = o.v[0], r->buf[1] = o.v[1], r->left = 2;
    }
    return r->buf[--r->left];
}

/* [0, 1) from the top 53 bits. */
static inline double gr_dsmc_uniform(gr_dsmc_rng *r) { return (double)(gr_dsmc_next64(r) >> 11) * 0x1.0p-53; }

/* [0, m) from u in [0, 1): the bias of the 53-bit product is below m / 2^53. */
static inline size_t gr_dsmc_below(double u, size_t m)
{
    size_t k = (size_t)(u * (double)m);
    return k < m ? k : m - 1;
}

#endif
