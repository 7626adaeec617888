/* grano bench dsmc --rng: the cost of the random generators. */
#ifndef GR_BENCH_RNG_H
#define GR_BENCH_RNG_H

/* Prints one line per generator: RESULT rng=NAME draws_per_s=X. */
int bench_rng_draws(void);

#endif
