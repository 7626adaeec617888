/* Random bits from Philox4x32-10 (Salmon et al., SC'11; Debian's
 * librandom123-dev): a pure function of the run's key and a counter made
 * of the word (lane and word in it), the purpose and the step, so a node
 * draws the same bits whichever thread updates it and after a restart. */
#include <Random123/philox.h>
#include <string.h>

#include "lgca_int.h"

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

/* ---- the same bits for a run of consecutive words, 16 Philox calls side
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

/* lgca_rand_biased on 16 words at once: a Philox call is made while any
 * of the 16 is undecided (the others ignore it, so the bits agree). Such a
 * batch makes more calls than one word alone would, but batches of 8 (and
 * 64-bit counters, without repacking) measured slower. */
LGCA_CLONES void lgca_rand_biased_words(const uint32_t key[2], uint64_t word0, size_t n, unsigned purpose,
                                        uint64_t step, uint32_t thr, uint64_t *out)
{
    philox_batch b;
    for (size_t w0 = 0; w0 < n; w0 += LGCA_BATCH) {
        size_t m = n - w0 < LGCA_BATCH ? n - w0 : LGCA_BATCH;
        if (m <= 4) { /* a batch of 256 lanes would waste more calls than it saves */
            for (size_t i = 0; i < m; i++)
                out[w0 + i] = lgca_rand_biased(key, word0 + w0 + i, purpose, step, thr);
            continue;
        }
        uint64_t lt[LGCA_BATCH] = {0}, eq[LGCA_BATCH];
        for (int i = 0; i < LGCA_BATCH; i++)
            eq[i] = thr == 0 || thr >= 65536u ? 0 : ~(uint64_t)0;
        for (int q = 7; q >= 0; q--) {
            uint64_t any = 0;
            for (size_t i = 0; i < m; i++)
                any |= eq[i];
            if (!any)
                break;
            draw_m(key, word0 + w0, NULL, purpose + (unsigned)q, step, &b, m);
            for (int h = 1; h >= 0; h--) {
                uint64_t tb = (thr >> (2 * q + h) & 1u) ? ~(uint64_t)0 : 0;
                for (size_t i = 0; i < m; i++) {
                    uint64_t u = (uint64_t)b.v[2 * h][i] | (uint64_t)b.v[2 * h + 1][i] << 32;
                    lt[i] |= eq[i] & ~u & tb;
                    eq[i] &= ~(u ^ tb);
                }
            }
        }
        for (size_t i = 0; i < m; i++)
            out[w0 + i] = thr >= 65536u ? ~(uint64_t)0 : lt[i];
    }
}

/* lgca_rand_biased's bits at the lanes of need, 0 elsewhere, word by word
 * as they are undecided: each pair of bits of U is drawn (batched over
 * the list idx of the words still undecided, compacted after each) only
 * for words with a needed lane not yet decided. A word with no needed lane
 * (no node whose collision the bit can change) costs no Philox call; one
 * whose lanes are decided after the first bits costs no more, whatever
 * its batch neighbours need. eq, idx: n words of scratch each. */
LGCA_CLONES void lgca_rand_biased_need(const uint32_t key[2], uint64_t word0, size_t n, unsigned purpose,
                                       uint64_t step, uint32_t thr, const uint64_t *need, uint64_t *out,
                                       uint64_t *eq, uint32_t *idx)
{
    size_t m = 0;
    for (size_t w = 0; w < n; w++) {
        out[w] = thr >= 65536u ? need[w] : 0;
        eq[w] = need[w];
        if (need[w] && thr && thr < 65536u)
            idx[m++] = (uint32_t)w;
    }
    philox_batch b;
    for (int q = 7; q >= 0 && m; q--) {
        for (size_t i0 = 0; i0 < m; i0 += LGCA_BATCH) {
            size_t k = m - i0 < LGCA_BATCH ? m - i0 : LGCA_BATCH;
            uint32_t ix[LGCA_BATCH] = {0};
            memcpy(ix, idx + i0, k * sizeof *ix);
            draw_m(key, word0, ix, purpose + (unsigned)q, step, &b, k);
            for (size_t i = 0; i < k; i++) {
                uint32_t w = ix[i];
                uint64_t lt = out[w], e = eq[w];
                for (int h = 1; h >= 0; h--) {
                    uint64_t tb = (thr >> (2 * q + h) & 1u) ? ~(uint64_t)0 : 0;
                    uint64_t u = (uint64_t)b.v[2 * h][i] | (uint64_t)b.v[2 * h + 1][i] << 32;
                    lt |= e & ~u & tb;
                    e &= ~(u ^ tb);
                }
                out[w] = lt, eq[w] = e;
            }
        }
        size_t m2 = 0;
        for (size_t i = 0; i < m; i++)
            if (eq[idx[i]])
                idx[m2++] = idx[i];
        m = m2;
    }
}
