/* The collision rules as a table: the readable reference from which the
 * bit-parallel kernel is generated (lgca_gen.c) and against which it is
 * tested bit for bit.
 *
 * States of equal mass and momentum form a class. FHP-III (Frisch et al.,
 * Complex Systems 1, 649 (1987)) sends each state to another member of its
 * class wherever one exists (collision saturation): a class of two swaps,
 * a class of three turns by one member, forward or backward by the
 * chirality bit; the two classes of five (mass 3 and 4 at zero momentum)
 * split by the rest bit into a pair that swaps (the two symmetric triples,
 * with or without the rest particle) and a triple that turns (rest + head-on
 * pair, or two head-on pairs). With equal chances for both chiralities each
 * transition matrix is symmetric, so semi-detailed balance holds, and the
 * Boltzmann shear viscosity is Frisch et al.'s
 * nu(d) = 1/(28 d (1-d) (1 - 8 d (1-d)/7)) - 1/8 (checked in the tests).
 *
 * The granular rules (Peng and Herrmann, Phys. Rev. E 49, R1796 (1994);
 * 51, 1745 (1995)) count a moving particle's energy 1/2 and the rest
 * particle's 0: collisions that keep the rest bit conserve energy and
 * always happen (the same turns within the part of the class with the
 * state's rest bit); a collision that makes a rest particle (two movers
 * become a mover and a rest particle, momentum kept) happens with
 * probability p (dissipation bit pb); the reverse, which would create
 * energy, never does. A symmetric triple, which would have three rest +
 * head-on-pair states to choose from, stays elastic. */
#include <string.h>

#include "lgca_int.h"

static const int QX[6] = {0, 1, 1, 0, -1, -1};
static const int QY[6] = {2, 1, -1, -2, -1, 1};

void lgca_state_momentum(unsigned s, int *qx, int *qy)
{
    *qx = *qy = 0;
    for (int k = 0; k < 6; k++)
        if (s >> k & 1u)
            *qx += QX[k], *qy += QY[k];
}

static int mass(unsigned s) { return __builtin_popcount(s & 127u); }

static int same_class(unsigned a, unsigned b)
{
    int ax, ay, bx, by;
    lgca_state_momentum(a, &ax, &ay);
    lgca_state_momentum(b, &bx, &by);
    return mass(a) == mass(b) && ax == bx && ay == by;
}

/* The members of s's class (ascending) with rest bit `rest` (-1: any). */
static int members(unsigned s, int rest, unsigned out[8])
{
    int n = 0;
    for (unsigned t = 0; t < 128; t++)
        if (same_class(s, t) && (rest < 0 || (int)(t >> LGCA_REST & 1u) == rest))
            out[n++] = t;
    return n;
}

/* The turn within a group: swap a pair, step a triple by the chirality. */
static unsigned turn(unsigned s, const unsigned *g, int n, int ch)
{
    int at = 0;
    while (g[at] != s)
        at++;
    if (n == 2)
        return g[1 - at];
    if (n == 3)
        return g[(at + (ch ? 2 : 1)) % 3];
    return s;
}

static unsigned fhp3(unsigned s, int ch)
{
    unsigned g[8];
    int n = members(s, -1, g);
    if (n == 5)
        n = members(s, (int)(s >> LGCA_REST & 1u), g);
    return turn(s, g, n, ch);
}

static unsigned granular(unsigned s, int ch, int pb)
{
    unsigned g[8];
    int rest = (int)(s >> LGCA_REST & 1u);
    if (pb && !rest) {
        int n = members(s, 1, g);
        if (n == 1 || n == 2)
            return g[n == 2 ? ch : 0];
    }
    int n = members(s, rest, g);
    return turn(s, g, n, ch);
}

void lgca_table_build(int rules, uint8_t out[LGCA_TABLE_SIZE])
{
    for (unsigned x = 0; x < LGCA_TABLE_SIZE; x++) {
        unsigned s = x & 127u;
        int ch = (int)(x >> 7 & 1u), pb = (int)(x >> 8 & 1u);
        out[x] = (uint8_t)(rules == LGCA_RULES_FHP3 ? fhp3(s, ch) : granular(s, ch, pb));
    }
}
