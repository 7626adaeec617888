/* Writes lgca_kernel.c: the collision of 64 nodes at once, as Boolean
 * expressions on bit planes, generated from the table of lgca_table.c so
 * that the two cannot disagree (the tests check it anyway, exhaustively).
 *
 * For each rule set, each state that changes is a minterm of the seven
 * channel bits (products of literal pairs of opposite channels, shared by
 * the compiler). States are grouped by their change (the XOR mask) and the
 * chirality and dissipation bits under which they make it: a group is the
 * OR of its minterms, gated once, and ORed into each bit of its mask (one
 * OR per state instead of one per changed bit: 226 ORs instead of 408 for
 * FHP-III). The body is written twice: on one 64-bit word (the tests'
 * entry, the tail of a lane) and on a GCC vector of four words, which the
 * lane loop uses; the baseline build lowers it to SSE2 pairs, and an AVX2
 * clone (target_clones, chosen at load time) to single instructions. The
 * body is forced inline: GCC otherwise calls it once per word and
 * vectorises nothing. Build time: run once by meson. */
#include <stdio.h>
#include <string.h>

#include "lgca_int.h"

static void literals(FILE *f, const char *T)
{
    fprintf(f, "    const %s a0 = s[0], a1 = s[1], a2 = s[2], a3 = s[3], a4 = s[4], a5 = s[5], r = s[6];\n", T);
    for (int p = 0; p < 3; p++)
        for (int v = 0; v < 4; v++)
            fprintf(f, "    const %s p%d_%d = %sa%d & %sa%d;\n", T, p, v, v & 1 ? "" : "~", p, v & 2 ? "" : "~",
                    p + 3);
    fprintf(f, "    const %s r_0 = ~r, r_1 = r;\n", T);
}

/* The expression for the combinations (ch, pb) in mask t (bit ch | pb << 1). */
static const char *gate(unsigned t, int with_pb)
{
    if (!with_pb)
        t = (t & 3u) | (t & 3u) << 2;
    switch (t) {
    case 15: return NULL;
    case 5: return "~ch";
    case 10: return "ch";
    case 3: return "~pb";
    case 12: return "pb";
    case 1: return "(~ch & ~pb)";
    case 2: return "(ch & ~pb)";
    case 4: return "(~ch & pb)";
    case 8: return "(ch & pb)";
    case 14: return "(ch | pb)";
    case 13: return "(~ch | pb)";
    case 11: return "(ch | ~pb)";
    case 7: return "(~ch | ~pb)";
    case 6: return "(ch ^ pb)";
    case 9: return "~(ch ^ pb)";
    default: return "0";
    }
}


/* The changes of a rule set grouped by (change, the combinations of the
 * chirality and dissipation bits that make it). */
typedef struct {
    uint8_t tab[LGCA_TABLE_SIZE];
    int ncombo, ng, used[128];
    unsigned gmask[512], gset[512];
} groups;

static void group(int rules, int with_pb, groups *G)
{
    lgca_table_build(rules, G->tab);
    const uint8_t *tab = G->tab;
    G->ncombo = with_pb ? 4 : 2;
    G->ng = 0;
    for (unsigned s = 0; s < 128; s++) {
        G->used[s] = 0;
        for (int c = 0; c < G->ncombo; c++) {
            unsigned m = s ^ tab[s | (unsigned)c << 7], t = 0;
            if (!m)
                continue;
            G->used[s] = 1;
            for (int c2 = 0; c2 < G->ncombo; c2++)
                if ((s ^ tab[s | (unsigned)c2 << 7]) == m)
                    t |= 1u << c2;
            int g = 0;
            while (g < G->ng && (G->gmask[g] != m || G->gset[g] != t))
                g++;
            if (g == G->ng)
                G->gmask[G->ng] = m, G->gset[G->ng] = t, G->ng++;
        }
    }
}

/* The collision on words of type T (a 64-bit word, or a vector of four):
 * d gets the bits that change. */
static void body(FILE *f, const groups *G, const char *name, const char *T, int with_pb)
{
    const uint8_t *tab = G->tab;
    /* the random words by pointer: a 64-byte vector by value draws GCC's ABI note */
    fprintf(f, "static inline __attribute__((always_inline)) void %s(const %s *s, const %s *chp, %s%s%s%s *d)\n{\n",
            name, T, T, with_pb ? "const " : "", with_pb ? T : "", with_pb ? " *pbp, " : "", T);
    fprintf(f, "    const %s ch = *chp%s;\n", T, with_pb ? ", pb = *pbp" : "");
    literals(f, T);
    for (unsigned s = 0; s < 128; s++)
        if (G->used[s])
            fprintf(f, "    const %s m%u = p0_%u & p1_%u & p2_%u & r_%u;\n", T, s,
                    (s & 1u) | (s >> 3 & 1u) << 1, (s >> 1 & 1u) | (s >> 4 & 1u) << 1,
                    (s >> 2 & 1u) | (s >> 5 & 1u) << 1, s >> 6 & 1u);
    /* one OR per state, then each group gated once and ORed into its bits */
    for (int g = 0; g < G->ng; g++) {
        fprintf(f, "    const %s g%d = (m%s", T, g, "");
        int first = 1;
        for (unsigned s = 0; s < 128; s++) {
            /* the state belongs if its change under exactly gset[g] is gmask[g] */
            unsigned t = 0;
            for (int c = 0; c < G->ncombo; c++)
                if ((s ^ tab[s | (unsigned)c << 7]) == G->gmask[g])
                    t |= 1u << c;
            if (t && t == G->gset[g]) {
                fprintf(f, first ? "%u" : " | m%u", s);
                first = 0;
            }
        }
        const char *gt = gate(G->gset[g], with_pb);
        fprintf(f, ")%s%s;\n", gt ? " & " : "", gt ? gt : "");
    }
    for (int k = 0; k < LGCA_CH; k++) {
        int first = 1;
        fprintf(f, "    d[%d] =", k);
        for (int g = 0; g < G->ng; g++)
            if (G->gmask[g] >> k & 1u) {
                fprintf(f, "%s g%d", first ? "" : " |", g);
                first = 0;
            }
        fprintf(f, "%s;\n", first ? " s[0] ^ s[0]" : "");
    }
    fprintf(f, "}\n\n");
}

/* A loop over words wd at a time (vectors of type T, body bname) from w. */
static void vloop(FILE *f, int wd, const char *T, const char *bname, int with_pb)
{
    fprintf(f,
            "    for (; w + %d <= nw; w += %d) {\n"
            "        %s s[7], d[7], c, fl%s;\n"
            "        for (int k = 0; k < 7; k++)\n"
            "            memcpy(&s[k], lane + k * nw + w, sizeof s[k]);\n"
            "        memcpy(&c, ch + w, sizeof c);\n"
            "        memcpy(&fl, fluid + w, sizeof fl);\n%s"
            "        %s(s, &c, %sd);\n"
            "        for (int k = 0; k < 7; k++) {\n"
            "            s[k] ^= d[k] & fl;\n"
            "            memcpy(lane + k * nw + w, &s[k], sizeof s[k]);\n"
            "        }\n"
            "    }\n",
            wd, wd, T, with_pb ? ", p" : "", with_pb ? "        memcpy(&p, pb + w, sizeof p);\n" : "", bname,
            with_pb ? "&p, " : "");
}

static void emit(FILE *f, int rules, const char *name, int with_pb)
{
    groups G;
    group(rules, with_pb, &G);
    char n1[64], n4[64], n8[64];
    snprintf(n1, sizeof n1, "%s_1", name);
    snprintf(n4, sizeof n4, "%s_4", name);
    snprintf(n8, sizeof n8, "%s_8", name);
    body(f, &G, n1, "uint64_t", with_pb);
    body(f, &G, n4, "lgca_v4", with_pb);
    body(f, &G, n8, "lgca_v8", with_pb);
    /* an exported copy for the tests, and the loops over the lanes' words:
     * eight (AVX-512) or four at a time, then the rest one by one; lanes
     * of four words go by pairs into eight-word vectors */
    const char *pa = with_pb ? "&pb, " : "", *pw = with_pb ? "&pb[w], " : "";
    const char *args = with_pb ? ", const uint64_t *pb0" : "";
    fprintf(f, "void %s(const uint64_t s[7], uint64_t ch, %suint64_t d[7])\n{\n    %s(s, &ch, %sd);\n}\n\n",
            name, with_pb ? "uint64_t pb, " : "", n1, pa);
    for (int v = 0; v < 2; v++) {
        if (v == 0)
            fprintf(f,
                    "#ifdef LGCA_AVX512\n__attribute__((target(\"avx512f\"))) static void %s_lanes8(uint64_t *lanes, "
                    "size_t nl, size_t nw,\n    const uint64_t *fluid0, const uint64_t *ch0%s)\n{\n    size_t l = 0;\n"
                    "    for (; nw == 4 && l + 2 <= nl; l += 2) {\n"
                    "        uint64_t *lane = lanes + l * 7 * nw;\n"
                    "        size_t o = l * nw;\n"
                    "        lgca_v8 s[7], d[7], c, fl%s;\n"
                    "        for (int k = 0; k < 7; k++) {\n"
                    "            memcpy(&s[k], lane + k * 4, 32);\n"
                    "            memcpy((char *)&s[k] + 32, lane + 28 + k * 4, 32);\n"
                    "        }\n"
                    "        memcpy(&c, ch0 + o, sizeof c);\n"
                    "        memcpy(&fl, fluid0 + o, sizeof fl);\n%s"
                    "        %s(s, &c, %sd);\n"
                    "        for (int k = 0; k < 7; k++) {\n"
                    "            s[k] ^= d[k] & fl;\n"
                    "            memcpy(lane + k * 4, &s[k], 32);\n"
                    "            memcpy(lane + 28 + k * 4, (char *)&s[k] + 32, 32);\n"
                    "        }\n"
                    "    }\n",
                    name, args, with_pb ? ", p" : "", with_pb ? "        memcpy(&p, pb0 + o, sizeof p);\n" : "", n8,
                    with_pb ? "&p, " : "");
        else
            fprintf(f, "LGCA_CLONES static void %s_lanes4(uint64_t *lanes, size_t nl, size_t nw, const uint64_t *fluid0, "
                       "const uint64_t *ch0%s)\n{\n    size_t l = 0;\n",
                    name, args);
        fprintf(f, "    for (; l < nl; l++) {\n"
                   "        uint64_t *lane = lanes + l * 7 * nw;\n"
                   "        const uint64_t *fluid = fluid0 + l * nw, *ch = ch0 + l * nw%s;\n"
                   "        size_t w = 0;\n",
                with_pb ? ", *pb = pb0 + l * nw" : "");
        if (v == 0)
            vloop(f, 8, "lgca_v8", n8, with_pb);
        vloop(f, 4, "lgca_v4", n4, with_pb);
        fprintf(f,
                "    for (; w < nw; w++) {\n"
                "        uint64_t s[7], d[7];\n"
                "        for (int k = 0; k < 7; k++)\n"
                "            s[k] = lane[k * nw + w];\n"
                "        %s(s, &ch[w], %sd);\n"
                "        for (int k = 0; k < 7; k++)\n"
                "            lane[k * nw + w] = s[k] ^ (d[k] & fluid[w]);\n"
                "    }\n    }\n}\n%s\n",
                n1, pw, v == 0 ? "#endif\n" : "");
    }
    fprintf(f, "void %s_lanes(uint64_t *lanes, size_t nl, size_t nw, const uint64_t *fluid0, const uint64_t *ch0%s)\n{\n"
               "#ifdef LGCA_AVX512\n"
               "    if ((nw >= 8 || (nw == 4 && nl >= 2)) && __builtin_cpu_supports(\"avx512f\")) {\n"
               "        %s_lanes8(lanes, nl, nw, fluid0, ch0%s);\n"
               "        return;\n"
               "    }\n"
               "#endif\n"
               "    %s_lanes4(lanes, nl, nw, fluid0, ch0%s);\n}\n\n",
            name, args, name, with_pb ? ", pb0" : "", name, with_pb ? ", pb0" : "");
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: lgca_gen OUT.c\n");
        return 2;
    }
    FILE *f = fopen(argv[1], "w");
    if (!f) {
        perror(argv[1]);
        return 1;
    }
    fprintf(f, "/* Generated by methods/lgca/lgca_gen.c from lgca_table.c: do not edit. */\n"
               "#include <stddef.h>\n#include <stdint.h>\n#include <string.h>\n\n"
               "/* The bodies keep some 90 vectors live: GCC's register-pressure-aware\n"
               " * scheduling before allocation spills less (AVX2 body 1305 -> 1238\n"
               " * instructions, 593 -> 514 of them on the stack; granular 8192^2 on one\n"
               " * thread, AVX2 build, 1.97-1.99e9 against 1.78-1.85e9 site updates/s). */\n"
               "#if defined(__GNUC__) && !defined(__clang__)\n"
               "#pragma GCC optimize(\"schedule-insns\", \"sched-pressure\")\n"
               "#endif\n\n"
               "typedef uint64_t lgca_v4 __attribute__((vector_size(32)));\n"
               "typedef uint64_t lgca_v8 __attribute__((vector_size(64)));\n\n"
               "/* The build is baseline x86-64 (SSE2, two words a vector); an AVX2 copy\n"
               " * (four words a vector) is picked at load time on CPUs that have it.\n"
               " * -DLGCA_NO_CLONES builds the baseline alone (to test it on any CPU). */\n"
               "#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(LGCA_NO_CLONES)\n"
               "#define LGCA_CLONES __attribute__((target_clones(\"avx2\", \"default\")))\n"
               "#ifndef LGCA_NO_AVX512 /* -DLGCA_NO_AVX512: what an AVX2-only CPU runs */\n"
               "#define LGCA_AVX512 1 /* eight words a vector, three-input logic (vpternlogq) */\n"
               "#endif\n"
               "#else\n#define LGCA_CLONES\n#endif\n\n"
               "void lgca_delta_fhp3(const uint64_t s[7], uint64_t ch, uint64_t d[7]);\n"
               "void lgca_delta_granular(const uint64_t s[7], uint64_t ch, uint64_t pb, uint64_t d[7]);\n"
               "void lgca_delta_fhp3_lanes(uint64_t *lanes, size_t nl, size_t nw, const uint64_t *fluid0,\n"
               "                           const uint64_t *ch0);\n"
               "void lgca_delta_granular_lanes(uint64_t *lanes, size_t nl, size_t nw, const uint64_t *fluid0,\n"
               "                               const uint64_t *ch0, const uint64_t *pb0);\n\n");
    emit(f, LGCA_RULES_FHP3, "lgca_delta_fhp3", 0);
    emit(f, LGCA_RULES_GRANULAR, "lgca_delta_granular", 1);
    return fclose(f) ? 1 : 0;
}
