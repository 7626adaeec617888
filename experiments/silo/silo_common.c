/* The thesis silo: its scene, filling and settling, opening. */
#include "silo_common.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <gsl/gsl_sort_double.h>

#include "fields.h"
#include "init.h"
#include "order.h"

void silo_cfg_thesis(silo_cfg *c, double D)
{
    *c = (silo_cfg){.n = 5000, .width = 50, .height = 100, .base = 5, .orifice = D,
                    .hopper = 1, .outlet = SILO_OUTLET, .reinsert = 0, .seed = 1, .method = gr_method_find("dem"),
                    .dt = 1.25e-4, .ke_tol = 1e-3, .fill_max = 400};
}

void silo_cfg_quick(silo_cfg *c, double D)
{
    *c = (silo_cfg){.n = 800, .width = 20, .height = 48, .base = 3, .orifice = D,
                    .hopper = 0, .outlet = SILO_OUTLET, .reinsert = 0, .seed = 1, .method = gr_method_find("dem"),
                    .dt = 1.25e-4, .ke_tol = 1e-3, .fill_max = 40};
}

/* Whether the experiments' steps are the method's own: dem's time steps. */
static int uses_steps(const silo_cfg *c)
{
    return !strcmp(c->method->name, "dem");
}

/* cd's time step in the experiments' steps: every chunk the silo commands
 * advance (settling checks 800, blocks 2000 and 10000, samples 100, frames 20,
 * the thesis's field times) is a multiple of it, so advancing by time
 * lands on the method's own steps and no rounding accumulates. */
#define CD_STEPS 20

/* Whether "key = value" lines set `key` (its first n characters). */
static int line_given(const char *lines, const char *key, size_t n)
{
    for (const char *l = lines; *l; l = strchr(l, '\n') ? strchr(l, '\n') + 1 : l + strlen(l))
        if (!strncmp(l, key, n) && (l[n] == ' ' || l[n] == '='))
            return 1;
    return 0;
}

static int param_given(const silo_cfg *c, const char *key) { return line_given(c->params, key, strlen(key)); }

/* [material]: the default lines whose keys --material does not set, then
 * the --material lines. */
static void material_lines(const silo_cfg *c, const char *defaults, char *mat, size_t nmat)
{
    size_t k = (size_t)snprintf(mat, nmat, "[material]\n");
    for (const char *l = defaults; *l && k < nmat;) {
        const char *e = strchr(l, '\n');
        size_t len = e ? (size_t)(e - l) + 1 : strlen(l);
        if (!line_given(c->material, l, strcspn(l, " =")))
            k += (size_t)snprintf(mat + k, nmat - k, "%.*s", (int)len, l);
        l += len;
    }
    if (k < nmat)
        snprintf(mat + k, nmat - k, "%s", c->material);
}

void silo_material(const silo_cfg *c, char *mat, size_t nmat)
{
    if (!strcmp(c->method->name, "cd"))
        material_lines(c, "tangential = coulomb\nmu = 0.5\nrestitution = 0\n", mat, nmat);
    else
        material_lines(c, "normal = hertz\ntangential = regularised\nkn = 1e5\ngamma_n = 100\ngamma_t = 300\nmu = 0.5\n",
                       mat, nmat);
}

/* The [material] and the method's own section. dem: Hertz with viscous
 * damping and regularised Coulomb friction (the thesis's law). cd: the
 * same Coulomb coefficient between rigid disks with e = 0, the dense
 * flow's usual choice (docs/methods/cd.md compares), and the time step and
 * tolerance the speed-against-error sweep of cd.md chose; --param lines
 * replace them. */
static void method_sections(const silo_cfg *c, char *mat, size_t nmat, char *own, size_t nown)
{
    own[0] = 0;
    silo_material(c, mat, nmat);
    if (!strcmp(c->method->name, "cd")) {
        char dt[64] = "", tol[32] = "", it[32] = "";
        if (!param_given(c, "dt"))
            snprintf(dt, sizeof dt, "dt = %.17g\n", CD_STEPS * c->dt);
        if (!param_given(c, "tol"))
            snprintf(tol, sizeof tol, "tol = 1e-3\n");
        if (!param_given(c, "max_iter"))
            snprintf(it, sizeof it, "max_iter = 500\n");
        snprintf(own, nown, "[cd]\n%s%s%s%s", dt, tol, it, c->params);
        return;
    }
    /* the time step is dem's own key; other methods run on their defaults */
    if (uses_steps(c))
        snprintf(own, nown, "[dem]\ndt = %.17g\nthreads = 1\nmax_overlap = 0.25\n%s", c->dt, c->params);
    else if (c->params[0])
        snprintf(own, nown, "[%s]\n%s", c->method->name, c->params);
}

/* Lattice geometry of [init]: pitch 1.05 d, rows from the bottom. */
#define SPACING 1.05

gr_scene *silo_scene(const silo_cfg *c, double open_time, gr_err *err)
{
    double W = c->width, H = c->height, b = c->base;
    long per_row = (long)floor((W - 0.1) / SPACING);
    long rows = (c->n + per_row - 1) / per_row + 1;
    double hop_bot = b + H + 3, hop_top = hop_bot + 0.24 * W;
    double r0, r1, dom_h;
    if (c->hopper) {
        r0 = hop_top + 0.6;
        r1 = r0 + rows * SPACING + 0.5;
        dom_h = r1 + 1;
    } else {
        r0 = b + 0.05;
        r1 = r0 + rows * SPACING + 0.5;
        dom_h = fmax(b + H + 2, r1 + 1);
    }
    char open[64] = "";
    if (isfinite(open_time))
        snprintf(open, sizeof open, "open_time = %.17g\n", open_time);
    char band[160] = "";
    if (c->reinsert && c->band_hi > c->band_lo)
        snprintf(band, sizeof band, "reinsert_bottom = %.17g\nreinsert_top = %.17g\n", c->band_lo, c->band_hi);
    char hop[256] = "hopper = no\n";
    if (c->hopper)
        snprintf(hop, sizeof hop, "hopper = yes\nhopper_outlet = %.17g\nhopper_bottom = %.17g\nhopper_top = %.17g\n",
                 c->outlet * W, hop_bot, hop_top);
    char mat[SILO_PARAMS + 160], own[SILO_PARAMS + 160];
    method_sections(c, mat, sizeof mat, own, sizeof own);
    size_t cap = 4096 + 2 * SILO_PARAMS;
    char *text = malloc(cap);
    if (!text) {
        gr_fail(err, GR_ERUN, "out of memory");
        return NULL;
    }
    snprintf(text, cap,
             "; silo of thesis section 3.1, generated by grano silo-*\n"
             "[scene]\nname = silo\nseed = %llu\n"
             "[domain]\nwidth = %.17g\nheight = %.17g\nbottom = open\ngravity = 1\n"
             "%s"
             "[species]\ndiameter = 1\ncount = %ld\n"
             "[silo]\nwidth = %.17g\nheight = %.17g\nbase = %.17g\norifice = %.17g\n%s"
             "walls = grains\nexit_below = %.17g\n%sreinsert = %s\n%s"
             "[init]\nkind = lattice\nregion = 1 %.17g %.17g %.17g\nspacing = %.17g\n"
             "velocity = gaussian\nv0 = 1\n"
             "%s"
             "[run]\nuntil = 1\n",
             (unsigned long long)c->seed, W + 2, dom_h, mat, c->n, W, H, b, c->orifice, open, b - 1.5, hop,
             c->reinsert ? "yes" : "no", band, r0, W + 1, r1, SPACING, own);
    const char *names[GR_MAX_METHODS + 1];
    gr_method_names(names, GR_MAX_METHODS + 1);
    gr_scene *sc = gr_scene_parse(text, "silo (generated)", names, err);
    free(text);
    return sc;
}

double silo_cpu_estimate(const silo_cfg *c, double steps)
{
    /* the wall grains: two sides and the base */
    double grains = (double)c->n + 2 * c->height + c->width;
    return uses_steps(c) ? steps * grains / SILO_DEM_RATE : NAN;
}

double silo_top(const gr_particles *p)
{
    double top = -INFINITY;
    for (size_t i = 0; i < p->n; i++)
        if (!(p->flags[i] & (GR_PF_FIXED | GR_PF_GONE)) && p->y[i] > top)
            top = p->y[i];
    return top;
}

double silo_surface(const gr_particles *p, size_t k, double *buf)
{
    size_t m = 0;
    for (size_t i = 0; i < p->n; i++)
        if (!(p->flags[i] & (GR_PF_FIXED | GR_PF_GONE)))
            buf[m++] = p->y[i];
    if (!m)
        return -INFINITY;
    k = k < m ? k : m;
    double *top = buf + m; /* room for k more */
    gsl_sort_largest(top, k, buf, 1, m);
    double s = 0;
    for (size_t i = 0; i < k; i++)
        s += top[i];
    return s / (double)k;
}

double silo_packing(const gr_particles *p, double x0, double y0, double x1, double y1)
{
    double a = 0;
    for (size_t i = 0; i < p->n; i++) {
        if (p->flags[i] & (GR_PF_FIXED | GR_PF_GONE))
            continue;
        double r = p->radius[i];
        if (p->x[i] + r < x0 || p->x[i] - r > x1 || p->y[i] + r < y0 || p->y[i] - r > y1)
            continue;
        a += gr_disk_rect_area(p->x[i], p->y[i], r, x0, x1, y0, y1);
    }
    return a / ((x1 - x0) * (y1 - y0));
}

int silo_choose_method(silo_cfg *c, const char *name, gr_err *err)
{
    if (gr_method_lookup(name, "--method", &c->method, err) ||
        gr_sim_require(c->method, GR_OP_SNAPSHOT, "the silo", err))
        return err->code;
    gr_scene *sc = silo_scene(c, 0.0, err);
    if (!sc)
        return err->code;
    int rc = gr_method_require_features(c->method, gr_scene_features(sc), "the silo", err);
    gr_scene_free(sc);
    return rc;
}

void silo_key_params(const silo_cfg *c, char *buf, size_t n)
{
    size_t k = strlen(buf);
    if (c->params[0] && k < n)
        k += (size_t)snprintf(buf + k, n - k, " param:%s", c->params);
    if (c->material[0] && k < n)
        snprintf(buf + k, n - k, " material:%s", c->material);
}

int silo_advance(const silo_cfg *c, gr_sim *sim, uint64_t steps, gr_err *err)
{
    if (!steps) /* gr_sim_advance reads 0 steps as "no step limit" */
        return GR_OK;
    if (uses_steps(c))
        return gr_sim_advance(sim, 1e300, steps, err);
    return gr_sim_advance(sim, gr_sim_time(sim) + (double)steps * c->dt, 0, err);
}

void silo_settled_free(silo_settled *s)
{
    if (!s)
        return;
    gr_particles_free(s->p);
    gr_particles_free(s->filling);
    free(s->trace);
    s->p = s->filling = NULL;
    s->trace = NULL;
    s->ntrace = 0;
}

/* The summed kinetic energy of the mobile grains, the most energetic 1%
 * left out: a few rattlers on the surface (a grain rolling without
 * rolling resistance) must not keep the whole silo from counting as
 * settled. *nm counts the mobile grains, *inside those below ytop; ebuf
 * has room for every grain. */
static double settling_energy(const gr_particles *p, double ytop, double *ebuf, size_t *nm, size_t *inside)
{
    double ek = 0;
    *nm = 0, *inside = 0;
    for (size_t i = 0; i < p->n; i++) {
        if (p->flags[i] & (GR_PF_FIXED | GR_PF_GONE))
            continue;
        *inside += p->y[i] < ytop;
        ebuf[(*nm)++] = 0.5 * p->mass[i] * (p->vx[i] * p->vx[i] + p->vy[i] * p->vy[i]) +
                        0.5 * p->inertia[i] * p->omega[i] * p->omega[i];
    }
    qsort(ebuf, *nm, sizeof *ebuf, exp_cmp_double);
    for (size_t i = 0; i < *nm - *nm / 100; i++)
        ek += ebuf[i];
    return ek;
}

/* The picture of the filling (thesis fig. 3.1): a copy of p at time t. */
static int keep_filling(silo_settled *out, const gr_particles *p, double t, gr_err *err)
{
    out->filling = gr_particles_create(0, err);
    if (!out->filling || gr_particles_copy(out->filling, p, err))
        return err->code;
    out->t_filling = t;
    return GR_OK;
}

/* One row of the filling's trace (silo_settled.trace). */
static int trace_row(silo_settled *out, double t, double cpu, double inside, double ek, gr_err *err)
{
    if ((out->ntrace & (out->ntrace - 1)) == 0) { /* 0 or a power of two: grow */
        double *m = realloc(out->trace, (out->ntrace ? 2 * out->ntrace : 64) * SILO_TRACE * sizeof *m);
        if (!m)
            return gr_fail(err, GR_ERUN, "out of memory");
        out->trace = m;
    }
    double *r = out->trace + out->ntrace++ * SILO_TRACE;
    r[0] = t, r[1] = cpu, r[2] = inside, r[3] = ek;
    return GR_OK;
}

/* Run p (closed orifice, scene sc) until every grain is inside the
 * container and the kinetic energy per grain is below ke_tol; p becomes
 * out->p. keep: take the picture of the filling. tmax > 0: accept the
 * state reached at tmax (a branch) instead of failing at fill_max. */
static int settle(const silo_cfg *c, const gr_scene *sc, gr_particles *p, int keep, double tmax,
                  silo_settled *out, volatile double *progress, gr_err *err)
{
    gr_sim *st = NULL;
    int rc = gr_sim_create(c->method, sc, p, &st, err);
    /* Inside: below the hopper's outlet, less half a diameter: the grains
     * fill the container to its rim, and one resting on the pile just above
     * the rim is settled, not still falling. */
    double ytop = sc->silo.hopper ? sc->silo.hopper_bottom - 0.5 : c->base + c->height;
    double *ebuf = malloc(((size_t)c->n + 1) * sizeof *ebuf);
    if (!ebuf && !rc)
        rc = gr_fail(err, GR_ERUN, "out of memory");
    const uint64_t chunk = (uint64_t)llround(SILO_CHECK / c->dt);
    const double cpu0 = (double)clock() / CLOCKS_PER_SEC;
    while (!rc) {
        if ((rc = silo_advance(c, st, chunk, err)) || (rc = gr_sim_snapshot(st, p, err)))
            break;
        double t = gr_sim_time(st);
        size_t nm, inside;
        double ek = settling_energy(p, ytop, ebuf, &nm, &inside);
        if (nm < (size_t)c->n) {
            rc = gr_fail(err, GR_ERUN, "silo filling (seed %llu): %zu grains escaped the closed silo",
                         (unsigned long long)c->seed, (size_t)c->n - nm);
            break;
        }
        ek /= (double)(nm - nm / 100);
        if (keep && !out->filling && (!c->hopper || inside >= nm / 2) && (rc = keep_filling(out, p, t, err)))
            break;
        if (keep && (rc = trace_row(out, t, (double)clock() / CLOCKS_PER_SEC - cpu0, (double)inside, ek, err)))
            break;
        if (progress)
            *progress = fmin(0.99, t / c->fill_max);
        if ((inside == nm && ek < c->ke_tol) || (tmax > 0 && t >= tmax)) {
            out->p = p;
            out->t_settle = t;
            out->top = silo_top(p);
            out->ekin = ek;
            break;
        }
        if (t >= c->fill_max) {
            rc = gr_fail(err, GR_ERUN,
                         "silo filling (seed %llu): not settled by t = %g (kinetic energy per grain %.3g, tolerance %.3g; %zu of %zu grains inside)",
                         (unsigned long long)c->seed, t, ek, c->ke_tol, inside, nm);
            break;
        }
    }
    gr_sim_free(st);
    free(ebuf);
    return rc;
}

int silo_fill(const silo_cfg *c, silo_settled *out, volatile double *progress, gr_err *err)
{
    *out = (silo_settled){0};
    if (!c->method)
        return gr_fail(err, GR_ERUN, "silo filling: no method");
    gr_scene *sc = silo_scene(c, INFINITY, err);
    if (!sc)
        return err->code;
    gr_particles *p = gr_particles_create(0, err);
    int rc = !p ? GR_ERUN : gr_init_particles(sc, p, err);
    if (!rc)
        rc = settle(c, sc, p, 1, 0, out, progress, err);
    if (rc || out->p != p)
        gr_particles_free(p);
    gr_scene_free(sc);
    if (rc)
        silo_settled_free(out);
    return rc;
}

/* The lift that frees every mobile grain of p (its first nm grains) from
 * the base and gate grains (centres below ybase) after them; the side
 * walls do not depend on the orifice. */
static double rebase_lift(const gr_particles *p, size_t nm, double ybase)
{
    double lift = 0;
    for (size_t j = nm; j < p->n; j++)
        for (size_t i = 0; i < nm && p->y[j] < ybase; i++) {
            double dx = p->x[i] - p->x[j], s = p->radius[i] + p->radius[j];
            if (fabs(dx) >= s || p->y[i] < p->y[j] || p->y[i] - p->y[j] > s)
                continue;
            double need = p->y[j] + sqrt(s * s - dx * dx) - p->y[i];
            lift = need > lift ? need : lift;
        }
    return lift;
}

int silo_rebase(const silo_cfg *c, const silo_settled *s, silo_settled *out, volatile double *progress,
                gr_err *err)
{
    *out = (silo_settled){0};
    gr_scene *sc = silo_scene(c, INFINITY, err);
    if (!sc)
        return err->code;
    gr_particles *walls = gr_particles_create(0, err), *p = gr_particles_create(0, err);
    int rc = !walls || !p ? GR_ERUN : gr_init_particles(sc, walls, err);
    for (size_t i = 0; i < s->p->n && !rc; i++)
        if (!(s->p->flags[i] & GR_PF_FIXED) &&
            gr_particles_push(p, s->p->x[i], s->p->y[i], s->p->radius[i], s->p->mass[i], s->p->flags[i],
                              s->p->species[i], err) < 0)
            rc = err->code;
    size_t nm = rc ? 0 : p->n; /* at rest, as pushed */
    for (size_t j = 0; j < walls->n && !rc; j++)
        if ((walls->flags[j] & GR_PF_FIXED) &&
            gr_particles_push(p, walls->x[j], walls->y[j], walls->radius[j], walls->mass[j], walls->flags[j],
                              walls->species[j], err) < 0)
            rc = err->code;
    if (!rc) {
        /* a clearance of 1e-3 d: the packing drops onto the new base */
        double lift = rebase_lift(p, nm, c->base);
        lift = lift > 0 ? lift + 1e-3 : 0;
        for (size_t i = 0; i < nm; i++)
            p->y[i] += lift;
        for (size_t i = 0; i < p->n; i++)
            p->id[i] = (int64_t)i;
        out->lift = lift;
        rc = settle(c, sc, p, 0, SILO_BRANCH_MAX, out, progress, err);
    }
    if (rc || out->p != p)
        gr_particles_free(p);
    gr_particles_free(walls);
    gr_scene_free(sc);
    if (rc)
        silo_settled_free(out);
    return rc;
}

int silo_open(const silo_cfg *c, const silo_settled *s, gr_scene **scp, gr_sim **state, gr_err *err)
{
    const gr_method_type *m = c->method;
    silo_cfg co = *c;
    if (co.reinsert)
        co.band_lo = s->top + 1.0, co.band_hi = s->top + 5.0;
    gr_scene *sc = silo_scene(&co, 0.0, err);
    if (!sc)
        return err->code;
    int rc = gr_sim_create(m, sc, s->p, state, err);
    if (rc) {
        gr_scene_free(sc);
        return rc;
    }
    *scp = sc;
    return GR_OK;
}
