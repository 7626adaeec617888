/* grano silo-start: the start of the discharge (thesis chapter 3). The
 * silo is filled and settled once per realisation (silo_fill.h); each unit
 * of work is one discharge: branch that settled silo to the orifice, open,
 * and follow the grains until the surface has fallen two diameters through
 * the outflow; the report averages the units of each orifice. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "fields.h"
#include "parts.h"
#include "progress.h"
#include "rng.h"
#include "silo_cli.h"
#include "silo_start.h"
#include "sweep.h"

void ss_label(size_t unit, void *ctx, char *buf, size_t n)
{
    const ss_ctx *c = ctx;
    silo_unit_label(c->orifice, c->nreal, unit, buf, n);
}

void ss_key(size_t unit, void *ctx, char *buf, size_t n)
{
    const ss_ctx *c = ctx;
    size_t o = unit / (size_t)c->nreal, r = unit % (size_t)c->nreal;
    const silo_cfg *b = &c->base;
    int k = snprintf(buf, n,
                     "silo-start 5 branchmax=%g surface+outflow n=%ld W=%.17g H=%.17g base=%.17g hopper=%d D=%.17g seed=%llu method=%s dt=%.17g "
                     "ke=%.17g fs=%ld min=%ld max=%ld fall=%.17g win=%.17g cell=%.17g cap=%zu sub=%d/%d lags=",
                     SILO_BRANCH_MAX, b->n, b->width, b->height, b->base, b->hopper, c->orifice[o],
                     (unsigned long long)(c->seed + r), b->method->name, b->dt, b->ke_tol, c->fs, c->min_steps,
                     c->max_steps, c->fall_stop, c->window, c->cell, c->sample_cap, c->subtract, SS_SUB_N);
    for (size_t s = 0; s < c->nslots && k > 0 && (size_t)k < n; s++)
        k += snprintf(buf + k, n - (size_t)k, "%ld,", c->lag[s]);
    for (size_t s = 0; s < c->ntimes && k > 0 && (size_t)k < n; s++)
        k += snprintf(buf + k, n - (size_t)k, "t%ld,", c->times[s]);
    if (k > 0 && (size_t)k < n) {
        k += snprintf(buf + k, n - (size_t)k, " ");
        silo_fill_key(r, (void *)&c->fills, buf + k, n - (size_t)k); /* ends with the --param lines */
    }
}

/* ------------------------------------------------------------ one unit */

#define QMAX 18

typedef struct {
    size_t m;
    long f0;
    int live;
    int32_t *idx;
    double *x, *y;
} origin;

typedef struct {
    origin q[QMAX];
    double *sx, *sy;
    size_t ns, seen;
    double fall_sum, fall_n;
} slotbuf;

typedef struct {
    const ss_ctx *c;
    size_t wcap;
    slotbuf sl[SS_MAX_SLOTS];
    gr_msd *msd;
    gr_rng *rng;
    double *dx, *dy;
    int32_t *widx;
    double *wx, *wy;
    size_t wm;
    size_t *cell;      /* subtraction cell of each displacement */
    double win[2];     /* the window's lower left corner */
} ustate;

static void ustate_free(ustate *u)
{
    for (size_t k = 0; k < SS_MAX_SLOTS; k++) {
        for (int j = 0; j < QMAX; j++)
            free(u->sl[k].q[j].idx), free(u->sl[k].q[j].x), free(u->sl[k].q[j].y);
        free(u->sl[k].sx), free(u->sl[k].sy);
    }
    gr_msd_free(u->msd);
    gr_rng_free(u->rng);
    free(u->dx), free(u->dy), free(u->widx), free(u->wx), free(u->wy), free(u->cell);
}

static int ustate_init(ustate *u, const ss_ctx *c, uint64_t seed, gr_err *err)
{
    memset(u, 0, sizeof *u);
    u->c = c;
    u->wcap = (size_t)((c->window + 2) * (c->window + 2) * 1.3) + 16;
    u->msd = gr_msd_create(c->nslots, err);
    u->rng = gr_rng_create(seed, GR_STREAM_SILO_START, err);
    u->dx = malloc(u->wcap * sizeof *u->dx), u->dy = malloc(u->wcap * sizeof *u->dy);
    u->widx = malloc(u->wcap * sizeof *u->widx);
    u->cell = malloc(u->wcap * sizeof *u->cell);
    u->wx = malloc(u->wcap * sizeof *u->wx), u->wy = malloc(u->wcap * sizeof *u->wy);
    int bad = !u->msd || !u->rng || !u->cell || !u->dx || !u->dy || !u->widx || !u->wx || !u->wy;
    for (size_t k = 0; k < c->nslots && !bad; k++) {
        slotbuf *s = &u->sl[k];
        s->sx = malloc(c->sample_cap * sizeof *s->sx), s->sy = malloc(c->sample_cap * sizeof *s->sy);
        bad |= !s->sx || !s->sy;
        for (int j = 0; j < QMAX && !bad; j++) {
            origin *o = &s->q[j];
            o->idx = malloc(u->wcap * sizeof *o->idx);
            o->x = malloc(u->wcap * sizeof *o->x), o->y = malloc(u->wcap * sizeof *o->y);
            bad |= !o->idx || !o->x || !o->y;
        }
    }
    if (bad) {
        ustate_free(u);
        return gr_fail(err, GR_ERUN, "out of memory");
    }
    return GR_OK;
}

/* Grains of the snapshot inside the window [x0, x0+w) x [y0, y0+w). */
static void window_scan(ustate *u, const gr_particles *p, double x0, double y0)
{
    double w = u->c->window;
    u->wm = 0;
    for (size_t i = 0; i < p->n && u->wm < u->wcap; i++) {
        if (p->flags[i] & (GR_PF_FIXED | GR_PF_GONE))
            continue;
        if (p->x[i] >= x0 && p->x[i] < x0 + w && p->y[i] >= y0 && p->y[i] < y0 + w) {
            u->widx[u->wm] = (int32_t)i;
            u->wx[u->wm] = p->x[i], u->wy[u->wm] = p->y[i];
            u->wm++;
        }
    }
}

/* The cell of the subtraction grid a grain starting at (x, y) belongs to:
 * one cell (the window), columns across x, or a square grid (SS_SUB_*). */
static size_t sub_cell(const ss_ctx *c, const double *win, double x, double y)
{
    if (c->subtract == SS_SUB_WINDOW)
        return 0;
    long nc = c->subtract == SS_SUB_COLUMNS ? SS_SUB_N : SS_SUB_N / 2;
    double h = c->window / (double)nc;
    long i = lround(floor((x - win[0]) / h)), j = lround(floor((y - win[1]) / h));
    i = i < 0 ? 0 : i >= nc ? nc - 1 : i;
    j = j < 0 ? 0 : j >= nc ? nc - 1 : j;
    return c->subtract == SS_SUB_COLUMNS ? (size_t)i : (size_t)(j * nc + i);
}

/* Displacements of an origin's grains now, the local mean flow subtracted
 * (thesis section 3.2: "sustraemos el movimiento debido al flujo"): the
 * mean displacement over the same lag of the grains that started in the
 * same cell of the window (c->subtract). The window's mean alone leaves
 * the shear of the velocity profile across the window in the
 * displacements. A cell with fewer than 2 grains gives no sample. */
static int complete(ustate *u, size_t k, origin *o, const gr_particles *p, double lag_time,
                    gr_err *err)
{
    slotbuf *s = &u->sl[k];
    size_t m = 0;
    double mx = 0, my = 0;
    double cx[SS_SUB_N * SS_SUB_N] = {0}, cy[SS_SUB_N * SS_SUB_N] = {0}, cn[SS_SUB_N * SS_SUB_N] = {0};
    for (size_t a = 0; a < o->m; a++) {
        size_t i = (size_t)o->idx[a];
        if (p->flags[i] & GR_PF_GONE)
            continue;
        u->dx[m] = p->x[i] - o->x[a], u->dy[m] = p->y[i] - o->y[a];
        size_t q = u->cell[m] = sub_cell(u->c, u->win, o->x[a], o->y[a]);
        mx += u->dx[m], my += u->dy[m];
        cx[q] += u->dx[m], cy[q] += u->dy[m], cn[q] += 1;
        m++;
    }
    o->live = 0;
    if (m < 2)
        return GR_OK;
    mx /= (double)m, my /= (double)m;
    s->fall_sum += -my * (double)m;
    s->fall_n += (double)m;
    size_t kept = 0;
    for (size_t a = 0; a < m; a++) {
        size_t q = u->cell[a];
        if (cn[q] < 2)
            continue;
        double ddx = u->dx[a] - cx[q] / cn[q], ddy = u->dy[a] - cy[q] / cn[q];
        u->dx[kept] = ddx, u->dy[kept] = ddy, kept++;
        /* reservoir sampling keeps a uniform subset of every sample seen */
        size_t slot = s->seen < u->c->sample_cap ? s->seen : gr_rng_below(u->rng, s->seen + 1);
        if (slot < u->c->sample_cap)
            s->sx[slot] = ddx, s->sy[slot] = ddy;
        s->seen++;
    }
    s->ns = s->seen < u->c->sample_cap ? s->seen : u->c->sample_cap;
    return kept ? gr_msd_add(u->msd, k, lag_time, u->dx, u->dy, kept, err) : GR_OK;
}

static int write_part(const char *part, const char *key, const ss_ctx *c, ustate *u,
                      const silo_settled *set, const gr_particles *fin, gr_field **fld,
                      const double *ts, size_t nts, double win[2], long steps, const double *cost,
                      const double *branch, gr_err *err)
{
    gr_ckpt *ck = gr_ckpt_create(part, err);
    if (!ck)
        return err->code;
    size_t ns = c->nslots, nt = c->ntimes, nc = gr_field_ncells(fld[0]);
    double *buf = malloc((7 * ns + 4 * nt * nc + 8) * sizeof *buf);
    int rc = buf ? GR_OK : gr_fail(err, GR_ERUN, "out of memory");
    if (!rc)
        rc = gr_ckpt_put_bytes(ck, "key", key, strlen(key), err);
    if (!rc) {
        double *lag = buf, *n = lag + ns, *sx2 = n + ns, *sx4 = sx2 + ns, *sy2 = sx4 + ns,
               *sy4 = sy2 + ns, *fall = sy4 + ns;
        for (size_t k = 0; k < ns; k++) {
            lag[k] = (double)(c->lag[k] * c->fs) * c->base.dt;
            n[k] = u->msd->n[k], sx2[k] = u->msd->sx2[k], sx4[k] = u->msd->sx4[k];
            sy2[k] = u->msd->sy2[k], sy4[k] = u->msd->sy4[k];
            fall[k] = u->sl[k].fall_n > 0 ? u->sl[k].fall_sum : 0.0;
        }
        const char *names[] = {"lag", "n", "sx2", "sx4", "sy2", "sy4", "fall_sum"};
        for (int a = 0; a < 7 && !rc; a++)
            rc = gr_ckpt_put_f64(ck, names[a], buf + (size_t)a * ns, ns, err);
    }
    for (size_t k = 0; k < ns && !rc; k++) {
        char nm[64];
        snprintf(nm, sizeof nm, "samples_x_%zu", k);
        rc = gr_ckpt_put_f64(ck, nm, u->sl[k].sx, u->sl[k].ns, err);
        snprintf(nm, sizeof nm, "samples_y_%zu", k);
        if (!rc)
            rc = gr_ckpt_put_f64(ck, nm, u->sl[k].sy, u->sl[k].ns, err);
    }
    if (!rc) {
        double *num = buf, *py = num + nt * nc, *mass = py + nt * nc, *wsum = mass + nt * nc;
        for (size_t j = 0; j < nt; j++) {
            memcpy(num + j * nc, fld[j]->num, nc * sizeof *num);
            memcpy(py + j * nc, fld[j]->py, nc * sizeof *py);
            memcpy(mass + j * nc, fld[j]->mass, nc * sizeof *mass);
            wsum[j] = fld[j]->wsum;
        }
        double grid[6] = {(double)fld[0]->nx, (double)fld[0]->ny, fld[0]->x0, fld[0]->y0, fld[0]->cx, fld[0]->cy};
        rc = gr_ckpt_put_f64(ck, "field_num", num, nt * nc, err);
        if (!rc) rc = gr_ckpt_put_f64(ck, "field_py", py, nt * nc, err);
        if (!rc) rc = gr_ckpt_put_f64(ck, "field_mass", mass, nt * nc, err);
        if (!rc) rc = gr_ckpt_put_f64(ck, "field_wsum", wsum, nt, err);
        if (!rc) rc = gr_ckpt_put_f64(ck, "field_grid", grid, 6, err);
    }
    if (!rc) rc = gr_ckpt_put_f64(ck, "series", ts, nts, err);
    if (!rc) rc = gr_ckpt_put_f64(ck, "window", win, 2, err);
    if (!rc) rc = exp_put_scalar(ck, "t_settle", set->t_settle, err);
    if (!rc) rc = exp_put_scalar(ck, "top0", set->top, err);
    if (!rc) rc = exp_put_scalar(ck, "steps", (double)steps, err);
    if (!rc) rc = exp_put_particles(ck, "final", fin, err);
    if (!rc && set->filling) rc = exp_put_particles(ck, "filling", set->filling, err);
    if (!rc && set->filling) rc = exp_put_scalar(ck, "t_filling", set->t_filling, err);
    if (!rc) rc = gr_ckpt_put_f64(ck, "cost", cost, 5, err);
    if (!rc) rc = gr_ckpt_put_f64(ck, "branch", branch, 4, err);
    free(buf);
    if (rc) {
        gr_ckpt_discard(ck);
        return rc;
    }
    return gr_ckpt_close(ck, err);
}

/* The window's grains at frame f become the origin of a free slot of s;
 * none is started when all QMAX are still running. */
static void start_origin(ustate *u, slotbuf *s, long f)
{
    for (int j = 0; j < QMAX; j++) {
        origin *q = &s->q[j];
        if (q->live)
            continue;
        q->live = 1, q->f0 = f, q->m = u->wm;
        memcpy(q->idx, u->widx, u->wm * sizeof *q->idx);
        memcpy(q->x, u->wx, u->wm * sizeof *q->x);
        memcpy(q->y, u->wy, u->wm * sizeof *q->y);
        break;
    }
}

/* Frame f (at step): complete the origins whose lag has come, and start
 * new ones every lag/8 frames (overlapping origins, many samples per
 * lag) while the lag still fits before max_steps. The window is scanned
 * once a frame at most, and only when an origin starts. */
static int lag_frame(ustate *u, const gr_particles *snap, long f, long step, const double *win, double dt,
                     gr_err *err)
{
    const ss_ctx *c = u->c;
    int scanned = 0, rc = GR_OK;
    for (size_t k = 0; k < c->nslots && !rc; k++) {
        slotbuf *s = &u->sl[k];
        long lag = c->lag[k], every = lag / 8 > 1 ? lag / 8 : 1;
        for (int j = 0; j < QMAX && !rc; j++)
            if (s->q[j].live && s->q[j].f0 + lag == f)
                rc = complete(u, k, &s->q[j], snap, (double)(lag * c->fs) * dt, err);
        if (f % every || step + lag * c->fs > c->max_steps)
            continue;
        if (!scanned)
            window_scan(u, snap, win[0], win[1]), scanned = 1;
        start_origin(u, s, f);
    }
    return rc;
}

/* One field grid a snapshot time (fig. 3.2), cells of c->cell over the
 * container from its left wall xl and base up. */
static int create_fields(const ss_ctx *c, const silo_cfg *cfg, double xl, gr_field **fld, gr_err *err)
{
    int nx = (int)floor(cfg->width / c->cell + 1e-9), ny = (int)floor(cfg->height / c->cell + 1e-9);
    for (size_t j = 0; j < c->ntimes; j++)
        if (!(fld[j] = gr_field_create(nx, ny, xl, cfg->base, c->cell, c->cell, err)))
            return err->code;
    return GR_OK;
}

/* The grains that fill the top `fall` d of the packing p (surface top0)
 * across the silo: as many as in a band 10 d deep below them, scaled. */
static double layer_grains(const gr_particles *p, double top0, double fall)
{
    double n = 0, lo = top0 - fall - 10, hi = top0 - fall;
    for (size_t i = 0; i < p->n; i++)
        n += !(p->flags[i] & (GR_PF_FIXED | GR_PF_GONE)) && p->y[i] >= lo && p->y[i] < hi;
    return n * fall / 10;
}

/* Follow the open silo frame by frame (every fs steps): the fields near
 * their snapshot times, the lagged displacements, the surface and the
 * outflow every 10 frames into ts (step, surface, outflow; at most tscap
 * numbers), until the surface has fallen fall_stop after min_steps and
 * as many grains have left as filled the top fall_stop of the packing
 * (need), or max_steps. The pile creeps (no static friction in the
 * thesis's law), so its surface sinks without any outflow too, the more
 * the sooner after the filling: the outflow makes the fall the
 * discharge's own. *step is the last step reached. */
static int follow_discharge(ustate *u, const silo_cfg *cfg, gr_sim *st, gr_particles *snap, gr_field **fld,
                            double *ts, size_t tscap, size_t *nts, const double *win, size_t klayer,
                            double *ybuf, double top0, double need, volatile double *progress, long *step,
                            gr_err *err)
{
    const ss_ctx *c = u->c;
    double top = top0, out = 0;
    long f = 0;
    int rc = GR_OK;
    while (!rc) {
        if ((rc = gr_sim_snapshot(st, snap, err)))
            break;
        for (size_t j = 0; j < c->ntimes; j++)
            if (labs(*step - c->times[j]) <= 2 * c->fs &&
                (rc = gr_field_add(fld[j], snap, GR_PF_FIXED | GR_PF_GONE, 1.0, err)))
                break;
        if (!rc)
            rc = lag_frame(u, snap, f, *step, win, cfg->dt, err);
        if (rc)
            break;
        if (f % 10 == 0)
            top = silo_surface(snap, klayer, ybuf);
        if (f % 10 == 0) {
            gr_obs ob;
            gr_obs_clear(&ob);
            if ((rc = gr_sim_observe(st, &ob, err)))
                break;
            out = (double)ob.outflow;
            if (*nts + 3 <= tscap)
                ts[(*nts)++] = (double)*step, ts[(*nts)++] = top, ts[(*nts)++] = out;
        }
        double done = fmin((top0 - top) / c->fall_stop, out / need);
        if (progress)
            *progress = fmax((double)*step / (double)c->max_steps, *step >= c->min_steps ? fmin(0.99, done) : 0.0);
        if ((*step >= c->min_steps && done >= 1) || *step >= c->max_steps)
            break;
        if ((rc = silo_advance(cfg, st, (uint64_t)c->fs, err)))
            break;
        f++, *step += c->fs;
    }
    return rc;
}

/* Realisation r's settled silo branched to the orifice of cfg: the
 * filling's picture stays with the branch (realisation 0's part keeps it
 * for fig. 3.1); branch[4] as silo-flow's: the branch's settling time, the
 * lift, the filling's CPU seconds, the kinetic energy per grain at opening. */
static int branch_fill(const ss_ctx *c, const silo_cfg *cfg, size_t r, silo_settled *set, double branch[4],
                       volatile double *progress, gr_err *err)
{
    silo_settled fill;
    double fill_cost[5];
    int rc = silo_fill_load(&c->fills, r, &fill, fill_cost, err);
    if (!rc)
        rc = silo_rebase(cfg, &fill, set, progress, err);
    if (!rc) {
        branch[0] = set->t_settle, branch[1] = set->lift, branch[2] = fill_cost[1], branch[3] = set->ekin;
        set->t_settle = fill.t_settle;
        set->filling = fill.filling, set->t_filling = fill.t_filling;
        fill.filling = NULL;
    }
    silo_settled_free(&fill);
    return rc;
}

int ss_unit(size_t unit, const char *part, const char *key, void *ctx, volatile double *progress,
            gr_err *err)
{
    const ss_ctx *c = ctx;
    size_t o = unit / (size_t)c->nreal, r = unit % (size_t)c->nreal;
    silo_cfg cfg = c->base;
    cfg.orifice = c->orifice[o];
    cfg.seed = c->seed + r;
    cfg.reinsert = 0;
    silo_settled set;
    ustate u;
    double branch[4] = {0};
    if (ustate_init(&u, c, cfg.seed, err))
        return err->code;
    double w0 = gr_wall_seconds(), c0 = (double)clock() / CLOCKS_PER_SEC;
    int rc = branch_fill(c, &cfg, r, &set, branch, progress, err);
    double w1 = gr_wall_seconds(), c1 = (double)clock() / CLOCKS_PER_SEC;
    if (rc) {
        ustate_free(&u);
        return rc;
    }
    gr_scene *sc = NULL;
    gr_sim *st = NULL;
    gr_particles *snap = gr_particles_create(0, err);
    gr_field *fld[SS_MAX_TIMES] = {0};
    size_t tscap = 3 * (size_t)(c->max_steps / (10 * c->fs) + 4), nts = 0;
    double *ts = malloc(tscap * sizeof *ts);
    if (!snap || !ts)
        rc = gr_fail(err, GR_ERUN, "out of memory");
    if (!rc)
        rc = silo_open(&cfg, &set, &sc, &st, err);
    double xl = rc ? 0 : sc->silo.x0, base = cfg.base, W = cfg.width;
    if (!rc)
        rc = create_fields(c, &cfg, xl, fld, err);
    /* the window is centred in the silo across and in the settled packing's height */
    double win[2] = {xl + 0.5 * (W - c->window), base + 0.5 * (set.top - base) - 0.5 * c->window};
    u.win[0] = win[0], u.win[1] = win[1];
    /* the thesis follows the discharge "hasta que el grano más alto cae dos
     * veces su diámetro"; the highest single grain is often a loose one
     * perched on the surface that rolls off at once, so the surface is the
     * mean height of the highest layer (as many grains as the silo is wide) */
    size_t klayer = (size_t)lround(cfg.width);
    double *ybuf = malloc(((size_t)cfg.n + klayer + 1) * sizeof *ybuf);
    if (!ybuf && !rc)
        rc = gr_fail(err, GR_ERUN, "out of memory");
    double top0 = ybuf ? silo_surface(set.p, klayer, ybuf) : 0;
    long step = 0;
    if (!rc)
        rc = follow_discharge(&u, &cfg, st, snap, fld, ts, tscap, &nts, win, klayer, ybuf, top0,
                              layer_grains(set.p, top0, c->fall_stop), progress, &step, err);
    double cost[5] = {w1 - w0, c1 - c0, gr_wall_seconds() - w1, (double)clock() / CLOCKS_PER_SEC - c1,
                      (double)step};
    if (!rc)
        set.top = top0, rc = write_part(part, key, c, &u, &set, snap, fld, ts, nts, win, step, cost, branch, err);
    for (size_t j = 0; j < c->ntimes; j++)
        gr_field_free(fld[j]);
    gr_sim_free(st);
    gr_scene_free(sc);
    gr_particles_free(snap);
    free(ts);
    free(ybuf);
    silo_settled_free(&set);
    ustate_free(&u);
    return rc;
}
