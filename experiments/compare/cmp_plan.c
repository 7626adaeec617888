/* The plan of a comparison: for each chosen case, every chosen method that
 * models its scene (or a row's own variant of it), over its row's knob
 * values and the case's seeds; the methods that do not model a scene, or
 * have no row yet, are noted. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmp.h"

const cmp_case *cmp_plan_cases(const cmp_plan *pl)
{
    return pl->cases ? pl->cases : cmp_cases();
}

int cmp_listed(const char *list, const char *name)
{
    if (!list)
        return 1;
    size_t k = strlen(name);
    for (const char *p = list; p && *p; p = strchr(p, ',') ? strchr(p, ',') + 1 : NULL)
        if (!strncmp(p, name, k) && (p[k] == ',' || !p[k]))
            return 1;
    return 0;
}

static void note(cmp_plan *pl, const char *fmt, const char *a, const char *b, const char *c)
{
    size_t k = strlen(pl->notes);
    snprintf(pl->notes + k, sizeof pl->notes - k, fmt, a, b, c);
}

/* Whether method m models scene sc (file `file`); notes why not. */
static int models(cmp_plan *pl, const cmp_case *c, const gr_method_type *m, const gr_scene *sc, const char *file)
{
    gr_err e = {0};
    if (!gr_method_require_features(m, gr_scene_features(sc), file, &e))
        return 1;
    note(pl, "# %s: %s: not modelled: %s\n", c->name, m->name, e.msg);
    return 0;
}

static int push(cmp_plan *pl, size_t *cap, const cmp_unit *u, gr_err *err)
{
    if (pl->nunits == *cap) {
        size_t nc = *cap ? 2 * *cap : 64;
        cmp_unit *nu = realloc(pl->units, nc * sizeof *nu);
        if (!nu)
            return gr_fail(err, GR_ERUN, "out of memory");
        pl->units = nu, *cap = nc;
    }
    pl->units[pl->nunits++] = *u;
    return GR_OK;
}

/* The units of one row: each value, each seed. */
static int row_units(cmp_plan *pl, size_t *cap, const cmp_case *c, const cmp_row *r, gr_err *err)
{
    char buf[256];
    snprintf(buf, sizeof buf, "%s", pl->quick ? r->quick : r->full);
    int seeds = pl->quick ? c->seeds_quick : c->seeds_full;
    char *save = NULL, *v = r->knob ? strtok_r(buf, ",", &save) : buf;
    for (int k = 0; v && k < CMP_MAXV; k++, v = r->knob ? strtok_r(NULL, ",", &save) : NULL) {
        for (int s = 1; s <= seeds; s++) {
            cmp_unit u = {.c = c, .row = r, .seed = s};
            snprintf(u.value, sizeof u.value, "%.31s", r->knob ? v : "");
            if (push(pl, cap, &u, err))
                return err->code;
        }
    }
    return GR_OK;
}

/* The rows of method m in case c: those on the case's scene if m models
 * it, and those on their own variant scene if m models that. */
static int method_rows(cmp_plan *pl, size_t *cap, const cmp_case *c, const gr_method_type *m, const gr_scene *sc,
                       gr_err *err)
{
    int rows = 0, own = 0, rc = GR_OK;
    for (const cmp_row *r = c->rows; r->method; r++)
        if (!strcmp(r->method, m->name))
            rows++, own += r->scene != NULL;
    int on_case = rows > own && models(pl, c, m, sc, c->scene);
    if (!rows && models(pl, c, m, sc, c->scene))
        note(pl, "# %s: %s: models the scene; no row in the case table yet%s\n", c->name, m->name, "");
    for (const cmp_row *r = c->rows; r->method && !rc; r++) {
        if (strcmp(r->method, m->name))
            continue;
        if (!r->scene) {
            rc = on_case ? row_units(pl, cap, c, r, err) : GR_OK;
            continue;
        }
        cmp_unit probe = {.c = c, .row = r, .seed = 1};
        gr_scene *own_sc = cmp_unit_scene(pl, &probe, err);
        if (!own_sc)
            return err->code;
        if (models(pl, c, m, own_sc, r->scene)) {
            note(pl, "# %s: %s: runs its own scene %s (the method's own model of the case; "
                     "docs/comparison.md)\n", c->name, r->label, r->scene);
            rc = row_units(pl, cap, c, r, err);
        }
        gr_scene_free(own_sc);
    }
    return rc;
}

static int plan_case(cmp_plan *pl, size_t *cap, const cmp_case *c, const char *methods, gr_err *err)
{
    cmp_unit probe = {.c = c, .row = &c->rows[0], .seed = 1};
    gr_scene *sc = cmp_unit_scene(pl, &probe, err);
    if (!sc)
        return err->code;
    int rc = GR_OK;
    for (const gr_method_type *const *m = gr_method_all(); *m && !rc; m++)
        if (cmp_listed(methods, (*m)->name))
            rc = method_rows(pl, cap, c, *m, sc, err);
    for (const cmp_row *r = c->rows; r->method; r++)
        if (!gr_method_find(r->method))
            note(pl, "# %s: %s: not registered in this build%s\n", c->name, r->method, "");
    gr_scene_free(sc);
    return rc;
}

int cmp_plan_build(cmp_plan *pl, const char *cases, const char *methods, gr_err *err)
{
    size_t cap = 0;
    for (const cmp_case *c = cmp_plan_cases(pl); c->name; c++)
        if (cmp_listed(cases, c->name) && plan_case(pl, &cap, c, methods, err))
            return err->code;
    if (!pl->nunits)
        return gr_fail(err, GR_EINPUT, "no method of --methods has a row in the cases of --cases");
    return GR_OK;
}
