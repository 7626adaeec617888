/* Measurements as the slides teach them: state observables integrated
 * exactly between the events that change them (K, and with gravity the
 * parabolic terms of K and U), event observables summed at the events
 * (momentum given to the walls, collisional virial, dissipation), and
 * hydrodynamic fields on the event cells, each particle's moments
 * integrated into its cell from its last field update to the next event
 * that touches it (a collision, a wall, a crossing). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "edmd_int.h"

double edmd_kinetic(const gr_edmd *s, int32_t i, double t)
{
    const edmd_p *p = &s->p[i];
    double vy = edmd_vy_at(p, t, edmd_g_of(p, s->g));
    return 0.5 * s->m[i] * (p->vx * p->vx + vy * vy) + 0.5 * s->inertia[i] * s->w[i] * s->w[i];
}

static void resync(gr_edmd *s)
{
    double K = 0, Kr = 0, U = 0, Sm = 0, Smvy = 0, t = s->t, g = s->g;
    for (size_t i = 0; i < s->n; i++) {
        const edmd_p *p = &s->p[i];
        if (s->gone[i])
            continue;
        K += edmd_kinetic(s, (int32_t)i, t);
        Kr += 0.5 * s->inertia[i] * s->w[i] * s->w[i];
        U += s->m[i] * g * edmd_y_at(p, t, edmd_g_of(p, g));
        if (p->asleep) /* at rest: its K and U stay what they are */
            continue;
        Sm += s->m[i];
        Smvy += s->m[i] * edmd_vy_at(p, t, g);
    }
    s->m_t = t;
    s->m_K = K;
    s->m_Krot = Kr;
    s->m_U = U;
    s->m_Sm = Sm;
    s->m_Smvy = Smvy;
}

void edmd_measure_init(gr_edmd *s)
{
    resync(s);
    s->obs_t0 = s->t;
    s->obs_mom = 0.0;
    gr_edmd_reset_averages(s);
}

void edmd_measure_advance(gr_edmd *s, double t)
{
    double d = t - s->m_t;
    if (!(d > 0.0))
        return;
    double g = s->g;
    if (g == 0.0) {
        s->a_K += s->m_K * d;
        s->a_U += s->m_U * d;
    } else {
        double d2 = d * d, d3 = d2 * d, Sm = s->m_Sm, Smvy = s->m_Smvy;
        s->a_K += s->m_K * d - 0.5 * g * Smvy * d2 + g * g * Sm * d3 / 6.0;
        s->a_U += s->m_U * d + 0.5 * g * Smvy * d2 - g * g * Sm * d3 / 6.0;
        s->m_K += -g * Smvy * d + 0.5 * g * g * Sm * d2;
        s->m_U += g * Smvy * d - 0.5 * g * g * Sm * d2;
        s->m_Smvy -= g * Sm * d;
    }
    s->a_Krot += s->m_Krot * d;
    s->m_t = t;
}

/* Grain i's moments since tacc[i], into its event cell (fields) and into
 * the stress window's cell of the flight's midpoint: between two flushes
 * a grain stays in one event cell, which may straddle two stress cells. */
void edmd_field_flush(gr_edmd *s, int32_t i, double t)
{
    double d = t - s->tacc[i];
    const edmd_p *p = &s->p[i];
    if (!(d > 0.0) || s->gone[i])
        return;
    double g = edmd_g_of(p, s->g), m = s->m[i], vx = p->vx;
    double vy = edmd_vy_at(p, s->tacc[i], g);
    double d2 = d * d, d3 = d2 * d;
    double Ivy = vy * d - 0.5 * g * d2;
    double Ivy2 = vy * vy * d - g * vy * d2 + g * g * d3 / 3.0;
    if (s->stress) {
        double tm = s->tacc[i] + 0.5 * d;
        const double mom[6] = {m * d, m * vx * d, m * Ivy, m * vx * vx * d, m * vx * Ivy, m * Ivy2};
        gr_stress_acc_kinetic(s->stress, edmd_x_at(p, tm), edmd_y_at(p, tm, g), mom);
    }
    s->tacc[i] = t;
    if (!s->cacc || p->cell < 0)
        return;
    double Ivy3 = vy * vy * vy * d - 1.5 * vy * vy * g * d2 + vy * g * g * d3 - 0.25 * g * g * g * d3 * d;
    edmd_cellacc *c = &s->cacc[p->cell];
    c->n += d;
    c->m += m * d;
    c->mvx += m * vx * d;
    c->mvy += m * Ivy;
    c->mvxx += m * vx * vx * d;
    c->mvxy += m * vx * Ivy;
    c->mvyy += m * Ivy2;
    c->mv2vx += m * vx * (vx * vx * d + Ivy2);
    c->mv2vy += m * (vx * vx * Ivy + Ivy3);
}

void edmd_field_flush_all(gr_edmd *s, double t)
{
    for (size_t i = 0; i < s->n; i++)
        edmd_field_flush(s, (int32_t)i, t);
}

/* Collisional transfers of a pair collision: stress (r_i - r_j) (x) J_i,
 * energy flux (dE_i - dE_j)/2 (r_i - r_j) and the energy lost, half to
 * each grain's event cell (fields); the stress also to the stress window,
 * shared in proportion to the radii as the contact stress is
 * (common/stress.h), which for equal grains is half each. */
void edmd_measure_pair(gr_edmd *s, int32_t i, int32_t j, double Jx, double Jy,
                       double dE_i, double dE_j, double rx, double ry)
{
    const edmd_p *a = &s->p[i], *b = &s->p[j];
    if (s->stress)
        gr_stress_acc_collision(s->stress, a->x, a->y, b->x, b->y, a->r / (a->r + b->r), rx, ry, Jx, Jy);
    if (!s->cacc)
        return;
    double h = 0.5 * (dE_i - dE_j);
    double loss = -(dE_i + dE_j);
    int cells[2] = {a->cell, b->cell};
    for (int k = 0; k < 2; k++) {
        edmd_cellacc *c = &s->cacc[cells[k]];
        c->cxx += 0.5 * rx * Jx;
        c->cxy += 0.25 * (rx * Jy + ry * Jx);
        c->cyy += 0.5 * ry * Jy;
        c->cqx += 0.5 * h * rx;
        c->cqy += 0.5 * h * ry;
        c->diss += 0.5 * loss;
    }
}

void gr_edmd_reset_averages(gr_edmd *s)
{
    resync(s);
    s->a_t0 = s->t;
    s->a_K = s->a_Krot = s->a_U = 0.0;
    for (int k = 0; k < 4; k++)
        s->a_mom[k] = 0.0;
    s->a_virial = s->a_inj = s->a_diss = 0.0;
    s->a_pair0 = s->cnt.pair;
    s->a_wall0 = s->cnt.wall;
    if (s->cacc) {
        if (s->stress) /* the stress window goes on: give it the moments so far */
            edmd_field_flush_all(s, s->t);
        memset(s->cacc, 0, (size_t)s->nx * (size_t)s->ny * sizeof *s->cacc);
        for (size_t i = 0; i < s->n; i++)
            s->tacc[i] = s->t;
    }
}

void gr_edmd_get_averages(gr_edmd *s, gr_edmd_averages *a)
{
    edmd_measure_advance(s, s->t);
    memset(a, 0, sizeof *a);
    a->t0 = s->a_t0;
    a->t1 = s->t;
    double T = a->t1 - a->t0;
    a->pair = s->cnt.pair - s->a_pair0;
    a->wall = s->cnt.wall - s->a_wall0;
    a->e_injected = s->a_inj;
    a->e_dissipated = s->a_diss;
    if (!(T > 0.0)) {
        a->ekin = s->m_K;
        a->ekin_rot = s->m_Krot;
        a->epot = s->m_U;
        for (int k = 0; k < 4; k++)
            a->pressure[k] = NAN;
        a->pressure_walls = a->virial_pressure = NAN;
        return;
    }
    a->ekin = s->a_K / T;
    a->ekin_rot = s->a_Krot / T;
    a->epot = s->a_U / T;
    double Ly = s->H - s->ybot, mom = 0.0, len = 0.0;
    for (int k = 0; k < 4; k++) {
        double L = k == GR_LEFT || k == GR_RIGHT ? Ly : s->W;
        a->pressure[k] = s->hard[k] ? s->a_mom[k] / (L * T) : NAN;
        if (s->hard[k]) {
            mom += s->a_mom[k];
            len += L;
        }
    }
    a->pressure_walls = len > 0 ? mom / (len * T) : NAN;
    /* 2D virial: P A = <K_trans> + sum_coll sigma_ij J_n / (2 T) */
    a->virial_pressure = ((a->ekin - a->ekin_rot) + 0.5 * s->a_virial / T) / (s->W * Ly);
    a->collision_rate = (double)a->pair / T;
    a->dissipation_rate = s->a_diss / T;
    a->injection_rate = s->a_inj / T;
}

void gr_edmd_fields_free(gr_edmd_fields *f)
{
    if (!f)
        return;
    free(f->density);
    memset(f, 0, sizeof *f);
}

int gr_edmd_get_fields(gr_edmd *s, gr_edmd_fields *f, gr_err *err)
{
    memset(f, 0, sizeof *f);
    if (!s->cacc)
        return gr_fail(err, GR_EINPUT, "edmd: fields were not accumulated (set [edmd] fields = yes)");
    size_t nc = (size_t)s->nx * (size_t)s->ny;
    double *buf = calloc(12 * nc, sizeof *buf);
    if (!buf)
        return gr_fail(err, GR_ERUN, "edmd: out of memory for the fields");
    edmd_field_flush_all(s, s->t);
    f->nx = s->nx;
    f->ny = s->ny;
    f->x0 = 0.0;
    f->y0 = s->ybot;
    f->cx = s->cw;
    f->cy = s->ch;
    double *arr[12];
    for (int k = 0; k < 12; k++)
        arr[k] = buf + (size_t)k * nc;
    f->density = arr[0];
    f->ux = arr[1];
    f->uy = arr[2];
    f->temperature = arr[3];
    f->qx = arr[4];
    f->qy = arr[5];
    f->pxx = arr[6];
    f->pxy = arr[7];
    f->pyy = arr[8];
    f->dissipation = arr[9];
    double T = s->t - s->a_t0, A = s->cw * s->ch;
    for (size_t c = 0; c < nc; c++) {
        const edmd_cellacc *a = &s->cacc[c];
        if (!(T > 0.0))
            break;
        double At = A * T;
        f->density[c] = a->n / At;
        f->pxx[c] = a->cxx / At;
        f->pxy[c] = a->cxy / At;
        f->pyy[c] = a->cyy / At;
        f->qx[c] = a->cqx / At;
        f->qy[c] = a->cqy / At;
        f->dissipation[c] = a->diss / At;
        if (!(a->m > 0.0)) {
            f->ux[c] = f->uy[c] = f->temperature[c] = NAN;
            continue;
        }
        double ux = a->mvx / a->m, uy = a->mvy / a->m;
        f->ux[c] = ux;
        f->uy[c] = uy;
        double kxx = a->mvxx - a->m * ux * ux, kxy = a->mvxy - a->m * ux * uy, kyy = a->mvyy - a->m * uy * uy;
        f->temperature[c] = 0.5 * (kxx + kyy) / a->n;
        f->pxx[c] += kxx / At;
        f->pxy[c] += kxy / At;
        f->pyy[c] += kyy / At;
        double tr = a->mvxx + a->mvyy, u2 = ux * ux + uy * uy;
        double qx = a->mv2vx - tr * ux - 2.0 * (a->mvxx * ux + a->mvxy * uy) + 2.0 * a->m * u2 * ux;
        double qy = a->mv2vy - tr * uy - 2.0 * (a->mvxy * ux + a->mvyy * uy) + 2.0 * a->m * u2 * uy;
        f->qx[c] += 0.5 * qx / At;
        f->qy[c] += 0.5 * qy / At;
    }
    return GR_OK;
}

int gr_edmd_stress(gr_edmd *s, int nx, int ny, double global[4], double *cells, gr_err *err)
{
    gr_stress_acc *a = s->stress;
    if (a && a->nx == nx && a->ny == ny) {
        edmd_field_flush_all(s, s->t);
        gr_stress_acc_read(a, s->t, global, cells);
        return GR_OK;
    }
    /* A new window: the moments so far go to the fields (if any), and
     * every grain's integral starts now. */
    gr_stress_acc_free(a);
    s->stress = NULL;
    if (s->cacc)
        edmd_field_flush_all(s, s->t);
    for (size_t i = 0; i < s->n; i++)
        s->tacc[i] = s->t;
    double H = s->H; /* the scene's domain [0, W] x [0, H]; a floor that dips counts in the bottom row */
    if (!(s->stress = gr_stress_acc_create(s->W, H, s->periodic_x, s->periodic_y, nx, ny, s->t, err)))
        return err->code;
    gr_stress_acc_read(s->stress, s->t, global, cells);
    return GR_OK;
}

void gr_edmd_energy_budget(const gr_edmd *s, double *injected, double *dissipated)
{
    *injected = s->e_inj;
    *dissipated = s->e_diss;
}
