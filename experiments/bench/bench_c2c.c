#include "bench_c2c.h"

#include <math.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>

#include "clock.h"

#ifdef _OPENMP
#include <omp.h>
#endif

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Thread 0 raises the flag to an odd value, thread 1 answers with the next
 * even one: each round trip moves the line there and back. */
static double batch(_Atomic uint64_t *flag, int n)
{
    double t0 = 0.0, t1 = 0.0;
    int two = 0;
    atomic_store_explicit(flag, 0, memory_order_relaxed);
#pragma omp parallel num_threads(2)
    {
#ifdef _OPENMP
        int t = omp_get_thread_num();
#pragma omp single
        two = omp_get_num_threads() == 2;
#else
        int t = 0;
#endif
        if (two && t == 0) {
            t0 = exp_wall_seconds();
            for (uint64_t k = 0; k < (uint64_t)n; k++) {
                atomic_store_explicit(flag, 2 * k + 1, memory_order_release);
                while (atomic_load_explicit(flag, memory_order_acquire) != 2 * k + 2)
                    ;
            }
            t1 = exp_wall_seconds();
        } else if (two) {
            for (uint64_t k = 0; k < (uint64_t)n; k++) {
                while (atomic_load_explicit(flag, memory_order_acquire) != 2 * k + 1)
                    ;
                atomic_store_explicit(flag, 2 * k + 2, memory_order_release);
            }
        }
    }
    return two ? (t1 - t0) * 1e9 / n : NAN;
}

double bench_c2c_ns(int n)
{
    _Atomic uint64_t *flag = aligned_alloc(64, 64);
    if (!flag || n < 1) {
        free(flag);
        return NAN;
    }
    atomic_init(flag, 0);
    double v[5];
    for (int k = 0; k < 5; k++)
        v[k] = batch(flag, n);
    free(flag);
    if (isnan(v[0]))
        return NAN;
    qsort(v, 5, sizeof *v, cmp_double);
    return v[2];
}
