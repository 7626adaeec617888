/* A result file seen as a sequence of pictures: grains coloured by a
 * quantity of the frame (with its contact network), or a field's samples. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "h5md.h"
#include "view.h"
#include "view_net.h"

enum { Q_SPEED, Q_VX, Q_VY, Q_OMEGA, Q_ID, Q_SPECIES, Q_RADIUS, Q_CONTACTS, Q_FORCE, NQ };
static const struct {
    const char *name, *label;
} quantities[NQ] = {
    {"speed", "|v| / (d/τ)"},  {"vx", "v_x / (d/τ)"},       {"vy", "v_y / (d/τ)"},
    {"omega", "ω / τ^{-1}"},   {"id", "grain id"},          {"species", "species"},
    {"radius", "radius / d"},  {"contacts", "contacts per grain"}, {"force", "Σ|f_n| / (m d τ^{-2})"},
};

struct vw_view {
    gr_h5md_reader *r;
    const gr_h5md_info *in;
    const char *path;
    size_t n, k; /* frames; the one loaded */
    double *t;
    int q;       /* quantity, or -1: a field */
    gr_particles *p;
    double *val, *pool;
    size_t npool;
    vw_net *net; /* NULL: no network needed */
    char field[128];
    int comp;    /* a field's component, -1: magnitude or (xx + yy)/2 */
    gr_field_desc fd;
    double *raw;
    double width, height;
    char label[300];
};

size_t vw_count(const vw_view *v) { return v->n; }
const double *vw_times(const vw_view *v) { return v->t; }
const char *vw_label(const vw_view *v) { return v->label; }

size_t vw_nearest(const vw_view *v, double t)
{
    size_t best = 0;
    for (size_t k = 1; k < v->n; k++)
        if (fabs(v->t[k] - t) < fabs(v->t[best] - t))
            best = k;
    return best;
}

void vw_free(vw_view *v)
{
    if (!v)
        return;
    gr_h5md_reader_free(v->r);
    gr_particles_free(v->p);
    vw_net_free(v->net);
    free(v->t);
    free(v->val);
    free(v->pool);
    free(v->raw);
    free(v);
}

static int quantity_of(const char *name, gr_err *err)
{
    for (int q = 0; q < NQ; q++)
        if (!strcmp(name, quantities[q].name))
            return q;
    if (!strcmp(name, "stress") || !strcmp(name, "pressure"))
        return gr_fail(err, GR_EINPUT, "--color %s: grano results hold no stress per grain; the stress is a field "
                       "([run] stress = yes with [measure] field_cells): --field stress draws it", name), -1;
    char all[400] = "";
    for (int q = 0; q < NQ; q++)
        snprintf(all + strlen(all), sizeof all - strlen(all), "%s%s", q ? ", " : "", quantities[q].name);
    return gr_fail(err, GR_EINPUT, "--color: '%s' is not one of %s", name, all), -1;
}

/* Grains: the frames' times, the quantity, and a contact network when the
 * quantity or --contacts needs one. */
static int open_grains(vw_view *v, const vw_opts *o, gr_err *err)
{
    if ((v->q = quantity_of(o->color ? o->color : "speed", err)) < 0)
        return err->code;
    v->n = v->in->nframes;
    v->width = v->in->box[0], v->height = v->in->box[1];
    snprintf(v->label, sizeof v->label, "%s", quantities[v->q].label);
    if (!(v->t = malloc((v->n + 1) * sizeof *v->t)) || !(v->p = gr_particles_create(v->in->nparticles, err)) ||
        !(v->val = malloc((v->in->nparticles + 1) * sizeof *v->val)) ||
        !(v->pool = malloc((v->in->nparticles + 1) * sizeof *v->pool)))
        return err->code ? err->code : gr_fail(err, GR_ERUN, "out of memory");
    if (gr_h5md_read_times(v->r, v->t, NULL, err))
        return err->code;
    if (v->q != Q_CONTACTS && v->q != Q_FORCE && !o->contacts)
        return GR_OK;
    const char *who = o->contacts ? "--contacts" : v->q == Q_CONTACTS ? "--color contacts" : "--color force";
    v->net = vw_net_open(v->r, who, o->contacts, err);
    return v->net ? GR_OK : err->code;
}

/* NAME, NAME.x / NAME.y of a vector, NAME.xx ... of a tensor. */
static int pick_component(vw_view *v, const char *comp, gr_err *err)
{
    static const char *const vec[] = {"x", "y"}, *const ten[] = {"xx", "xy", "yx", "yy"};
    int nc = v->fd.ncomp;
    const char *const *names = nc == 2 ? vec : ten;
    v->comp = -1;
    if (nc != 1 && nc != 2 && nc != 4)
        return gr_fail(err, GR_EINPUT, "--field %s: %d components per cell; a scalar, a vector or a 2 x 2 "
                       "tensor is drawn", v->field, nc);
    for (int c = 0; comp && (nc == 2 || nc == 4) && c < nc; c++)
        if (!strcmp(comp, names[c]))
            v->comp = c;
    if (comp && v->comp < 0)
        return gr_fail(err, GR_EINPUT, "--field %s.%s: field '%s' has %s", v->field, comp, v->field,
                       nc == 1 ? "one component (a scalar)" : nc == 2 ? "components x and y"
                                                                   : "components xx, xy, yx, yy");
    char name[128];
    snprintf(name, sizeof name, "%s", v->field);
    for (char *s = name; *s; s++)
        *s = *s == '_' ? ' ' : *s;
    if (nc == 1)
        snprintf(v->label, sizeof v->label, "%s", name);
    else if (v->comp >= 0)
        snprintf(v->label, sizeof v->label, "%s, component %s", name, names[v->comp]);
    else
        snprintf(v->label, sizeof v->label, nc == 2 ? "%s, magnitude" : "%s, (xx + yy)/2", name);
    return GR_OK;
}

static int open_field(vw_view *v, const char *want, char **names, size_t nn, gr_err *err)
{
    const char *comp = NULL;
    size_t i = 0;
    while (i < nn && strcmp(names[i], want))
        i++;
    const char *dot = strrchr(want, '.');
    for (size_t j = 0; i == nn && dot && j < nn; j++)
        if (strlen(names[j]) == (size_t)(dot - want) && !strncmp(names[j], want, (size_t)(dot - want)))
            i = j, comp = dot + 1;
    if (i == nn) {
        char all[600] = "";
        for (size_t j = 0; j < nn; j++)
            snprintf(all + strlen(all), sizeof all - strlen(all), "%s%s", j ? ", " : "", names[j]);
        return gr_fail(err, GR_EINPUT, "--field: %s has no field '%s' (%s)", v->path, want,
                       nn ? all : "it holds no fields: a scene with [measure] field_cells writes them");
    }
    snprintf(v->field, sizeof v->field, "%s", names[i]);
    if (gr_h5md_field_info(v->r, v->field, &v->fd, &v->n, err) || pick_component(v, comp, err))
        return err->code;
    size_t nc = (size_t)v->fd.nx * (size_t)v->fd.ny;
    char series[200];
    snprintf(series, sizeof series, "fields/%s", v->field);
    if (!(v->t = malloc((v->n + 1) * sizeof *v->t)) || !(v->raw = malloc(nc * (size_t)v->fd.ncomp * sizeof *v->raw)) ||
        !(v->val = malloc(nc * sizeof *v->val)) || !(v->pool = malloc(nc * sizeof *v->pool)))
        return gr_fail(err, GR_ERUN, "out of memory");
    v->width = fmax(v->in->box[0], v->fd.x0 + v->fd.nx * v->fd.dx);
    v->height = fmax(v->in->box[1], v->fd.y0 + v->fd.ny * v->fd.dy);
    return gr_h5md_series_times(v->r, series, v->n, v->t, err);
}

/* Why a file without frames or fields has nothing to draw. */
static int nothing(vw_view *v, gr_err *err)
{
    char **names = NULL;
    size_t nn = 0;
    gr_err ignore = {0};
    gr_h5md_list(v->r, "results", &names, &nn, &ignore);
    gr_h5md_names_free(names, nn);
    return gr_fail(err, GR_EINPUT, "%s holds nothing to draw: no trajectory frames and no fields (%s)", v->path,
                   nn ? "a file of result tables: grano info prints them"
                      : "a run writes fields only when its scene has [measure] field_cells");
}

/* Grains when the file has frames, else its fields; --field or --color
 * asking for what is not there is refused by name. */
static int choose(vw_view *v, const vw_opts *o, gr_err *err)
{
    char **names = NULL;
    size_t nn = 0;
    if (gr_h5md_list(v->r, "fields", &names, &nn, err))
        return err->code;
    int rc;
    if (o->field)
        rc = open_field(v, o->field, names, nn, err);
    else if (v->in->nframes)
        rc = open_grains(v, o, err);
    else if (nn && (o->color || o->contacts))
        rc = gr_fail(err, GR_EINPUT, "%s: %s holds no grains (method %s writes fields: --field %s draws one)",
                     o->color ? "--color" : "--contacts", v->path, v->in->method ? v->in->method : "?", names[0]);
    else if (nn) {
        size_t i = 0;
        while (i < nn && strcmp(names[i], "packing_fraction"))
            i++;
        rc = open_field(v, names[i < nn ? i : 0], names, nn, err);
    } else
        rc = nothing(v, err);
    gr_h5md_names_free(names, nn);
    if (!rc && !v->n)
        rc = gr_fail(err, GR_EINPUT, "%s holds nothing to draw: %s has no sample yet", v->path,
                     v->q < 0 ? v->field : "the trajectory");
    return rc;
}

vw_view *vw_open(const char *path, const vw_opts *o, gr_err *err)
{
    vw_view *v = calloc(1, sizeof *v);
    if (!v) {
        gr_fail(err, GR_ERUN, "out of memory");
        return NULL;
    }
    v->path = path;
    v->q = -1;
    if (!(v->r = gr_h5md_open(path, err)) || (v->in = gr_h5md_info_of(v->r), choose(v, o, err))) {
        vw_free(v);
        return NULL;
    }
    return v;
}

static double grain_value(const vw_view *v, size_t i)
{
    const gr_particles *p = v->p;
    switch (v->q) {
    case Q_SPEED: return hypot(p->vx[i], p->vy[i]);
    case Q_VX: return p->vx[i];
    case Q_VY: return p->vy[i];
    case Q_OMEGA: return p->omega[i];
    case Q_ID: return (double)p->id[i];
    case Q_SPECIES: return p->species[i];
    case Q_RADIUS: return p->radius[i];
    case Q_CONTACTS: return vw_net_count(v->net, i);
    default: return vw_net_force(v->net, i);
    }
}

static int load_field(vw_view *v, size_t k, gr_err *err)
{
    size_t nc = (size_t)v->fd.nx * (size_t)v->fd.ny;
    int m = v->fd.ncomp;
    if (gr_h5md_read_field(v->r, v->field, k, v->raw, NULL, NULL, err))
        return err->code;
    v->npool = 0;
    for (size_t c = 0; c < nc; c++) {
        const double *x = v->raw + c * (size_t)m;
        v->val[c] = m == 1 || v->comp >= 0 ? x[v->comp > 0 ? v->comp : 0]
                  : m == 2            ? hypot(x[0], x[1])
                                      : 0.5 * (x[0] + x[3]);
        if (isfinite(v->val[c]))
            v->pool[v->npool++] = v->val[c];
    }
    return GR_OK;
}

int vw_load(vw_view *v, size_t k, gr_err *err)
{
    v->k = k;
    if (v->q < 0)
        return load_field(v, k, err);
    if (gr_h5md_read_frame(v->r, k, v->p, NULL, NULL, err) ||
        (v->net && vw_net_load(v->net, v->p, v->t[k], v->in->box, v->in->periodic, err)))
        return err->code;
    v->npool = 0;
    for (size_t i = 0; i < v->p->n; i++) {
        v->val[i] = grain_value(v, i);
        if (!(v->p->flags[i] & (GR_PF_FIXED | GR_PF_GONE)))
            v->pool[v->npool++] = v->val[i];
    }
    return GR_OK;
}

void vw_values(const vw_view *v, const double **val, size_t *n)
{
    *val = v->pool, *n = v->npool;
}

void vw_forces(const vw_view *v, const double **fn, size_t *n)
{
    vw_net_forces(v->net, fn, n);
}

void vw_size(const vw_view *v, int *w, int *h)
{
    if (v->q < 0)
        gr_plot_field_size(v->width, v->height, w, h);
    else
        gr_plot_disks_size(v->width, v->height, w, h);
}

void vw_body(vw_view *v, FILE *f, double lo, double hi, double fref, const char *label)
{
    char title[400];
    const char *scene = v->in->scene_name ? v->in->scene_name : "result", *m = v->in->method ? v->in->method : "?";
    if (v->q < 0)
        snprintf(title, sizeof title, "%s (%s), %s, frame %zu", scene, m, v->field, v->k);
    else
        snprintf(title, sizeof title, "%s (%s), frame %zu", scene, m, v->k);
    if (v->q < 0) {
        gr_plot_grid g = {v->fd.nx, v->fd.ny, v->fd.x0, v->fd.y0, v->fd.dx, v->fd.dy, v->val, label, lo, hi};
        gr_plot_field_body(f, &g, v->width, v->height, v->t[v->k], title);
        return;
    }
    gr_plot_disks d = {.p = v->p, .value = v->val, .lo = lo, .hi = hi, .label = label,
                       .width = v->width, .height = v->height, .t = v->t[v->k], .title = title};
    if (v->net)
        vw_net_lines(v->net, fref, &d.lines, &d.nlines);
    gr_plot_disks_body(f, &d);
}
