/* The readable reference of one step: one byte per node, the collision by
 * table lookup, propagation node by node into a second buffer. It draws
 * the same random bits as the bit-parallel step and must give the same
 * bytes (tests/method/lgca). Scenes with a silo exit are not covered. */
#include <stdlib.h>
#include <string.h>

#include "lgca_int.h"

void lgca_to_bytes(const lgca *L, uint8_t *bytes)
{
    for (int j = 0; j < L->nj; j++)
        for (int i = 0; i < L->ni; i++) {
            unsigned s = 0;
            for (int c = 0; c < LGCA_CH; c++)
                s |= (unsigned)lgca_get(L, i, j, c) << c;
            bytes[(size_t)j * (size_t)L->ni + (size_t)i] = (uint8_t)s;
        }
}

/* Gravity on one node's byte (lgca_step.c's rule, one node). */
static unsigned gravity(unsigned s, const unsigned char mv[3][2])
{
    for (int k = 0; k < 3; k++)
        if ((s >> mv[k][0] & 1u) && !(s >> mv[k][1] & 1u))
            return s ^ (1u << mv[k][0] | 1u << mv[k][1]);
    return s;
}

/* A dissipation bit can change the collision of a fluid node with no rest
 * particle and two movers or more; gravity, a node it can move. The fast
 * step draws bits for these nodes only, numbered in order along the lane
 * (lgca_dense.c), so the reference asks for the same. */
static int needs_p(unsigned s)
{
    return !(s >> LGCA_REST & 1u) && __builtin_popcount(s & 63u) >= 2;
}

/* One lane: chirality, the collision (by table), gravity; need, bits and
 * scratch: the lane's words. */
static void collide_lane(const lgca *L, int j, uint8_t *b, uint64_t step, const uint8_t *tab, uint64_t *need,
                         uint64_t *bits, uint64_t *scratch)
{
    size_t nw = (size_t)L->nw;
    int granular = L->par.rules == LGCA_RULES_GRANULAR;
    memset(need, 0, nw * sizeof *need), memset(bits, 0, nw * sizeof *bits);
    for (int i = 0; i < L->ni; i++)
        if (granular && !lgca_is_solid(L, i, j) && needs_p(b[i]))
            need[i >> 6] |= (uint64_t)1 << (i & 63);
    if (granular)
        lgca_rand_biased_lanes(L->key, (uint64_t)j, 1, nw, LGCA_RND_P, step, L->thr_p, need, bits, scratch);
    for (int i = 0; i < L->ni; i++) {
        if (lgca_is_solid(L, i, j))
            continue;
        uint64_t word = (uint64_t)j * nw + (uint64_t)(i >> 6);
        unsigned ch = (unsigned)(lgca_rand_word(L->key, word, LGCA_RND_CHIRAL, step) >> (i & 63) & 1u);
        unsigned pb = (unsigned)(bits[i >> 6] >> (i & 63) & 1u);
        b[i] = tab[b[i] | ch << 7 | pb << 8];
    }
    if (!L->thr_g)
        return;
    unsigned char mv[3][2];
    lgca_gravity_moves(L->par.gravity, step, mv);
    memset(need, 0, nw * sizeof *need);
    for (int i = 0; i < L->ni; i++)
        if (!lgca_is_solid(L, i, j) && gravity(b[i], mv) != b[i])
            need[i >> 6] |= (uint64_t)1 << (i & 63);
    lgca_rand_biased_lanes(L->key, (uint64_t)j, 1, nw, LGCA_RND_G, step, L->thr_g, need, bits, scratch);
    for (int i = 0; i < L->ni; i++)
        if (bits[i >> 6] >> (i & 63) & 1u)
            b[i] = (uint8_t)gravity(b[i], mv);
}

static int collide(const lgca *L, uint8_t *b, uint64_t step, const uint8_t *tab)
{
    size_t nw = (size_t)L->nw;
    uint64_t *w = malloc((2 + LGCA_DENSE_SCRATCH) * nw * sizeof *w);
    if (!w)
        return GR_ERUN;
    for (int j = 0; j < L->nj; j++)
        collide_lane(L, j, b + (size_t)j * (size_t)L->ni, step, tab, w, w + nw, w + 2 * nw);
    free(w);
    return GR_OK;
}

static void reflect(const lgca *L, uint8_t *b, uint64_t step)
{
    for (size_t k = 0; k < L->nwalls; k++) {
        const lgca_wall *w = &L->walls[k];
        if (!lgca_is_solid(L, (int)w->i, (int)w->j))
            continue;
        size_t at = (size_t)w->j * (size_t)L->ni + w->i;
        uint64_t node = (uint64_t)w->j * (uint64_t)L->ni + w->i;
        int m = (int)w->mirror;
        if (L->thr_b && lgca_rand_u32(L->key, node, LGCA_RND_WALL, step) < L->thr_b)
            m = 6;
        unsigned in = b[at], out = in & 1u << LGCA_REST;
        for (int c = 0; c < 6; c++)
            out |= (in >> c & 1u) << lgca_mirror(m, c);
        b[at] = (uint8_t)out;
    }
}

typedef struct {
    const lgca *L;
    uint8_t *b;
} bytes_ctx;

static unsigned byte_get(const void *ctx, int i, int j)
{
    const bytes_ctx *c = ctx;
    return c->b[(size_t)j * (size_t)c->L->ni + (size_t)i];
}

static void byte_set(void *ctx, int i, int j, unsigned s)
{
    bytes_ctx *c = ctx;
    c->b[(size_t)j * (size_t)c->L->ni + (size_t)i] = (uint8_t)s;
}

/* The rest collision: the nodes that qualify before the pass, in order. */
static int stop_pass(const lgca *L, uint8_t *b, uint64_t step)
{
    size_t n = (size_t)L->ni * (size_t)L->nj;
    uint8_t *q = malloc(n);
    if (!q)
        return GR_ERUN;
    for (size_t k = 0; k < n; k++) {
        unsigned s = b[k];
        q[k] = (s >> LGCA_REST & 1u) && (s & s >> 3 & 7u);
    }
    bytes_ctx c = {L, b};
    lgca_access a = {byte_get, byte_set, &c};
    for (int j = 0; j < L->nj; j++)
        for (int i = 0; i < L->ni; i++)
            if (q[(size_t)j * (size_t)L->ni + (size_t)i] && !lgca_is_solid(L, i, j))
                lgca_stop_node(L, i, j, step, &a);
    free(q);
    return GR_OK;
}

int lgca_ref_step(const lgca *L, uint8_t *b, uint64_t step, gr_err *err)
{
    if (L->exits)
        return gr_fail(err, GR_EINPUT, "the reference step covers no silo exit");
    uint8_t tab[LGCA_TABLE_SIZE];
    lgca_table_build(L->par.rules, tab);
    size_t n = (size_t)L->ni * (size_t)L->nj;
    uint8_t *nb = calloc(n, 1);
    if (!nb)
        return gr_fail(err, GR_ERUN, "out of memory");
    if (collide(L, b, step, tab) || (L->thr_stop && stop_pass(L, b, step))) {
        free(nb);
        return gr_fail(err, GR_ERUN, "out of memory");
    }
    reflect(L, b, step);
    for (int j = 0; j < L->nj; j++)
        for (int i = 0; i < L->ni; i++) {
            unsigned s = b[(size_t)j * (size_t)L->ni + (size_t)i];
            nb[(size_t)j * (size_t)L->ni + (size_t)i] |= (uint8_t)(s & 1u << LGCA_REST);
            for (int c = 0; c < 6; c++) {
                int ti, tj;
                if ((s >> c & 1u) && lgca_neighbour(L, i, j, c, &ti, &tj))
                    nb[(size_t)tj * (size_t)L->ni + (size_t)ti] |= (uint8_t)(1u << c);
            }
        }
    memcpy(b, nb, n);
    free(nb);
    return GR_OK;
}
