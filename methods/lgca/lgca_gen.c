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
 * FHP-III). Build time: run once by meson. */
#include <stdio.h>

#include "lgca_int.h"

static void literals(FILE *f)
{
    fprintf(f, "    const uint64_t a0 = s[0], a1 = s[1], a2 = s[2], a3 = s[3], a4 = s[4], a5 = s[5], r = s[6];\n");
    for (int p = 0; p < 3; p++)
        for (int v = 0; v < 4; v++)
            fprintf(f, "    const uint64_t p%d_%d = %sa%d & %sa%d;\n", p, v, v & 1 ? "" : "~", p,
                    v & 2 ? "" : "~", p + 3);
    fprintf(f, "    const uint64_t r_0 = ~r, r_1 = r;\n");
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

static void emit(FILE *f, int rules, const char *name, int with_pb)
{
    uint8_t tab[LGCA_TABLE_SIZE];
    lgca_table_build(rules, tab);
    int ncombo = with_pb ? 4 : 2;
    unsigned flips[128][LGCA_CH]; /* combos in which bit k of state s flips */
    int used[128] = {0};
    for (unsigned s = 0; s < 128; s++)
        for (int k = 0; k < LGCA_CH; k++) {
            flips[s][k] = 0;
            for (int c = 0; c < ncombo; c++)
                if ((s ^ tab[s | (unsigned)c << 7]) >> k & 1u)
                    flips[s][k] |= 1u << c;
            used[s] |= flips[s][k] != 0;
        }
    fprintf(f, "static inline void %s_in(const uint64_t s[7], uint64_t ch, %suint64_t d[7])\n{\n", name,
            with_pb ? "uint64_t pb, " : "");
    literals(f);
    if (!with_pb)
        fprintf(f, "    const uint64_t pb = 0;\n    (void)pb;\n");
    for (unsigned s = 0; s < 128; s++)
        if (used[s])
            fprintf(f, "    const uint64_t m%u = p0_%u & p1_%u & p2_%u & r_%u;\n", s,
                    (s & 1u) | (s >> 3 & 1u) << 1, (s >> 1 & 1u) | (s >> 4 & 1u) << 1,
                    (s >> 2 & 1u) | (s >> 5 & 1u) << 1, s >> 6 & 1u);
    /* group the states by (change, the combinations that make it): one OR
     * per state, then each group gated once and ORed into its bits */
    unsigned gmask[512], gset[512];
    int ng = 0;
    for (unsigned s = 0; s < 128; s++)
        for (int c = 0; c < ncombo; c++) {
            unsigned m = s ^ tab[s | (unsigned)c << 7], t = 0;
            if (!m)
                continue;
            for (int c2 = 0; c2 < ncombo; c2++)
                if ((s ^ tab[s | (unsigned)c2 << 7]) == m)
                    t |= 1u << c2;
            int g = 0;
            while (g < ng && (gmask[g] != m || gset[g] != t))
                g++;
            if (g == ng)
                gmask[ng] = m, gset[ng] = t, ng++;
        }
    for (int g = 0; g < ng; g++) {
        fprintf(f, "    const uint64_t g%d = (0", g);
        for (unsigned s = 0; s < 128; s++) {
            int in = 0;
            for (int c = 0; c < ncombo && !in; c++)
                in = (gset[g] >> c & 1u) && (s ^ tab[s | (unsigned)c << 7]) == gmask[g];
            /* the state belongs if its change under exactly gset[g] is gmask[g] */
            unsigned t = 0;
            for (int c = 0; c < ncombo; c++)
                if ((s ^ tab[s | (unsigned)c << 7]) == gmask[g])
                    t |= 1u << c;
            if (in && t == gset[g])
                fprintf(f, " | m%u", s);
        }
        const char *gt = gate(gset[g], with_pb);
        fprintf(f, ")%s%s;\n", gt ? " & " : "", gt ? gt : "");
    }
    for (int k = 0; k < LGCA_CH; k++) {
        fprintf(f, "    d[%d] = 0", k);
        for (int g = 0; g < ng; g++)
            if (gmask[g] >> k & 1u)
                fprintf(f, " | g%d", g);
        fprintf(f, ";\n");
    }
    (void)flips;
    fprintf(f, "}\n\n");
    /* an exported copy for the tests, and the loop over a lane's words in
     * the same unit so that the compiler vectorises it */
    fprintf(f, "void %s(const uint64_t s[7], uint64_t ch, %suint64_t d[7])\n{\n    %s_in(s, ch, %sd);\n}\n\n",
            name, with_pb ? "uint64_t pb, " : "", name, with_pb ? "pb, " : "");
    fprintf(f, "void %s_lane(uint64_t *lane, size_t nw, const uint64_t *fluid, const uint64_t *ch%s)\n{\n"
               "    for (size_t w = 0; w < nw; w++) {\n"
               "        uint64_t s[7], d[7];\n"
               "        for (int k = 0; k < 7; k++)\n"
               "            s[k] = lane[k * nw + w];\n"
               "        %s_in(s, ch[w], %sd);\n"
               "        for (int k = 0; k < 7; k++)\n"
               "            lane[k * nw + w] = s[k] ^ (d[k] & fluid[w]);\n"
               "    }\n}\n\n",
            name, with_pb ? ", const uint64_t *pb" : "", name, with_pb ? "pb[w], " : "");
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
               "#include <stddef.h>\n#include <stdint.h>\n\n"
               "void lgca_delta_fhp3(const uint64_t s[7], uint64_t ch, uint64_t d[7]);\n"
               "void lgca_delta_granular(const uint64_t s[7], uint64_t ch, uint64_t pb, uint64_t d[7]);\n"
               "void lgca_delta_fhp3_lane(uint64_t *lane, size_t nw, const uint64_t *fluid, const uint64_t *ch);\n"
               "void lgca_delta_granular_lane(uint64_t *lane, size_t nw, const uint64_t *fluid, const uint64_t *ch,\n"
               "                              const uint64_t *pb);\n\n");
    emit(f, LGCA_RULES_FHP3, "lgca_delta_fhp3", 0);
    emit(f, LGCA_RULES_GRANULAR, "lgca_delta_granular", 1);
    return fclose(f) ? 1 : 0;
}
