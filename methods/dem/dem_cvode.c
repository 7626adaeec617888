/* Reference integrator: CVODE (Adams, fixed-point iteration) with tight
 * tolerances on the same forces, for small systems. Contact laws without
 * history only: the right-hand side must be a function of the state. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include "dem.h"

typedef struct {
    SUNContext ctx;
    void *mem;
    N_Vector y;
    SUNNonlinearSolver nls;
    int per;              /* values per grain: x y vx vy [w] */
    int mode;
    gr_err rhs_err;
    int rhs_failed;
} dem_cv;

/* Copy the ODE state into parity q (positions wrapped). */
static void unpack(gr_dem *d, dem_cv *c, const double *y, int q)
{
    for (size_t i = 0; i < d->n; i++) {
        const double *s = y + (size_t)c->per * i;
        double x = s[0], yy = s[1];
        if (d->Lx > 0) x -= d->Lx * floor(x / d->Lx);
        if (d->Ly > 0) yy -= d->Ly * floor(yy / d->Ly);
        d->f[F_X][q][i] = x;
        d->f[F_Y][q][i] = yy;
        d->f[F_VX][q][i] = s[2];
        d->f[F_VY][q][i] = s[3];
        if (d->rot)
            d->f[F_W][q][i] = s[4];
    }
}

static int rhs(sunrealtype t, N_Vector yv, N_Vector ydot, void *user)
{
    gr_dem *d = user;
    dem_cv *c = d->cv;
    const double *y = N_VGetArrayPointer(yv);
    double *f = N_VGetArrayPointer(ydot);
    int q = 1 - d->cur;
    unpack(d, c, y, q);
    gr_err e = {0};
    d->par.max_overlap = INFINITY; /* CVODE probes trial states; judged after */
    if (gr_dem_eval_at(d, q, t, 0, 0.0, c->mode, d->seg_force, &e)) {
        c->rhs_err = e;
        c->rhs_failed = 1;
        return -1;
    }
    for (size_t i = 0; i < d->n; i++) {
        const double *s = y + (size_t)c->per * i;
        double *o = f + (size_t)c->per * i;
        o[0] = s[2];
        o[1] = s[3];
        o[2] = d->f[F_FX][q][i] * d->im[i];
        o[3] = d->f[F_FY][q][i] * d->im[i] - d->gf[i];
        if (d->rot)
            o[4] = d->f[F_TQ][q][i] * d->iI[i];
    }
    return 0;
}

void gr_dem_cv_free(gr_dem *d)
{
    dem_cv *c = d->cv;
    if (!c)
        return;
    if (c->mem)
        CVodeFree(&c->mem);
    if (c->nls)
        SUNNonlinSolFree(c->nls);
    if (c->y)
        N_VDestroy(c->y);
    if (c->ctx)
        SUNContext_Free(&c->ctx);
    free(c);
    d->cv = NULL;
}

int gr_dem_cv_create(gr_dem *d, gr_err *err)
{
    const gr_scene *sc = &d->sc;
    for (int s = 0; s < 4; s++)
        if (sc->side[s] == GR_BC_OPEN)
            return gr_fail(err, GR_EINPUT, "[dem] integrator = cvode (reference for small closed systems) does not support open sides");
    if (sc->silo.present && (isfinite(sc->silo.open_time) || sc->silo.reinsert))
        return gr_fail(err, GR_EINPUT, "[dem] integrator = cvode does not support an opening orifice or reinsertion");
    dem_cv *c = calloc(1, sizeof *c);
    if (!c)
        return gr_fail(err, GR_ERUN, "out of memory");
    d->cv = c;
    c->per = d->rot ? 5 : 4;
    c->mode = d->par.neighbour == GR_DEM_NB_BRUTE ? GR_DEM_NB_BRUTE : GR_DEM_NB_CELLS;
    if (SUNContext_Create(NULL, &c->ctx))
        return gr_fail(err, GR_ERUN, "SUNDIALS context creation failed");
    sunindextype len = (sunindextype)(d->n * (size_t)c->per);
    c->y = N_VNew_Serial(len, c->ctx);
    if (!c->y)
        return gr_fail(err, GR_ERUN, "SUNDIALS vector of %ld failed", (long)len);
    double *y = N_VGetArrayPointer(c->y);
    int p = d->cur;
    for (size_t i = 0; i < d->n; i++) {
        double *s = y + (size_t)c->per * i;
        s[0] = d->f[F_X][p][i];
        s[1] = d->f[F_Y][p][i];
        s[2] = d->f[F_VX][p][i];
        s[3] = d->f[F_VY][p][i];
        if (d->rot)
            s[4] = d->f[F_W][p][i];
    }
    c->mem = CVodeCreate(CV_ADAMS, c->ctx);
    if (!c->mem || CVodeInit(c->mem, rhs, d->t, c->y) || CVodeSetUserData(c->mem, d) ||
        CVodeSStolerances(c->mem, d->par.cvode_rtol, d->par.cvode_atol) ||
        CVodeSetMaxNumSteps(c->mem, 100000000L))
        return gr_fail(err, GR_ERUN, "CVODE setup failed");
    c->nls = SUNNonlinSol_FixedPoint(c->y, 0, c->ctx);
    if (!c->nls || CVodeSetNonlinearSolver(c->mem, c->nls))
        return gr_fail(err, GR_ERUN, "CVODE fixed-point solver setup failed");
    /* forces of the initial state, for observables */
    unpack(d, c, y, p);
    return gr_dem_eval_at(d, p, d->t, 0, 0.0, c->mode, d->seg_force, err);
}

int gr_dem_cv_advance(gr_dem *d, double t_end, uint64_t max_steps, gr_err *err)
{
    dem_cv *c = d->cv;
    if (!(t_end > d->t))
        return GR_OK;
    double bound = d->par.max_overlap;
    if (CVodeSetStopTime(c->mem, t_end))
        return gr_fail(err, GR_ERUN, "CVODE: bad stop time %g", t_end);
    uint64_t done = 0;
    double t = d->t;
    int rc = GR_OK;
    while (t < t_end && (max_steps == 0 || done < max_steps)) {
        int flag = CVode(c->mem, t_end, c->y, &t, max_steps ? CV_ONE_STEP : CV_NORMAL);
        if (flag < 0) {
            rc = c->rhs_failed ? gr_fail(err, GR_ERUN, "%s", c->rhs_err.msg)
                               : gr_fail(err, GR_ERUN, "CVODE failed at t = %.9g (flag %d)", t, flag);
            break;
        }
        done++;
    }
    d->par.max_overlap = bound;
    if (rc)
        return rc;
    long nst = 0;
    CVodeGetNumSteps(c->mem, &nst);
    d->step = (uint64_t)nst;
    d->t = t;
    int p = d->cur;
    unpack(d, c, N_VGetArrayPointer(c->y), p);
    if (gr_dem_eval_at(d, p, t, 0, 0.0, c->mode, d->seg_force, err))
        return err->code;
    return GR_OK;
}
