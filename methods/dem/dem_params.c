/* The [dem] section: defaults, reading, and the time-step limit from the
 * contact time (eqs. 2.2 and 2.5). */
#include <math.h>
#include <stdio.h>

#include "dem.h"
#include "dem_params.h"

void gr_dem_params_default(gr_dem_params *p)
{
    p->dt = 0.0;
    p->dt_fraction = 0.1;
    p->v_impact = 0.0;
    p->integrator = GR_DEM_VERLET;
    p->neighbour = GR_DEM_NB_VERLET;
    p->skin = 0.2;
    p->threads = 1;
    p->max_overlap = 0.3;
    p->energy_jump = 1.0;
    p->sort_every = 100;
    p->cvode_rtol = 1e-10;
    p->cvode_atol = 1e-12;
}

static const char *const integrators[] = {"verlet", "gear", "euler", "cvode", NULL};
static const char *const neighbours[] = {"verlet", "cells", "brute", NULL};

double gr_dem_default_v_impact(const gr_scene *sc, const gr_particles *init)
{
    double v = 1.0;
    if (sc->gravity > 0)
        v = fmax(v, sqrt(2.0 * sc->gravity * sc->height));
    if (sc->init.velocity == GR_VEL_GAUSSIAN)
        v = fmax(v, 4.0 * sc->init.v0);
    else if (sc->init.velocity == GR_VEL_SPEED)
        v = fmax(v, sc->init.v0);
    for (size_t i = 0; init && i < init->n; i++)
        v = fmax(v, 2.0 * hypot(init->vx[i], init->vy[i]));
    return v;
}

/* Lightest mobile grain. */
static double min_mass(const gr_particles *init)
{
    double m1 = INFINITY;
    for (size_t i = 0; i < init->n; i++)
        if (!(init->flags[i] & (GR_PF_FIXED | GR_PF_GONE)))
            m1 = fmin(m1, init->mass[i]);
    return isfinite(m1) ? m1 : 1.0;
}

/* The damping in force: gamma_n, or derived from a restitution; a scene the
 * derivation refuses is refused by gr_dem_check_dt and gr_dem_create, so
 * here the given gamma_n stands in. */
static void damping(const gr_scene *sc, const gr_particles *init, double *gn, double *gw)
{
    gr_err e = {0};
    if (gr_dem_damping(sc, init, gn, gw, &e))
        *gn = *gw = sc->mat.gamma_n;
}

/* Lightest pair: two mobile grains, or one grain on a wall. */
static double min_meff(const gr_particles *init)
{
    double m1 = INFINITY;
    size_t nm = 0;
    for (size_t i = 0; i < init->n; i++) {
        if (init->flags[i] & (GR_PF_FIXED | GR_PF_GONE))
            continue;
        nm++;
        m1 = fmin(m1, init->mass[i]);
    }
    if (!nm)
        return 1.0;
    return nm >= 2 ? 0.5 * m1 : m1;
}

double gr_dem_contact_time(const gr_scene *sc, const gr_particles *init, double v)
{
    double me = min_meff(init), kn = sc->mat.kn, gn, gw;
    damping(sc, init, &gn, &gw);
    if (sc->mat.normal == GR_NORMAL_HERTZ)
        return 3.21 * pow(me / kn, 0.4) * pow(v, -0.2);
    double w2 = kn / me, z = gn / (2 * me);
    return w2 > z * z ? M_PI / sqrt(w2 - z * z) : M_PI / sqrt(w2);
}

int gr_dem_check_dt(const gr_scene *sc, const gr_particles *init, gr_dem_params *p, gr_err *err)
{
    if (p->v_impact <= 0)
        p->v_impact = gr_dem_default_v_impact(sc, init);
    double me = min_meff(init), gn, gw;
    if (gr_dem_damping(sc, init, &gn, &gw, err))
        return err->code;
    double tc = gr_dem_contact_time(sc, init, p->v_impact);
    const char *what = sc->mat.normal == GR_NORMAL_HERTZ ? "Hertz contact time (eq. 2.5)" : "contact time (eq. 2.2)";
    double limit = p->dt_fraction * tc;
    /* a dashpot alone is integrated explicitly, stable for dt < 2 m / gamma:
     * keep half of that (tangential: effective mass m_eff/3 for disks) */
    double tdn = fmin(gn > 0 ? me / gn : INFINITY, gw > 0 ? min_mass(init) / gw : INFINITY);
    int tang_damped = sc->mat.tangential == GR_TANG_VISCOUS || sc->mat.tangential == GR_TANG_REGULARISED ||
                      sc->mat.tangential == GR_TANG_SPRING;
    double tdt = tang_damped && sc->mat.gamma_t > 0 ? me / 3.0 / sc->mat.gamma_t : INFINITY;
    double lim_d = fmin(tdn, tdt);
    if (p->dt <= 0) {
        /* a fifth of the limit, rounded down to 1, 2, 2.5, 4, 5 or 8 x 10^k so
         * that usual output times are whole numbers of steps */
        double raw = 0.2 * fmin(limit, lim_d), dec = pow(10.0, floor(log10(raw)));
        static const double nice[] = {8, 5, 4, 2.5, 2, 1};
        p->dt = dec;
        for (int k = 0; k < 6; k++) {
            if (nice[k] * dec <= raw) {
                p->dt = nice[k] * dec;
                break;
            }
        }
    }
    char where[1200];
    gr_scene_where(sc, "dem", "dt", where, sizeof where);
    if (p->dt > limit)
        return gr_fail(err, GR_EINPUT,
                       "%s: dt = %g is above the stable limit %.6g = dt_fraction %g x the %s %.6g (m_eff %g, kn %g, impact speed %g); use dt <= %.6g",
                       where, p->dt, limit, p->dt_fraction, what, tc, me, sc->mat.kn, p->v_impact, limit);
    if (p->dt > lim_d)
        return gr_fail(err, GR_EINPUT,
                       "%s: dt = %g is above the damping limit %.6g = m_eff / gamma, half the explicit stability bound (gamma_n %g, at walls %g, gamma_t %g on m_eff/3, m_eff %g); use dt <= %.6g",
                       where, p->dt, lim_d, gn, gw, sc->mat.gamma_t, me, lim_d);
    double dense = gr_dem_dense_dt(sc, init, p->v_impact);
    if (p->integrator == GR_DEM_VERLET && p->dt > dense)
        return gr_fail(err, GR_EINPUT,
                       "%s: dt = %g is above %.6g, velocity Verlet's stability bound in a dense packing (a triangular lattice of these contacts, docs/reliability.md); a dt_fraction this large leaves a pile unstable: use dt <= %.6g",
                       where, p->dt, dense, dense);
    return GR_OK;
}

/* Velocity Verlet in a dense packing: six contacts per grain (a triangular
 * lattice, the most a monodisperse 2-D packing has) raise the fastest mode
 * to omega_max^2 = 3 omega_0^2 (omega_0 the pair's undamped frequency,
 * m_eff = m/2), damped with ratio zeta = gamma_n omega_max / (2 k) where
 * k = m_eff omega_0^2; stable for dt < (2 / omega_max)(sqrt(1 + zeta^2) -
 * zeta). It lies 2.5 to 3.4 times above the default limit 0.1 t_c, so only
 * a raised dt_fraction reaches it (docs/reliability.md). */
double gr_dem_dense_dt(const gr_scene *sc, const gr_particles *init, double v_impact)
{
    double me = min_meff(init), gn, gw;
    damping(sc, init, &gn, &gw);
    double w0 = sc->mat.normal == GR_NORMAL_HERTZ
                    ? M_PI / (3.21 * pow(me / sc->mat.kn, 0.4) * pow(v_impact > 0 ? v_impact : 1.0, -0.2))
                    : sqrt(sc->mat.kn / me);
    double wmax = sqrt(3.0) * w0, zeta = gn * wmax / (2.0 * me * w0 * w0);
    return 2.0 / wmax * (sqrt(1.0 + zeta * zeta) - zeta);
}

const gr_param gr_dem_param_table[] = {
    {"dt", GR_PARAM_REAL, NAN, 0, INFINITY, 1, NULL, "tau",
     "time step; absent: a fifth of the stable limit, rounded down to 1, 2, 2.5, 4, 5 or 8 x 10^k"},
    {"dt_fraction", GR_PARAM_REAL, 0.1, 0, INFINITY, 1, NULL, "1",
     "refuse dt above this fraction of the contact time t_c"},
    {"v_impact", GR_PARAM_REAL, NAN, 0, INFINITY, 1, NULL, "d tau-1",
     "impact speed for the Hertz t_c; absent: from gravity, height and initial speeds"},
    {"integrator", GR_PARAM_CHOICE, GR_DEM_VERLET, 0, 0, 0, integrators, "", "time integrator"},
    {"neighbour", GR_PARAM_CHOICE, GR_DEM_NB_VERLET, 0, 0, 0, neighbours, "", "neighbour search"},
    {"skin", GR_PARAM_REAL, 0.2, 0, INFINITY, 0, NULL, "d", "Verlet-list skin"},
    {"threads", GR_PARAM_INT, 1, 1, 256, 0, NULL, "1", "threads (results do not depend on it)"},
    {"max_overlap", GR_PARAM_REAL, 0.3, 0, INFINITY, 1, NULL, "1",
     "failure bound on overlap / smaller diameter"},
    {"energy_jump", GR_PARAM_REAL, 1.0, 0, INFINITY, 1, NULL, "1",
     "failure bound on the relative energy rise in one step"},
    {"sort_every", GR_PARAM_INT, 100, 1, 1e15, 0, NULL, "steps",
     "spatial sort period with neighbour = cells"},
    {"cvode_rtol", GR_PARAM_REAL, 1e-10, 0, INFINITY, 1, NULL, "1", "CVODE relative tolerance"},
    {"cvode_atol", GR_PARAM_REAL, 1e-12, 0, INFINITY, 1, NULL, "d", "CVODE absolute tolerance"},
    {NULL, 0, 0, 0, 0, 0, NULL, NULL, NULL},
};

void gr_dem_params_from(const gr_param_values *pv, gr_dem_params *p)
{
    gr_dem_params_default(p);
    double dt = gr_param_get(pv, "dt"), v = gr_param_get(pv, "v_impact");
    p->dt = isnan(dt) ? 0.0 : dt;
    p->v_impact = isnan(v) ? 0.0 : v;
    p->dt_fraction = gr_param_get(pv, "dt_fraction");
    p->integrator = (int)gr_param_get(pv, "integrator");
    p->neighbour = (int)gr_param_get(pv, "neighbour");
    p->skin = gr_param_get(pv, "skin");
    p->threads = (long)gr_param_get(pv, "threads");
    p->max_overlap = gr_param_get(pv, "max_overlap");
    p->energy_jump = gr_param_get(pv, "energy_jump");
    p->sort_every = (long)gr_param_get(pv, "sort_every");
    p->cvode_rtol = gr_param_get(pv, "cvode_rtol");
    p->cvode_atol = gr_param_get(pv, "cvode_atol");
}

int gr_dem_params_read(const gr_scene *sc, gr_dem_params *p, gr_err *err)
{
    gr_param_values pv;
    if (gr_params_read(sc, "dem", gr_dem_param_table, &pv, err))
        return err->code;
    gr_dem_params_from(&pv, p);
    return GR_OK;
}
