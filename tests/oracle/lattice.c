/* The lattice gas's mean-field answers (lattice.h), from the rules alone. */
#include <math.h>

#include "lattice.h"

static double q_gravity(double d)
{
    double miss = 1 - d * (1 - d);
    return 1 - miss * miss * miss;
}

/* The profile from the floor's occupation d0 upward (each row from the
 * one below by Newton on the implicit midpoint relation); its mean, or
 * NaN when it empties before the top. */
static double profile(double d0, double g, int rows, double *d)
{
    double sum = d[0] = d0;
    for (int i = 1; i < rows; i++) {
        double lo = d[i - 1], x = lo - g * q_gravity(lo) / 3;
        for (int it = 0; it < 50; it++) {
            double h = 1e-7, f = 3 * (lo - x) - g * (q_gravity(lo) + q_gravity(x)) / 2;
            double dx = f / (-3 - g * (q_gravity(x + h) - q_gravity(x - h)) / (4 * h));
            x -= dx;
            if (fabs(dx) < 1e-15)
                break;
        }
        if (!(x > 0))
            return NAN;
        sum += d[i] = x;
    }
    return sum / rows;
}

int gr_lattice_column(double dbar, double g, int rows, double *d)
{
    if (!(dbar > 0 && dbar < 1) || !(g >= 0 && g <= 1) || rows < 1)
        return -1;
    /* the mean grows with the floor's occupation: bisect on it */
    double lo = dbar, hi = 1;
    for (int it = 0; it < 200 && hi - lo > 1e-15; it++) {
        double mid = 0.5 * (lo + hi), m = profile(mid, g, rows, d);
        if (isnan(m) || m < dbar)
            lo = mid;
        else
            hi = mid;
    }
    return isnan(profile(0.5 * (lo + hi), g, rows, d)) ? -1 : 0;
}

/* Momentum of the movers of s in integer units (x: sign of sin 60k; y:
 * 2 cos 60k), exact. */
static void momentum(unsigned s, int *qx, int *qy)
{
    static const int mx[6] = {0, 1, 1, 0, -1, -1}, my[6] = {2, 1, -1, -2, -1, 1};
    *qx = *qy = 0;
    for (int k = 0; k < 6; k++)
        if (s >> k & 1u)
            *qx += mx[k], *qy += my[k];
}

/* Whether the movers s (no rest particle) can dissipate: one or two
 * states of one mover fewer carry their momentum. */
static int dissipative(unsigned s)
{
    int qx, qy, n = 0, m = __builtin_popcount(s);
    momentum(s, &qx, &qy);
    for (unsigned t = 0; t < 64; t++) {
        int tx, ty;
        momentum(t, &tx, &ty);
        n += __builtin_popcount(t) == m - 1 && tx == qx && ty == qy;
    }
    return m >= 2 && (n == 1 || n == 2);
}

int gr_lattice_cooling(double f0, double r0, double p, long steps, double *f, double *r)
{
    if (!(f0 >= 0 && f0 <= 1) || !(r0 >= 0 && r0 <= 1) || !(p >= 0 && p <= 1) || steps < 0)
        return -1;
    int weight[7] = {0}; /* dissipative mover states by their number of movers */
    for (unsigned s = 0; s < 64; s++)
        weight[__builtin_popcount(s)] += dissipative(s);
    *f = f0, *r = r0;
    for (long n = 0; n < steps; n++) {
        double x = 0;
        for (int m = 2; m <= 6; m++)
            x += weight[m] * pow(*f, m) * pow(1 - *f, 6 - m);
        double made = p * (1 - *r) * x; /* rest particles made per node */
        *f -= made / 6, *r += made;
    }
    return 0;
}
