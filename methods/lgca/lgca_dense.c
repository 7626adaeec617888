/* Biased random bits (each 1 with probability thr / 2^16) at the needed
 * nodes of whole lanes, drawn on dense words of needed nodes.
 *
 * A node compares a 16-bit uniform U with thr from the most significant
 * bit, two bits a round, and is decided at the first round where they
 * differ (3/4 of the nodes still undecided are decided each round). Drawn
 * word by word in place, a word must draw until all its ~20 needed nodes
 * are decided: ~3 Philox calls. Here the K needed nodes of lane j are
 * numbered in order; round r gives dense word d (undecided nodes 64 d ..
 * 64 d + 63 of the round, in order) the two bits of one Philox call
 * counted (j nw + d, purpose + q, step), q = 7 - r; the undecided nodes
 * of round r are numbered again for round r + 1. A lane thus costs about
 * (4/3) K / 64 calls, plus one a round for the rounds' last words.
 *
 * Going back needs only a deposit of bits (pdep): a round's results fill
 * the undecided bits of the round before, and round 0's fill the needed
 * nodes. Results depend on the lane, not on which thread draws it. BMI2's
 * pdep is used where it is fast; AMD Zen 1 and 2 run it in microcode
 * (tens to hundreds of cycles, growing with the mask's set bits), so
 * they take the portable loop, which gives the same bits (and so does a
 * -DLGCA_NO_CLONES build). */
#include <string.h>

#include "lgca_int.h"
#include "lgca_philox.h"

#define ROUNDS 8

/* The 64 bits of stream s from bit pos on; only the low ones are used (a
 * deposit takes as many as its mask has set), so there is no branch on
 * the length or on the word boundary (a mispredicted branch a word, when
 * a third of the words straddle). Reads s[pos / 64 + 1], which the
 * scratch always holds. */
static inline uint64_t bits_from(const uint64_t *s, size_t pos)
{
    size_t w = pos >> 6;
    unsigned b = (unsigned)(pos & 63);
    return s[w] >> b | (s[w + 1] << 1) << (63 - b);
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(LGCA_NO_CLONES)
#include <immintrin.h>
#define HAVE_BMI2_PATH 1
static inline __attribute__((always_inline, target("bmi2"))) uint64_t pdep_hw(uint64_t src, uint64_t mask)
{
    return _pdep_u64(src, mask);
}
#endif

/* Results back from the deepest round to the nodes: a round's dense words
 * (lt) take, at their undecided bits (eq), the next bits of the following
 * round's results; cnt[r nl + l]: undecided nodes of lane l entering round r. */
static inline __attribute__((always_inline)) void
scatter_t(size_t nl, size_t nw, int nr, const uint32_t *cnt, uint64_t *lt, const uint64_t *eq, const uint64_t *need,
          uint64_t *out, uint64_t (*dep)(uint64_t, uint64_t))
{
    size_t base[ROUNDS + 1] = {0};
    for (int r = 0; r < nr; r++) {
        base[r + 1] = base[r];
        for (size_t l = 0; l < nl; l++)
            base[r + 1] += (cnt[(size_t)r * nl + l] + 63) / 64;
    }
    for (int r = nr - 2; r >= 0; r--) {
        size_t at = base[r], next = base[r + 1];
        for (size_t l = 0; l < nl; l++) {
            size_t nd = (cnt[(size_t)r * nl + l] + 63) / 64, pos = 0;
            for (size_t d = 0; d < nd; d++) {
                unsigned k = (unsigned)__builtin_popcountll(eq[at + d]);
                lt[at + d] |= dep(bits_from(lt + next, pos), eq[at + d]);
                pos += k;
            }
            at += nd, next += (cnt[(size_t)(r + 1) * nl + l] + 63) / 64;
        }
    }
    size_t at = 0;
    for (size_t l = 0; l < nl; l++) {
        size_t pos = 0;
        for (size_t w = 0; w < nw; w++) {
            uint64_t m = need[l * nw + w];
            unsigned k = (unsigned)__builtin_popcountll(m);
            out[l * nw + w] = dep(bits_from(lt + at, pos), m);
            pos += k;
        }
        at += (cnt[l] + 63) / 64;
    }
}

/* Round r (Philox purpose + q) on the nd dense words from lt + 0, eq + 0
 * of the lanes' undecided counts c; the undecided counts of the next round
 * into cn. */
static inline __attribute__((always_inline)) void round_t(const uint32_t key[2], uint64_t word0, size_t nw,
                                                          unsigned purpose, int q, uint64_t step, uint32_t thr,
                                                          const uint32_t *c, uint32_t *cn, size_t nd, uint64_t *lt,
                                                          uint64_t *eq)
{
    philox_batch b;
    uint32_t ix[LGCA_BATCH] = {0};
    uint64_t tb1 = (thr >> (2 * q + 1) & 1u) ? ~(uint64_t)0 : 0, tb0 = (thr >> (2 * q) & 1u) ? ~(uint64_t)0 : 0;
    size_t l = 0, d = 0;
    for (size_t k0 = 0; k0 < nd; k0 += LGCA_BATCH) {
        size_t m = nd - k0 < LGCA_BATCH ? nd - k0 : LGCA_BATCH;
        uint64_t valid[LGCA_BATCH];
        for (size_t i = 0; i < m; i++, d++) {
            while (d * 64 >= c[l])
                l++, d = 0;
            ix[i] = (uint32_t)(l * nw + d);
            size_t left = c[l] - d * 64;
            valid[i] = left >= 64 ? ~(uint64_t)0 : ((uint64_t)1 << left) - 1;
        }
        draw_m(key, word0, ix, purpose + (unsigned)q, step, &b, m);
        for (size_t i = 0; i < m; i++) {
            uint64_t u1 = (uint64_t)b.v[2][i] | (uint64_t)b.v[3][i] << 32;
            uint64_t u0 = (uint64_t)b.v[0][i] | (uint64_t)b.v[1][i] << 32;
            uint64_t e = valid[i];
            uint64_t t = e & ~u1 & tb1;
            e &= ~(u1 ^ tb1);
            t |= e & ~u0 & tb0;
            e &= ~(u0 ^ tb0);
            lt[k0 + i] = t, eq[k0 + i] = e;
            cn[ix[i] / nw] += (uint32_t)__builtin_popcountll(e);
        }
    }
}

static inline __attribute__((always_inline)) void
biased_t(const uint32_t key[2], uint64_t lane0, size_t nl, size_t nw, unsigned purpose, uint64_t step, uint32_t thr,
         const uint64_t *need, uint64_t *out, uint64_t *scratch, uint64_t (*dep)(uint64_t, uint64_t))
{
    uint32_t cnt[(ROUNDS + 1) * LGCA_CHUNK_WORDS]; /* [r * nl + l]; the row after the last round unused */
    uint64_t *lt = scratch, *eq = scratch + ROUNDS * nl * nw;
    size_t nd = 0, at = 0;
    for (size_t l = 0; l < nl; l++) {
        uint32_t k = 0;
        for (size_t w = 0; w < nw; w++)
            k += (uint32_t)__builtin_popcountll(need[l * nw + w]);
        cnt[l] = k, nd += (k + 63) / 64;
    }
    int nr = 0;
    for (; nd && nr < ROUNDS; nr++) {
        uint32_t *c = cnt + (size_t)nr * nl, *cn = c + nl;
        memset(cn, 0, nl * sizeof *cn);
        round_t(key, lane0 * nw, nw, purpose, ROUNDS - 1 - nr, step, thr, c, cn, nd, lt + at, eq + at);
        at += nd, nd = 0;
        for (size_t l = 0; l < nl; l++)
            nd += (cn[l] + 63) / 64;
    }
    scatter_t(nl, nw, nr, cnt, lt, eq, need, out, dep);
}

#define BIASED_ARGS                                                                                             \
    const uint32_t key[2], uint64_t lane0, size_t nl, size_t nw, unsigned purpose, uint64_t step, uint32_t thr, \
        const uint64_t *need, uint64_t *out, uint64_t *scratch
static void biased_base(BIASED_ARGS)
{
    biased_t(key, lane0, nl, nw, purpose, step, thr, need, out, scratch, lgca_pdep_soft);
}

#ifdef HAVE_BMI2_PATH
/* popcnt too: AVX2 alone leaves popcount to a call into libgcc */
__attribute__((target("avx2,popcnt"))) static void biased_avx2(BIASED_ARGS)
{
    biased_t(key, lane0, nl, nw, purpose, step, thr, need, out, scratch, lgca_pdep_soft);
}

__attribute__((target("avx2,popcnt,bmi2"))) static void biased_bmi2(BIASED_ARGS)
{
    biased_t(key, lane0, nl, nw, purpose, step, thr, need, out, scratch, pdep_hw);
}
#endif

void lgca_rand_biased_lanes(BIASED_ARGS)
{
    if (thr == 0 || thr >= 65536u) {
        for (size_t w = 0; w < nl * nw; w++)
            out[w] = thr ? need[w] : 0;
        return;
    }
#ifdef HAVE_BMI2_PATH
    __builtin_cpu_init();
    int avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("popcnt");
    /* Zen 1 and 2 run pdep in microcode */
    if (avx2 && __builtin_cpu_supports("bmi2") && !__builtin_cpu_is("znver1") && !__builtin_cpu_is("znver2"))
        biased_bmi2(key, lane0, nl, nw, purpose, step, thr, need, out, scratch);
    else if (avx2)
        biased_avx2(key, lane0, nl, nw, purpose, step, thr, need, out, scratch);
    else
#endif
        biased_base(key, lane0, nl, nw, purpose, step, thr, need, out, scratch);
}
