/* Random bits from Philox4x32-10 (Salmon et al., SC'11; Debian's
 * librandom123-dev): a pure function of the run's key and a counter made
 * of the word (lane and word in it), the purpose and the step, so a node
 * draws the same bits whichever thread updates it and after a restart. */
#include <Random123/philox.h>
#include <string.h>

#include "lgca_int.h"
#include "lgca_philox.h"

static philox4x32_ctr_t draw(const uint32_t key[2], uint64_t word, unsigned purpose, uint64_t step)
{
    philox4x32_ctr_t c = {{(uint32_t)word, (uint32_t)(word >> 32) ^ (purpose << 24),
                           (uint32_t)step, (uint32_t)(step >> 32)}};
    philox4x32_key_t k = {{key[0], key[1]}};
    return philox4x32(c, k);
}

/* A call's 128 bits make two words: word w is half w & 1 of call w >> 1. */
uint64_t lgca_rand_word(const uint32_t key[2], uint64_t word, unsigned purpose, uint64_t step)
{
    philox4x32_ctr_t r = draw(key, word >> 1, purpose, step);
    int h = (int)(word & 1u) * 2;
    return (uint64_t)r.v[h] | (uint64_t)r.v[h + 1] << 32;
}

uint32_t lgca_rand_u32(const uint32_t key[2], uint64_t node, unsigned purpose, uint64_t step)
{
    return draw(key, node, purpose, step).v[0];
}

LGCA_CLONES void lgca_rand_words(const uint32_t key[2], uint64_t word0, size_t n, unsigned purpose, uint64_t step,
                                 uint64_t *out)
{
    if (!n)
        return;
    philox_batch b;
    uint64_t c0 = word0 >> 1, nc = ((word0 + n - 1) >> 1) - c0 + 1;
    for (uint64_t k0 = 0; k0 < nc; k0 += LGCA_BATCH) {
        size_t m = nc - k0 < LGCA_BATCH ? (size_t)(nc - k0) : LGCA_BATCH;
        draw_m(key, c0 + k0, NULL, purpose, step, &b, m);
        for (size_t i = 0; i < m; i++)
            for (int h = 0; h < 2; h++) {
                uint64_t w = 2 * (c0 + k0 + i) + (uint64_t)h;
                if (w >= word0 && w - word0 < n)
                    out[w - word0] = (uint64_t)b.v[2 * h][i] | (uint64_t)b.v[2 * h + 1][i] << 32;
            }
    }
}
