/* Creation from a scene and parameters, freeing, and the small public calls
 * (advance, time, restitution, counters, event hook). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "edmd_int.h"
#include "observe.h"
#include "restitution.h"

void gr_edmd_free(gr_edmd *s)
{
    if (!s)
        return;
    free(s->p);
    free(s->w);
    free(s->m);
    free(s->inertia);
    free(s->tlast);
    free(s->tacc);
    free(s->id);
    free(s->order);
    free(s->chead);
    free(s->wmask);
    free(s->corder);
    free(s->sort_p);
    free(s->sort_ev);
    free(s->sort_perm);
    free(s->sort_inv);
    free(s->sort_buf);
    free(s->ev);
    if (s->q)
        s->q->free(s);
    free(s->cacc);
    gr_stress_acc_free(s->stress);
    free(s->species);
    free(s->seg);
    free(s->seg_len);
    free(s->cseg_start);
    free(s->cseg);
    free(s->gone);
    free(s->wake_stack);
    free(s->sc_silo);
    gr_particles_free(s->scratch);
    gr_rng_free(s->own_rng);
    free(s);
}

static int setup_scene(gr_edmd *s, const gr_scene *sc, const gr_particles *init, gr_err *err)
{
    const gr_material *mt = &sc->mat;
    gr_restitution rs;
    if (gr_scene_restitution(sc, init, &rs, err))
        return err->code;
    if (mt->tangential != GR_TANG_NONE && mt->tangential != GR_TANG_COULOMB) {
        char where[1200];
        gr_scene_where(sc, "material", "tangential", where, sizeof where);
        return gr_fail(err, GR_EINPUT,
                       "%s: method 'edmd' has no viscous, regularised or spring tangential law: "
                       "rough hard disks use [material] tangential_restitution and mu",
                       where);
    }
    s->W = sc->width;
    s->H = sc->height;
    s->g = sc->gravity;
    for (int k = 0; k < 4; k++)
        s->hard[k] = sc->side[k] == GR_BC_WALL;
    s->periodic_x = sc->side[GR_LEFT] == GR_BC_PERIODIC;
    s->periodic_y = sc->side[GR_BOTTOM] == GR_BC_PERIODIC;
    s->alpha = isnan(rs.e) ? 1.0 : rs.e;
    s->alpha_w = isnan(rs.e_wall) ? s->alpha : rs.e_wall;
    s->beta = !isnan(mt->tangential_restitution) ? mt->tangential_restitution
              : mt->tangential == GR_TANG_COULOMB ? 1.0 : -1.0;
    s->mu = mt->tangential == GR_TANG_NONE && isnan(mt->tangential_restitution) ? 0.0 : mt->mu;
    s->rough = s->beta > -1.0 && s->mu > 0.0;
    s->floor = sc->floor.motion;
    s->fA = sc->floor.amplitude;
    s->fomega = sc->floor.omega;
    s->fV0 = s->fA * s->fomega;
    s->ybot = 0.0;
    if (s->floor != GR_FLOOR_FIXED) {
        if (sc->side[GR_BOTTOM] != GR_BC_WALL)
            return gr_fail(err, GR_EINPUT, "%s: a moving floor needs [domain] bottom = wall", sc->path);
        if ((s->floor == GR_FLOOR_SINE || s->floor == GR_FLOOR_SAWTOOTH) && !(s->fomega > 0.0 && s->fA >= 0.0))
            return gr_fail(err, GR_EINPUT, "%s: [floor] needs amplitude >= 0 and omega > 0", sc->path);
        if (s->floor == GR_FLOOR_SINE || s->floor == GR_FLOOR_SAWTOOTH)
            s->ybot = -s->fA;
    }
    for (int k = 0; k < 4; k++)
        s->open[k] = sc->side[k] == GR_BC_OPEN;
    s->y_exit = -EDMD_INF;
    if (sc->silo.present)
        s->y_exit = sc->silo.exit_below;
    else if (s->open[GR_BOTTOM])
        s->y_exit = s->ybot;
    s->reinsert = sc->silo.present && sc->silo.reinsert;
    if (s->reinsert) {
        /* gr_reinsert_spot reads the silo only: keep a copy without pointers */
        if (!(s->sc_silo = calloc(1, sizeof *s->sc_silo)))
            return gr_fail(err, GR_ERUN, "edmd: out of memory");
        s->sc_silo->silo = sc->silo;
        s->sc_silo->width = sc->width;
        s->sc_silo->height = sc->height;
    }
    for (int k = 0; k < sc->nsegments; k++)
        if (sc->segments[k].vibrating)
            return gr_fail(err, GR_EINPUT, "%s:%d: method 'edmd' vibrates only the bottom side, not segments",
                           sc->path, sc->segments[k].line);
    if (!(s->W > 0.0 && s->H > s->ybot))
        return gr_fail(err, GR_EINPUT, "%s: edmd needs a domain of positive size", sc->path);
    return GR_OK;
}

static void *big_zalloc(size_t bytes)
{
    void *m = edmd_big_alloc(bytes);
    if (m)
        memset(m, 0, bytes);
    return m;
}

static int grains_alloc(gr_edmd *s)
{
    size_t n = s->n;
    /* one grain per 64-byte line */
    s->p = edmd_big_alloc(n * sizeof *s->p);
    if (s->p)
        memset(s->p, 0, n * sizeof *s->p);
    /* read at random by the collisions: huge pages, as the grains */
    s->w = big_zalloc(n * sizeof *s->w);
    s->m = big_zalloc(n * sizeof *s->m);
    s->inertia = big_zalloc(n * sizeof *s->inertia);
    s->tlast = big_zalloc(n * sizeof *s->tlast);
    s->tacc = big_zalloc(n * sizeof *s->tacc);
    s->id = calloc(n, sizeof *s->id);
    s->order = calloc(n, sizeof *s->order);
    s->species = calloc(n, sizeof *s->species);
    s->gone = calloc(n, 1);
    if (!s->gone || !s->p || !s->w || !s->m || !s->inertia || !s->tlast || !s->tacc || !s->id || !s->order ||
        !s->species)
        return GR_ERUN;
    return GR_OK;
}

/* The mobile grains of init, in their order. */
static int grains_fill(gr_edmd *s, const gr_particles *init, gr_err *err)
{
    size_t k = 0;
    s->rmax = 0.0;
    for (size_t i = 0; i < init->n; i++) {
        if (init->flags[i] & GR_PF_GONE)
            continue;
        edmd_p *p = &s->p[k];
        p->x = init->x[i];
        p->y = init->y[i];
        p->vx = init->vx[i];
        p->vy = init->vy[i];
        p->r = init->radius[i];
        p->t = 0.0;
        p->cell = -1;
        p->nev = 0;
        p->cnext = -1;
        s->w[k] = init->omega[i];
        s->m[k] = init->mass[i];
        s->inertia[k] = init->inertia[i] > 0 ? init->inertia[i] : gr_disk_inertia(init->mass[i], init->radius[i]);
        s->tlast[k] = -EDMD_INF;
        s->id[k] = init->id[i];
        s->species[k] = init->species[i];
        s->order[k] = k;
        if (!(p->r > 0.0 && s->m[k] > 0.0) || !isfinite(p->x + p->y + p->vx + p->vy))
            return gr_fail(err, GR_EINPUT, "edmd: grain %lld has a bad radius, mass, position or velocity",
                           (long long)s->id[k]);
        if (p->r > s->rmax)
            s->rmax = p->r;
        k++;
    }
    return GR_OK;
}

static int setup_particles(gr_edmd *s, const gr_scene *sc, const gr_particles *init, gr_err *err)
{
    size_t n = 0;
    for (size_t i = 0; i < init->n; i++) {
        if (init->flags[i] & GR_PF_FIXED)
            return gr_fail(err, GR_EINPUT, "edmd: grain %lld is fixed; edmd walls are the sides and the floor",
                           (long long)init->id[i]);
        if (!(init->flags[i] & GR_PF_GONE))
            n++;
    }
    if (n == 0)
        return gr_scene_no_grains(sc, err); /* names the key, as the other particle methods do */
    if (n >= (size_t)INT32_MAX / 2)
        return gr_fail(err, GR_EINPUT, "edmd: too many grains (%zu)", n);
    s->n = n;
    if (grains_alloc(s))
        return gr_fail(err, GR_ERUN, "edmd: out of memory for %zu grains", n);
    if (grains_fill(s, init, err))
        return err->code;
    s->m_one = s->m[0];
    for (size_t i = 1; i < n; i++)
        if (s->m[i] != s->m_one)
            s->m_one = 0.0;
    gr_id_index *ix = malloc(n * sizeof *ix);
    if (!ix)
        return gr_fail(err, GR_ERUN, "edmd: out of memory for %zu grains", n);
    gr_id_index_sort(s->id, n, ix);
    for (size_t i = 0; i < n; i++)
        s->order[i] = ix[i].i;
    free(ix);
    return GR_OK;
}

/* Where the grains came from, and what fixes a soft packing's overlaps:
 * "scene.ini:12: [init] key 'file': 'bed.data', grains counted from 1 ...". */
static void start_origin(const gr_scene *sc, char *buf, size_t n)
{
    char where[1100];
    gr_scene_where(sc, "init", sc->init.kind == GR_INIT_FILE ? "file" : "kind", where, sizeof where);
    if (sc->init.kind == GR_INIT_FILE)
        snprintf(buf, n, "%s: '%.900s', grains counted from 1 in its order:", where, sc->init.file);
    else
        snprintf(buf, n, "%s:", where);
}

#define START_HINT                                                                                  \
    "hard disks never overlap; [init] overlap = push moves a soft packing's grains apart and inside " \
    "its walls (docs/scene-format.md)"

/* How deep grain p cuts the domain's wall sides (the floor where it is at
 * t = 0); *side gets the deepest. */
static double wall_depth(const gr_edmd *s, const edmd_p *p, int *side)
{
    double fl = s->floor == GR_FLOOR_SINE ? s->fA * cos(0.0) : s->floor == GR_FLOOR_SAWTOOTH ? -s->fA : 0.0;
    double d[4] = {p->r - p->x, p->x - (s->W - p->r), fl + p->r - p->y, p->y - (s->H - p->r)}, worst = -INFINITY;
    for (int k = 0; k < 4; k++)
        if (s->hard[k] && d[k] > worst)
            worst = d[k], *side = k;
    return worst;
}

/* The deepest of the overlaps at the start: between grains i and j, or
 * (j < 0) of grain i into wall side. */
typedef struct {
    double depth;
    long i, j;
    int side;
    size_t count;
} start_overlap;

static void note_overlap(start_overlap *w, double depth, long i, long j, int side)
{
    w->count++;
    if (depth > w->depth)
        *w = (start_overlap){depth, i, j, side, w->count};
}

static void wall_overlaps(const gr_edmd *s, double tol, start_overlap *w)
{
    for (size_t i = 0; i < s->n; i++) {
        int side = 0;
        double depth = wall_depth(s, &s->p[i], &side);
        if (depth > tol)
            note_overlap(w, depth, (long)i, -1, side);
    }
}

static void pair_overlaps(const gr_edmd *s, double tol, start_overlap *w)
{
    for (size_t i = 0; i < s->n; i++) {
        const edmd_p *p = &s->p[i];
        int c = p->cell, ix = c % s->nx, iy = c / s->nx;
        for (int dy = -1; dy <= 1; dy++)
            for (int dx = -1; dx <= 1; dx++) {
                int jx = ix + dx, jy = iy + dy;
                if (s->periodic_x)
                    jx = (jx + s->nx) % s->nx;
                if (s->periodic_y)
                    jy = (jy + s->ny) % s->ny;
                if (jx < 0 || jy < 0 || jx >= s->nx || jy >= s->ny)
                    continue;
                for (int32_t j = s->chead[jx + s->nx * jy]; j >= 0; j = s->p[j].cnext) {
                    if ((size_t)j <= i)
                        continue;
                    double ddx = s->p[j].x - p->x, ddy = s->p[j].y - p->y;
                    if (s->periodic_x)
                        ddx = edmd_min_image(ddx, s->W);
                    if (s->periodic_y)
                        ddy = edmd_min_image(ddy, s->H - s->ybot);
                    double sig = p->r + s->p[j].r;
                    if (ddx * ddx + ddy * ddy < sig * sig * (1.0 - 2.0 * tol))
                        note_overlap(w, sig - hypot(ddx, ddy), (long)i, j, 0);
                }
            }
    }
}

/* Every grain inside the domain and above the floor, no pair overlapping;
 * a refusal names the deepest overlap of each kind and how many there are. */
static int check_start(gr_edmd *s, const gr_scene *sc, gr_err *err)
{
    static const char *const sides[4] = {"left wall", "right wall", "floor", "top wall"};
    double tol = 1e-9;
    char origin[2100], pair[300] = "", wall[300] = "";
    start_origin(sc, origin, sizeof origin);
    for (size_t i = 0; i < s->n; i++) {
        const edmd_p *p = &s->p[i];
        if (p->x < 0.0 || p->x > s->W || p->y < s->ybot || p->y > s->H)
            return gr_fail(err, GR_EINPUT, "%s grain %lld at (%g, %g) lies outside the domain", origin,
                           (long long)s->id[i] + 1, p->x, p->y);
    }
    start_overlap w = {0, -1, -1, 0, 0}, pw = {0, -1, -1, 0, 0};
    wall_overlaps(s, tol, &w);
    if (s->prm.algorithm != GR_EDMD_NAIVE)
        pair_overlaps(s, tol, &pw);
    if (!w.count && !pw.count)
        return GR_OK;
    if (pw.count)
        snprintf(pair, sizeof pair, " grains %lld and %lld overlap by %.4g (the deepest of %zu overlapping pairs)%s",
                 (long long)s->id[pw.i] + 1, (long long)s->id[pw.j] + 1, pw.depth, pw.count, w.count ? ";" : "");
    if (w.count)
        snprintf(wall, sizeof wall, " grain %lld at (%.6g, %.6g) cuts the %s by %.4g (the deepest of %zu grains cutting walls)",
                 (long long)s->id[w.i] + 1, s->p[w.i].x, s->p[w.i].y, sides[w.side], w.depth, w.count);
    return gr_fail(err, GR_EINPUT, "%s%s%s: " START_HINT, origin, pair, wall);
}

static int setup_cells(gr_edmd *s, gr_err *err)
{
    double cmin = s->prm.cell > 0.0 ? s->prm.cell : 2.0 * s->rmax;
    if (cmin < 2.0 * s->rmax)
        return gr_fail(err, GR_EINPUT, "edmd: [edmd] cell = %g is smaller than the largest diameter %g",
                       cmin, 2.0 * s->rmax);
    double Ly = s->H - s->ybot;
    s->nx = (int)fmax(1.0, floor(s->W / cmin));
    s->ny = (int)fmax(1.0, floor(Ly / cmin));
    if (s->prm.algorithm == GR_EDMD_NAIVE)
        s->nx = s->ny = 1;
    if ((s->periodic_x && s->nx < 4) || (s->periodic_y && s->ny < 4))
        return gr_fail(err, GR_EINPUT,
                       "edmd: a periodic side must be at least 4 cells (4 largest diameters) long");
    if ((double)s->nx * s->ny > 1e9)
        return gr_fail(err, GR_EINPUT, "edmd: %d x %d cells is too many; raise [edmd] cell", s->nx, s->ny);
    s->cw = s->W / s->nx;
    s->ch = Ly / s->ny;
    size_t nc = (size_t)s->nx * (size_t)s->ny;
    s->chead = edmd_big_alloc(nc * sizeof *s->chead); /* huge pages: prefetches that miss the TLB are dropped */
    if (!s->chead)
        return gr_fail(err, GR_ERUN, "edmd: out of memory for %zu cells", nc);
    for (size_t c = 0; c < nc; c++)
        s->chead[c] = -1;
    for (size_t i = s->n; i-- > 0;) {
        edmd_p *p = &s->p[i];
        int c = edmd_cell_of(s, p->x, p->y);
        p->cell = c;
        p->cnext = s->chead[c];
        s->chead[c] = (int32_t)i;
    }
    s->wmask = calloc(nc, 1);
    if (!s->wmask)
        return gr_fail(err, GR_ERUN, "edmd: out of memory for %zu cells", nc);
    for (size_t c = 0; c < nc; c++)
        for (int w = 0; w <= W_EXIT; w++)
            if (edmd_wall_relevant(s, (int)c, w))
                s->wmask[c] |= (uint8_t)(1u << w);
    for (size_t c = 0; c < nc; c++)
        s->any_wall |= s->wmask[c] != 0;
    if (s->prm.algorithm == GR_EDMD_TREE) {
        double every = s->prm.sort_every < 0 ? (s->n >= 16384 ? 20.0 : 0.0) : s->prm.sort_every;
        s->sort_period = (uint64_t)(every * (double)s->n);
        if (s->sort_period && edmd_sort_setup(s, err))
            return err->code;
    }
    if (s->prm.fields) {
        if (s->prm.algorithm == GR_EDMD_NAIVE)
            return gr_fail(err, GR_EINPUT, "edmd: fields need algorithm = tree");
        s->cacc = calloc(nc, sizeof *s->cacc);
        if (!s->cacc)
            return gr_fail(err, GR_ERUN, "edmd: out of memory for the fields");
    }
    return GR_OK;
}

/* Elastic collisions never collapse: the guard (on by default) then keeps
 * no collision clocks, whose random writes would slow every collision. */
static void set_guard(gr_edmd *s)
{
    int dissipative = s->alpha < 1.0 || s->alpha_w < 1.0 || (s->rough && s->beta < 1.0);
    s->prm.collapse = dissipative ? s->collapse_asked : GR_EDMD_COLLAPSE_NONE;
    s->sleep_on = s->prm.collapse == GR_EDMD_COLLAPSE_SLEEP && s->g > 0.0;
}

int gr_edmd_create(const gr_scene *sc, const gr_particles *init, const gr_edmd_params *prm, gr_rng *rng,
                   gr_edmd **out, gr_err *err)
{
    *out = NULL;
    gr_edmd *s = calloc(1, sizeof *s);
    if (!s)
        return gr_fail(err, GR_ERUN, "edmd: out of memory");
    s->prm = *prm;
    s->q = prm->calendar && prm->algorithm == GR_EDMD_TREE ? &edmd_queue_calendar : &edmd_queue_tree;
    s->collapse_asked = prm->collapse;
    /* the naive loop's pair times know no sleepers (their contacts need a
     * horizon, the next cell crossing): the default sleep is tc there (a
     * scene that asks for both is refused, params.c) */
    if (s->collapse_asked == GR_EDMD_COLLAPSE_SLEEP && prm->algorithm == GR_EDMD_NAIVE)
        s->collapse_asked = GR_EDMD_COLLAPSE_TC;
    int rc = setup_scene(s, sc, init, err);
    set_guard(s);
    if (!rc)
        rc = setup_particles(s, sc, init, err);
    if (!rc)
        rc = setup_cells(s, err);
    if (!rc)
        rc = edmd_segments_setup(s, sc, err);
    if (!rc)
        rc = check_start(s, sc, err);
    if (!rc && !(s->rng = rng) && !(s->rng = s->own_rng = gr_rng_create(sc->seed, GR_STREAM_EDMD, err)))
        rc = err->code;
    s->tshift = s->prm.tree_arity == 4 ? 2 : 1;
    if (!rc)
        rc = edmd_events_init(s, err);
    s->t = 0.0;
    s->t_prev_coll = -EDMD_INF;
    if (!rc && s->prm.algorithm == GR_EDMD_TREE)
        rc = (s->sort_period && edmd_sort(s, err)) ? err->code : edmd_schedule_all(s, err);
    if (rc) {
        gr_edmd_free(s);
        return rc;
    }
    edmd_measure_init(s);
    *out = s;
    return GR_OK;
}

int gr_edmd_advance(gr_edmd *s, double t_end, uint64_t max_collisions, gr_err *err)
{
    int rc = s->prm.algorithm == GR_EDMD_NAIVE ? edmd_advance_naive(s, t_end, max_collisions, err)
                                               : edmd_advance_tree(s, t_end, max_collisions, err);
    return rc ? rc : edmd_check_inside(s, s->t, err);
}

double gr_edmd_time(const gr_edmd *s) { return s->t; }

void gr_edmd_set_restitution(gr_edmd *s, double alpha, double alpha_wall)
{
    s->alpha = alpha;
    s->alpha_w = isnan(alpha_wall) ? alpha : alpha_wall;
    set_guard(s);
}

void gr_edmd_get_counters(const gr_edmd *s, gr_edmd_counters *c) { *c = s->cnt; }

void gr_edmd_set_event_hook(gr_edmd *s, gr_edmd_event_fn fn, void *user)
{
    s->hook = fn;
    s->hook_user = user;
}
