/* Room for the large arrays (grains, slabs, queues, cells): the lowest
 * layer of the backend, used by every file that allocates them. */
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

#include "edmd_int.h"

/* Events land on random grains, so at large N nearly every access to the
 * grain, slab, leaf and tree arrays also misses the TLB with 4 KiB pages
 * (a 10^6-grain run spans some 250 MB). Arrays of 2 MiB or more are
 * aligned to 2 MiB and flagged for transparent huge pages (where the kernel
 * has them in madvise mode, as here, this is what turns them on; a refusal
 * is harmless). Smaller arrays start on 64-byte lines. Both are zeroed:
 * checkpoints store the event slabs whole, unused slots included, and a
 * checkpoint must be the same bytes whichever process wrote it (grano run,
 * or a run from Python whose allocator held other data before). */
void *edmd_big_alloc(size_t bytes)
{
    const size_t huge = (size_t)2 << 20;
    void *m;
    if (bytes < huge) {
        bytes = (bytes + 63) & ~(size_t)63;
        m = aligned_alloc(64, bytes);
    } else {
        bytes = (bytes + huge - 1) & ~(huge - 1);
        m = aligned_alloc(huge, bytes);
#ifdef MADV_HUGEPAGE
        if (m)
            (void)madvise(m, bytes, MADV_HUGEPAGE);
#endif
    }
    if (m)
        memset(m, 0, bytes);
    return m;
}

/* Slabs start on 64-byte lines (a slab of 8 events is two lines). */
edmd_ev *edmd_ev_alloc(size_t count)
{
    return edmd_big_alloc(count * sizeof(edmd_ev));
}
