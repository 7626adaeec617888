/* Memory that shares no cache line, and no pair of lines, with any other
 * allocation: for what the threads of a team share. A core's L2
 * prefetcher fetches a line's 128-byte partner with it and streams a few
 * lines ahead, so an array that one thread writes every step beside one
 * that another thread reads every step costs a transfer of lines between
 * the cores each time, though no byte is shared; between cores that share
 * no cache each costs about 330 ns (docs/performance.md). */
#ifndef GR_APART_H
#define GR_APART_H

#include <stdlib.h>
#include <string.h>

/* bytes zeroed, on 128-byte pairs of lines, followed by 256 bytes that
 * nothing uses; free() releases it. Enough for the lattice gas's shared
 * arrays; a core streaming through the end of an array can prefetch on to
 * the page boundary, which soft DEM's per-grain arrays guard against with
 * a page (dem_grains.c, DEM_TAIL). */
static inline void *gr_zalloc_apart(size_t bytes)
{
    size_t n = ((bytes + 127) & ~(size_t)127) + 256;
    void *p = aligned_alloc(128, n);
    if (p)
        memset(p, 0, n);
    return p;
}

#endif
