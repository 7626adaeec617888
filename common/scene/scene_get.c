/* The scene reader's typed getters with range checks, its error naming
 * file, line and key, and the counts over species: shared by scene.c and
 * scene_geom.c, calling only scene_parse.c. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "scene.h"
#include "scene_get.h"
#include "scene_impl.h"

static const char *const yesno_names[] = {"no", "yes", NULL};

/* Typed getters with a range check; the message names file, line and key. */
int gr_scene_get_num(const gr_scene *sc, const char *s, const char *k, double def,
                   double lo, int lo_open, double hi, double *out, gr_err *err)
{
    if (gr_scene_get_double(sc, s, k, def, out, err))
        return err->code;
    const gr_scene_entry *e = gr_scene_find(sc, s, k);
    if (!e)
        return GR_OK;
    if (fabs(*out) > GR_SCENE_MAX_MAGNITUDE)
        return gr_fail(err, GR_EINPUT, "%s:%d: [%s] key '%s': %s is beyond +-%g (energies and products would overflow)",
                       sc->path, e->line, s, k, e->value, GR_SCENE_MAX_MAGNITUDE);
    int bad_lo = lo_open ? !(*out > lo) : !(*out >= lo);
    if (bad_lo || *out > hi) {
        if (isinf(hi))
            return gr_fail(err, GR_EINPUT, "%s:%d: [%s] key '%s': must be %s %g, got %s",
                           sc->path, e->line, s, k, lo_open ? ">" : ">=", lo, e->value);
        return gr_fail(err, GR_EINPUT, "%s:%d: [%s] key '%s': must be in %s%g, %g], got %s",
                       sc->path, e->line, s, k, lo_open ? "(" : "[", lo, hi, e->value);
    }
    return GR_OK;
}

int gr_scene_get_yesno(const gr_scene *sc, const char *s, const char *k, int def, int *out, gr_err *err)
{
    return gr_scene_get_choice(sc, s, k, yesno_names, def, out, err);
}

int gr_scene_entry_fail(const gr_scene *sc, const char *s, const char *k, gr_err *err, const char *what)
{
    char where[1200];
    gr_scene_where(sc, s, k, where, sizeof where);
    return gr_fail(err, GR_EINPUT, "%s: %s", where, what);
}

int gr_scene_no_grains(const gr_scene *sc, gr_err *err)
{
    if (gr_scene_find(sc, "init", "kind"))
        return gr_scene_entry_fail(sc, "init", "kind", err,
                                   "the scene has no grains (a particle method needs [species] count or a file of grains)");
    return gr_scene_entry_fail(sc, "species", "count", err, "the scene has no grains");
}

/* Which section does a name belong to: "species.big" -> "species". */
const char *gr_scene_section_kind(const char *name)
{
    if (!strncmp(name, "species.", 8))
        return "species";
    if (!strncmp(name, "wall.", 5))
        return "wall";
    return name;
}

long gr_scene_count(const gr_scene *sc)
{
    long n = 0;
    for (int k = 0; k < sc->nspecies; k++)
        n += sc->species[k].count;
    return n;
}

double gr_scene_max_diameter(const gr_scene *sc)
{
    double d = 0;
    for (int k = 0; k < sc->nspecies; k++) {
        double dk = sc->species[k].diameter * (1.0 + sc->species[k].polydispersity);
        if (dk > d)
            d = dk;
    }
    return d > 0 ? d : 1.0;
}
