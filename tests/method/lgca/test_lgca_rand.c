/* The biased random bits of lgca_dense.c: the bits its definition gives
 * (written out node by node here, independently of the dense words), the
 * portable pdep against a bit loop, and their statistics: the frequency of
 * ones against p, and no correlation between nodes, lanes, steps and
 * purposes. */
#include <Random123/philox.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lgca_test.h"

#define MAXNODES (70 * 64)

/* lgca_rand_biased_lanes' definition for lane j: round by round (q = 7
 * .. 0) the still undecided needed nodes in order, the k-th drawing bits
 * 2q + 1 and 2q of its 16-bit U from bit k % 64 of words 1 and 0 of the
 * Philox call counted (j nw + k / 64, purpose + q, step). */
static void biased_by_definition(const uint32_t key[2], uint64_t j, size_t nw, unsigned purpose, uint64_t step,
                                 uint32_t thr, const uint64_t *need, uint64_t *out)
{
    static int list[MAXNODES];
    int n = 0;
    memset(out, 0, nw * sizeof *out);
    for (int i = 0; i < (int)nw * 64; i++)
        if (need[i >> 6] >> (i & 63) & 1u)
            list[n++] = i;
    for (int q = 7; q >= 0 && thr && n; q--) {
        int m = 0;
        for (int k = 0; k < n; k++) {
            uint64_t word = j * nw + (uint64_t)(k / 64);
            philox4x32_ctr_t c = {{(uint32_t)word, (uint32_t)(word >> 32) ^ ((purpose + (unsigned)q) << 24),
                                   (uint32_t)step, (uint32_t)(step >> 32)}};
            philox4x32_key_t kk = {{key[0], key[1]}};
            philox4x32_ctr_t r = philox4x32(c, kk);
            int b = k % 64, i = list[k];
            unsigned u1 = (b < 32 ? r.v[2] >> b : r.v[3] >> (b - 32)) & 1u;
            unsigned u0 = (b < 32 ? r.v[0] >> b : r.v[1] >> (b - 32)) & 1u;
            unsigned t1 = thr >> (2 * q + 1) & 1u, t0 = thr >> (2 * q) & 1u;
            if (thr >= 65536u || u1 < t1 || (u1 == t1 && u0 < t0))
                out[i >> 6] |= (uint64_t)1 << (i & 63);
            else if (u1 == t1 && u0 == t0)
                list[m++] = i;
        }
        n = thr >= 65536u ? 0 : m;
    }
}

/* Lanes of 1, 3 and 70 words drawn together in one call, with no, one,
 * some and all nodes needed, at thresholds from never to always: each lane
 * as its definition, whatever lanes it is drawn with. */
static void biased_lanes_follow_definition(void **unused)
{
    (void)unused;
    const uint32_t key[2] = {0x12345678u, 0x9abcdef0u};
    const uint32_t thr[] = {0, 1, 6554, 32768, 65535, 65536};
    const size_t nws[] = {1, 3, 70}, nl = 5;
    uint64_t *need = malloc(nl * 70 * sizeof *need), *out = malloc(nl * 70 * sizeof *out);
    uint64_t *scr = malloc(LGCA_DENSE_SCRATCH * nl * 70 * sizeof *scr), ref[70];
    assert_non_null(need), assert_non_null(out), assert_non_null(scr);
    for (size_t a = 0; a < 3; a++)
        for (size_t t = 0; t < sizeof thr / sizeof thr[0]; t++) {
            size_t nw = nws[a];
            uint64_t step = ((uint64_t)1 << 33) + t, lane0 = 1000 + a;
            for (size_t l = 0; l < nl; l++)
                for (size_t w = 0; w < nw; w++)
                    need[l * nw + w] = l == 0 ? 0 : l == 1 ? (uint64_t)(w == nw / 2) << 17
                                                 : l == 2 ? lgca_rand_word(key, w, 99, step)
                                                 : l == 3 ? lgca_rand_word(key, w, 98, step) | 1u : ~(uint64_t)0;
            lgca_rand_biased_lanes(key, lane0, nl, nw, LGCA_RND_P, step, thr[t], need, out, scr);
            for (size_t l = 0; l < nl; l++) {
                biased_by_definition(key, lane0 + l, nw, LGCA_RND_P, step, thr[t], need + l * nw, ref);
                for (size_t w = 0; w < nw; w++)
                    assert_true(out[l * nw + w] == ref[w]);
            }
        }
    free(need), free(out), free(scr);
}

static void pdep_soft_deposits(void **unused)
{
    (void)unused;
    const uint32_t key[2] = {1, 2};
    for (uint64_t k = 0; k < 2000; k++) {
        uint64_t src = lgca_rand_word(key, k, 0, 0), mask = lgca_rand_word(key, k, 1, 0);
        mask = k % 3 == 0 ? mask & lgca_rand_word(key, k, 2, 0) : k % 3 == 1 ? mask : ~(uint64_t)0 >> (k % 64);
        uint64_t want = 0;
        for (int b = 0, n = 0; b < 64; b++)
            if (mask >> b & 1u)
                want |= (src >> n++ & 1u) << b;
        assert_true(lgca_pdep_soft(src, mask) == want);
    }
}

/* Over NL lanes of NW words, 35 % of nodes needed (as a hot gas), S steps:
 * the frequency of ones at p = 0, 2^-16, 0.1, 0.5 within 5 sigma of p, and
 * the correlation of a node's bit with that of the next node, of the same
 * node in the next lane, at the next step and for the next purpose (where
 * both are needed) within 5 / sqrt(pairs) of 0. */
#define NL 64
#define NW 8
#define S 100
static void biased_bits_statistics(void **unused)
{
    (void)unused;
    const uint32_t key[2] = {0xdeadbeefu, 42};
    const uint32_t thr[] = {0, 1, 6554, 32768};
    static uint64_t need[2][NL * NW], bits[2][2][NL * NW], scr[LGCA_DENSE_SCRATCH * NL * NW];
    for (size_t t = 0; t < sizeof thr / sizeof thr[0]; t++) {
        double n = 0, ones = 0, pr[4][4] = {{0}}; /* pairs: count, sum x, sum y, sum xy */
        for (uint64_t step = 0; step < S; step++) {
            int c = (int)(step & 1u);
            for (size_t w = 0; w < NL * NW; w++) {
                uint64_t a = lgca_rand_word(key, w, 50, step), b = lgca_rand_word(key, w, 51, step);
                need[c][w] = (a & b) | (a & ~b & lgca_rand_word(key, w, 52, step) & lgca_rand_word(key, w, 53, step));
            }
            for (unsigned pu = 0; pu < 2; pu++)
                lgca_rand_biased_lanes(key, 0, NL, NW, pu ? LGCA_RND_G : LGCA_RND_P, step, thr[t], need[c],
                                       bits[c][pu], scr);
            for (size_t w = 0; w < NL * NW; w++)
                for (int i = 0; i < 64; i++) {
                    if (!(need[c][w] >> i & 1u))
                        continue;
                    double x = (double)(bits[c][0][w] >> i & 1u);
                    n++, ones += x;
                    /* the partners: next node, next lane, previous step, other purpose */
                    size_t pw[4] = {w + (i == 63), w + NW, w, w};
                    int pi[4] = {(i + 1) & 63, i, i, i};
                    const uint64_t *pn[4] = {need[c], need[c], need[!c], need[c]};
                    const uint64_t *pb[4] = {bits[c][0], bits[c][0], bits[!c][0], bits[c][1]};
                    for (int k = 0; k < 4; k++) {
                        if (pw[k] >= NL * NW || (k == 2 && !step) || !(pn[k][pw[k]] >> pi[k] & 1u))
                            continue;
                        double y = (double)(pb[k][pw[k]] >> pi[k] & 1u);
                        pr[k][0]++, pr[k][1] += x, pr[k][2] += y, pr[k][3] += x * y;
                    }
                }
        }
        double p = thr[t] / 65536.0;
        assert_true(n > 1e6);
        assert_true(fabs(ones - n * p) <= 5 * sqrt(n * p * (1 - p)) + 1e-9);
        for (int k = 0; k < 4 && thr[t] > 1; k++) {
            double m = pr[k][0], cov = pr[k][3] / m - pr[k][1] / m * pr[k][2] / m;
            double rho = cov / (p * (1 - p));
            assert_true(m > 2e5);
            assert_true(fabs(rho) < 5 / sqrt(m));
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(biased_lanes_follow_definition),
        cmocka_unit_test(pdep_soft_deposits),
        cmocka_unit_test(biased_bits_statistics),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
