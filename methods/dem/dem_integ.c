/* Velocity Verlet's per-grain passes, drift and kick (2.17-2.21; Gear's
 * and Euler's are in dem_gear.c), each written into the other buffer so
 * that a refused step leaves the last good state in place. They read and
 * write grains only: below the force evaluation (which fuses the kick)
 * and the step. */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "dem.h"
#include "geom.h"

/* Per-particle loops run over fixed blocks, threads taking whole blocks;
 * block results are combined in block order, so sums do not depend on the
 * number of threads. gr_dem_grow keeps d->blk at two results per block of
 * the capacity. */

int gr_dem_exit_box(const gr_dem *d, double box[4])
{
    const gr_scene *sc = &d->sc;
    box[0] = sc->side[GR_LEFT] == GR_BC_OPEN ? 0.0 : -INFINITY;
    box[1] = sc->side[GR_RIGHT] == GR_BC_OPEN ? sc->width : INFINITY;
    box[2] = sc->side[GR_BOTTOM] == GR_BC_OPEN ? 0.0 : -INFINITY;
    box[3] = sc->side[GR_TOP] == GR_BC_OPEN ? sc->height : INFINITY;
    if (sc->silo.present)
        box[2] = fmax(box[2], sc->silo.exit_below);
    return isfinite(box[0]) || isfinite(box[1]) || isfinite(box[2]) || isfinite(box[3]);
}

/* Four lanes of doubles (GCC's vector extension: one AVX2 register, two
 * SSE2 ones in the baseline clone) for the per-lane maxima and sums that
 * the vectoriser does not make of scalar code; each lane rounds as the
 * scalar operation would. */
typedef double v4d __attribute__((vector_size(32)));
typedef long long v4l __attribute__((vector_size(32)));

/* (macros: a function taking or returning a 32-byte vector changes the
 * ABI between the clones) */
#define V4_LOAD(v, p) memcpy(&(v), (p), sizeof(v))
/* r = a < b ? a : b, or > for max, per lane (b where a is NaN, as the
 * scalar select) */
#define V4_SEL(r, a, op, b)                                                   \
    do {                                                                       \
        v4l m_ = (a)op(b);                                                     \
        (r) = (v4d)((m_ & (v4l)(a)) | (~m_ & (v4l)(b)));                       \
    } while (0)

/* The Verlet kick and drift without periodic sides, the same operations
 * per grain as gr_dem_drift and the scalar kick, four grains at a time in
 * GCC's vector extension (one AVX2 register, two SSE2 ones in the
 * baseline clone; each lane rounds as the scalar operation, nothing is
 * fused). KICK: the second kick of velocity Verlet, v(t+dt) = u + (dt/2)
 * (a(t+dt) - a(t)) in buffer pc from the old forces of po, where u is the
 * predicted velocity (gravity cancels); its kinetic energy (m v^2 / 2 as
 * v^2 / (2 im): no mass array to stream) is returned, and in *v2max the
 * largest squared speed of the next drift's half kick. DRIFT: drift and
 * first kick from pc into pn, the two largest squared moves since the
 * list build in top2, the mobile grains put outside the exit box added to
 * *exits_out. Both (the kick of a strip and its drift done ahead): one
 * pass, the kicked velocities drifted from registers. Grain i0 + k adds
 * its energy to lane k mod 4 (one chain of additions over the grains made
 * the loop wait on it), the lanes summed at the end: the order is the
 * code's, the same for any thread count and either clone. */
typedef struct {
    double *vx, *vy, *w;                          /* pc, kicked in place */
    const double *fx, *fy, *tq, *fxo, *fyo, *tqo; /* pc, po */
    const double *x, *y, *im, *iI, *xr, *yr;
    double *xn, *yn, *vxn, *vyn, *wn, *fxn, *fyn, *tqn; /* pn */
} kd_arr;

typedef struct {
    v4d ek, vm, t1, t2; /* energy, largest speed, two largest moves per lane */
    v4l out;            /* minus the grains put outside the exit box */
} kd_acc;

#define V4_STORE(p, v) memcpy((p), &(v), sizeof(v))
#define V4_SPLAT(s) ((v4d){(s), (s), (s), (s)})

/* Grains i .. i + 3 of A into lanes 0 .. 3 of s. */
static inline __attribute__((always_inline)) void kd_four(const kd_arr *A, size_t i, const int KICK, const int DRIFT,
                                                          int rot, double h, double dt, double g,
                                                          const double box[4], kd_acc *s)
{
    const v4d zero = V4_SPLAT(0.0), hv = V4_SPLAT(h), dtv = V4_SPLAT(dt), half = V4_SPLAT(0.5);
    v4d im, fx, fy, ux, uy, e = zero;
    V4_LOAD(im, A->im + i);
    V4_LOAD(fx, A->fx + i);
    V4_LOAD(fy, A->fy + i);
    V4_LOAD(ux, A->vx + i);
    V4_LOAD(uy, A->vy + i);
    v4l mobile = im != zero;
    v4d mob = (v4d)(mobile & (v4l)V4_SPLAT(1.0)); /* as the bool in gr_dem_drift */
    if (KICK) {
        v4d fxo, fyo;
        V4_LOAD(fxo, A->fxo + i);
        V4_LOAD(fyo, A->fyo + i);
        ux = ux + hv * (fx - fxo) * im;
        uy = uy + hv * (fy - fyo) * im;
        V4_STORE(A->vx + i, ux);
        V4_STORE(A->vy + i, uy);
        v4d hx = ux + hv * fx * im, hy = uy + hv * (fy * im - V4_SPLAT(g) * mob);
        v4d v2 = hx * hx + hy * hy;
        V4_SEL(s->vm, v2, >, s->vm); /* not fmax: a libm call */
        v4d et = half * (ux * ux + uy * uy) / im; /* selected away when im = 0 */
        e = (v4d)(mobile & (v4l)et);
    }
    if (DRIFT) {
        v4d x, y, xr, yr;
        V4_LOAD(x, A->x + i);
        V4_LOAD(y, A->y + i);
        V4_LOAD(xr, A->xr + i);
        V4_LOAD(yr, A->yr + i);
        v4d ax = fx * im, ay = fy * im - V4_SPLAT(g) * mob;
        v4d hx = ux + hv * ax, hy = uy + hv * ay;
        v4d nx = x + dtv * hx, ny = y + dtv * hy;
        V4_STORE(A->fxn + i, zero);
        V4_STORE(A->fyn + i, zero);
        V4_STORE(A->xn + i, nx);
        V4_STORE(A->yn + i, ny);
        s->out += ((nx < V4_SPLAT(box[0])) | (nx > V4_SPLAT(box[1])) | (ny < V4_SPLAT(box[2])) |
                   (ny > V4_SPLAT(box[3]))) & mobile;
        v4d vxn = hx + hv * ax, vyn = hy + hv * ay;
        V4_STORE(A->vxn + i, vxn);
        V4_STORE(A->vyn + i, vyn);
        v4d dx = nx - xr, dy = ny - yr, s2 = dx * dx + dy * dy, lo;
        /* t2 = max(t2, min(t1, s2)), t1 = max(t1, s2) */
        V4_SEL(lo, s->t1, <, s2);
        V4_SEL(s->t2, lo, >, s->t2);
        V4_SEL(s->t1, s2, >, s->t1);
    }
    if (rot) {
        v4d ww, tq, iI;
        V4_LOAD(ww, A->w + i);
        V4_LOAD(tq, A->tq + i);
        V4_LOAD(iI, A->iI + i);
        if (KICK) {
            v4d tqo;
            V4_LOAD(tqo, A->tqo + i);
            ww = ww + hv * (tq - tqo) * iI;
            V4_STORE(A->w + i, ww);
            v4d er = half * ww * ww / iI;
            e += (v4d)((iI != zero) & (v4l)er);
        }
        if (DRIFT) {
            v4d wn = ww + dtv * tq * iI;
            V4_STORE(A->wn + i, wn);
            V4_STORE(A->tqn + i, zero);
        }
    }
    s->ek += e;
}

static inline __attribute__((always_inline)) double
kick_drift(gr_dem *d, const int KICK, const int DRIFT, int po, int pc, int pn, size_t i0, size_t i1,
           double *v2max, double top2[2], _Atomic long *exits_out)
{
    const double dt = d->par.dt, h = 0.5 * dt, g = d->g;
    const int rot = d->rot;
    kd_arr A = {d->f[F_VX][pc], d->f[F_VY][pc], d->f[F_W][pc],
                d->f[F_FX][pc], d->f[F_FY][pc], d->f[F_TQ][pc], d->f[F_FX][po], d->f[F_FY][po], d->f[F_TQ][po],
                d->f[F_X][pc], d->f[F_Y][pc], d->im, d->iI, d->xref, d->yref,
                d->f[F_X][pn], d->f[F_Y][pn], d->f[F_VX][pn], d->f[F_VY][pn], d->f[F_W][pn],
                d->f[F_FX][pn], d->f[F_FY][pn], d->f[F_TQ][pn]};
    double box[4] = {0, 0, 0, 0};
    if (DRIFT)
        gr_dem_exit_box(d, box);
    kd_acc s = {{0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}};
    size_t i = i0;
    for (; i + 4 <= i1; i += 4)
        kd_four(&A, i, KICK, DRIFT, rot, h, dt, g, box, &s);
    if (i < i1) {
        /* the last one to three grains: through copies padded with fixed
         * grains at rest (im = iI = 0), which add nothing to any lane */
        enum { NIN = 15, NOUT = 11 };
        double in[NIN][4] = {{0}}, o[NOUT][4] = {{0}};
        const double *src[NIN] = {A.vx, A.vy, A.w, A.fx, A.fy, A.tq, A.fxo, A.fyo, A.tqo,
                                  A.x, A.y, A.im, A.iI, A.xr, A.yr};
        size_t r = i1 - i;
        for (int f = 0; f < NIN; f++)
            for (size_t l = 0; src[f] && l < r; l++) /* (absent: a field the scene does not need) */
                in[f][l] = src[f][i + l];
        for (int f = 0; f < 3; f++)
            for (int l = 0; l < 4; l++)
                o[f][l] = in[f][l];
        kd_arr B = {o[0], o[1], o[2], in[3], in[4], in[5], in[6], in[7], in[8], in[9], in[10], in[11], in[12],
                    in[13], in[14], o[3], o[4], o[5], o[6], o[7], o[8], o[9], o[10]};
        kd_four(&B, 0, KICK, DRIFT, rot, h, dt, g, box, &s);
        double *dst[NOUT] = {A.vx, A.vy, A.w, A.xn, A.yn, A.vxn, A.vyn, A.wn, A.fxn, A.fyn, A.tqn};
        for (int f = 0; f < NOUT; f++) {
            int kicked = f < 3 && f != 2, drifted = f >= 3 && f != 7 && f != 10;
            if ((KICK && (kicked || (f == 2 && rot))) || (DRIFT && (drifted || ((f == 7 || f == 10) && rot))))
                for (size_t l = 0; l < r; l++)
                    dst[f][i + l] = o[f][l];
        }
    }
    if (DRIFT) {
        /* the two largest of the lanes' two largest: those of all grains */
        double m1 = 0, m2 = 0;
        for (int l = 0; l < 8; l++) {
            double sv = l < 4 ? s.t1[l] : s.t2[l - 4];
            if (sv > m2) {
                if (sv > m1) {
                    m2 = m1;
                    m1 = sv;
                } else {
                    m2 = sv;
                }
            }
        }
        top2[0] = m1;
        top2[1] = m2;
        long out = -(long)(s.out[0] + s.out[1] + s.out[2] + s.out[3]);
        if (out)
            atomic_fetch_add_explicit(exits_out, out, memory_order_relaxed);
    }
    if (!KICK)
        return 0.0;
    if (v2max) {
        double a = s.vm[0] > s.vm[1] ? s.vm[0] : s.vm[1], b = s.vm[2] > s.vm[3] ? s.vm[2] : s.vm[3];
        *v2max = a > b ? a : b;
    }
    return (s.ek[0] + s.ek[1]) + (s.ek[2] + s.ek[3]);
}

static DEM_CLONES DEM_NOTRAP DEM_NODIST void drift_flat(gr_dem *d, int p, int q, size_t i0, size_t i1,
                                                        double top2[2], _Atomic long *exits_out)
{
    kick_drift(d, 0, 1, p, p, q, i0, i1, NULL, top2, exits_out);
}

/* Drift and first kick of grains [i0, i1) from buffer p into q (2: the
 * next step's, done ahead); their two largest squared displacements since
 * the list build go to top2[0], top2[1] when track != 0; the count of
 * mobile grains it put outside the exit box is added to *exits. */
void gr_dem_drift(gr_dem *d, int p, int q, int track, size_t i0, size_t i1, double top2[2], _Atomic long *exits_out)
{
    if (track && !(d->Lx > 0) && !(d->Ly > 0)) {
        drift_flat(d, p, q, i0, i1, top2, exits_out);
        return;
    }
    double dt = d->par.dt, h = 0.5 * dt;
    const double *restrict x = d->f[F_X][p], *restrict y = d->f[F_Y][p];
    const double *restrict vx = d->f[F_VX][p], *restrict vy = d->f[F_VY][p];
    const double *restrict fx = d->f[F_FX][p], *restrict fy = d->f[F_FY][p];
    double *restrict xn = d->f[F_X][q], *restrict yn = d->f[F_Y][q];
    double *restrict vxn = d->f[F_VX][q], *restrict vyn = d->f[F_VY][q];
    const double *restrict im = d->im;
    const double *restrict xr = d->xref, *restrict yr = d->yref;
    double *restrict fxn = d->f[F_FX][q], *restrict fyn = d->f[F_FY][q], *restrict tqn = d->f[F_TQ][q];
    double g = d->g;
    const double *restrict w = d->f[F_W][p], *restrict tq = d->f[F_TQ][p];
    double *restrict wn = d->f[F_W][q];
    const double *restrict iI = d->iI;
    double Lx = d->Lx, Ly = d->Ly;
    int rot = d->rot;
    double m1 = 0, m2 = 0, box[4];
    int exits = gr_dem_exit_box(d, box);
    long out = 0;
    for (size_t i = i0; i < i1; i++) {
        /* fixed grains (im = 0) feel no gravity */
        double ax = fx[i] * im[i], ay = fy[i] * im[i] - g * (im[i] != 0);
        double hx = vx[i] + h * ax, hy = vy[i] + h * ay;
        double nx = gr_wrap(x[i] + dt * hx, Lx), ny = gr_wrap(y[i] + dt * hy, Ly);
        /* the new forces start from zero here, saving a pass */
        fxn[i] = 0.0;
        fyn[i] = 0.0;
        xn[i] = nx;
        yn[i] = ny;
        if (exits)
            out += (im[i] != 0) & ((nx < box[0]) | (nx > box[1]) | (ny < box[2]) | (ny > box[3]));
        /* the new buffer holds v(t+dt) predicted to second order,
         * v(t+dt/2) + (dt/2) a(t), which the damping sees (the half-step
         * velocity would make the dissipation first order); the second
         * kick corrects it with a(t+dt) - a(t) */
        vxn[i] = hx + h * ax;
        vyn[i] = hy + h * ay;
        if (rot) {
            wn[i] = w[i] + dt * tq[i] * iI[i];
            tqn[i] = 0.0;
        }
        if (track) {
            double dx = gr_min_image(nx - xr[i], Lx), dy = gr_min_image(ny - yr[i], Ly);
            double s2 = dx * dx + dy * dy;
            if (s2 > m2) {
                if (s2 > m1) {
                    m2 = m1;
                    m1 = s2;
                } else {
                    m2 = s2;
                }
            }
        }
    }
    top2[0] = m1;
    top2[1] = m2;
    if (out)
        atomic_fetch_add_explicit(exits_out, out, memory_order_relaxed);
}

void gr_dem_predict_block(gr_dem *d, int p, int q, int track, size_t b)
{
    size_t i0 = b * DEM_BLOCK, i1 = i0 + DEM_BLOCK < d->n ? i0 + DEM_BLOCK : d->n;
    gr_dem_drift(d, p, q, track, i0, i1, d->blk + 2 * b, &d->exits);
}

/* Sum of the two largest displacements from the per-block maxima that
 * gr_dem_predict_block left (the same whatever the thread count: a maximum). */
double gr_dem_moved_blocks(const gr_dem *d)
{
    return gr_dem_top2_sum(d->blk, 2 * ((d->n + DEM_BLOCK - 1) / DEM_BLOCK));
}

/* Returns the sum of the two largest displacements since the list build
 * when track != 0 (section 2.4.1), else 0. */
double gr_dem_predict_verlet(gr_dem *d, int p, int q, int track)
{
    atomic_store_explicit(&d->exits, 0, memory_order_relaxed);
    d->exits_known = 1;
    size_t nb = (d->n + DEM_BLOCK - 1) / DEM_BLOCK;
    int nth = gr_dem_threads(d);
    if (nth > 1 && nb > 1) {
#pragma omp parallel for schedule(static) num_threads(nth)
        for (size_t b = 0; b < nb; b++)
            gr_dem_predict_block(d, p, q, track, b);
    } else {
        for (size_t b = 0; b < nb; b++)
            gr_dem_predict_block(d, p, q, track, b);
    }
    return track ? gr_dem_moved_blocks(d) : 0.0;
}

DEM_CLONES DEM_NOTRAP DEM_NODIST double gr_dem_kick(gr_dem *d, int p, int q, size_t i0, size_t i1, double *v2max)
{
    return kick_drift(d, 1, 0, p, q, q, i0, i1, v2max, NULL, NULL);
}

DEM_CLONES DEM_NOTRAP DEM_NODIST double gr_dem_kick_drift(gr_dem *d, int p, int q, int r, size_t i0, size_t i1,
                                                          double *v2max, double top2[2], _Atomic long *exits)
{
    if (d->Lx > 0 || d->Ly > 0) {
        double ek = gr_dem_kick(d, p, q, i0, i1, v2max);
        gr_dem_drift(d, q, r, 1, i0, i1, top2, exits);
        return ek;
    }
    return kick_drift(d, 1, 1, p, q, r, i0, i1, v2max, top2, exits);
}

void gr_dem_kick_block(gr_dem *d, int p, int q, size_t b)
{
    size_t i0 = b * DEM_BLOCK, i1 = i0 + DEM_BLOCK < d->n ? i0 + DEM_BLOCK : d->n;
    d->blk[b] = gr_dem_kick(d, p, q, i0, i1, NULL);
}

/* Kinetic energy from the kick's per-block sums, in block order (the same
 * bits whatever the thread count). */
double gr_dem_kinetic_blocks(const gr_dem *d, size_t nb)
{
    double ek = 0;
    for (size_t b = 0; b < nb; b++)
        ek += d->blk[b];
    return ek;
}

/* Second kick; returns the kinetic energy of the new state. */
double gr_dem_correct_verlet(gr_dem *d, int p, int q)
{
    size_t nb = (d->n + DEM_BLOCK - 1) / DEM_BLOCK;
    int nth = gr_dem_threads(d);
    if (nth > 1 && nb > 1) {
#pragma omp parallel for schedule(static) num_threads(nth)
        for (size_t b = 0; b < nb; b++)
            gr_dem_kick_block(d, p, q, b);
    } else {
        for (size_t b = 0; b < nb; b++)
            gr_dem_kick_block(d, p, q, b);
    }
    return gr_dem_kinetic_blocks(d, nb);
}
