/* Peng and Herrmann's rest collision (as described in the thesis of
 * /work/shared/references, section 1.2.5, after Mueller's summary of the
 * model): a head-on pair meeting a rest particle comes to rest with
 * probability `stop`; a node holds one rest particle, so the two new ones
 * hop to the free rest channels of two neighbours drawn at random (fluid
 * nodes only; with fewer than two free, nothing happens). Mass and momentum
 * are kept (the pair has none), its energy is lost. It makes a rest
 * particle an obstacle: without it a mover passes through a resting one.
 *
 * The pass is serial, after the collision and gravity: the nodes that
 * qualify are those that did so when the pass began, taken lane by lane,
 * node by node; a hop may fill a later node's free channel. The same code
 * runs on bit planes (lgca_step.c) and on bytes (lgca_ref.c) through
 * lgca_access. */
#include "lgca_int.h"

/* Does state s qualify: a rest particle and at least one head-on pair. */
static unsigned pairs(unsigned s)
{
    if (!(s >> LGCA_REST & 1u))
        return 0;
    return (s & s >> 3) & 7u;
}

void lgca_stop_node(const lgca *L, int i, int j, uint64_t step, const lgca_access *a)
{
    unsigned p = pairs(a->get(a->ctx, i, j));
    uint64_t node = (uint64_t)j * (uint64_t)L->ni + (uint64_t)i;
    if (!p || lgca_rand_u32(L->key, node, LGCA_RND_STOP, step) >= L->thr_stop)
        return;
    int free[6], nf = 0, ti[6], tj[6];
    for (int k = 0; k < 6; k++)
        if (lgca_neighbour(L, i, j, k, &ti[k], &tj[k]) && !lgca_is_solid(L, ti[k], tj[k]) &&
            !(a->get(a->ctx, ti[k], tj[k]) >> LGCA_REST & 1u))
            free[nf++] = k;
    if (nf < 2)
        return;
    uint32_t r = lgca_rand_u32(L->key, node, LGCA_RND_STOP + 1, step);
    int np = __builtin_popcount(p), pick = (int)(r % (uint32_t)np), k1 = (int)((r >> 8) % (uint32_t)nf);
    int k2 = (int)((r >> 16) % (uint32_t)(nf - 1));
    k2 += k2 >= k1;
    int c = 0;
    for (;; c++)
        if ((p >> c & 1u) && pick-- == 0)
            break;
    unsigned s = a->get(a->ctx, i, j) & ~(1u << c | 1u << (c + 3));
    a->set(a->ctx, i, j, s);
    int n1 = free[k1], n2 = free[k2];
    a->set(a->ctx, ti[n1], tj[n1], a->get(a->ctx, ti[n1], tj[n1]) | 1u << LGCA_REST);
    a->set(a->ctx, ti[n2], tj[n2], a->get(a->ctx, ti[n2], tj[n2]) | 1u << LGCA_REST);
}

static unsigned plane_get(const void *ctx, int i, int j)
{
    const lgca *L = ctx;
    unsigned s = 0;
    for (int c = 0; c < LGCA_CH; c++)
        s |= (unsigned)lgca_get(L, i, j, c) << c;
    return s;
}

static void plane_set(void *ctx, int i, int j, unsigned s)
{
    for (int c = 0; c < LGCA_CH; c++)
        lgca_put(ctx, i, j, c, (int)(s >> c & 1u));
}

/* The bit-plane pass: the qualifying nodes of each word found at once
 * (before any hop, as the rule says), then visited in order. */
void lgca_stop_pass(lgca *L, uint64_t *mask)
{
    lgca_access a = {plane_get, plane_set, L};
    size_t nw = (size_t)L->nw;
    for (int j = 0; j < L->nj; j++) {
        const uint64_t *s = L->lane[j];
        for (size_t w = 0; w < nw; w++)
            mask[(size_t)j * nw + w] = s[LGCA_REST * nw + w] & L->valid[w] & ~L->solid[(size_t)j * nw + w] &
                                       ((s[w] & s[3 * nw + w]) | (s[nw + w] & s[4 * nw + w]) |
                                        (s[2 * nw + w] & s[5 * nw + w]));
    }
    for (int j = 0; j < L->nj; j++)
        for (size_t w = 0; w < nw; w++)
            for (uint64_t m = mask[(size_t)j * nw + w]; m; m &= m - 1)
                lgca_stop_node(L, (int)(w * 64 + (size_t)__builtin_ctzll(m)), j, L->step, &a);
}
