/* docs/roof.c: the machine's ceilings for docs/performance.md ("The machine's
 * ceilings"); not part of the build.
 * gcc -O3 -fopenmp -mavx2 -mfma docs/roof.c -o roof; OMP_NUM_THREADS=1 ./roof
 * Rates per CPU second, so that other jobs on the cores do not count. */
#define _GNU_SOURCE
#include <omp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/mman.h>
#include <time.h>
/* CPU seconds of the process: other jobs on the cores take wall time, not this */
static double cpu(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}
typedef double v4 __attribute__((vector_size(32)));
typedef uint64_t u4 __attribute__((vector_size(32)));
#define REG10(t) __asm__("" : "+x"(t##0), "+x"(t##1), "+x"(t##2), "+x"(t##3), "+x"(t##4), \
                                "+x"(t##5), "+x"(t##6), "+x"(t##7), "+x"(t##8), "+x"(t##9))
static double triad(size_t n, int reps) /* best GB per CPU second of each thread, 24 bytes an element (STREAM's count) */
{
    double *a = aligned_alloc(64, n * 8), *b = aligned_alloc(64, n * 8), *c = aligned_alloc(64, n * 8), best = 0;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) a[i] = 0, b[i] = 1, c[i] = 2;
    for (int r = 0; r < 10; r++) {
        double t = cpu();
#pragma omp parallel
        for (int q = 0; q < reps; q++) {
#pragma omp for schedule(static)
            for (size_t i = 0; i < n; i++) a[i] = b[i] + 3.0 * c[i];
        }
        t = cpu() - t;
        t /= omp_get_max_threads(); /* each thread's CPU seconds */
        if (24.0 * n * reps / t > best) best = 24.0 * n * reps / t;
    }
    free(a), free(b), free(c);
    return best / 1e9;
}
int main(void)
{
    int T = omp_get_max_threads();
    printf("triad, %d threads: L2-sized (3 x 96 KiB) %.0f GB/s, L3-sized (3 x 2 MiB) %.0f GB/s, DRAM (3 x 256 MiB) %.1f GB/s\n",
           T, triad(12288 / T * T, 4000), triad(262144, 200), triad((size_t)1 << 25, 1));
    double bf = 0, bb = 0;
    long it = 200000000;
    for (int r = 0; r < 5; r++) {
        double t = cpu(), s = 0;
#pragma omp parallel reduction(+ : s)
        {
            v4 m = {1.0000001, 1.0000001, 1.0000001, 1.0000001}, p = {1e-9, 1e-9, 1e-9, 1e-9};
            v4 x0 = p, x1 = p + 1, x2 = p + 2, x3 = p + 3, x4 = p + 4, x5 = p + 5, x6 = p + 6, x7 = p + 7, x8 = p + 8, x9 = p + 9;
            for (long i = 0; i < it; i++) {
                x0 = x0 * m + p, x1 = x1 * m + p, x2 = x2 * m + p, x3 = x3 * m + p, x4 = x4 * m + p;
                x5 = x5 * m + p, x6 = x6 * m + p, x7 = x7 * m + p, x8 = x8 * m + p, x9 = x9 * m + p;
                REG10(x);
            }
            s += (x0 + x1 + x2 + x3 + x4 + x5 + x6 + x7 + x8 + x9)[0];
        }
        t = cpu() - t;
        t /= T;
        if (80.0 * it * T / t > bf) bf = 80.0 * it * T / t;
        t = cpu();
        uint64_t o = 0;
#pragma omp parallel reduction(| : o)
        {
            u4 m = {3, 5, 7, 9}, p = {11, 13, 17, 19};
            u4 y0 = p, y1 = p + 1, y2 = p + 2, y3 = p + 3, y4 = p + 4, y5 = p + 5, y6 = p + 6, y7 = p + 7, y8 = p + 8, y9 = p + 9;
            for (long i = 0; i < it; i++) {
                y0 = (y0 & m) ^ p, y1 = (y1 & m) ^ p, y2 = (y2 & m) ^ p, y3 = (y3 & m) ^ p, y4 = (y4 & m) ^ p;
                y5 = (y5 & m) ^ p, y6 = (y6 & m) ^ p, y7 = (y7 & m) ^ p, y8 = (y8 & m) ^ p, y9 = (y9 & m) ^ p;
                REG10(y);
            }
            o |= (y0 | y1 | y2 | y3 | y4 | y5 | y6 | y7 | y8 | y9)[1];
        }
        t = cpu() - t;
        t /= T;
        if (20.0 * 4 * it * T / t > bb) bb = 20.0 * 4 * it * T / t; /* 64-bit word operations */
        if (s == 42 || o == 42) puts("");
    }
    printf("peak, %d threads: %.1f GFLOP/s (AVX2 FMA, 4 lanes), %.1f G 64-bit logic ops/s (AVX2 and/xor)\n", T, bf / 1e9, bb / 1e9);
    size_t bytes = (size_t)1 << 30, m = bytes / 64; /* 1 GiB of lines on 2 MiB pages */
    uint32_t *nx = aligned_alloc(1 << 21, bytes);
    madvise(nx, bytes, MADV_HUGEPAGE);
    for (size_t i = 0; i < m; i++) nx[i * 16] = (uint32_t)i;
    uint64_t z = 88172645463325252ull;
    for (size_t i = m - 1; i > 0; i--) { /* Sattolo: one random cycle through every line */
        z ^= z << 13, z ^= z >> 7, z ^= z << 17;
        size_t j = z % i;
        uint32_t t = nx[i * 16]; nx[i * 16] = nx[j * 16], nx[j * 16] = t;
    }
    for (int k = 1; k <= 32; k *= 2) {
        double bl = 0;
        for (int r = 0; r < 3; r++) {
            uint32_t p[32];
            for (int q = 0; q < k; q++) p[q] = (uint32_t)(q * (m / 32));
            long steps = 8000000 / k;
            double t = cpu();
            for (long s = 0; s < steps; s++)
                for (int q = 0; q < k; q++) p[q] = nx[(size_t)p[q] * 16];
            t = cpu() - t;
            if (steps * k / t > bl) bl = steps * k / t;
            if (p[0] == 0xffffffffu) puts("");
        }
        printf("random 64-byte lines in 1 GiB (2 MiB pages), one thread, %2d chains: %4.0f ns a line, %5.1f M lines/s\n",
               k, 1e9 / bl, bl / 1e6);
    }
    return 0;
}
