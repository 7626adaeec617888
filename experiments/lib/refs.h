/* Reference laws the experiments compare against: the hard-disk fluid's
 * contact value and equation of state, homogeneous cooling with its first
 * Sonine correction, and the linear spring-dashpot collision. */
#ifndef GR_EXP_REFS_H
#define GR_EXP_REFS_H

/* Pair correlation at contact chi(eta) of Luding's hard-disk equation of
 * state (Phys. Rev. E 63, 042201, 2001), with Z = 1 + 2 eta chi: Henderson's
 * form with a correction fitted to simulations of the dense fluid (it and
 * Henderson's differ by 0.03 % at eta = 0.3, 0.4 % at 0.5). */
double exp_chi_luding(double eta);
double exp_z_luding(double eta);
/* Henderson's Z = (1 + eta^2/8) / (1 - eta)^2 (Mol. Phys. 30, 971, 1975). */
double exp_z_henderson(double eta);

/* Second Sonine coefficient a2 of the homogeneous cooling state of inelastic
 * disks (d = 2), van Noije and Ernst, Granular Matter 1, 57 (1998):
 * a2 = 16 (1 - a)(1 - 2 a^2) / (57 - 25 a + 30 a^2 (1 - a)). */
double exp_sonine_a2(double alpha);
/* Haff's time tau of T(t) = T0 / (1 + t / tau)^2 for disks of diameter 1 and
 * mass 1 at number density n, packing eta and temperature T0 (T = m<v^2>/2
 * per disk): tau = 2 / zeta0, zeta0 = (1 - alpha^2) n chi sqrt(pi T0)
 * times (1 + 3 a2 / 16) when sonine != 0. */
double exp_haff_tau(double alpha, double n, double eta, double T0, int sonine);

/* Head-on collision of the linear law F = kn xi + gamma_n dxi/dt with
 * reduced mass meff (thesis eqs. 2.2-2.3, without the clip of attraction):
 * the restitution, and the contact time in *tc. NaN when overdamped. */
double exp_lsd_restitution(double kn, double gamma_n, double meff, double *tc);

/* The 2-D Beverloo law of the thesis's fig. 4.1 (eq. 4.1 with rho sqrt(g),
 * docs/experiments.md): grains per unit time through an orifice of width
 * D, W = C rho sqrt(g) (D - k d)^(3/2), rho = 4 phi / (pi d^2) the number
 * density at packing fraction phi; 0 when D <= k d. */
double exp_beverloo_2d(double C, double k, double phi, double g, double D, double d);

#endif
