/* gr_fc2d_solve: Siconos's fc2d_nsgs_dense behind grano's conventions
 * (status and gr_err, no printing).  Built only where Siconos is found. */
#include "fc2d.h"

#ifdef GR_FC2D_DLOPEN
#include <dlfcn.h>
#endif
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

/* The Siconos calls. The oracle's test links Siconos; grano (the bench,
 * GR_FC2D_DLOPEN) loads it on its first solve instead. Linked into grano,
 * Siconos's OpenBLAS started its thread pool in every run of every
 * command, and its worker spun for the first 0.2 s on the cores grano's
 * own threads needed: 52-64 ms of each thread's time lost waiting to run,
 * and the two-thread rate of a short bench cut by a fifth
 * (docs/performance.md). */
typedef struct {
    __typeof__(&NM_create_from_data) nm_create;
    __typeof__(&NM_free) nm_free;
    __typeof__(&frictionContactProblem_new_with_data) problem_new;
    __typeof__(&frictionContactProblem_free) problem_free;
    __typeof__(&solver_options_create) options_create;
    __typeof__(&solver_options_delete) options_delete;
    __typeof__(&fc2d_nsgs_dense) nsgs_dense;
    __typeof__(&fc2d_compute_error) compute_error;
} sic_ops;

#ifdef GR_FC2D_DLOPEN
/* dlsym's object pointer into a function pointer (POSIX guarantees the
 * representation). */
static int sym(void *h, const char *name, void *fn, gr_err *err)
{
    void *p = dlsym(h, name);
    if (!p)
        return gr_fail(err, GR_ERUN, "fc2d: Siconos numerics has no %s", name);
    memcpy(fn, &p, sizeof p);
    return GR_OK;
}

/* Never unloaded (RTLD_NODELETE): OpenBLAS's threads outlive the call. */
static int sic_load(sic_ops *o, gr_err *err)
{
    static const char *const names[] = {"libsiconos_numerics.so", "libsiconos_numerics.so.7"};
    void *h = NULL;
    for (size_t k = 0; !h && k < sizeof names / sizeof names[0]; k++)
        h = dlopen(names[k], RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
    if (!h)
        return gr_fail(err, GR_ERUN, "fc2d: cannot load Siconos numerics (%s)", dlerror());
    int rc = sym(h, "NM_create_from_data", &o->nm_create, err);
    rc = rc ? rc : sym(h, "NM_free", &o->nm_free, err);
    rc = rc ? rc : sym(h, "frictionContactProblem_new_with_data", &o->problem_new, err);
    rc = rc ? rc : sym(h, "frictionContactProblem_free", &o->problem_free, err);
    rc = rc ? rc : sym(h, "solver_options_create", &o->options_create, err);
    rc = rc ? rc : sym(h, "solver_options_delete", &o->options_delete, err);
    rc = rc ? rc : sym(h, "fc2d_nsgs_dense", &o->nsgs_dense, err);
    rc = rc ? rc : sym(h, "fc2d_compute_error", &o->compute_error, err);
    dlclose(h);
    return rc;
}
#else
static int sic_load(sic_ops *o, gr_err *err)
{
    (void)err;
    *o = (sic_ops){NM_create_from_data, NM_free, frictionContactProblem_new_with_data, frictionContactProblem_free,
                   solver_options_create, solver_options_delete, fc2d_nsgs_dense, fc2d_compute_error};
    return GR_OK;
}
#endif

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* A problem owning column-major copies of W, q and mu, all malloc'd because
 * frictionContactProblem_free frees them. */
static FrictionContactProblem *make_problem(const sic_ops *o, int nc, const double *W, const double *q,
                                            const double *mu)
{
    size_t n = 2 * (size_t)nc;
    double *wc = malloc(n * n * sizeof *wc), *qc = malloc(n * sizeof *qc);
    double *mc = malloc((size_t)nc * sizeof *mc);
    NumericsMatrix *M = wc && qc && mc ? o->nm_create(NM_DENSE, (int)n, (int)n, wc) : NULL;
    FrictionContactProblem *p = M ? o->problem_new(2, nc, M, qc, mc) : NULL;
    if (!p) {
        if (M) {
            M->matrix0 = NULL;
            o->nm_free(M);
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
    sic_ops o = {0};
    if ((rc = sic_load(&o, err)))
        return rc;
    FrictionContactProblem *p = make_problem(&o, nc, W, q, mu);
    SolverOptions *opt = p ? o.options_create(SICONOS_FRICTION_2D_NSGS) : NULL;
    if (!opt) {
        if (p)
            o.problem_free(p);
        return gr_fail(err, GR_ERUN, "fc2d: out of memory for %d contacts", nc);
    }
    opt->iparam[SICONOS_IPARAM_MAX_ITER] = max_iter;
    opt->dparam[SICONOS_DPARAM_TOL] = tol;
    int info = 0;
    double t0 = now();
    o.nsgs_dense(p, r, u, &info, opt);
    st->seconds = now() - t0;
    st->info = info;
    st->iterations = opt->iparam[SICONOS_IPARAM_ITER_DONE];
    st->nsgs_error = opt->dparam[SICONOS_DPARAM_RESIDU];
    /* Also overwrites u with W r + q: the solver's u is each contact's
     * velocity as of its own last local solve, stale by up to tol. */
    o.compute_error(p, r, u, tol, qn, &st->siconos_error);
    o.options_delete(opt);
    free(opt); /* 4.4's solver_options_delete leaves the struct */
    o.problem_free(p);
    if (info)
        return gr_fail(err, GR_ERUN,
                       "fc2d_nsgs_dense: info %d after %d sweeps (error %.3g, tolerance %.3g)",
                       info, st->iterations, st->nsgs_error, tol);
    return GR_OK;
}
