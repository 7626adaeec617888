#include "refs.h"

#include <math.h>

double exp_chi_luding(double eta)
{
    double u = 1 - eta;
    return (1 - 7 * eta / 16) / (u * u) - eta * eta * eta / (128 * u * u * u * u);
}

double exp_z_luding(double eta)
{
    return 1 + 2 * eta * exp_chi_luding(eta);
}

double exp_z_henderson(double eta)
{
    return (1 + eta * eta / 8) / ((1 - eta) * (1 - eta));
}

double exp_sonine_a2(double a)
{
    return 16 * (1 - a) * (1 - 2 * a * a) / (57 - 25 * a + 30 * a * a * (1 - a));
}

double exp_haff_tau(double alpha, double n, double eta, double T0, int sonine)
{
    double zeta0 = (1 - alpha * alpha) * n * exp_chi_luding(eta) * sqrt(M_PI * T0);
    if (sonine)
        zeta0 *= 1 + 3 * exp_sonine_a2(alpha) / 16;
    return 2 / zeta0;
}

double exp_lsd_restitution(double kn, double gamma_n, double meff, double *tc)
{
    double w0 = kn / meff, b = gamma_n / (2 * meff);
    if (b * b >= w0) {
        *tc = NAN;
        return NAN;
    }
    double w = sqrt(w0 - b * b);
    *tc = M_PI / w;
    return exp(-b * *tc);
}

double exp_beverloo_2d(double C, double k, double phi, double g, double D, double d)
{
    return D > k * d ? C * (4 * phi / (M_PI * d * d)) * sqrt(g) * pow(D - k * d, 1.5) : 0;
}
