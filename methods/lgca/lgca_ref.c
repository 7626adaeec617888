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
static unsigned gravity(unsigned s)
{
    if ((s >> 6 & 1u) && !(s >> 3 & 1u))
        return s ^ (1u << 6 | 1u << 3);
    if ((s >> 1 & 1u) && !(s >> 2 & 1u))
        return s ^ (1u << 1 | 1u << 2);
    if ((s >> 5 & 1u) && !(s >> 4 & 1u))
        return s ^ (1u << 5 | 1u << 4);
    return s;
}

static void collide(const lgca *L, uint8_t *b, uint64_t step, const uint8_t *tab)
{
    int granular = L->par.rules == LGCA_RULES_GRANULAR;
    for (int j = 0; j < L->nj; j++)
        for (int i = 0; i < L->ni; i++) {
            if (lgca_is_solid(L, i, j))
                continue;
            uint64_t word = (uint64_t)j * (uint64_t)L->nw + (uint64_t)(i >> 6);
            unsigned bit = (unsigned)(i & 63);
            unsigned ch = (unsigned)(lgca_rand_word(L->key, word, LGCA_RND_CHIRAL, step) >> bit & 1u);
            unsigned pb = granular ? (unsigned)(lgca_rand_biased(L->key, word, LGCA_RND_P, step, L->thr_p) >> bit & 1u) : 0;
            uint8_t *s = &b[(size_t)j * (size_t)L->ni + (size_t)i];
            unsigned out = tab[*s | ch << 7 | pb << 8];
            if (L->thr_g && (lgca_rand_biased(L->key, word, LGCA_RND_G, step, L->thr_g) >> bit & 1u))
                out = gravity(out);
            *s = (uint8_t)out;
        }
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
    collide(L, b, step, tab);
    if (L->thr_stop && stop_pass(L, b, step)) {
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
