/* Uniform doubles per CPU second: GSL's generators through gsl_rng_uniform
 * (the call common/rng.h makes) against Random123's counter-based Philox
 * and Threefry, keyed and counted as a DSMC step would key them (key:
 * seed and stream, counter: step, cell and draw). */
#include <stdint.h>
#include <stdio.h>

#include <Random123/philox.h>
#include <Random123/threefry.h>
#include <gsl/gsl_rng.h>

#include "bench_rng.h"
#include "clock.h"

#define DRAWS 40000000L

/* 53 random bits to [0, 1). */
static inline double u01(uint64_t x) { return (double)(x >> 11) * 0x1.0p-53; }

static double gsl_rate(const gsl_rng_type *t, double *sink)
{
    gsl_rng *g = gsl_rng_alloc(t);
    gsl_rng_set(g, 12345);
    double s = 0, c0 = exp_cpu_seconds();
    for (long k = 0; k < DRAWS; k++)
        s += gsl_rng_uniform(g);
    double c = exp_cpu_seconds() - c0;
    gsl_rng_free(g);
    *sink += s;
    return DRAWS / c;
}

static double philox2x64_rate(double *sink)
{
    philox2x64_key_t key = {{0x1234567u}};
    philox2x64_ctr_t ctr = {{0, 77}};
    double s = 0, c0 = exp_cpu_seconds();
    for (long k = 0; k < DRAWS; k += 2) {
        ctr.v[0] = (uint64_t)k;
        philox2x64_ctr_t r = philox2x64(ctr, key);
        s += u01(r.v[0]) + u01(r.v[1]);
    }
    double c = exp_cpu_seconds() - c0;
    *sink += s;
    return DRAWS / c;
}

static double philox4x32_rate(double *sink)
{
    philox4x32_key_t key = {{0x1234567u, 99u}};
    philox4x32_ctr_t ctr = {{0, 0, 77, 0}};
    double s = 0, c0 = exp_cpu_seconds();
    for (long k = 0; k < DRAWS; k += 2) {
        ctr.v[0] = (uint32_t)k, ctr.v[1] = (uint32_t)((uint64_t)k >> 32);
        philox4x32_ctr_t r = philox4x32(ctr, key);
        s += u01((uint64_t)r.v[0] << 32 | r.v[1]) + u01((uint64_t)r.v[2] << 32 | r.v[3]);
    }
    double c = exp_cpu_seconds() - c0;
    *sink += s;
    return DRAWS / c;
}

static double threefry2x64_rate(double *sink)
{
    threefry2x64_key_t key = {{0x1234567u, 99u}};
    threefry2x64_ctr_t ctr = {{0, 77}};
    double s = 0, c0 = exp_cpu_seconds();
    for (long k = 0; k < DRAWS; k += 2) {
        ctr.v[0] = (uint64_t)k;
        threefry2x64_ctr_t r = threefry2x64(ctr, key);
        s += u01(r.v[0]) + u01(r.v[1]);
    }
    double c = exp_cpu_seconds() - c0;
    *sink += s;
    return DRAWS / c;
}

int bench_rng_draws(void)
{
    double sink = 0;
    const struct {
        const char *name;
        const gsl_rng_type *t;
    } g[] = {{"gsl_mt19937", gsl_rng_mt19937}, {"gsl_taus2", gsl_rng_taus2}, {"gsl_ranlxs0", gsl_rng_ranlxs0}};
    printf("# uniform doubles per CPU second, %ld draws each\n", DRAWS);
    for (int k = 0; k < 3; k++)
        printf("RESULT rng=%s draws_per_s=%.4g\n", g[k].name, gsl_rate(g[k].t, &sink));
    printf("RESULT rng=philox2x64_10 draws_per_s=%.4g\n", philox2x64_rate(&sink));
    printf("RESULT rng=philox4x32_10 draws_per_s=%.4g\n", philox4x32_rate(&sink));
    printf("RESULT rng=threefry2x64_20 draws_per_s=%.4g\n", threefry2x64_rate(&sink));
    printf("# checksum %.6f\n", sink);
    return 0;
}
