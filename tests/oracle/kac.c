/* The Kac process of kac.h. */
#include "kac.h"

#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

typedef struct {
    double *v; /* v[2i], v[2i+1]: one cache line per disk, whose draws are random */
    size_t n;
    double alpha;
    double c2max; /* max |v|^2 */
    double G;     /* 2 sqrt(c2max) >= |v_i - v_j| for every pair */
    gsl_rng *r;
    uint64_t drawn, accepted;
} kac_gas;

/* Zero momentum, T = 1 (<c^2> = 2 in 2-D, unit mass), and the bound
 * recomputed: it only grows between rescalings, and a loose one costs
 * draws. a2 of the peculiar velocities is returned, being at hand. */
static double rescale(kac_gas *s)
{
    double mx = 0, my = 0, s2 = 0, s4 = 0, n = (double)s->n, *v = s->v;
    for (size_t i = 0; i < s->n; i++)
        mx += v[2 * i], my += v[2 * i + 1];
    mx /= n, my /= n;
    for (size_t i = 0; i < s->n; i++) {
        double ux = v[2 * i] - mx, uy = v[2 * i + 1] - my, u2 = ux * ux + uy * uy;
        s2 += u2, s4 += u2 * u2;
    }
    s2 /= n, s4 /= n;
    double f = sqrt(2 / s2);
    s->c2max = 0;
    for (size_t i = 0; i < s->n; i++) {
        v[2 * i] = (v[2 * i] - mx) * f, v[2 * i + 1] = (v[2 * i + 1] - my) * f;
        s->c2max = fmax(s->c2max, v[2 * i] * v[2 * i] + v[2 * i + 1] * v[2 * i + 1]);
    }
    s->G = 2 * sqrt(s->c2max);
    return s4 / (2 * s2 * s2) - 1;
}

/* A pair (i, j), i != j, uniform; its two cache lines asked for now, as
 * they are used a draw later: the velocities overflow the cache, and the
 * random reads were most of the time. */
static void draw_pair(kac_gas *s, size_t *i, size_t *j)
{
    *i = gsl_rng_uniform_int(s->r, s->n), *j = gsl_rng_uniform_int(s->r, s->n - 1);
    *j += *j >= *i;
    __builtin_prefetch(s->v + 2 * *i, 1), __builtin_prefetch(s->v + 2 * *j, 1);
}

/* The pair passes with |g| / G, then its n (uniform on the circle) with
 * |g.n| / |g|: together |g.n| / G, with the trigonometry only for the
 * fifth that pass the first. The rule depends on n only through (g.n) n,
 * so n and -n give the same collision and the approaching orientation
 * needs no flip. 1 if it collided. */
static int try_pair(kac_gas *s, double *a, double *b)
{
    double gx = a[0] - b[0], gy = a[1] - b[1], gm = sqrt(gx * gx + gy * gy);
    if (s->G * gsl_rng_uniform(s->r) >= gm)
        return 0;
    double th = 2 * M_PI * gsl_rng_uniform(s->r), nx = cos(th), ny = sin(th), gn = gx * nx + gy * ny;
    if (gm * gsl_rng_uniform(s->r) >= fabs(gn))
        return 0;
    double d = (1 + s->alpha) / 2 * gn;
    a[0] -= d * nx, a[1] -= d * ny, b[0] += d * nx, b[1] += d * ny;
    double c2 = fmax(a[0] * a[0] + a[1] * a[1], b[0] * b[0] + b[1] * b[1]);
    if (c2 > s->c2max) /* an inelastic collision can speed one disk up */
        s->c2max = c2, s->G = 2 * sqrt(c2);
    return 1;
}

/* Draws until `count` collisions are accepted. */
static void collide(kac_gas *s, uint64_t count)
{
    size_t i, j, ni, nj;
    draw_pair(s, &i, &j);
    for (uint64_t done = 0; done < count; s->drawn++, i = ni, j = nj) {
        draw_pair(s, &ni, &nj);
        done += (uint64_t)try_pair(s, s->v + 2 * i, s->v + 2 * j);
    }
    s->accepted += count;
}

/* Mean and standard error of the means of blocks of b samples. */
static void block_stats(const double *x, int k, int b, double *mean, double *err)
{
    int nb = k / b;
    double s = 0, s2 = 0;
    for (int j = 0; j < nb; j++) {
        double m = 0;
        for (int i = 0; i < b; i++)
            m += x[j * b + i];
        m /= b;
        s += m, s2 += m * m;
    }
    *mean = s / nb;
    *err = sqrt(fmax(0, s2 / nb - *mean * *mean) / (nb - 1));
}

/* Maxwellian start; every N/2 collisions (one per particle) a rescaling
 * and, after the transient, an a2 sample. */
static void run(kac_gas *s, const kac_opts *o, double *x)
{
    for (size_t i = 0; i < s->n; i++)
        s->v[2 * i] = gsl_ran_gaussian(s->r, 1), s->v[2 * i + 1] = gsl_ran_gaussian(s->r, 1);
    rescale(s);
    for (int k = -o->transient; k < o->samples; k++) {
        collide(s, s->n / 2);
        double a2 = rescale(s);
        if (k >= 0)
            x[k] = a2;
    }
}

int kac_hcs(const kac_opts *o, kac_result *r)
{
    if (!(o->alpha >= 0 && o->alpha <= 1) || o->n < 2 || o->transient < 0 || o->block < 1 ||
        o->samples < 2 * o->block)
        return -1;
    kac_gas s = {.n = (size_t)o->n, .alpha = o->alpha};
    s.v = malloc(sizeof *s.v * 2 * s.n);
    double *x = malloc(sizeof *x * (size_t)o->samples);
    s.r = gsl_rng_alloc(gsl_rng_taus2);
    int rc = -1;
    if (s.v && x && s.r) {
        gsl_rng_set(s.r, o->seed);
        run(&s, o, x);
        block_stats(x, o->samples, o->block, &r->a2, &r->err);
        r->a2 += 1.0 / o->n; /* the sample a2's -1/N at fixed energy and momentum */
        r->accept = (double)s.accepted / (double)s.drawn;
        r->collisions = s.accepted;
        rc = 0;
    }
    gsl_rng_free(s.r);
    free(x);
    free(s.v);
    return rc;
}
