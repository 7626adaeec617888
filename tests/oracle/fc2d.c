/* gr_fc2d_solve: Siconos's fc2d_nsgs_dense behind grano's conventions
 * (status and gr_err, no printing).  Built only where Siconos is found. */
#include "fc2d.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "FrictionContactProblem.h"
#include "Friction_cst.h"
#include "NumericsMatrix.h"
#include "SolverOptions.h"
#include "fc2d_Solvers.h"
#include "fc2d_compute_error.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* A problem owning column-major copies of W, q and mu, all malloc'd because
 * frictionContactProblem_free frees them. */
static FrictionContactProblem *make_problem(int nc, const double *W, const double *q,
                                            const double *mu)
{
    size_t n = 2 * (size_t)nc;
    double *wc = malloc(n * n * sizeof *wc), *qc = malloc(n * sizeof *qc);
    double *mc = malloc((size_t)nc * sizeof *mc);
    NumericsMatrix *M = wc && qc && mc ? NM_create_from_data(NM_DENSE, (int)n, (int)n, wc) : NULL;
    FrictionContactProblem *p = M ? frictionContactProblem_new_with_data(2, nc, M, qc, mc) : NULL;
    if (!p) {
        if (M) {
            M->matrix0 = NULL;
            NM_free(M);
        }
        free(wc);
        free(qc);
        free(mc);
        return NULL;
    }
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < n; j++)
            wc[j * n + i] = W[i * n + j];
    memcpy(qc, q, n * sizeof *qc);
    memcpy(mc, mu, (size_t)nc * sizeof *mc);
    return p;
}

static double norm2(size_t n, const double *x)
{
    double s = 0;
    for (size_t i = 0; i < n; i++)
        s += x[i] * x[i];
    return sqrt(s);
}

int gr_fc2d_solve(int nc, const double *W, const double *q, const double *mu, double tol,
                  int max_iter, double *r, double *u, gr_fc2d_stats *st, gr_err *err)
{
    *st = (gr_fc2d_stats){0};
    int rc = gr_fc2d_check(nc, W, q, mu, err);
    if (rc)
        return rc;
    if (!(tol > 0) || max_iter < 1)
        return gr_fail(err, GR_EINPUT, "fc2d: tolerance %g, iteration cap %d", tol, max_iter);
    size_t n = 2 * (size_t)nc;
    double qn = norm2(n, q);
    if (qn == 0) {
        memset(r, 0, n * sizeof *r);
        memset(u, 0, n * sizeof *u);
        return GR_OK;
    }
    FrictionContactProblem *p = make_problem(nc, W, q, mu);
    SolverOptions *opt = p ? solver_options_create(SICONOS_FRICTION_2D_NSGS) : NULL;
    if (!opt) {
        if (p)
            frictionContactProblem_free(p);
        return gr_fail(err, GR_ERUN, "fc2d: out of memory for %d contacts", nc);
    }
    opt->iparam[SICONOS_IPARAM_MAX_ITER] = max_iter;
    opt->dparam[SICONOS_DPARAM_TOL] = tol;
    int info = 0;
    double t0 = now();
    fc2d_nsgs_dense(p, r, u, &info, opt);
    st->seconds = now() - t0;
    st->info = info;
    st->iterations = opt->iparam[SICONOS_IPARAM_ITER_DONE];
    st->nsgs_error = opt->dparam[SICONOS_DPARAM_RESIDU];
    /* Also overwrites u with W r + q: the solver's u is each contact's
     * velocity as of its own last local solve, stale by up to tol. */
    fc2d_compute_error(p, r, u, tol, qn, &st->siconos_error);
    solver_options_delete(opt);
    free(opt); /* 4.4's solver_options_delete leaves the struct */
    frictionContactProblem_free(p);
    if (info)
        return gr_fail(err, GR_ERUN,
                       "fc2d_nsgs_dense: info %d after %d sweeps (error %.3g, tolerance %.3g)",
                       info, st->iterations, st->nsgs_error, tol);
    return GR_OK;
}
