/* How a thread of a step waits for another without the OpenMP runtime's
 * barriers (dem's one-barrier step, lgca's neighbour exchange): on a flag
 * the other raises to an epoch, spinning a while, then giving the core
 * away between checks, so that a thread whose core another job took gets
 * it back. Yielding rather than napping: on the test machine (a VM) a
 * 20 us nanosleep returns after 90-190 us; an idle run of dem's flowing
 * silo napped 500-2600 times in 32 000 steps (88-520 ms), and a 256^2
 * lattice gas on two threads with one core taken by another job ran at
 * 0.13 of one thread napping, 0.45 yielding (25 Nov 2026). */
#ifndef GR_SPIN_H
#define GR_SPIN_H

#include <sched.h>
#include <stdatomic.h>
#include <stdint.h>

/* Until *f reaches epoch: `spins` pauses, then sched_yield between checks. */
static inline void gr_spin_until(_Atomic uint64_t *f, uint64_t epoch, unsigned spins)
{
    for (unsigned k = 0; atomic_load_explicit(f, memory_order_acquire) < epoch; k++) {
        if (k < spins) {
#if defined(__x86_64__) || defined(__i386__)
            __builtin_ia32_pause();
#endif
        } else {
            sched_yield();
        }
    }
}

#endif
