/* The round trip of a cache line between the two threads a two-thread
 * bench runs on. On a VM the host may place the two virtual CPUs on cores
 * that share a last-level cache or on cores that do not: on the 2-core
 * AMD EPYC VM of 27 Nov 2026 the round trip moved between about 60 and
 * about 340 ns from one minute to the next, and the two-thread speed-ups
 * of dem and lgca with it (docs/performance.md, "On an AMD EPYC, and two
 * threads on cores apart"). A speed-up is printed with this figure so that it says which
 * placement it was measured on. */
#ifndef GR_BENCH_C2C_H
#define GR_BENCH_C2C_H

/* Median over 5 batches of n round trips each (a batch stops after 50 ms),
 * in ns; NAN without two threads (no OpenMP, or the runtime gave one). */
double bench_c2c_ns(int n);

#endif
