/* Random bits from Philox4x32-10 (Salmon et al., SC'11; Debian's
 * librandom123-dev): a pure function of the run's key and a counter made
 * of the word (lane and word in it), the purpose and the step, so a node
 * draws the same bits whichever thread updates it and after a restart. */
#include <Random123/philox.h>

#include "lgca_int.h"

static philox4x32_ctr_t draw(const uint32_t key[2], uint64_t word, unsigned purpose, uint64_t step)
{
    philox4x32_ctr_t c = {{(uint32_t)word, (uint32_t)(word >> 32) ^ (purpose << 24),
                           (uint32_t)step, (uint32_t)(step >> 32)}};
    philox4x32_key_t k = {{key[0], key[1]}};
    return philox4x32(c, k);
}

uint64_t lgca_rand_word(const uint32_t key[2], uint64_t word, unsigned purpose, uint64_t step)
{
    philox4x32_ctr_t r = draw(key, word, purpose, step);
    return (uint64_t)r.v[0] | (uint64_t)r.v[1] << 32;
}

uint32_t lgca_rand_u32(const uint32_t key[2], uint64_t node, unsigned purpose, uint64_t step)
{
    return draw(key, node, purpose, step).v[0];
}

/* Lane by lane, a 16-bit uniform number U compared with thr bit-sliced from
 * its most significant bit: a lane is decided at the first bit where U and
 * thr differ, so the loop stops once all 64 are (usually after 8 bits).
 * Bits 2q and 2q+1 of U come from one Philox call (purpose + q). */
uint64_t lgca_rand_biased(const uint32_t key[2], uint64_t word, unsigned purpose, uint64_t step,
                          uint32_t thr)
{
    if (thr == 0)
        return 0;
    if (thr >= 65536u)
        return ~(uint64_t)0;
    uint64_t lt = 0, eq = ~(uint64_t)0;
    for (int q = 7; q >= 0 && eq; q--) {
        philox4x32_ctr_t r = draw(key, word, purpose + (unsigned)q, step);
        uint64_t u[2] = {(uint64_t)r.v[0] | (uint64_t)r.v[1] << 32,
                         (uint64_t)r.v[2] | (uint64_t)r.v[3] << 32};
        for (int h = 1; h >= 0 && eq; h--) {
            int bit = 2 * q + h;
            uint64_t tb = (thr >> bit & 1u) ? ~(uint64_t)0 : 0;
            lt |= eq & ~u[h] & tb;
            eq &= ~(u[h] ^ tb);
        }
    }
    return lt;
}
