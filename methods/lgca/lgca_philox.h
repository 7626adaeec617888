/* Philox4x32-10 calls side by side (lgca_rand.c, lgca_dense.c). */
#ifndef GR_LGCA_PHILOX_H
#define GR_LGCA_PHILOX_H

#include <Random123/philox.h>
#include <stdint.h>
#include <stddef.h>

/* Up to 16 Philox calls side
 * by side in arrays that GCC vectorises (pmuludq for the 32x32->64-bit
 * products; four or eight lanes a vector in the AVX2 clone): the round of
 * Random123's philox4x32, written out, must agree with draw() (tested). */
#define LGCA_BATCH 16

typedef struct {
    uint32_t v[4][LGCA_BATCH];
} philox_batch;

/* nb <= LGCA_BATCH calls (a constant once inlined); ix: the words'
 * offsets from word0 (NULL: 0, 1, 2, ...). omp simd: without it GCC
 * unrolls eight calls into scalar code instead of vectorising them. */
static inline __attribute__((always_inline)) void drawn(const uint32_t key[2], uint64_t word0, const uint32_t *ix,
                                                        unsigned purpose, uint64_t step, philox_batch *b, int nb)
{
    uint32_t *c0 = b->v[0], *c1 = b->v[1], *c2 = b->v[2], *c3 = b->v[3];
    for (int i = 0; i < nb; i++) {
        uint64_t w = word0 + (ix ? (uint64_t)ix[i] : (uint64_t)i);
        c0[i] = (uint32_t)w, c1[i] = (uint32_t)(w >> 32) ^ (purpose << 24);
        c2[i] = (uint32_t)step, c3[i] = (uint32_t)(step >> 32);
    }
    uint32_t k0 = key[0], k1 = key[1];
    for (int r = 0; r < 10; r++) {
        if (r)
            k0 += PHILOX_W32_0, k1 += PHILOX_W32_1;
#pragma omp simd
        for (int i = 0; i < nb; i++) {
            uint64_t p0 = (uint64_t)PHILOX_M4x32_0 * c0[i], p1 = (uint64_t)PHILOX_M4x32_1 * c2[i];
            uint32_t n0 = (uint32_t)(p1 >> 32) ^ c1[i] ^ k0, n2 = (uint32_t)(p0 >> 32) ^ c3[i] ^ k1;
            c1[i] = (uint32_t)p1, c3[i] = (uint32_t)p0, c0[i] = n0, c2[i] = n2;
        }
    }
}

/* The m <= LGCA_BATCH calls wanted, rounded up to 8 or 16 (constants). */
static inline __attribute__((always_inline)) void draw_m(const uint32_t key[2], uint64_t word0, const uint32_t *ix,
                                                         unsigned purpose, uint64_t step, philox_batch *b, size_t m)
{
    if (m > 8)
        drawn(key, word0, ix, purpose, step, b, LGCA_BATCH);
    else
        drawn(key, word0, ix, purpose, step, b, 8);
}

#endif
