/* One step of the automaton on bit planes: collision (and dissipation) and
 * gravity at fluid nodes, Peng and Herrmann's rest collision (lgca_stop.c),
 * reflection at wall nodes, propagation, then the
 * silo's exit and reinsertion. Lanes are split into one block per thread;
 * every random bit is a function of (key, word, purpose, step), so the
 * result does not depend on the split. */
#include <omp.h>
#include <stdatomic.h>
#include <string.h>

#include "lgca_int.h"
#include "lgca_philox.h"
#include "spin.h"

/* Gravity: at a fluid node drawn with probability g, one unit of downward
 * momentum: the first of the order's moves whose particle is there and
 * whose target channel is empty (rest particle to down, up-right to
 * down-right, up-left to down-left). */
static const unsigned char grav_moves[2][3][2] = {{{6, 3}, {1, 2}, {5, 4}}, {{6, 3}, {5, 4}, {1, 2}}};

/* The order of the three moves at step `step` (lgca_ref.c applies it too). */
void lgca_gravity_moves(int order, uint64_t step, unsigned char mv[3][2])
{
    int alt = order == LGCA_GRAV_ALTERNATE && (step & 1), first = order == LGCA_GRAV_MOVERS;
    for (int k = 0; k < 3; k++)
        for (int e = 0; e < 2; e++)
            mv[k][e] = grav_moves[alt][(k + first) % 3][e];
}

static void gravity(uint64_t *lane, size_t nw, size_t w, uint64_t m, const unsigned char mv[3][2])
{
    uint64_t *c = lane + w;
    for (int k = 0; k < 3; k++) {
        size_t a = mv[k][0] * nw, b = mv[k][1] * nw;
        uint64_t t = m & c[a] & ~c[b];
        c[a] ^= t, c[b] |= t;
        m &= ~t;
    }
}

/* ---- propagation ---- */

/* Node i moves to i + 1; returns the particles that fell off the end
 * (re-entering at i = 0 when the axis is periodic). */
static uint64_t shift_up(const lgca *L, uint64_t *dst, const uint64_t *src)
{
    size_t nw = (size_t)L->nw;
    int top = L->ni - 1;
    uint64_t out = src[top >> 6] >> (top & 63) & 1u;
    for (size_t w = nw; w-- > 0;)
        dst[w] = src[w] << 1 | (w ? src[w - 1] >> 63 : 0);
    dst[nw - 1] &= L->valid[nw - 1];
    if (L->per_i) {
        dst[0] |= out;
        return 0;
    }
    return out;
}

static uint64_t shift_down(const lgca *L, uint64_t *dst, const uint64_t *src)
{
    size_t nw = (size_t)L->nw;
    int top = L->ni - 1;
    uint64_t out = src[0] & 1u;
    for (size_t w = 0; w < nw; w++)
        dst[w] = src[w] >> 1 | (w + 1 < nw ? src[w + 1] << 63 : 0);
    if (L->per_i) {
        dst[top >> 6] |= out << (top & 63);
        return 0;
    }
    return out;
}

/* The nodes whose collision a dissipation bit can change (no rest
 * particle, two movers or more: a superset of the table's), and those that
 * gravity can change (after the collision); elsewhere no bit is drawn. */
static inline __attribute__((always_inline)) void need_dissipation_t(const uint64_t *lane, size_t nw,
                                                                      const uint64_t *fluid, uint64_t *need,
                                                                      const uint64_t *pf)
{
    for (size_t w = 0; w < nw; w++) {
        if (pf && !(w & 7))
            for (int k = 0; k < LGCA_CH; k++)
                __builtin_prefetch(pf + (size_t)k * nw + w, 0, 2);
        uint64_t one = 0, two = 0;
        for (int k = 0; k < 6; k++) {
            uint64_t a = lane[(size_t)k * nw + w];
            two |= one & a, one |= a;
        }
        need[w] = fluid[w] & ~lane[LGCA_REST * nw + w] & two;
    }
}

/* pf: the lane to prefetch alongside, or NULL; a loop for each, so that
 * lattices in the caches (no prefetch) pay no test per word */
static void need_dissipation(const uint64_t *lane, size_t nw, const uint64_t *fluid, uint64_t *need,
                             const uint64_t *pf)
{
    if (pf)
        need_dissipation_t(lane, nw, fluid, need, pf);
    else
        need_dissipation_t(lane, nw, fluid, need, NULL);
}

static void need_gravity(const uint64_t *lane, size_t nw, const uint64_t *fluid, uint64_t *need)
{
    for (size_t w = 0; w < nw; w++) {
        const uint64_t *c = lane + w;
        need[w] = fluid[w] & ((c[6 * nw] & ~c[3 * nw]) | (c[1 * nw] & ~c[2 * nw]) | (c[5 * nw] & ~c[4 * nw]));
    }
}

/* The lanes from jb on (before jend, at most as many as [ja, jb)) that
 * the next chunk of collide_block will first touch, into *pf if they
 * follow lanes in memory; returns their words (0: none). */
static size_t next_lanes(const lgca *L, const uint64_t *lanes, int ja, int jb, int jend, const uint64_t **pf)
{
    int nn = jb - ja < jend - jb ? jb - ja : jend - jb;
    size_t lw = (size_t)LGCA_CH * (size_t)L->nw;
    if (nn <= 0 || L->lane[jb] != lanes + (size_t)(jb - ja) * lw ||
        L->lane[jb + nn - 1] != L->lane[jb] + (size_t)(nn - 1) * lw)
        return 0;
    *pf = L->lane[jb];
    return (size_t)nn * (size_t)L->nw;
}

/* Lanes [j0, j1) in chunks of L->chunk lanes, whose random words are
 * drawn together (word j nw + w of lane j). The lanes [j1, jpf) are the
 * caller's next ones, prefetched while the last chunk computes. */
static uint64_t collide_block(lgca *L, int j0, int j1, int jpf, uint64_t *scr, uint64_t step, int fuse)
{
    uint64_t out = 0;
    size_t nw = (size_t)L->nw, cw = (size_t)L->chunk * nw;
    uint64_t *fluid = scr, *ch = scr + cw, *pb = scr + 2 * cw, *need = scr + 3 * cw, *dense = scr + 4 * cw;
    int granular = L->par.rules == LGCA_RULES_GRANULAR;
    for (int ja = j0, jb; ja < j1; ja = jb) {
        int k = 0;
        while (L->seg_j[k + 1] <= ja)
            k++;
        jb = ja + L->chunk < j1 ? ja + L->chunk : j1;
        jb = jb < L->seg_j[k + 1] ? jb : L->seg_j[k + 1]; /* a chunk's lanes lie in one allocation */
        size_t n = (size_t)(jb - ja) * nw;
        uint64_t base = (uint64_t)ja * nw;
        uint64_t *lanes = L->lane[ja];
        if (L->nwalls)
            for (size_t o = 0; o < n; o += nw)
                for (size_t w = 0; w < nw; w++)
                    fluid[o + w] = L->valid[w] & ~L->solid[base + o + w];
        else /* no wall node: the mask need not be read (8 MiB a step at 8192^2) */
            for (size_t o = 0; o < n; o += nw)
                memcpy(fluid + o, L->valid, nw * sizeof *fluid);
        lgca_rand_words(L->key, base, n, LGCA_RND_CHIRAL, step, ch);
        if (granular) {
            /* Each step's first touch of the lanes: from DRAM once the
             * lattice outgrows the caches, in seven planes at once, which the
             * hardware prefetchers do not follow. The next chunk goes to L2
             * (prefetcht1; to L1, or with prefetchw, it evicts this chunk's
             * scratch: 2.09-2.13e9): AVX2-only build, granular 8192^2,
             * 2.02 -> 2.26e9 site updates/s. */
            const uint64_t *pf = NULL;
            size_t npf = L->prefetch ? next_lanes(L, lanes, ja, jb, jb < j1 ? j1 : jpf, &pf) : 0;
            for (size_t o = 0; o < n; o += nw)
                need_dissipation(lanes + o * LGCA_CH, nw, fluid + o, need + o, o < npf ? pf + o * LGCA_CH : NULL);
            lgca_rand_biased_lanes(L->key, (uint64_t)ja, (size_t)(jb - ja), nw, LGCA_RND_P, step, L->thr_p, need, pb,
                                   dense);
            lgca_delta_granular_lanes(lanes, (size_t)(jb - ja), nw, fluid, ch, pb);
        } else
            lgca_delta_fhp3_lanes(lanes, (size_t)(jb - ja), nw, fluid, ch);
        if (L->thr_g) {
            unsigned char mv[3][2];
            lgca_gravity_moves(L->par.gravity, step, mv);
            for (size_t o = 0; o < n; o += nw)
                need_gravity(lanes + o * LGCA_CH, nw, fluid + o, need + o);
            lgca_rand_biased_lanes(L->key, (uint64_t)ja, (size_t)(jb - ja), nw, LGCA_RND_G, step, L->thr_g, need, pb,
                                   dense);
            for (size_t o = 0; o < n; o += nw)
                for (size_t w = 0; w < nw; w++)
                    gravity(lanes + o * LGCA_CH, nw, w, pb[o + w], mv);
        }
        /* without serial work between, channels 0 and 3 move along the lane
         * while the chunk is in cache */
        for (size_t o = 0; fuse && o < n; o += nw) {
            uint64_t *l = lanes + o * LGCA_CH;
            out += shift_up(L, l, l) + shift_down(L, l + 3 * nw, l + 3 * nw);
        }
    }
    return out;
}

/* Wall nodes: the mirror image of every particle (bounce-back with
 * probability b). Serial: walls are a perimeter, not an area. */
static void reflect(lgca *L)
{
    for (size_t k = 0; k < L->nwalls; k++) {
        const lgca_wall *w = &L->walls[k];
        int i = (int)w->i, j = (int)w->j;
        if (!lgca_is_solid(L, i, j))
            continue; /* an open gate */
        int in[6], any = 0;
        for (int c = 0; c < 6; c++)
            any |= in[c] = lgca_get(L, i, j, c);
        if (!any)
            continue;
        int m = (int)w->mirror;
        uint64_t node = (uint64_t)j * (uint64_t)L->ni + (uint64_t)i;
        if (L->thr_b && lgca_rand_u32(L->key, node, LGCA_RND_WALL, L->step) < L->thr_b)
            m = 6;
        for (int c = 0; c < 6; c++)
            lgca_put(L, i, j, lgca_mirror(m, c), in[c]);
    }
}

static uint64_t *plane(lgca *L, int j, int c)
{
    return L->lane[j] + (size_t)c * (size_t)L->nw;
}

static uint64_t count(const uint64_t *x, size_t nw)
{
    uint64_t n = 0;
    for (size_t w = 0; w < nw; w++)
        n += (uint64_t)__builtin_popcountll(x[w]);
    return n;
}

/* Channel c of a lane from src, the plane of source lane js: channels 1
 * and 5 climb half a node, 2 and 4 descend; the half is a whole row from an
 * odd lane for 1 and 5, from an even lane for 2 and 4. */
static uint64_t move_across(lgca *L, int c, int js, const uint64_t *src, uint64_t *dst)
{
    int odd = js & 1;
    if ((c == 1 || c == 5) && odd)
        return shift_up(L, dst, src);
    if ((c == 2 || c == 4) && !odd)
        return shift_down(L, dst, src);
    memcpy(dst, src, (size_t)L->nw * sizeof *dst);
    return 0;
}

/* Channel c across block [j0, j1), but for the lane that takes its
 * neighbour's edge lane: rightward channels (1, 2) take lane j - 1,
 * leftward (4, 5) lane j + 1, in the order that reads each source before
 * it is overwritten. */
static uint64_t propagate_inner(lgca *L, int c, int j0, int j1)
{
    uint64_t lost = 0;
    if (c == 1 || c == 2)
        for (int j = j1 - 1; j > j0; j--)
            lost += move_across(L, c, j - 1, plane(L, j - 1, c), plane(L, j, c));
    else
        for (int j = j0; j < j1 - 1; j++)
            lost += move_across(L, c, j + 1, plane(L, j + 1, c), plane(L, j, c));
    return lost;
}

/* The block's first lane (channels 1, 2) or last (4, 5) from the edge lane
 * saved by the neighbour of thread t in slot q of the step's parity, once
 * the neighbour has published it. */
static uint64_t propagate_edge(lgca *L, int q, int c, int t, int T, int j0, int j1, int par)
{
    size_t nw = (size_t)L->nw, slot = lgca_edge_slot(L);
    const uint64_t *edge = L->edge + (size_t)par * (size_t)T * slot + (size_t)q * nw;
    int right = c == 1 || c == 2, jd = right ? j0 : j1 - 1;
    int js = right ? (j0 > 0 ? j0 - 1 : L->nj - 1) : (j1 < L->nj ? j1 : 0);
    if (!L->per_j && (right ? j0 == 0 : j1 == L->nj)) {
        memset(plane(L, jd, c), 0, nw * sizeof *edge);
        return 0;
    }
    const uint64_t *e = edge + (size_t)(right ? (t > 0 ? t - 1 : T - 1) : (t + 1 < T ? t + 1 : 0)) * slot;
    return move_across(L, c, js, e, plane(L, jd, c));
}

/* The block's edge lane that a neighbouring block reads (slot q of the
 * thread's four); particles leaving the lattice sideways are counted. */
static uint64_t save_edge(lgca *L, int q, int c, int t, int T, int j0, int j1, int par)
{
    size_t nw = (size_t)L->nw;
    int right = c == 1 || c == 2;
    int je = right ? j1 - 1 : j0;
    uint64_t *slot = L->edge + ((size_t)par * (size_t)T + (size_t)t) * lgca_edge_slot(L);
    memcpy(slot + (size_t)q * nw, plane(L, je, c), nw * sizeof *slot);
    int off = right ? je == L->nj - 1 : je == 0;
    return off && !L->per_j ? count(plane(L, je, c), nw) : 0;
}

/* Gates whose time has come turn fluid (idempotent, so a load needs no
 * more than the step number). */
static void open_gates(lgca *L)
{
    if (!L->has_gates)
        return;
    for (size_t k = 0; k < L->nwalls; k++)
        if (L->walls[k].open_step <= L->step) {
            const lgca_wall *w = &L->walls[k];
            L->solid[(size_t)w->j * (size_t)L->nw + (w->i >> 6)] &= ~((uint64_t)1 << (w->i & 63));
        }
}

/* One per thread, on a cache line of its own: the steps whose edge lanes
 * the thread has saved. */
typedef struct {
    _Alignas(64) _Atomic uint64_t saved;
    char pad[64 - sizeof(uint64_t)];
} lgca_flag;

/* Until both neighbours of t have saved the edge lanes of step s. A
 * barrier would also wait for the far blocks; on a 256^2 lattice (a step
 * of 16 microseconds) the team barrier cost a tenth of the step. */
static void wait_neighbours(lgca_flag *f, int t, int T, uint64_t s)
{
    gr_spin_until(&f[t > 0 ? t - 1 : T - 1].saved, s, 4096);
    gr_spin_until(&f[t + 1 < T ? t + 1 : 0].saved, s, 4096);
}

static const int across[4] = {1, 2, 4, 5};

/* The lanes at each end of a block collided ahead of the rest: enough
 * words for a whole batch of Philox calls (lgca_philox.h), as a lane or two
 * alone would leave most of their batch idle. */
static int end_lanes(const lgca *L, int j0, int j1)
{
    int e = (2 * LGCA_BATCH + L->nw - 1) / L->nw;
    return e < (j1 - j0) / 2 ? e : (j1 - j0) / 2;
}

/* Collision and propagation of lanes [j0, j1) in one sweep, chunk by
 * chunk, so that each step reads and writes a lane once rather than in a
 * collision pass and a propagation pass: after a chunk is collided its
 * rightward channels (1, 2) move in from the lane before (the chunk's first
 * lane from the copy of the previous chunk's last one, rnext and rprev in
 * rb), its leftward channels (4, 5) from the lane after, the chunk's last
 * lane waiting for the next chunk. The lanes [j0, j0 + e) and [j1 - e, j1)
 * were collided ahead (a team's ends). What enters lane j0 from the left
 * and lane j1 - 1 from the right comes later, from the edge slots, which a
 * lone thread fills here. Where the lattice outgrows the caches this pays:
 * one thread's granular rate rose about 10 % at 4096^2 and 20 % at 8192^2,
 * FHP-III's about 30 % at 8192^2 (docs/methods/lgca.md, "One sweep"). */
static uint64_t sweep(lgca *L, int T, int j0, int j1, int e, uint64_t *scr, uint64_t step, uint64_t *rb, int par)
{
    size_t nw = (size_t)L->nw;
    uint64_t out = 0, *rprev = rb, *rnext = rb + 2 * nw;
    for (int a = j0, b; a < j1; a = b) {
        int ahead = a < j0 + e || a >= j1 - e;
        b = a < j0 + e ? j0 + e : a >= j1 - e ? j1 : (a + L->chunk < j1 - e ? a + L->chunk : j1 - e);
        if (!ahead)
            out += collide_block(L, a, b, j1, scr, step, 1);
        for (int q = 0; q < 4 && T == 1; q++)
            if (q < 2 ? b == j1 : a == j0)
                out += save_edge(L, q, across[q], 0, 1, j0, j1, par);
        for (int q = 0; q < 2; q++) {
            int c = across[q];
            if (b < j1)
                memcpy(rnext + (size_t)q * nw, plane(L, b - 1, c), nw * sizeof *rnext);
            out += propagate_inner(L, c, a, b);
            if (a > j0)
                out += move_across(L, c, a - 1, rprev + (size_t)q * nw, plane(L, a, c));
        }
        uint64_t *tmp = rprev;
        rprev = rnext, rnext = tmp;
        for (int q = 2; q < 4; q++)
            out += propagate_inner(L, across[q], a > j0 ? a - 1 : j0, b);
    }
    return out;
}

/* One step of thread t without serial work: one synchronisation, with the
 * neighbours only. The block's end lanes are collided first, their edge
 * planes saved and the step published; the rest of the block is swept
 * while the neighbours do the same, so that by the time the thread needs
 * their edge lanes (to propagate its end lanes) they were published long
 * ago and the wait rarely blocks. A collision touches the block's own
 * lanes only, and its random bits are a function of the lane, not of the
 * chunk. Edge slots of the step's parity are written again two steps
 * later, after the thread saw the neighbours publish the step in between,
 * which they do after moving the slot's lanes into their end lanes
 * (program order, release and acquire). */
static uint64_t step_alone(lgca *L, int t, int T, int j0, int j1, uint64_t *scr, uint64_t step, lgca_flag *flag)
{
    int par = (int)(step & 1u), e = T > 1 ? end_lanes(L, j0, j1) : 0;
    uint64_t out = 0, *rb = L->sweep + (size_t)t * lgca_sweep_words(L);
    if (T > 1) {
        out += collide_block(L, j0, j0 + e, j0 + e, scr, step, 1);
        out += collide_block(L, j1 - e, j1, j1, scr, step, 1);
        for (int q = 0; q < 4; q++)
            out += save_edge(L, q, across[q], t, T, j0, j1, par);
        atomic_store_explicit(&flag[t].saved, step + 1, memory_order_release);
    }
    out += sweep(L, T, j0, j1, e, scr, step, rb, par);
    if (T > 1)
        wait_neighbours(flag, t, T, step + 1);
    for (int q = 0; q < 4; q++)
        out += propagate_edge(L, q, across[q], t, T, j0, j1, par);
    return out;
}

/* With serial work (rest collision, walls, exits, gates) four team
 * synchronisations a step. */
static uint64_t step_serial(lgca *L, int t, int T, int j0, int j1, uint64_t *scr, uint64_t step)
{
    int par = (int)(step & 1u);
    uint64_t out = collide_block(L, j0, j1, j1, scr, step, 0);
#pragma omp barrier
#pragma omp single
    {
        if (L->thr_stop)
            lgca_stop_pass(L, L->stop_mask);
        reflect(L);
    }
    for (int q = 0; q < 4; q++)
        out += save_edge(L, q, across[q], t, T, j0, j1, par);
    for (int j = j0; j < j1; j++) {
        out += shift_up(L, plane(L, j, 0), plane(L, j, 0));
        out += shift_down(L, plane(L, j, 3), plane(L, j, 3));
    }
#pragma omp barrier
    for (int q = 0; q < 4; q++)
        out += propagate_inner(L, across[q], j0, j1) + propagate_edge(L, q, across[q], t, T, j0, j1, par);
#pragma omp barrier
#pragma omp single
    {
        if (L->exits)
            lgca_exits(L);
        L->step++;
        open_gates(L);
    }
    return out;
}

/* n steps by thread t of a team of T on lanes [j0, j1); the particles that
 * left the lattice go to lost[t]. */
static void run_block(lgca *L, int t, int T, uint64_t n, uint64_t *lost, lgca_flag *flag)
{
    int j0 = (int)((long)L->nj * t / T), j1 = (int)((long)L->nj * (t + 1) / T);
    uint64_t *scr = L->scratch + (size_t)t * LGCA_SCRATCH * (size_t)L->chunk * (size_t)L->nw;
    int serial = L->thr_stop || L->nwalls || L->exits || L->has_gates;
    uint64_t step0 = L->step, mine = 0;
    for (uint64_t k = 0; k < n; k++)
        mine += serial ? step_serial(L, t, T, j0, j1, scr, step0 + k)
                       : step_alone(L, t, T, j0, j1, scr, step0 + k, flag);
    lost[t] = mine;
    if (!serial) {
#pragma omp barrier
#pragma omp single
        L->step = step0 + n;
    }
}

int lgca_steps(lgca *L, uint64_t n, gr_err *err)
{
    (void)err;
    open_gates(L);
    int T = L->nthreads < L->nj / 2 ? L->nthreads : L->nj / 2;
    uint64_t lost[256] = {0};
    lgca_flag flag[256];
    for (int t = 0; t < T; t++)
        atomic_init(&flag[t].saved, L->step);
    /* a region even for one thread: run_block's barriers and single
     * constructs would otherwise bind to a caller's team (two lattices
     * advanced by the threads of a program's parallel loop); the team may
     * be smaller than asked: blocks follow its size */
    if (n > 0) {
#pragma omp parallel num_threads(T)
        run_block(L, omp_get_thread_num(), omp_get_num_threads(), n, lost, flag);
    }
    for (int t = 0; t < 256; t++)
        L->lost += lost[t];
    return GR_OK;
}
