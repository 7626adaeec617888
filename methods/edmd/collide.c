/* Collision rules. Pair: normal restitution (eqs. 1.1-1.3 of the thesis)
 * and, for rough disks, the rule of the slides: try a sticking collision
 * with tangential restitution beta (contact tangential velocity -> -beta
 * times itself), and fall back to a sliding one with |Jt| = mu Jn when the
 * sticking impulse breaks the Coulomb bound. Walls: the same with infinite
 * mass, moving with the floor velocity (v'_n = (1+e) V_p - e v_n, which is
 * the slides' 2 V_p - v_n for e = 1). */
#include <math.h>

#include "edmd_int.h"
#include "init.h"

/* The guard against inelastic collapse: a guarded collision is elastic and
 * smooth (no tangential impulse), so that neither the normal nor the
 * tangential rule can drain energy in an accumulation of collisions (a
 * rough grain wedged in a corner collapses through friction alone). */
/* The collision clocks are read only under the tc rule: at large N each
 * is a random line, which an elastic run would wait for in vain. */
static int guarded(gr_edmd *s, int dissipative, double gn, int32_t i, int32_t j, double t)
{
    if (!dissipative)
        return 0;
    int on = 0;
    switch (s->prm.collapse) {
    case GR_EDMD_COLLAPSE_TC:
        on = t - s->tlast[i] < s->prm.tc || (j >= 0 && t - s->tlast[j] < s->prm.tc);
        break;
    case GR_EDMD_COLLAPSE_THRESHOLD:
        on = -gn < s->prm.v_threshold;
        break;
    default:
        break;
    }
    s->cnt.elastic_guard += (uint64_t)on;
    return on;
}

/* Tangential impulse: sticking with restitution beta, capped by Coulomb. */
static double tangential_impulse(const gr_edmd *s, double gt, double inv_mt, double Jn)
{
    double Jt = -(1.0 + s->beta) * gt / inv_mt;
    double cap = s->mu * Jn;
    if (fabs(Jt) > cap)
        Jt = gt > 0.0 ? -cap : cap;
    return Jt;
}

void edmd_collide_pair(gr_edmd *s, int32_t i, int32_t j, double t)
{
    edmd_p *a = &s->p[i], *b = &s->p[j];
    double g = s->g;
    edmd_measure_advance(s, t);
    if (s->cacc) {
        edmd_field_flush(s, i, t);
        edmd_field_flush(s, j, t);
    }
    edmd_advance_p(a, t, g);
    edmd_advance_p(b, t, g);
    double dx = b->x - a->x, dy = b->y - a->y;
    if (s->periodic_x)
        dx = edmd_min_image(dx, s->W);
    if (s->periodic_y)
        dy = edmd_min_image(dy, s->H - s->ybot);
    double dist = sqrt(dx * dx + dy * dy);
    double nx = dx / dist, ny = dy / dist;
    double gn = (b->vx - a->vx) * nx + (b->vy - a->vy) * ny;
    /* equal masses: no random read of the mass array */
    double mi = s->m_one > 0.0 ? s->m_one : s->m[i], mj = s->m_one > 0.0 ? s->m_one : s->m[j];
    /* spins enter only for rough disks */
    double ri0 = s->rough ? 0.5 * s->inertia[i] * s->w[i] * s->w[i] : 0.0;
    double rj0 = s->rough ? 0.5 * s->inertia[j] * s->w[j] * s->w[j] : 0.0;
    double e0 = 0.5 * mi * (a->vx * a->vx + a->vy * a->vy) + ri0;
    double f0 = 0.5 * mj * (b->vx * b->vx + b->vy * b->vy) + rj0;
    double vy0i = a->vy, vy0j = b->vy;
    double Jn = 0.0, Jt = 0.0;
    if (gn < 0.0) {
        int guard = guarded(s, s->alpha < 1.0 || (s->rough && s->beta < 1.0), gn, i, j, t);
        double al = guard ? 1.0 : s->alpha;
        double mred = mi * mj / (mi + mj);
        Jn = -(1.0 + al) * mred * gn;
        double tx = -ny, ty = nx;
        if (s->rough && !guard) {
            double gt = (b->vx - a->vx) * tx + (b->vy - a->vy) * ty - (s->w[j] * b->r + s->w[i] * a->r);
            double inv_mt = 1.0 / mi + 1.0 / mj + a->r * a->r / s->inertia[i] + b->r * b->r / s->inertia[j];
            Jt = tangential_impulse(s, gt, inv_mt, Jn);
            s->w[i] -= a->r * Jt / s->inertia[i];
            s->w[j] -= b->r * Jt / s->inertia[j];
        }
        double Jx = Jn * nx + Jt * tx, Jy = Jn * ny + Jt * ty;
        a->vx -= Jx / mi;
        a->vy -= Jy / mi;
        b->vx += Jx / mj;
        b->vy += Jy / mj;
    }
    double ri1 = s->rough ? 0.5 * s->inertia[i] * s->w[i] * s->w[i] : 0.0;
    double rj1 = s->rough ? 0.5 * s->inertia[j] * s->w[j] * s->w[j] : 0.0;
    double e1 = 0.5 * mi * (a->vx * a->vx + a->vy * a->vy) + ri1;
    double f1 = 0.5 * mj * (b->vx * b->vx + b->vy * b->vy) + rj1;
    double dE = (e1 - e0) + (f1 - f0);
    s->m_K += dE;
    s->m_Krot += (ri1 + rj1) - (ri0 + rj0);
    s->m_Smvy += mi * (a->vy - vy0i) + mj * (b->vy - vy0j);
    s->e_diss -= dE;
    s->a_diss -= dE;
    s->a_virial += dist * Jn;
    if (s->cacc)
        edmd_measure_pair(s, i, j, -(Jn * nx + Jt * -ny), -(Jn * ny + Jt * nx), e1 - e0, f1 - f0, -dx, -dy);
    a->ncol++;
    b->ncol++;
    if (s->prm.collapse == GR_EDMD_COLLAPSE_TC)
        s->tlast[i] = s->tlast[j] = t;
    s->cnt.pair++;
    if (s->hook) {
        long ia = (long)s->id[i], ib = (long)s->id[j];
        s->hook(s->hook_user, 0, ia < ib ? ia : ib, ia < ib ? ib : ia, t);
    }
}

/* High-frequency sinusoidal floor: the phase met is weighted by the
 * relative approach speed (the flux of collisions), v_p = V0 cos(phase). */
static double hf_sine_velocity(gr_edmd *s, double vy)
{
    double V0 = s->fV0;
    if (V0 <= 0.0 || vy >= 0.0)
        return 0.0;
    for (int k = 0; k < 1000; k++) {
        double vp = V0 * cos(2.0 * M_PI * gr_rng_uniform(s->rng));
        if (gr_rng_uniform(s->rng) * (V0 - vy) < vp - vy)
            return vp;
    }
    return 0.0;
}

void edmd_collide_wall(gr_edmd *s, int32_t i, int wall, double t)
{
    edmd_p *a = &s->p[i];
    edmd_measure_advance(s, t);
    if (s->cacc)
        edmd_field_flush(s, i, t);
    edmd_advance_p(a, t, s->g);
    double nx = 0.0, ny = 0.0, Vn = 0.0;
    int side = wall;
    switch (wall) {
    case GR_LEFT: nx = 1.0; break;
    case GR_RIGHT: nx = -1.0; break;
    case GR_TOP: ny = -1.0; break;
    case GR_BOTTOM: ny = 1.0; break;
    default:
        if (wall >= W_SEG) {
            edmd_segment_normal(s, wall - W_SEG, a->x, a->y, &nx, &ny);
            side = -1;
            break;
        }
        ny = 1.0;
        side = GR_BOTTOM;
        switch (s->floor) {
        case GR_FLOOR_SINE: Vn = -s->fA * s->fomega * sin(s->fomega * t); break;
        case GR_FLOOR_SAWTOOTH: Vn = s->fA * s->fomega / M_PI; break;
        case GR_FLOOR_SINE_HF: Vn = hf_sine_velocity(s, a->vy); break;
        case GR_FLOOR_SAWTOOTH_HF: Vn = s->fV0; break;
        default: break;
        }
    }
    double m = s->m[i];
    double gn = a->vx * nx + a->vy * ny - Vn;
    double e0 = 0.5 * m * (a->vx * a->vx + a->vy * a->vy) + 0.5 * s->inertia[i] * s->w[i] * s->w[i];
    double kr0 = 0.5 * s->inertia[i] * s->w[i] * s->w[i];
    double vy0 = a->vy;
    double Jn = 0.0;
    if (gn < 0.0) {
        int guard = guarded(s, s->alpha_w < 1.0 || (s->rough && s->beta < 1.0), gn, i, -1, t);
        double e = guard ? 1.0 : s->alpha_w;
        Jn = -(1.0 + e) * m * gn;
        double Jt = 0.0, tx = -ny, ty = nx;
        if (s->rough && !guard) {
            double gt = a->vx * tx + a->vy * ty - s->w[i] * a->r;
            Jt = tangential_impulse(s, gt, 1.0 / m + a->r * a->r / s->inertia[i], Jn);
            s->w[i] -= a->r * Jt / s->inertia[i];
        }
        a->vx += (Jn * nx + Jt * tx) / m;
        a->vy += (Jn * ny + Jt * ty) / m;
    }
    double e1 = 0.5 * m * (a->vx * a->vx + a->vy * a->vy) + 0.5 * s->inertia[i] * s->w[i] * s->w[i];
    double dE = e1 - e0;
    s->m_K += dE;
    s->m_Krot += 0.5 * s->inertia[i] * s->w[i] * s->w[i] - kr0;
    s->m_Smvy += m * (a->vy - vy0);
    if (wall == W_FLOOR) {
        s->e_inj += dE;
        s->a_inj += dE;
        s->cnt.floor++;
    } else {
        s->e_diss -= dE;
        s->a_diss -= dE;
    }
    if (side >= 0) {
        s->a_mom[side] += Jn;
        s->obs_mom += Jn;
    }
    if (s->cacc) {
        /* the wall's share of the collisional stress and dissipation */
        edmd_cellacc *c = &s->cacc[a->cell];
        double r = a->r;
        c->cxx += r * nx * Jn * nx;
        c->cxy += r * nx * Jn * ny;
        c->cyy += r * ny * Jn * ny;
        if (wall != W_FLOOR)
            c->diss -= dE;
    }
    a->ncol++;
    s->tlast[i] = t;
    s->cnt.wall++;
    if (s->hook)
        s->hook(s->hook_user, 1, (long)s->id[i], -1 - wall, t);
}

/* A grain leaves through an open side or below the silo: it is reinserted
 * at rest at a free spot of the silo's reinsertion band, or gone. */
int edmd_exit(gr_edmd *s, int32_t i, double t, gr_err *err)
{
    edmd_p *a = &s->p[i];
    double m = s->m[i], g = s->g;
    edmd_measure_advance(s, t);
    if (s->cacc)
        edmd_field_flush(s, i, t);
    edmd_advance_p(a, t, g);
    double krot = 0.5 * s->inertia[i] * s->w[i] * s->w[i];
    s->m_K -= 0.5 * m * (a->vx * a->vx + a->vy * a->vy) + krot;
    s->m_Krot -= krot;
    s->m_U -= m * g * a->y;
    s->m_Smvy -= m * a->vy;
    s->m_Sm -= m;
    s->outflow++;
    a->ncol++;
    s->tlast[i] = t;
    edmd_cell_remove(s, i);
    a->cell = -1;
    s->gone[i] = 1;
    if (s->hook)
        s->hook(s->hook_user, 1, (long)s->id[i], -1 - W_EXIT, t);
    if (!s->reinsert)
        return GR_OK;
    if (!s->scratch && !(s->scratch = gr_particles_create(s->n, err)))
        return err->code;
    if (gr_edmd_snapshot(s, s->scratch, err))
        return err->code;
    double x, y;
    if (!gr_reinsert_spot(s->sc_silo, s->scratch, a->r, s->rng, 1000, &x, &y))
        return GR_OK; /* no room: the grain stays out */
    s->gone[i] = 0;
    a->x = x;
    a->y = y;
    a->vx = a->vy = 0.0;
    s->w[i] = 0.0;
    a->t = t;
    s->tacc[i] = t;
    edmd_cell_insert(s, i, edmd_cell_of(s, x, y));
    s->m_U += m * g * y;
    s->m_Sm += m;
    return GR_OK;
}
