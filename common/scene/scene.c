/* Scene: from the key/value entries to the checked scene structure. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "scene.h"
#include "scene_get.h"
#include "scene_impl.h"

static const char *const common_sections[] = {
    "scene", "domain", "material", "species", "floor", "silo", "init", "measure", "run", NULL};

static const char *const keys_scene[] = {"name", "seed", NULL};
static const char *const keys_domain[] = {"width", "height", "left", "right", "bottom", "top", "gravity", NULL};
static const char *const keys_material[] = {
    "normal", "tangential", "kn", "gamma_n", "kt", "gamma_t", "mu", "restitution",
    "tangential_restitution", "wall_restitution", "clip_attraction", NULL};
static const char *const keys_species[] = {"diameter", "polydispersity", "density", "count", "weight", NULL};
static const char *const keys_floor[] = {"motion", "amplitude", "omega", NULL};
static const char *const keys_silo[] = {
    "width", "height", "left", "base", "orifice", "orifice_center", "open_time", "walls",
    "hopper", "hopper_outlet", "hopper_bottom", "hopper_top", "reinsert", "reinsert_bottom",
    "reinsert_top", "exit_below", NULL};
static const char *const keys_wall[] = {"from", "to", "open_time", "vibrating", NULL};
static const char *const keys_init[] = {"kind", "region", "spacing", "velocity", "v0", "file",
                                        "occupation", "rest_occupation", "overlap", NULL};
static const char *const keys_measure[] = {"window", "field_cells", NULL};
static const char *const keys_run[] = {"until", "output_every", "observe_every", "checkpoint_every", "contacts",
                                       "thermo_every", "stress", "strict", "stall_steps", "stall_seconds",
                                       "max_cost_growth", NULL};

static const char *const bc_names[] = {"wall", "periodic", "open", NULL};
static const char *const normal_names[] = {"linear", "hertz", NULL};
static const char *const tang_names[] = {"none", "coulomb", "viscous", "regularised", "spring", NULL};
static const char *const init_names[] = {"lattice", "random", "file", "occupation", NULL};
static const char *const vel_names[] = {"zero", "gaussian", "speed", NULL};
static const char *const overlap_names[] = {"refuse", "push", NULL};

/* Densest packing of equal disks: no scene may ask for more. */
#define GR_HEX_PACKING 0.9068996821171089

static int in_list(const char *const *list, const char *s)
{
    for (size_t i = 0; list[i]; i++)
        if (!strcmp(list[i], s))
            return 1;
    return 0;
}

static int check_sections(gr_scene *sc, const char *const *extra, gr_err *err)
{
    const char *all[64];
    size_t n = 0;
    for (size_t i = 0; common_sections[i]; i++)
        all[n++] = common_sections[i];
    all[n++] = "wall.NAME";
    all[n++] = "species.NAME";
    for (size_t i = 0; extra && extra[i] && n < 63; i++)
        all[n++] = extra[i];
    all[n] = NULL;
    for (size_t i = 0; i < sc->nentries; i++) {
        const gr_scene_entry *e = &sc->entries[i];
        const char *kind = gr_scene_section_kind(e->section);
        int known = !strcmp(kind, "wall") || !strcmp(kind, "species");
        for (size_t j = 0; all[j] && !known; j++)
            known = !strcmp(all[j], e->section);
        if (!e->section[0] && e->key[0])
            return gr_fail(err, GR_EINPUT, "%s:%d: key '%s' outside any [section]",
                           sc->path, e->line, e->key);
        if (!known) {
            const char *near = gr_nearest(e->section, all);
            if (near)
                return gr_fail(err, GR_EINPUT, "%s:%d: unknown section [%s]; did you mean [%s]?",
                               sc->path, e->line, e->section, near);
            return gr_fail(err, GR_EINPUT, "%s:%d: unknown section [%s]", sc->path, e->line, e->section);
        }
        const char *const *valid = NULL;
        if (!strcmp(kind, "scene")) valid = keys_scene;
        else if (!strcmp(kind, "domain")) valid = keys_domain;
        else if (!strcmp(kind, "material")) valid = keys_material;
        else if (!strcmp(kind, "species")) valid = keys_species;
        else if (!strcmp(kind, "floor")) valid = keys_floor;
        else if (!strcmp(kind, "silo")) valid = keys_silo;
        else if (!strcmp(kind, "wall")) valid = keys_wall;
        else if (!strcmp(kind, "init")) valid = keys_init;
        else if (!strcmp(kind, "measure")) valid = keys_measure;
        else if (!strcmp(kind, "run")) valid = keys_run;
        /* Backend sections are checked by the backend. */
        if (valid && e->key[0] && !in_list(valid, e->key)) {
            const char *near = gr_nearest(e->key, valid);
            return gr_fail(err, GR_EINPUT, "%s:%d: unknown key '%s' in [%s]%s%s%s", sc->path, e->line,
                           e->key, e->section, near ? "; did you mean '" : "", near ? near : "",
                           near ? "'?" : "");
        }
    }
    return GR_OK;
}

static int read_domain(gr_scene *sc, gr_err *err)
{
    static const char *const sides[4] = {"left", "right", "bottom", "top"};
    const char *name = "scene";
    const gr_scene_entry *ne = gr_scene_find(sc, "scene", "name");
    if (ne)
        name = ne->value;
    snprintf(sc->name, sizeof sc->name, "%.63s", name);
    long seed;
    if (gr_scene_get_long(sc, "scene", "seed", 1, &seed, err))
        return err->code;
    if (seed < 0)
        return gr_scene_entry_fail(sc, "scene", "seed", err, "must be >= 0");
    sc->seed = (uint64_t)seed;
    if (!gr_scene_find(sc, "domain", "width") || !gr_scene_find(sc, "domain", "height"))
        return gr_scene_entry_fail(sc, "domain", gr_scene_find(sc, "domain", "width") ? "height" : "width", err,
                          "[domain] needs 'width' and 'height'");
    if (POSITIVE("domain", "width", 0, &sc->width) || POSITIVE("domain", "height", 0, &sc->height))
        return err->code;
    for (int s = 0; s < 4; s++) {
        int v;
        if (gr_scene_get_choice(sc, "domain", sides[s], bc_names, GR_BC_WALL, &v, err))
            return err->code;
        sc->side[s] = (gr_bc)v;
    }
    if ((sc->side[GR_LEFT] == GR_BC_PERIODIC) != (sc->side[GR_RIGHT] == GR_BC_PERIODIC))
        return gr_scene_entry_fail(sc, "domain", sc->side[GR_LEFT] == GR_BC_PERIODIC ? "right" : "left", err,
                          "a periodic side needs its opposite side periodic too");
    if ((sc->side[GR_BOTTOM] == GR_BC_PERIODIC) != (sc->side[GR_TOP] == GR_BC_PERIODIC))
        return gr_scene_entry_fail(sc, "domain", sc->side[GR_BOTTOM] == GR_BC_PERIODIC ? "top" : "bottom", err,
                          "a periodic side needs its opposite side periodic too");
    if (NONNEG("domain", "gravity", 0.0, &sc->gravity))
        return err->code;
    if (sc->gravity > 0 && sc->side[GR_BOTTOM] == GR_BC_PERIODIC)
        return gr_scene_entry_fail(sc, "domain", "bottom", err, "gravity along a periodic direction is not supported");
    return GR_OK;
}

static int read_material(gr_scene *sc, gr_err *err)
{
    gr_material *m = &sc->mat;
    int v;
    if (gr_scene_get_choice(sc, "material", "normal", normal_names, GR_NORMAL_LINEAR, &v, err))
        return err->code;
    m->normal = (gr_normal_law)v;
    if (gr_scene_get_choice(sc, "material", "tangential", tang_names, GR_TANG_NONE, &v, err))
        return err->code;
    m->tangential = (gr_tang_law)v;
    if (POSITIVE("material", "kn", 1e5, &m->kn) || NONNEG("material", "gamma_n", 0.0, &m->gamma_n) ||
        POSITIVE("material", "kt", 2.0 / 7.0 * 1e5, &m->kt) || NONNEG("material", "gamma_t", 0.0, &m->gamma_t) ||
        NONNEG("material", "mu", 0.5, &m->mu) ||
        gr_scene_get_num(sc, "material", "restitution", NAN, 0.0, 0, 1.0, &m->restitution, err) ||
        gr_scene_get_num(sc, "material", "tangential_restitution", NAN, -1.0, 0, 1.0, &m->tangential_restitution, err) ||
        gr_scene_get_num(sc, "material", "wall_restitution", NAN, 0.0, 0, 1.0, &m->wall_restitution, err) ||
        gr_scene_get_yesno(sc, "material", "clip_attraction", 1, &m->clip_attraction, err))
        return err->code;
    if (gr_scene_find(sc, "material", "kt") == NULL && gr_scene_find(sc, "material", "kn"))
        m->kt = 2.0 / 7.0 * m->kn; /* the usual choice: equal normal and tangential periods */
    if ((m->tangential == GR_TANG_VISCOUS || m->tangential == GR_TANG_REGULARISED) &&
        !gr_scene_find(sc, "material", "gamma_t"))
        return gr_scene_entry_fail(sc, "material", "gamma_t", err, "the viscous and regularised tangential laws need gamma_t");
    return GR_OK;
}

static int read_species(gr_scene *sc, gr_err *err)
{
    /* [species] alone, or several [species.NAME], in file order. */
    sc->nspecies = 0;
    for (size_t i = 0; i < sc->nentries; i++) {
        const char *sec = sc->entries[i].section;
        if (strcmp(gr_scene_section_kind(sec), "species"))
            continue;
        int seen = 0;
        for (int k = 0; k < sc->nspecies; k++) {
            char full[80];
            snprintf(full, sizeof full, "%s%s%s", "species", sc->species[k].name[0] ? "." : "",
                     sc->species[k].name);
            seen |= !strcmp(full, sec);
        }
        if (seen)
            continue;
        if (sc->nspecies == GR_MAX_SPECIES)
            return gr_fail(err, GR_EINPUT, "%s:%d: [%s]: at most %d species", sc->path,
                           sc->entries[i].line, sec, GR_MAX_SPECIES);
        gr_species *sp = &sc->species[sc->nspecies++];
        snprintf(sp->name, sizeof sp->name, "%s", strchr(sec, '.') ? strchr(sec, '.') + 1 : "");
        if (POSITIVE(sec, "diameter", 1.0, &sp->diameter) ||
            gr_scene_get_num(sc, sec, "polydispersity", 0.0, 0.0, 0, 0.9, &sp->polydispersity, err) ||
            POSITIVE(sec, "density", 4.0 / M_PI, &sp->density) ||
            POSITIVE(sec, "weight", 1.0, &sp->weight))
            return err->code;
        if (gr_scene_get_long(sc, sec, "count", 0, &sp->count, err))
            return err->code;
        if (sp->count < 0 || !gr_scene_find(sc, sec, "count"))
            return gr_scene_entry_fail(sc, sec, "count", err, "a species needs a count >= 0");
        /* Checked one species at a time, so the sum cannot overflow. */
        if (sp->count > GR_SCENE_MAX_GRAINS || gr_scene_count(sc) > GR_SCENE_MAX_GRAINS) {
            char msg[200];
            snprintf(msg, sizeof msg, "more than %ld grains in all, the largest count grano is tested and sized for (docs/reliability.md)",
                     (long)GR_SCENE_MAX_GRAINS);
            return gr_scene_entry_fail(sc, sec, "count", err, msg);
        }
    }
    if (sc->nspecies == 0) {
        /* No species: grains of unit diameter and mass only if the init reads a file. */
        gr_species *sp = &sc->species[sc->nspecies++];
        sp->diameter = 1.0;
        sp->density = 4.0 / M_PI;
        sp->weight = 1.0;
        sp->count = 0;
    }
    return GR_OK;
}

/* Default region: above the hopper, else inside the silo, else the domain. */
static void default_init_region(const gr_scene *sc, double d, double r[4])
{
    r[0] = 0, r[1] = 0, r[2] = sc->width, r[3] = sc->height;
    if (sc->silo.present) {
        r[0] = sc->silo.x0;
        r[2] = sc->silo.x0 + sc->silo.width;
        r[1] = sc->silo.hopper ? sc->silo.hopper_top + 0.5 * d : sc->silo.base;
        r[3] = sc->silo.hopper ? sc->height : sc->silo.base + sc->silo.height;
    }
}

static int read_init_file(gr_scene *sc, const gr_scene_entry *fe, gr_err *err)
{
    gr_init *in = &sc->init;
    if (!fe)
        return gr_scene_entry_fail(sc, "init", "kind", err, "kind = file needs a 'file' key");
    /* Relative paths are relative to the scene file. */
    const char *slash = strrchr(sc->path, '/');
    int len;
    if (fe->value[0] == '/' || !slash)
        len = snprintf(in->file, sizeof in->file, "%s", fe->value);
    else
        len = snprintf(in->file, sizeof in->file, "%.*s/%s", (int)(slash - sc->path), sc->path, fe->value);
    if (len < 0 || (size_t)len >= sizeof in->file)
        return gr_scene_entry_fail(sc, "init", "file", err, "the path is longer than 1023 characters");
    FILE *f = fopen(in->file, "r");
    if (!f) {
        char msg[1200];
        snprintf(msg, sizeof msg, "cannot read '%s': %s", in->file, strerror(errno));
        return gr_scene_entry_fail(sc, "init", "file", err, msg);
    }
    fclose(f);
    return GR_OK;
}

/* Too many grains for the region: blame the region if the scene sets
 * one, else the species counts. */
static int crowded_fail(const gr_scene *sc, gr_err *err, const char *msg)
{
    return gr_scene_entry_fail(sc, gr_scene_find(sc, "init", "region") ? "init" : "species",
                      gr_scene_find(sc, "init", "region") ? "region" : "count", err, msg);
}

/* The lattice pitch: the widest grain any species can draw, spaced. */
static double lattice_pitch(const gr_scene *sc, double d)
{
    const gr_init *in = &sc->init;
    double a = in->spacing * d * (1.0 + sc->species[0].polydispersity);
    for (int k = 1; k < sc->nspecies; k++) {
        double ak = in->spacing * sc->species[k].diameter * (1.0 + sc->species[k].polydispersity);
        if (ak > a)
            a = ak;
    }
    return a;
}

/* More grains than fit: by area for any kind; by sites for a lattice;
 * random sequential placement jams near 0.547, so refuse beyond 0.5. */
static int check_init_fits(const gr_scene *sc, double d, gr_err *err)
{
    const gr_init *in = &sc->init;
    double area = (in->x1 - in->x0) * (in->y1 - in->y0), grains = 0;
    long n = gr_scene_count(sc);
    for (int k = 0; k < sc->nspecies; k++) {
        double dk = sc->species[k].diameter;
        grains += sc->species[k].count * M_PI * dk * dk / 4;
    }
    double phi = grains / area;
    char msg[512];
    if (phi > GR_HEX_PACKING) {
        snprintf(msg, sizeof msg, "%ld grains cover %.3g of the initial region's area (%.4g x %.4g), more than the densest packing %.4f allows",
                 n, phi, in->x1 - in->x0, in->y1 - in->y0, GR_HEX_PACKING);
        return crowded_fail(sc, err, msg);
    }
    if (in->kind == GR_INIT_LATTICE) {
        double a = lattice_pitch(sc, d);
        /* In double: the site count of a huge region overflows a long. */
        double nx = floor((in->x1 - in->x0) / a), ny = floor((in->y1 - in->y0) / a);
        if (nx * ny < (double)n) {
            snprintf(msg, sizeof msg, "%ld grains do not fit: the initial region holds %.0f x %.0f = %.0f lattice sites of pitch %.4g",
                     n, nx, ny, nx * ny, a);
            return crowded_fail(sc, err, msg);
        }
    } else if (phi > 0.5) {
        snprintf(msg, sizeof msg, "random placement without overlap cannot reach packing fraction %.3g (> 0.5); use kind = lattice", phi);
        return gr_scene_entry_fail(sc, "init", "kind", err, msg);
    }
    return GR_OK;
}

/* kind = occupation: mean occupations of the moving and rest channels,
 * each in [0, 1]; grains are no longer counted (the lattice holds them). */
static int read_init_occupation(gr_scene *sc, gr_err *err)
{
    gr_init *in = &sc->init;
    if (!gr_scene_find(sc, "init", "occupation"))
        return gr_scene_entry_fail(sc, "init", "kind", err, "kind = occupation needs an 'occupation' key (mean occupation of a moving channel, in [0, 1])");
    if (gr_scene_get_num(sc, "init", "occupation", 0.0, 0.0, 0, 1.0, &in->occupation, err) ||
        gr_scene_get_num(sc, "init", "rest_occupation", in->occupation, 0.0, 0, 1.0, &in->rest_occupation, err))
        return err->code;
    if (gr_scene_count(sc) > 0)
        return gr_scene_entry_fail(sc, "init", "kind", err, "kind = occupation places no grains; give no species count (or count = 0)");
    return GR_OK;
}

static int read_init(gr_scene *sc, gr_err *err)
{
    gr_init *in = &sc->init;
    int v, found;
    if (gr_scene_get_choice(sc, "init", "kind", init_names, GR_INIT_LATTICE, &v, err))
        return err->code;
    in->kind = (gr_init_kind)v;
    double d = gr_scene_max_diameter(sc);
    double r[4];
    default_init_region(sc, d, r);
    if (gr_scene_get_vec(sc, "init", "region", 4, r, &found, err))
        return err->code;
    if (!(r[2] > r[0]) || !(r[3] > r[1]))
        return gr_scene_entry_fail(sc, "init", "region", err, "the region must be 'x0 y0 x1 y1' with x1 > x0 and y1 > y0");
    if (found && (r[0] < 0 || r[1] < 0 || r[2] > sc->width || r[3] > sc->height))
        return gr_scene_entry_fail(sc, "init", "region", err, "the region reaches outside the domain [0, width] x [0, height]");
    in->x0 = r[0], in->y0 = r[1], in->x1 = r[2], in->y1 = r[3];
    if (gr_scene_get_num(sc, "init", "spacing", 1.05, 1.0, 0, 10.0, &in->spacing, err))
        return err->code;
    if (gr_scene_get_choice(sc, "init", "velocity", vel_names, GR_VEL_ZERO, &v, err))
        return err->code;
    in->velocity = (gr_vel_kind)v;
    if (NONNEG("init", "v0", 1.0, &in->v0))
        return err->code;
    if (gr_scene_get_choice(sc, "init", "overlap", overlap_names, GR_OVERLAP_REFUSE, &v, err))
        return err->code;
    in->overlap = (gr_overlap_policy)v;
    const gr_scene_entry *fe = gr_scene_find(sc, "init", "file");
    if (in->kind == GR_INIT_FILE)
        return read_init_file(sc, fe, err);
    if (in->kind == GR_INIT_OCCUPATION)
        return read_init_occupation(sc, err);
    return check_init_fits(sc, d, err);
}

static int read_measure_run(gr_scene *sc, gr_err *err)
{
    double w[4];
    int found;
    if (gr_scene_get_vec(sc, "measure", "window", 4, w, &found, err))
        return err->code;
    sc->window.present = found;
    if (found) {
        if (!(w[2] > w[0]) || !(w[3] > w[1]))
            return gr_scene_entry_fail(sc, "measure", "window", err, "the window must be 'x0 y0 x1 y1' with x1 > x0 and y1 > y0");
        if (w[0] < 0 || w[1] < 0 || w[2] > sc->width || w[3] > sc->height)
            return gr_scene_entry_fail(sc, "measure", "window", err, "the window reaches outside the domain [0, width] x [0, height]");
        sc->window.x0 = w[0], sc->window.y0 = w[1], sc->window.x1 = w[2], sc->window.y1 = w[3];
    }
    double c[2];
    if (gr_scene_get_vec(sc, "measure", "field_cells", 2, c, &found, err))
        return err->code;
    if (found) {
        if (c[0] < 1 || c[1] < 1 || c[0] != floor(c[0]) || c[1] != floor(c[1]) || c[0] * c[1] > 1e7)
            return gr_scene_entry_fail(sc, "measure", "field_cells", err, "expected two positive integers 'nx ny'");
        sc->run.field_nx = (int)c[0], sc->run.field_ny = (int)c[1];
    }
    if (POSITIVE("run", "until", 10.0, &sc->run.until) ||
        POSITIVE("run", "output_every", sc->run.until / 100.0, &sc->run.output_every) ||
        POSITIVE("run", "observe_every", sc->run.output_every / 10.0, &sc->run.observe_every) ||
        POSITIVE("run", "checkpoint_every", sc->run.until / 10.0, &sc->run.checkpoint_every) ||
        NONNEG("run", "thermo_every", sc->run.output_every, &sc->run.thermo_every) ||
        gr_scene_get_yesno(sc, "run", "contacts", 0, &sc->run.contacts, err) ||
        gr_scene_get_yesno(sc, "run", "stress", 0, &sc->run.stress, err) ||
        gr_scene_get_yesno(sc, "run", "strict", 0, &sc->run.strict, err) ||
        POSITIVE("run", "stall_steps", 1e6, &sc->run.stall_steps) ||
        NONNEG("run", "stall_seconds", 10.0, &sc->run.stall_seconds) ||
        NONNEG("run", "max_cost_growth", 1000.0, &sc->run.max_cost_growth))
        return err->code;
    if (sc->run.max_cost_growth > 0 && sc->run.max_cost_growth < 1)
        return gr_scene_entry_fail(sc, "run", "max_cost_growth", err, "expected 0 (no bound) or at least 1");
    return GR_OK;
}

gr_scene *gr_scene_parse(const char *text, const char *path, const char *const *extra, gr_err *err)
{
    gr_scene *sc = calloc(1, sizeof *sc);
    if (!sc) {
        gr_fail(err, GR_ERUN, "out of memory");
        return NULL;
    }
    snprintf(sc->path, sizeof sc->path, "%s", path);
    sc->text = strdup(text);
    if (!sc->text) {
        gr_fail(err, GR_ERUN, "out of memory");
        gr_scene_free(sc);
        return NULL;
    }
    if (gr_scene_read_entries(sc, text, err) || check_sections(sc, extra, err) ||
        read_domain(sc, err) || read_material(sc, err) || read_species(sc, err) ||
        gr_scene_read_geometry(sc, err) ||
        read_init(sc, err) || read_measure_run(sc, err)) {
        gr_scene_free(sc);
        return NULL;
    }
    return sc;
}

char *gr_scene_read_text(const char *path, gr_err *err)
{
    struct stat st;
    if (stat(path, &st) == 0 && (S_ISDIR(st.st_mode) || S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode))) {
        gr_fail(err, GR_EINPUT, "%s: cannot read scene file: a directory or a device", path);
        return NULL;
    }
    FILE *f = fopen(path, "rb");
    if (!f) {
        gr_fail(err, GR_EINPUT, "%s: cannot read scene file: %s", path, strerror(errno));
        return NULL;
    }
    size_t cap = 4096, n = 0;
    char *buf = malloc(cap);
    while (buf) {
        n += fread(buf + n, 1, cap - n - 1, f);
        if (n < cap - 1)
            break;
        if (cap >= GR_SCENE_MAX_BYTES) {
            fclose(f);
            free(buf);
            gr_fail(err, GR_EINPUT, "%s: scene file larger than %d MB", path, GR_SCENE_MAX_BYTES >> 20);
            return NULL;
        }
        char *q = realloc(buf, cap * 2);
        if (!q) {
            free(buf);
            buf = NULL;
            break;
        }
        buf = q;
        cap *= 2;
    }
    int bad = ferror(f);
    fclose(f);
    if (!buf || bad) {
        free(buf);
        gr_fail(err, GR_EINPUT, "%s: cannot read scene file", path);
        return NULL;
    }
    buf[n] = '\0';
    if (strlen(buf) != n) {
        int line = 1;
        for (const char *q = buf; *q; q++)
            line += *q == '\n';
        gr_fail(err, GR_EINPUT, "%s:%d: not a text file (NUL byte at offset %zu)", path, line, strlen(buf));
        free(buf);
        return NULL;
    }
    return buf;
}

gr_scene *gr_scene_load(const char *path, const char *const *extra, gr_err *err)
{
    char *text = gr_scene_read_text(path, err);
    if (!text)
        return NULL;
    gr_scene *sc = gr_scene_parse(text, path, extra, err);
    free(text);
    return sc;
}

void gr_scene_free(gr_scene *sc)
{
    if (!sc)
        return;
    free(sc->text);
    free(sc->entries);
    free(sc->parsed);
    free(sc->index);
    free(sc->segments);
    free(sc);
}
