/* An oracle for 2D frictional contact: Siconos's fc2d_nsgs on the problem
 * the contact dynamics backend solves, and a residual that judges any
 * solver's answer (Siconos's, or methods/cd/'s) by the same rule.
 *
 * The problem (Siconos's FrictionContactProblem with dimension 2): nc
 * contacts, impulses r = (r_n0, r_t0, r_n1, r_t1, ...), local velocities
 *     u = W r + q,
 * and at each contact i the Signorini-Coulomb law with coefficient mu_i:
 *     r_n >= 0, u_n >= 0, r_n u_n = 0, |r_t| <= mu r_n, and when r_n > 0:
 *     u_t > 0 => r_t = -mu r_n,  u_t < 0 => r_t = +mu r_n  (friction opposes
 *     sliding), |r_t| < mu r_n => u_t = 0 (stick).
 * q is the velocity the contacts would have with no impulse; a contact
 * closes when q_n < 0.
 *
 * Storage: W is dense, 2nc x 2nc, ROW-MAJOR (W[i * 2nc + j] is row i,
 * column j), the C order.  Siconos's NumericsMatrix dense storage is
 * column-major: gr_fc2d_solve transposes into its own copy, so a
 * non-symmetric W is passed correctly (physical Delassus operators are
 * symmetric anyway).  fc2d_nsgs_dense's local solve uses W_nt of each
 * diagonal 2x2 block for W_tn too, so gr_fc2d_check rejects diagonal
 * blocks that are not symmetric.
 *
 * The residual (gr_fc2d_residual), solver-independent: for contact i, with
 * rho_i = 1 / W_nn,i (so that rho u is an impulse: r and rho u have the
 * same unit whatever the units of W), the natural map with De Saxce's
 * correction
 *     x_i = r_i - rho_i (u_i + mu_i |u_t,i| e_n),
 *     e_i = r_i - proj_{K_i}(x_i),   K_i = {(a, b): |b| <= mu_i a},
 * which is zero exactly when (r_i, u_i) obey the law (for any rho_i > 0;
 * Siconos's fc2d_compute_error is the same map with rho = 1).  Reported:
 *     cone  = ||e||_2 / s,
 *     eq    = ||rho (u - W r - q)||_2 / s   (u given by the candidate;
 *             0 when u is NULL and taken as W r + q),
 *     total = max(cone, eq),
 * with the impulse scale s = max(||r||_2, ||rho q||_2) (rho applied per
 * contact to both components): -rho q is the impulse that would cancel the
 * free velocity, so s does not vanish for a wrong r = 0.  If s = 0 (q = 0
 * and r = 0) the residuals are absolute.
 *
 * Written against Siconos numerics 4.4.0 (Debian libsiconos-numerics-dev
 * 4.4.0+dfsg-2): solver_options_create/solver_options_delete (the latter
 * does not free the struct itself in 4.4), fc2d_nsgs_dense, and
 * fc2d_compute_error (natural map, rho = 1, divided by
 * max(||r||, ||u||, ||q||)).  fc2d_nsgs_dense stops when
 * ||W r + q - v|| / ||q|| <= tol, v being each contact's velocity as of its
 * last local solve: that is Siconos's own error, reported as nsgs_error.
 *
 * gr_fc2d_check and gr_fc2d_residual do not need Siconos (fc2d_residual.c);
 * gr_fc2d_solve is built only where Siconos is found (fc2d.c). */
#ifndef GR_ORACLE_FC2D_H
#define GR_ORACLE_FC2D_H

#include "err.h"

typedef struct {
    int iterations;       /* Gauss-Seidel sweeps done */
    int info;             /* fc2d_nsgs_dense: 0 converged, 1 iteration cap, 2 singular block */
    double nsgs_error;    /* its stopping measure on the last sweep (above) */
    double siconos_error; /* fc2d_compute_error on the returned (r, u) */
    double seconds;       /* wall time of the fc2d_nsgs_dense call alone */
} gr_fc2d_stats;

typedef struct {
    double cone, eq, total, scale; /* as defined above */
    int worst;                     /* contact with the largest |e_i|, -1 if none */
} gr_fc2d_res;

/* GR_EINPUT unless nc >= 0, every entry finite, mu_i >= 0, W_nn,i > 0,
 * W_tt,i > 0 and each diagonal block symmetric (relative 1e-12). */
int gr_fc2d_check(int nc, const double *W, const double *q, const double *mu, gr_err *err);

/* The residual above of the candidate (r, u); u may be NULL (u = W r + q). */
int gr_fc2d_residual(int nc, const double *W, const double *q, const double *mu,
                     const double *r, const double *u, gr_fc2d_res *res, gr_err *err);

/* Solve with fc2d_nsgs_dense from r = 0 (tolerance tol on nsgs_error, at
 * most max_iter sweeps).  r and u (2nc each) are filled even when it does
 * not converge; u is recomputed as W r + q.  Returns GR_ERUN if Siconos
 * reports info != 0, GR_EINPUT on bad input.  q = 0 returns r = u = 0 with
 * no sweep (Siconos would divide by ||q||). */
int gr_fc2d_solve(int nc, const double *W, const double *q, const double *mu, double tol,
                  int max_iter, double *r, double *u, gr_fc2d_stats *st, gr_err *err);

#endif
