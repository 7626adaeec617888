/* How the threads of the DEM step wait for one another without the
 * OpenMP runtime's barriers (common/spin.h). Included by the files that
 * run a step on several threads. */
#ifndef GR_DEM_SYNC_H
#define GR_DEM_SYNC_H

#include <stdatomic.h>
#include <stdint.h>

#include "spin.h"

/* Wait until *f reaches epoch (a flag another thread of the step sets):
 * 2^14 pauses (0.15 ms on the test machine), then yields (common/spin.h). */
static inline void gr_dem_wait_epoch(_Atomic uint64_t *f, uint64_t epoch) { gr_spin_until(f, epoch, 1u << 14); }

/* Where the threads of a parallel region meet (a barrier that waits as
 * gr_dem_wait_epoch does): gr_dem_meet returns 1 to the last thread to
 * arrive, which may then run a serial part before gr_dem_meet_release,
 * and waits for that release in the others (returning 0); val carries a
 * value from that thread to all. */
typedef struct gr_dem_meet {
    _Alignas(64) _Atomic int arrived;
    _Alignas(64) _Atomic uint64_t gen;
    int val;
} gr_dem_meet_t;

static inline void gr_dem_meet_init(gr_dem_meet_t *m)
{
    atomic_init(&m->arrived, 0);
    atomic_init(&m->gen, 0);
    m->val = 0;
}

static inline void gr_dem_meet_release(gr_dem_meet_t *m)
{
    uint64_t g = atomic_load_explicit(&m->gen, memory_order_relaxed);
    atomic_store_explicit(&m->gen, g + 1, memory_order_release);
}

static inline int gr_dem_meet(gr_dem_meet_t *m, int nth)
{
    /* no generation passes before this thread arrives */
    uint64_t g = atomic_load_explicit(&m->gen, memory_order_relaxed);
    if (atomic_fetch_add_explicit(&m->arrived, 1, memory_order_acq_rel) == nth - 1) {
        atomic_store_explicit(&m->arrived, 0, memory_order_relaxed);
        return 1;
    }
    gr_dem_wait_epoch(&m->gen, g + 1);
    return 0;
}

/* A plain barrier. */
static inline void gr_dem_meet_all(gr_dem_meet_t *m, int nth)
{
    if (gr_dem_meet(m, nth))
        gr_dem_meet_release(m);
}

#endif
