/* The collision rules of lgca: the table checked exhaustively (mass and
 * momentum over all 128 states and every random bit, semi-detailed
 * balance, collision saturation, the granular rules never creating
 * energy), the generated bit-parallel kernel against the table on all 512
 * inputs, the Boltzmann viscosity of the table against Frisch et al.'s
 * FHP-III formula, and whole steps of the bit-parallel backend against the
 * byte-per-node reference, bit for bit, on 1 and 3 threads. */
#include "lgca_test.h"

#include <stdlib.h>
#include <string.h>

static void table_conserves(void **unused)
{
    (void)unused;
    for (int rules = 0; rules < LGCA_NRULES; rules++) {
        uint8_t t[LGCA_TABLE_SIZE];
        lgca_table_build(rules, t);
        for (unsigned x = 0; x < LGCA_TABLE_SIZE; x++) {
            unsigned s = x & 127u, o = t[x];
            int ax, ay, bx, by;
            lgca_state_momentum(s, &ax, &ay);
            lgca_state_momentum(o, &bx, &by);
            assert_int_equal(__builtin_popcount(s), __builtin_popcount(o));
            assert_int_equal(ax, bx);
            assert_int_equal(ay, by);
            if (rules == LGCA_RULES_GRANULAR) {
                /* a rest particle is never set in motion by a collision */
                assert_true(!(s >> LGCA_REST & 1u) || (o >> LGCA_REST & 1u));
                if (!(x >> 8 & 1u)) /* no dissipation bit: energy kept */
                    assert_int_equal(s >> LGCA_REST & 1u, o >> LGCA_REST & 1u);
            }
        }
    }
}

/* Each chirality's map is a permutation of the 128 states, so the matrix
 * A(s -> s') = (delta_{out0(s)} + delta_{out1(s)}) / 2 has unit column
 * sums (semi-detailed balance); FHP-III changes every state whose class
 * has another member (collision saturation). */
static void fhp3_balance_and_saturation(void **unused)
{
    (void)unused;
    uint8_t t[LGCA_TABLE_SIZE];
    lgca_table_build(LGCA_RULES_FHP3, t);
    int changed = 0;
    for (unsigned ch = 0; ch < 2; ch++) {
        int hit[128] = {0};
        for (unsigned s = 0; s < 128; s++)
            hit[t[s | ch << 7]]++;
        for (unsigned s = 0; s < 128; s++)
            assert_int_equal(hit[s], 1);
    }
    for (unsigned s = 0; s < 128; s++) {
        int others = 0, sx, sy;
        lgca_state_momentum(s, &sx, &sy);
        for (unsigned u = 0; u < 128; u++) {
            int ux, uy;
            lgca_state_momentum(u, &ux, &uy);
            others += u != s && ux == sx && uy == sy && __builtin_popcount(u) == __builtin_popcount(s);
        }
        assert_int_equal(t[s] != s, others > 0);
        assert_int_equal(t[s | 128u] != s, others > 0);
        changed += t[s] != s;
    }
    assert_int_equal(changed, 76); /* the 76 states of Frisch et al.'s FHP-III that collide */
}

/* The kernel on all 512 (state, chirality, dissipation) inputs at once,
 * one per bit of 8 words. */
static void kernel_matches_table(void **unused)
{
    (void)unused;
    for (int rules = 0; rules < LGCA_NRULES; rules++) {
        uint8_t t[LGCA_TABLE_SIZE];
        lgca_table_build(rules, t);
        for (unsigned w = 0; w < 8; w++) {
            uint64_t s[LGCA_CH] = {0}, ch = 0, pb = 0, d[LGCA_CH];
            for (unsigned b = 0; b < 64; b++) {
                unsigned x = w * 64 + b;
                for (int c = 0; c < LGCA_CH; c++)
                    s[c] |= (uint64_t)(x >> c & 1u) << b;
                ch |= (uint64_t)(x >> 7 & 1u) << b;
                pb |= (uint64_t)(x >> 8 & 1u) << b;
            }
            if (rules == LGCA_RULES_FHP3)
                lgca_delta_fhp3(s, ch, d);
            else
                lgca_delta_granular(s, ch, pb, d);
            for (unsigned b = 0; b < 64; b++) {
                unsigned x = w * 64 + b, out = 0;
                for (int c = 0; c < LGCA_CH; c++)
                    out |= (unsigned)((s[c] ^ d[c]) >> b & 1u) << c;
                if (rules == LGCA_RULES_FHP3 && (x >> 8))
                    continue; /* fhp3 has no dissipation bit */
                assert_int_equal(out, t[x]);
            }
        }
    }
}

/* Boltzmann (uncorrelated) relaxation of the shear mode Q = sum c_x c_y n
 * in one collision, from the table: lambda = sum_s,s' P(s) A(s,s')
 * (Q(s) - Q(s'))^2 / 2 / (d (1-d) sum_k Q_k^2), and nu = 1/(4 lambda) - 1/8
 * (Henon, Complex Systems 1, 475 (1987)). Frisch et al. (1987) give for
 * FHP-III nu = 1/(28 d (1-d) (1 - 8 d (1-d)/7)) - 1/8. */
static void table_viscosity_is_frisch(void **unused)
{
    (void)unused;
    uint8_t t[LGCA_TABLE_SIZE];
    lgca_table_build(LGCA_RULES_FHP3, t);
    double Q[LGCA_CH] = {0}, q2 = 0;
    for (int k = 0; k < 6; k++) {
        Q[k] = sin(M_PI * k / 3) * cos(M_PI * k / 3);
        q2 += Q[k] * Q[k];
    }
    double ds[] = {0.05, 0.1, 0.2, 0.3, 0.5, 0.7};
    for (size_t n = 0; n < sizeof ds / sizeof ds[0]; n++) {
        double d = ds[n], num = 0;
        for (unsigned s = 0; s < 128; s++) {
            int m = __builtin_popcount(s);
            double P = pow(d, m) * pow(1 - d, 7 - m), qs = 0;
            for (int k = 0; k < 6; k++)
                qs += (s >> k & 1u) * Q[k];
            for (unsigned ch = 0; ch < 2; ch++) {
                unsigned o = t[s | ch << 7];
                double qo = 0;
                for (int k = 0; k < 6; k++)
                    qo += (o >> k & 1u) * Q[k];
                num += 0.5 * P * (qs - qo) * (qs - qo) / 2;
            }
        }
        double lambda = num / (d * (1 - d) * q2);
        double nu = 1 / (4 * lambda) - 0.125;
        double frisch = 1 / (28 * d * (1 - d) * (1 - 8 * d * (1 - d) / 7)) - 0.125;
        printf("# d = %.2f: nu(table) = %.10f, Frisch et al. %.10f\n", d, nu, frisch);
        assert_rel(nu, frisch, 1e-12);
    }
}

/* 35 steps of each variant (base + variant), per_call steps a call
 * (1: through gr_sim_step), against the byte reference, every byte after
 * each call; thr_g > 0: that gravity threshold set on the lattice of the
 * granular rules without walls or rest collision. */
static void against_reference(const char *base, const char *const *variants, size_t nv, int per_call, uint32_t thr_g)
{
    for (size_t v = 0; v < nv; v++) {
        char text[2048];
        snprintf(text, sizeof text, "%s%s", base, variants[v]);
        gr_scene *sc;
        gr_sim *s = lgca_make(text, &sc);
        lgca *L = gr_sim_state(s);
        L->prefetch = 1; /* the path of lattices past L2, on small ones */
        if (thr_g) {
            assert_true(L->nwalls == 0 && !L->thr_stop);
            if (L->par.rules == LGCA_RULES_GRANULAR)
                L->thr_g = thr_g;
        }
        size_t n = (size_t)L->ni * (size_t)L->nj;
        uint8_t *ref = malloc(n), *fast = malloc(n);
        lgca_to_bytes(L, ref);
        gr_err e = {0};
        for (int k = 0; k < 35; k += per_call) {
            uint64_t step = L->step;
            for (int r = 0; r < per_call; r++)
                assert_int_equal(lgca_ref_step(L, ref, step + (uint64_t)r, &e), GR_OK);
            if (per_call == 1)
                assert_int_equal(gr_sim_step(s, &e), GR_OK);
            else
                assert_int_equal(lgca_steps(L, (uint64_t)per_call, &e), GR_OK);
            assert_true(L->step == step + (uint64_t)per_call);
            lgca_to_bytes(L, fast);
            assert_memory_equal(ref, fast, n);
        }
        free(ref), free(fast);
        lgca_drop(s, sc);
    }
}

/* Steps of the backend against the reference, every byte, on a scene with
 * every rule in play: walls (segments, rough), gravity, dissipation, the
 * rest collision (stop). Lanes
 * of 300 nodes (5 words) take both the kernel's four-word vector path and
 * its one-word tail. */
static void fast_equals_reference(void **unused)
{
    (void)unused;
    const char *base =
        "[scene]\nseed = 11\n[domain]\nwidth = 60\nheight = 300\ngravity = 1\nleft = periodic\n"
        "right = periodic\n[wall.a]\nfrom = 10 40\nto = 45 70\n[wall.b]\nfrom = 20 100\nto = 50 100\n"
        "[init]\nkind = occupation\noccupation = 0.3\nrest_occupation = 0.2\n[lgca]\nb = 0.3\n";
    const char *variants[] = {"rules = fhp3\nthreads = 1\n", "rules = granular\np = 0.3\nthreads = 1\n",
                              "rules = granular\np = 0.3\nthreads = 3\n", "rules = fhp3\nthreads = 2\ng = 0\n",
                              "rules = granular\np = 0.3\nstop = 0.5\nthreads = 1\n",
                              "rules = granular\np = 0.3\nstop = 0.5\nthreads = 2\n",
                              "rules = granular\np = 0.3\nstop = 0.5\ngravity_order = movers\nthreads = 2\n",
                              "rules = fhp3\ngravity_order = alternate\nthreads = 1\n"};
    against_reference(base, variants, sizeof variants / sizeof variants[0], 1, 0);
}

/* Without serial work (no wall, no rest collision) a team synchronises
 * once a step, with the edge lanes double-buffered: several steps in one
 * call against the reference, on 1, 2 and 3 threads. */
static void fast_equals_reference_unwalled(void **unused)
{
    (void)unused;
    const char *base = "[scene]\nseed = 12\n[domain]\nwidth = 60\nheight = 300\nleft = periodic\n"
                       "right = periodic\nbottom = periodic\ntop = periodic\n[init]\nkind = occupation\n"
                       "occupation = 0.3\nrest_occupation = 0.2\n[lgca]\ndt = 1\n";
    const char *variants[] = {"rules = fhp3\nthreads = 2\n", "rules = granular\np = 0.3\nthreads = 3\n",
                              "rules = granular\np = 0.3\nthreads = 1\n",
                              "rules = granular\np = 0.3\ngravity_order = alternate\nthreads = 2\n",
                              "rules = granular\np = 0.3\ngravity_order = movers\nthreads = 1\n"};
    /* g = 0.05 set on the lattice for the granular rules (a periodic scene has no gravity) */
    against_reference(base, variants, sizeof variants / sizeof variants[0], 7, 3277);
    /* lanes of 900 nodes (15 words): the kernel's eight-word (AVX-512),
     * four-word and one-word paths */
    const char *lanes = "[scene]\nseed = 13\n[domain]\nwidth = 8\nheight = 900\nleft = periodic\n"
                        "right = periodic\nbottom = periodic\ntop = periodic\n[init]\nkind = occupation\n"
                        "occupation = 0.3\nrest_occupation = 0.2\n[lgca]\ndt = 1\n";
    against_reference(lanes, variants, sizeof variants / sizeof variants[0], 7, 3277);
    /* 23 lanes of 250 nodes (4 words): by pairs in eight-word vectors, and
     * an odd one */
    const char *pairs = "[scene]\nseed = 14\n[domain]\nwidth = 20\nheight = 250\nleft = periodic\n"
                        "right = periodic\nbottom = periodic\ntop = periodic\n[init]\nkind = occupation\n"
                        "occupation = 0.3\nrest_occupation = 0.2\n[lgca]\ndt = 1\n";
    against_reference(pairs, variants, sizeof variants / sizeof variants[0], 7, 3277);
    /* open sides across the lanes and along them: particles leave at the
     * lattice's edges, the lanes of several chunks (lgca_step.c's sweep) */
    const char *open = "[scene]\nseed = 15\n[domain]\nwidth = 60\nheight = 300\nleft = open\n"
                       "right = open\nbottom = open\ntop = open\n[init]\nkind = occupation\n"
                       "occupation = 0.3\nrest_occupation = 0.2\n[lgca]\ndt = 1\n";
    against_reference(open, variants, sizeof variants / sizeof variants[0], 7, 3277);
}

/* The batched random words (vectorised Philox rounds) against Random123's
 * philox4x32 word by word, over more than two batches (the biased bits:
 * test_lgca_rand.c). */
static void batched_random_words(void **unused)
{
    (void)unused;
    const uint32_t key[2] = {0x12345678u, 0x9abcdef0u};
    const size_t ns[] = {3, 7, 37}; /* batches of 4, 8, and 16 + 16 + 8 calls */
    uint64_t out[37];
    for (size_t k = 0; k < sizeof ns / sizeof ns[0]; k++)
        for (uint64_t step = 0; step < (uint64_t)1 << 40; step += (uint64_t)1 << 39) {
            size_t n = ns[k];
            uint64_t word0 = ((uint64_t)3 << 32) + 1000 + (step >> 39); /* even and odd */
            lgca_rand_words(key, word0, n, LGCA_RND_CHIRAL, step, out);
            for (size_t w = 0; w < n; w++)
                assert_true(out[w] == lgca_rand_word(key, word0 + w, LGCA_RND_CHIRAL, step));
        }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(table_conserves),
        cmocka_unit_test(fhp3_balance_and_saturation),
        cmocka_unit_test(kernel_matches_table),
        cmocka_unit_test(table_viscosity_is_frisch),
        cmocka_unit_test(fast_equals_reference),
        cmocka_unit_test(fast_equals_reference_unwalled),
        cmocka_unit_test(batched_random_words),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
