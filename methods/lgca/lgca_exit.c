/* The silo's outflow and reinsertion (see lgca_int.h). */
#include "lgca_int.h"

/* The lane to start from is drawn uniformly across the band (a function of
 * the key, the outflow count and the step), so that reinserted particles do
 * not fall back as a curtain over the orifice; from a full lane the search
 * goes right or left as the top bit of the same draw says. Always to the
 * right, it made the pipe scene's density lopsided once the rest collision
 * fills the band (the left side denser, the right after reversing it). */
static int reinsert(lgca *L, int c)
{
    int n = L->band_j1 - L->band_j0;
    if (n <= 0)
        return 0;
    uint32_t r = lgca_rand_u32(L->key, L->outflow, LGCA_RND_REINSERT, L->step);
    int start = (int)(r % (uint32_t)n), dir = r >> 31 ? n - 1 : 1;
    for (int q = 0; q < n; q++) {
        int jj = L->band_j0 + (int)(((long)start + (long)q * dir) % n);
        for (int i = L->band_i1[jj & 1] - 1; i >= L->band_i0[jj & 1]; i--)
            if (!lgca_is_solid(L, i, jj) && !lgca_get(L, i, jj, c)) {
                lgca_put(L, i, jj, c, 1);
                return 1;
            }
    }
    return 0;
}

void lgca_exits(lgca *L)
{
    for (int j = 0; j < L->nj; j++)
        for (int i = 0; i < L->exit_n[j & 1]; i++)
            for (int c = 0; c < LGCA_CH; c++) {
                if (!lgca_get(L, i, j, c))
                    continue;
                lgca_put(L, i, j, c, 0);
                L->outflow++;
                if (!L->reinsert)
                    continue;
                if (reinsert(L, c))
                    L->reinserted++;
                else
                    L->lost++;
            }
}
