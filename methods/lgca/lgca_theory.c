/* The lattice gas's mean-field answers (lgca_theory.h). */
#include <math.h>

#include "lgca_int.h"
#include "lgca_theory.h"

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
            double df = -3 - g * (q_gravity(x + h) - q_gravity(x - h)) / (4 * h);
            double dx = f / df;
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

int lgca_theory_column(double dbar, double g, int rows, double *d)
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

/* The mean occupation of every channel after one collision of a node
 * whose channels are independent: movers at f, rest at r. */
static void collide_mean(const uint8_t *tab, double f, double r, double p, double *fo, double *ro)
{
    double mov = 0, rest = 0;
    for (unsigned s = 0; s < 128; s++) {
        int nm = __builtin_popcount(s & 63u), nr = (int)(s >> LGCA_REST & 1u);
        double w = pow(f, nm) * pow(1 - f, 6 - nm) * (nr ? r : 1 - r);
        if (w == 0)
            continue;
        for (unsigned x = 0; x < 4; x++) {
            double wx = w * 0.5 * (x >> 1 ? p : 1 - p);
            unsigned o = tab[s | (x & 1u) << 7 | (x >> 1) << 8];
            mov += wx * __builtin_popcount(o & 63u);
            rest += wx * (double)(o >> LGCA_REST & 1u);
        }
    }
    *fo = mov / 6, *ro = rest;
}

int lgca_theory_cooling(double f0, double r0, double p, long steps, double *f, double *r)
{
    if (!(f0 >= 0 && f0 <= 1) || !(r0 >= 0 && r0 <= 1) || !(p >= 0 && p <= 1) || steps < 0)
        return -1;
    uint8_t tab[LGCA_TABLE_SIZE];
    lgca_table_build(LGCA_RULES_GRANULAR, tab);
    *f = f0, *r = r0;
    /* the homogeneous state stays isotropic: a mover's channel is any one */
    for (long n = 0; n < steps; n++)
        collide_mean(tab, *f, *r, p, f, r);
    return 0;
}
