/* Initial particles: mobile grains, then the silo's wall grains. */
#include "init.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "geom.h"
#include "grid.h"
#include "rng.h"

/* Streams of the scene seed used here; methods use others. */

static double species_mass(const gr_species *sp, double d) { return sp->density * M_PI * d * d / 4; }

/* Species of the k-th grain: species interleaved in proportion to their
 * counts, so a mixture starts mixed. */
static int pick_species(const gr_scene *sc, long *left, gr_rng *rng)
{
    long total = 0;
    for (int s = 0; s < sc->nspecies; s++)
        total += left[s];
    long u = (long)gr_rng_below(rng, (unsigned long)total);
    for (int s = 0; s < sc->nspecies; s++) {
        if (u < left[s]) {
            left[s]--;
            return s;
        }
        u -= left[s];
    }
    return sc->nspecies - 1;
}

static double draw_diameter(const gr_species *sp, gr_rng *rng)
{
    if (sp->polydispersity <= 0)
        return sp->diameter;
    return sp->diameter * (1.0 + sp->polydispersity * (2.0 * gr_rng_uniform(rng) - 1.0));
}

static int place_lattice(const gr_scene *sc, gr_particles *p, gr_rng *rng, gr_err *err)
{
    const gr_init *in = &sc->init;
    double a = 0;
    for (int s = 0; s < sc->nspecies; s++) {
        double as = in->spacing * sc->species[s].diameter * (1.0 + sc->species[s].polydispersity);
        a = as > a ? as : a;
    }
    long nx = (long)floor((in->x1 - in->x0) / a);
    long n = gr_scene_count(sc);
    long left[GR_MAX_SPECIES];
    for (int s = 0; s < sc->nspecies; s++)
        left[s] = sc->species[s].count;
    /* Rows from the bottom, centred horizontally in the region. */
    double xoff = in->x0 + 0.5 * ((in->x1 - in->x0) - nx * a) + 0.5 * a;
    for (long k = 0; k < n; k++) {
        int s = pick_species(sc, left, rng);
        double d = draw_diameter(&sc->species[s], rng);
        double x = xoff + (double)(k % nx) * a, y = in->y0 + 0.5 * a + (double)(k / nx) * a;
        if (gr_particles_push(p, x, y, 0.5 * d, species_mass(&sc->species[s], d), 0, s, err) < 0)
            return err->code;
    }
    return GR_OK;
}

typedef struct {
    const gr_particles *p;
    double x, y, r;
} overlap_query;

static int overlaps_any(const gr_grid *g, const gr_particles *p, double x, double y, double r,
                        double Lx, double Ly)
{
    long nb[9];
    int m = gr_grid_neighbours(g, gr_grid_cell(g, x, y), nb);
    for (int k = 0; k < m; k++) {
        for (long j = g->head[nb[k]]; j >= 0; j = g->next[j]) {
            double dx = gr_min_image(x - p->x[j], Lx), dy = gr_min_image(y - p->y[j], Ly);
            double s = r + p->radius[j];
            if (dx * dx + dy * dy < s * s)
                return 1;
        }
    }
    return 0;
}

static int place_random(const gr_scene *sc, gr_particles *p, gr_rng *rng, gr_err *err)
{
    const gr_init *in = &sc->init;
    double dmax = gr_scene_max_diameter(sc);
    int px = sc->side[GR_LEFT] == GR_BC_PERIODIC, py = sc->side[GR_BOTTOM] == GR_BC_PERIODIC;
    double lx = in->x1 - in->x0, ly = in->y1 - in->y0;
    gr_grid *g = gr_grid_create(in->x0, in->y0, lx, ly, dmax, px, py, err);
    if (!g)
        return err->code;
    long n = gr_scene_count(sc);
    long left[GR_MAX_SPECIES];
    for (int s = 0; s < sc->nspecies; s++)
        left[s] = sc->species[s].count;
    /* Incremental linked cells: push each accepted grain onto its cell. */
    long *next = malloc((size_t)(n > 0 ? n : 1) * sizeof *next);
    if (!next) {
        gr_grid_free(g);
        return gr_fail(err, GR_ERUN, "out of memory");
    }
    free(g->next);
    g->next = next;
    g->cap = (size_t)n;
    for (long c = 0; c < (long)g->nx * g->ny; c++)
        g->head[c] = -1;
    const long max_tries = 100000;
    for (long k = 0; k < n; k++) {
        int s = pick_species(sc, left, rng);
        double d = draw_diameter(&sc->species[s], rng), r = 0.5 * d;
        /* Periodic directions need no margin; walls keep grains inside. */
        double mx = px ? 0 : r, my = py ? 0 : r;
        long t;
        double x = 0, y = 0;
        for (t = 0; t < max_tries; t++) {
            x = in->x0 + mx + (lx - 2 * mx) * gr_rng_uniform(rng);
            y = in->y0 + my + (ly - 2 * my) * gr_rng_uniform(rng);
            if (!overlaps_any(g, p, x, y, r, px ? lx : 0, py ? ly : 0))
                break;
        }
        if (t == max_tries) {
            gr_grid_free(g);
            char where[1200];
            gr_scene_where(sc, "init", "kind", where, sizeof where);
            return gr_fail(err, GR_EINPUT, "%s: random placement found no free spot for grain %ld of %ld after %ld tries; lower the count or use kind = lattice",
                           where, k + 1, n, max_tries);
        }
        long i = gr_particles_push(p, x, y, r, species_mass(&sc->species[s], d), 0, s, err);
        if (i < 0) {
            gr_grid_free(g);
            return err->code;
        }
        long c = gr_grid_cell(g, x, y);
        g->next[i] = g->head[c];
        g->head[c] = i;
    }
    gr_grid_free(g);
    return GR_OK;
}


/* The file's grains must lie in the domain, and number the species count
 * when the scene gives one. */
static int check_file_grains(const gr_scene *sc, const gr_particles *p, gr_err *err)
{
    for (size_t i = 0; i < p->n; i++)
        if (!(p->x[i] >= 0 && p->x[i] <= sc->width && p->y[i] >= 0 && p->y[i] <= sc->height))
            return gr_fail(err, GR_EINPUT, "%s: grain %zu at (%g, %g) lies outside the domain [0, %g] x [0, %g]",
                           sc->init.file, i + 1, p->x[i], p->y[i], sc->width, sc->height);
    if (gr_scene_find(sc, "species", "count") && (long)p->n != sc->species[0].count) {
        char where[1200];
        gr_scene_where(sc, "species", "count", where, sizeof where);
        return gr_fail(err, GR_EINPUT, "%s: %ld grains, but %s holds %zu", where, sc->species[0].count,
                       sc->init.file, p->n);
    }
    return GR_OK;
}

/* The grains file must be a regular file (a device or a pipe such as
 * /dev/zero would be read for ever); its grains are then checked against
 * the scene. */
static int read_grains_file(const gr_scene *sc, gr_particles *p, gr_err *err)
{
    struct stat st;
    char where[1200];
    gr_scene_where(sc, "init", "file", where, sizeof where);
    if (stat(sc->init.file, &st) || !S_ISREG(st.st_mode))
        return gr_fail(err, GR_EINPUT, "%s: '%s' is not a regular file", where, sc->init.file);
    if (gr_init_read_file(sc->init.file, &sc->species[0], p, err))
        return err->code;
    return check_file_grains(sc, p, err);
}

static void draw_velocities(const gr_scene *sc, gr_particles *p, size_t from, gr_rng *rng)
{
    const gr_init *in = &sc->init;
    for (size_t i = from; i < p->n; i++) {
        if (in->velocity == GR_VEL_GAUSSIAN) {
            p->vx[i] = gr_rng_gaussian(rng, in->v0);
            p->vy[i] = gr_rng_gaussian(rng, in->v0);
        } else if (in->velocity == GR_VEL_SPEED) {
            double a = 2 * M_PI * gr_rng_uniform(rng);
            p->vx[i] = in->v0 * cos(a);
            p->vy[i] = in->v0 * sin(a);
        }
    }
}

/* A row of fixed grains of diameter d from a to b, centres spaced at most d. */
static int grain_line(gr_particles *p, double ax, double ay, double bx, double by, double d,
                      double mass, uint32_t flags, gr_err *err)
{
    double len = hypot(bx - ax, by - ay);
    long n = (long)ceil(len / d - 1e-9);
    for (long k = 0; k <= n; k++) {
        double t = n ? (double)k / (double)n : 0.0;
        if (gr_particles_push(p, ax + t * (bx - ax), ay + t * (by - ay), 0.5 * d, mass, flags, 0, err) < 0)
            return err->code;
    }
    return GR_OK;
}

/* Walls of fixed grains whose inner surfaces lie on the silo's inner
 * edges; the orifice is the gap of width D between the base grains that
 * border it, closed by gate grains until it opens. */
static int silo_grains(const gr_scene *sc, gr_particles *p, gr_err *err)
{
    const gr_silo *s = &sc->silo;
    double d = sc->species[0].diameter, r = 0.5 * d, m = species_mass(&sc->species[0], d);
    double x0 = s->x0 - r, x1 = s->x0 + s->width + r, yb = s->base - r, yt = s->base + s->height;
    double ol = s->orifice_center - 0.5 * s->orifice - r, orr = s->orifice_center + 0.5 * s->orifice + r;
    if (grain_line(p, x0, yb + d, x0, yt, d, m, GR_PF_FIXED, err) ||
        grain_line(p, x1, yb + d, x1, yt, d, m, GR_PF_FIXED, err))
        return err->code;
    /* Base: from each orifice edge outwards, so the edge grains sit exactly
     * at distance D apart whatever the widths; the corners close it. */
    for (double x = ol; x > x0 + 1e-9; x -= d)
        if (gr_particles_push(p, x, yb, r, m, GR_PF_FIXED, 0, err) < 0)
            return err->code;
    for (double x = orr; x < x1 - 1e-9; x += d)
        if (gr_particles_push(p, x, yb, r, m, GR_PF_FIXED, 0, err) < 0)
            return err->code;
    if (gr_particles_push(p, x0, yb, r, m, GR_PF_FIXED, 0, err) < 0 ||
        gr_particles_push(p, x1, yb, r, m, GR_PF_FIXED, 0, err) < 0)
        return err->code;
    if (s->open_time > 0) {
        /* Gate grains fill the gap, touching its edges, until it opens. */
        double gl = ol + d, gr_ = orr - d;
        if (grain_line(p, gl, yb, gr_ < gl ? gl : gr_, yb, d, m, GR_PF_FIXED | GR_PF_GATE, err))
            return err->code;
    }
    if (s->hopper) {
        double c = s->orifice_center, h = 0.5 * s->hopper_outlet + r;
        /* the top ends sit over the container's walls: ending them further
         * in left a notch between the end grain and the domain's side where
         * falling grains came to rest for good */
        if (grain_line(p, x0, s->hopper_top, c - h, s->hopper_bottom, d, m, GR_PF_FIXED, err) ||
            grain_line(p, c + h, s->hopper_bottom, x1, s->hopper_top, d, m, GR_PF_FIXED, err))
            return err->code;
        /* A grain sliding down a domain side came to rest exactly on top
         * of an end grain, balanced, pressed to the side by nothing; it
         * rolled off only when round-off had grown, about 38 tau later
         * (every filling of the silo commands waited for it). One more
         * fixed grain on each slope's extension, past the side, turns that
         * perch into slope. */
        double dx = x0 - (c - h), dy = s->hopper_top - s->hopper_bottom, len = hypot(dx, dy);
        double lx = 2 * r * dx / len, ly = s->hopper_top + 2 * r * dy / len;
        if (gr_particles_push(p, x0 + lx, ly, r, m, GR_PF_FIXED, 0, err) < 0 ||
            gr_particles_push(p, x1 - lx, ly, r, m, GR_PF_FIXED, 0, err) < 0)
            return err->code;
    }
    return GR_OK;
}

int gr_init_particles(const gr_scene *sc, gr_particles *out, gr_err *err)
{
    return gr_init_particles_noted(sc, out, NULL, 0, err);
}

/* What overlap = push did, for the run's log. */
static void say_pushed(const gr_init_relax_report *r, char *note, size_t n)
{
    if (!note)
        return;
    if (r->overlap > 0)
        snprintf(note, n, "[init] overlap = push: largest overlap %.4g (%s) pushed apart in %d sweeps, "
                 "largest displacement %.4g", r->overlap, r->where, r->sweeps, r->max_displacement);
    else
        snprintf(note, n, "[init] overlap = push: no grains overlapped");
}

int gr_init_particles_noted(const gr_scene *sc, gr_particles *out, char *note, size_t n, gr_err *err)
{
    if (note)
        note[0] = 0;
    gr_rng *rng = gr_rng_create(sc->seed, GR_STREAM_INIT, err);
    if (!rng)
        return err->code;
    out->n = 0;
    int rc;
    switch (sc->init.kind) {
    case GR_INIT_LATTICE: rc = place_lattice(sc, out, rng, err); break;
    case GR_INIT_RANDOM: rc = place_random(sc, out, rng, err); break;
    case GR_INIT_OCCUPATION: rc = GR_OK; break; /* the lattice backend fills it */
    default: rc = read_grains_file(sc, out, err); break;
    }
    if (!rc)
        draw_velocities(sc, out, 0, rng);
    if (!rc && sc->silo.present && sc->silo.walls == GR_WALLS_GRAINS)
        rc = silo_grains(sc, out, err);
    for (size_t i = 0; i < out->n; i++)
        out->id[i] = (int64_t)i;
    gr_rng_free(rng);
    gr_init_relax_report rep;
    if (!rc && sc->init.overlap == GR_OVERLAP_PUSH && !(rc = gr_init_push_apart(sc, out, &rep, err)))
        say_pushed(&rep, note, n);
    return rc;
}
