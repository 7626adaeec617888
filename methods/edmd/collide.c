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
/* The sleep model guards with both rules: tc for chatter, the threshold
 * for a grain sliding over a sleeper, whose contacts come further apart
 * than tc (the slack time, roots.c) and would otherwise sink it by
 * inelastic bounces into a Zeno sequence. The collision clocks are read
 * only under the tc and sleep rules: at large N each is a random line,
 * which an elastic run would wait for in vain. */
static int guarded(gr_edmd *s, int dissipative, double gn, int32_t i, int32_t j, double t)
{
    if (!dissipative)
        return 0;
    int on = 0;
    switch (s->prm.collapse) {
    case GR_EDMD_COLLAPSE_SLEEP:
        on = -gn < s->prm.v_threshold || t - s->tlast[i] < s->prm.tc || (j >= 0 && t - s->tlast[j] < s->prm.tc);
        break;
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

/* The kinetic energy of grain i, translational plus rotational; *rot gets
 * the rotational part, which only rough disks have (smooth disks never
 * read the spin arrays, so that a smooth run touches less memory). */
static inline double grain_energy(const gr_edmd *s, const edmd_p *a, int32_t i, double m, double *rot)
{
    *rot = s->rough ? 0.5 * s->inertia[i] * s->w[i] * s->w[i] : 0.0;
    return 0.5 * m * (a->vx * a->vx + a->vy * a->vy) + *rot;
}

/* The pair's impulse along the normal (nx, ny) and the tangent (-ny, nx),
 * applied to both grains; the tangent impulse only for rough disks, and
 * neither rule dissipates under the collapse guard. */
static inline void pair_impulse(gr_edmd *s, int32_t i, int32_t j, double mi, double mj, double nx, double ny,
                                double gn, double t, double *Jn_out, double *Jt_out)
{
    edmd_p *a = &s->p[i], *b = &s->p[j];
    int guard = guarded(s, s->alpha < 1.0 || (s->rough && s->beta < 1.0), gn, i, j, t);
    double al = guard ? 1.0 : s->alpha;
    double mred = mi * mj / (mi + mj);
    double Jn = -(1.0 + al) * mred * gn, Jt = 0.0;
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
    *Jn_out = Jn;
    *Jt_out = Jt;
}

/* Under the sleep model two grains woken at rest fall side by side at
 * the same speed: touching, with no normal speed between them, they have
 * their next contact at once, with no impulse, for ever, as a grain on a
 * static contact has (lift, below). Once a grain has woken, pairs leave
 * each other at v_threshold at least (before, no two grains can share a
 * velocity exactly, and a run whose grains never sleep, a vibrated bed,
 * stays the one of collapse = tc bit for bit); the energy this gives enters the budget as negative
 * dissipation. Returns the normal impulse added. */
static inline double pair_lift(edmd_p *a, edmd_p *b, double mi, double mj, double nx, double ny, double v)
{
    double gn = (b->vx - a->vx) * nx + (b->vy - a->vy) * ny;
    if (!(gn < v))
        return 0.0;
    double J = (v - gn) * mi * mj / (mi + mj);
    a->vx -= J * nx / mi;
    a->vy -= J * ny / mi;
    b->vx += J * nx / mj;
    b->vy += J * ny / mj;
    return J;
}

/* The counters every pair collision moves, and the observer's hook, which
 * sees the pair by identity (smaller id first) rather than by the slot
 * that a reordering may change. */
static inline void pair_count(gr_edmd *s, int32_t i, int32_t j, double t)
{
    s->p[i].ncol++;
    s->p[j].ncol++;
    if (s->prm.collapse == GR_EDMD_COLLAPSE_TC || s->prm.collapse == GR_EDMD_COLLAPSE_SLEEP)
        s->tlast[i] = s->tlast[j] = t;
    s->cnt.pair++;
    if (s->hook) {
        long ia = (long)s->id[i], ib = (long)s->id[j];
        s->hook(s->hook_user, 0, ia < ib ? ia : ib, ia < ib ? ib : ia, t);
    }
}

void edmd_collide_pair(gr_edmd *s, int32_t i, int32_t j, double t)
{
    edmd_p *a = &s->p[i], *b = &s->p[j];
    double g = s->g;
    edmd_measure_advance(s, t);
    if (edmd_measuring_cells(s)) {
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
    double ri0, rj0, ri1, rj1;
    double e0 = grain_energy(s, a, i, mi, &ri0), f0 = grain_energy(s, b, j, mj, &rj0);
    double vy0i = a->vy, vy0j = b->vy;
    double Jn = 0.0, Jt = 0.0;
    if (gn < 0.0)
        pair_impulse(s, i, j, mi, mj, nx, ny, gn, t, &Jn, &Jt);
    if (s->sleep_on && s->cnt.wakes)
        Jn += pair_lift(a, b, mi, mj, nx, ny, s->prm.v_threshold);
    /* the running sums take the change, not a recount, so that a step
     * costs O(1) whatever N */
    double e1 = grain_energy(s, a, i, mi, &ri1), f1 = grain_energy(s, b, j, mj, &rj1);
    double dE = (e1 - e0) + (f1 - f0);
    s->m_K += dE;
    s->m_Krot += (ri1 + rj1) - (ri0 + rj0);
    s->m_Smvy += mi * (a->vy - vy0i) + mj * (b->vy - vy0j);
    s->e_diss -= dE;
    s->a_diss -= dE;
    s->a_virial += dist * Jn;
    if (edmd_measuring_cells(s))
        edmd_measure_pair(s, i, j, -(Jn * nx + Jt * -ny), -(Jn * ny + Jt * nx), e1 - e0, f1 - f0, -dx, -dy);
    pair_count(s, i, j, t);
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

/* The inward normal (nx, ny) of the wall met and, for the driven floor,
 * its normal velocity at time t; returns the side whose momentum the wall
 * takes (a segment's goes to no side, -1). */
static inline int wall_normal(gr_edmd *s, const edmd_p *a, int wall, double t, double *nx, double *ny, double *Vn)
{
    *nx = 0.0;
    *ny = 0.0;
    *Vn = 0.0;
    switch (wall) {
    case GR_LEFT: *nx = 1.0; return wall;
    case GR_RIGHT: *nx = -1.0; return wall;
    case GR_TOP: *ny = -1.0; return wall;
    case GR_BOTTOM: *ny = 1.0; return wall;
    default: break;
    }
    if (wall >= W_SEG) {
        edmd_segment_normal(s, wall - W_SEG, a->x, a->y, nx, ny);
        return -1;
    }
    *ny = 1.0;
    switch (s->floor) {
    case GR_FLOOR_SINE: *Vn = -s->fA * s->fomega * sin(s->fomega * t); break;
    case GR_FLOOR_SAWTOOTH: *Vn = s->fA * s->fomega / M_PI; break;
    case GR_FLOOR_SINE_HF: *Vn = hf_sine_velocity(s, a->vy); break;
    case GR_FLOOR_SAWTOOTH_HF: *Vn = s->fV0; break;
    default: break;
    }
    return GR_BOTTOM;
}

/* The wall's impulse on grain i, the wall having infinite mass; returns the
 * normal part, *Jt_out the tangential one (only rough disks off the guard
 * have one). */
static inline double wall_impulse(gr_edmd *s, int32_t i, double m, double nx, double ny, double gn, double t,
                                  double *Jt_out)
{
    edmd_p *a = &s->p[i];
    int guard = guarded(s, s->alpha_w < 1.0 || (s->rough && s->beta < 1.0), gn, i, -1, t);
    double e = guard ? 1.0 : s->alpha_w;
    double Jn = -(1.0 + e) * m * gn;
    double Jt = 0.0, tx = -ny, ty = nx;
    if (s->rough && !guard) {
        double gt = a->vx * tx + a->vy * ty - s->w[i] * a->r;
        Jt = tangential_impulse(s, gt, 1.0 / m + a->r * a->r / s->inertia[i], Jn);
        s->w[i] -= a->r * Jt / s->inertia[i];
    }
    a->vx += (Jn * nx + Jt * tx) / m;
    a->vy += (Jn * ny + Jt * ty) / m;
    *Jt_out = Jt;
    return Jn;
}

/* Where the energy dE went: the driven floor injects it, every other wall
 * dissipates it; the side's momentum feeds the pressure on the walls, and
 * the collisional stress r n (x) J (branch from the contact point to the
 * centre) the fields and the stress window, in the grain's cell. */
static inline void wall_tally(gr_edmd *s, int32_t i, int wall, int side, double nx, double ny, double Jn,
                              double Jt, double dE)
{
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
    double r = s->p[i].r, lx = r * nx, ly = r * ny, Jx = Jn * nx - Jt * ny, Jy = Jn * ny + Jt * nx;
    if (s->stress)
        gr_stress_acc_collision(s->stress, s->p[i].x, s->p[i].y, 0, 0, 1.0, lx, ly, Jx, Jy);
    if (s->cacc) {
        edmd_cellacc *c = &s->cacc[s->p[i].cell];
        c->cxx += lx * Jx;
        c->cxy += 0.5 * (lx * Jy + ly * Jx);
        c->cyy += ly * Jy;
        if (wall != W_FLOOR)
            c->diss -= dE;
    }
}

/* The sleep rule (collapse = sleep; Bannerman et al., Phys. Rev. E 84,
 * 011301, 2011): a grain that leaves a static contact (the fixed floor, a
 * segment that never opens, a sleeping grain) with gravity pressing it
 * into that contact (normal n_y > 0) comes to rest there when it is slower
 * than v_sleep, or, whatever its speed, when it is jammed: it collided
 * less than tc ago (the TC guard's regime, a grain squeezed between static
 * contacts, whose elastic bounces would pass its momentum to and fro
 * without time advancing). Its velocity and spin are zeroed, the energy
 * they held is counted as dissipated, and it no longer falls nor has
 * events. Elastic bounces of the guard wear down no speed; without this a
 * bed at rest keeps bouncing at the guard's scale and its events per unit
 * time grow without bound. `since` is the time since its previous
 * collision. */
static void maybe_sleep(gr_edmd *s, int32_t i, double ny, double since)
{
    edmd_p *a = &s->p[i];
    if (!s->sleep_on || !(ny > 0.0))
        return;
    if ((!edmd_slow(s, i) && !(since < s->prm.tc)) || !edmd_held(s, i))
        return;
    double m = s->m[i], rot, e = grain_energy(s, a, i, m, &rot);
    s->m_K -= e;
    s->m_Krot -= rot;
    s->m_Smvy -= m * a->vy;
    s->m_Sm -= m;
    s->e_diss += e;
    s->a_diss += e;
    if (s->cacc)
        s->cacc[a->cell].diss += e;
    a->vx = a->vy = 0.0;
    if (s->rough)
        s->w[i] = 0.0;
    a->asleep = 1;
    a->ncol++;
    s->cnt.sleeps++;
}

/* A grain left touching a static contact without normal speed (a woken
 * grain on the floor pushed sideways, a grain grazing a sleeper, where the
 * contact search and the rule may round the sign of the normal speed
 * apart) has its next contact at once, with no impulse, for ever: time
 * stops. Under the sleep model it leaves such a contact at v_threshold at
 * least, the scale of the guard's elastic bounces; the energy this gives
 * (m v_threshold^2 / 2 at most) enters the budget as negative dissipation. */
static void lift(gr_edmd *s, edmd_p *a, double nx, double ny)
{
    if (!s->sleep_on)
        return;
    double vn = a->vx * nx + a->vy * ny;
    if (vn < s->prm.v_threshold) {
        a->vx += (s->prm.v_threshold - vn) * nx;
        a->vy += (s->prm.v_threshold - vn) * ny;
    }
}

/* Static contacts: the fixed floor and segments that never open. */
static int static_wall(const gr_edmd *s, int wall)
{
    return wall == GR_BOTTOM || (wall >= W_SEG && !(s->seg[wall - W_SEG].open_time < EDMD_INF));
}

void edmd_collide_wall(gr_edmd *s, int32_t i, int wall, double t)
{
    edmd_p *a = &s->p[i];
    edmd_measure_advance(s, t);
    if (edmd_measuring_cells(s))
        edmd_field_flush(s, i, t);
    edmd_advance_p(a, t, s->g);
    double nx, ny, Vn;
    int side = wall_normal(s, a, wall, t, &nx, &ny, &Vn);
    double m = s->m[i];
    double gn = a->vx * nx + a->vy * ny - Vn;
    double e0 = 0.5 * m * (a->vx * a->vx + a->vy * a->vy) + 0.5 * s->inertia[i] * s->w[i] * s->w[i];
    double kr0 = 0.5 * s->inertia[i] * s->w[i] * s->w[i];
    double vy0 = a->vy, since = t - s->tlast[i];
    double Jn = 0.0, Jt = 0.0;
    if (gn < 0.0)
        Jn = wall_impulse(s, i, m, nx, ny, gn, t, &Jt);
    if (static_wall(s, wall))
        lift(s, a, nx, ny);
    double e1 = 0.5 * m * (a->vx * a->vx + a->vy * a->vy) + 0.5 * s->inertia[i] * s->w[i] * s->w[i];
    double dE = e1 - e0;
    s->m_K += dE;
    s->m_Krot += 0.5 * s->inertia[i] * s->w[i] * s->w[i] - kr0;
    s->m_Smvy += m * (a->vy - vy0);
    wall_tally(s, i, wall, side, nx, ny, Jn, Jt, dE);
    a->ncol++;
    s->tlast[i] = t;
    s->cnt.wall++;
    if (s->hook)
        s->hook(s->hook_user, 1, (long)s->id[i], -1 - wall, t);
    if (static_wall(s, wall))
        maybe_sleep(s, i, ny, since);
}

void edmd_wake(gr_edmd *s, int32_t j, double t)
{
    edmd_p *b = &s->p[j];
    b->t = t;
    b->asleep = 0;
    s->m_Sm += s->m[j];
    s->cnt.wakes++;
}

/* An impact faster than v_wake wakes the sleeper and the pair collides as
 * any other; a slower one leaves it asleep, fixed: grain i bounces off it
 * as off a wall of infinite mass (guard and rough rule included), and may
 * fall asleep in turn. A resting grain pressed into its supports passes a
 * blow from above on to them at once in the hard-disk limit, which is why
 * the bed may stand in for the floor up to v_wake (its sweep:
 * docs/methods/edmd.md, "Coming to rest"). The collision counts as a pair collision and enters the virial, fields
 * and stress as one. */
void edmd_collide_sleeper(gr_edmd *s, int32_t i, int32_t j, double t)
{
    edmd_p *a = &s->p[i], *b = &s->p[j];
    edmd_measure_advance(s, t);
    if (edmd_measuring_cells(s)) {
        edmd_field_flush(s, i, t);
        edmd_field_flush(s, j, t);
    }
    edmd_advance_p(a, t, s->g);
    double dx = a->x - b->x, dy = a->y - b->y; /* from the sleeper to the mover */
    double dist = sqrt(dx * dx + dy * dy), nx = dx / dist, ny = dy / dist;
    double gn = a->vx * nx + a->vy * ny;
    if (-gn > s->prm.v_wake) {
        edmd_wake(s, j, t);
        edmd_collide_pair(s, i, j, t);
        return;
    }
    double m = s->m[i], rot0, since = t - s->tlast[i];
    double e0 = grain_energy(s, a, i, m, &rot0), vy0 = a->vy;
    double Jn = 0.0, Jt = 0.0;
    if (gn < 0.0)
        Jn = wall_impulse(s, i, m, nx, ny, gn, t, &Jt);
    lift(s, a, nx, ny);
    double rot1, e1 = grain_energy(s, a, i, m, &rot1), dE = e1 - e0;
    s->m_K += dE;
    s->m_Krot += rot1 - rot0;
    s->m_Smvy += m * (a->vy - vy0);
    s->e_diss -= dE;
    s->a_diss -= dE;
    s->a_virial += dist * Jn;
    if (edmd_measuring_cells(s))
        edmd_measure_pair(s, i, j, Jn * nx - Jt * ny, Jn * ny + Jt * nx, dE, 0.0, dx, dy);
    a->ncol++;
    s->tlast[i] = t;
    s->cnt.pair++;
    if (s->hook) {
        long ia = (long)s->id[i], ib = (long)s->id[j];
        s->hook(s->hook_user, 0, ia < ib ? ia : ib, ia < ib ? ib : ia, t);
    }
    maybe_sleep(s, i, ny, since);
}

/* A grain leaves through an open side or below the silo: it is reinserted
 * at rest at a free spot of the silo's reinsertion band, or gone. */
int edmd_exit(gr_edmd *s, int32_t i, double t, gr_err *err)
{
    edmd_p *a = &s->p[i];
    double m = s->m[i], g = s->g;
    edmd_measure_advance(s, t);
    if (edmd_measuring_cells(s))
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
