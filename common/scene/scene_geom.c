/* The scene's geometry: the vibrating floor, the [wall.*] segments and the
 * silo (box, orifice, hopper, reinsertion band) with the segments it
 * stands for. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scene.h"
#include "scene_get.h"
#include "scene_impl.h"

static const char *const floor_names[] = {"fixed", "sine", "sawtooth", "sine-hf", "sawtooth-hf", NULL};
static const char *const walls_names[] = {"segments", "grains", NULL};

static int read_floor(gr_scene *sc, gr_err *err)
{
    int v;
    if (gr_scene_get_choice(sc, "floor", "motion", floor_names, GR_FLOOR_FIXED, &v, err))
        return err->code;
    sc->floor.motion = (gr_floor_motion)v;
    if (NONNEG("floor", "amplitude", 0.0, &sc->floor.amplitude) ||
        NONNEG("floor", "omega", 0.0, &sc->floor.omega))
        return err->code;
    if (sc->floor.motion != GR_FLOOR_FIXED) {
        if (sc->side[GR_BOTTOM] != GR_BC_WALL)
            return gr_scene_entry_fail(sc, "floor", "motion", err, "a vibrating floor needs [domain] bottom = wall");
        if (!(sc->floor.amplitude > 0) || !(sc->floor.omega > 0))
            return gr_scene_entry_fail(sc, "floor", "motion", err, "a vibrating floor needs amplitude > 0 and omega > 0");
    }
    return GR_OK;
}

static int add_segment(gr_scene *sc, gr_segment s, gr_err *err)
{
    gr_segment *q = realloc(sc->segments, (size_t)(sc->nsegments + 1) * sizeof *q);
    if (!q)
        return gr_fail(err, GR_ERUN, "out of memory");
    sc->segments = q;
    sc->segments[sc->nsegments++] = s;
    return GR_OK;
}

static int read_walls(gr_scene *sc, gr_err *err)
{
    for (size_t i = 0; i < sc->nentries; i++) {
        const char *sec = sc->entries[i].section;
        if (strcmp(gr_scene_section_kind(sec), "wall"))
            continue;
        /* Once per wall: at its header, the section's first entry. */
        if (sc->entries[i].key[0])
            continue;
        double a[2], b[2];
        int fa, fb, vib;
        if (gr_scene_get_vec(sc, sec, "from", 2, a, &fa, err) || gr_scene_get_vec(sc, sec, "to", 2, b, &fb, err))
            return err->code;
        if (!fa || !fb)
            return gr_scene_entry_fail(sc, sec, fa ? "to" : "from", err, "a wall needs 'from = x y' and 'to = x y'");
        if (a[0] == b[0] && a[1] == b[1])
            return gr_scene_entry_fail(sc, sec, "to", err, "a wall needs two distinct end points");
        if (sc->nsegments >= GR_SCENE_MAX_WALLS)
            return gr_scene_entry_fail(sc, sec, "from", err, "more than " GR_STR(GR_SCENE_MAX_WALLS)
                              " walls, the most grano is tested with (docs/reliability.md)");
        gr_segment s = {a[0], a[1], b[0], b[1], INFINITY, 0, sc->entries[i].line};
        if (NONNEG(sec, "open_time", INFINITY, &s.open_time) || gr_scene_get_yesno(sc, sec, "vibrating", 0, &vib, err))
            return err->code;
        s.vibrating = vib;
        if (add_segment(sc, s, err))
            return err->code;
    }
    return GR_OK;
}

/* The silo's box and orifice; margin is the thickness of its walls. */
static int read_silo_box(gr_scene *sc, double margin, gr_err *err)
{
    gr_silo *s = &sc->silo;
    if (POSITIVE("silo", "width", sc->width - 2 * margin, &s->width) ||
        POSITIVE("silo", "height", 0.0, &s->height) ||
        ANYNUM("silo", "left", 0.5 * (sc->width - s->width), &s->x0) ||
        ANYNUM("silo", "base", 0.0, &s->base) ||
        POSITIVE("silo", "orifice", 0.0, &s->orifice) ||
        ANYNUM("silo", "orifice_center", s->x0 + 0.5 * s->width, &s->orifice_center) ||
        NONNEG("silo", "open_time", INFINITY, &s->open_time))
        return err->code;
    if (!gr_scene_find(sc, "silo", "height") || !gr_scene_find(sc, "silo", "orifice") ||
        !gr_scene_find(sc, "silo", "base"))
        return gr_scene_entry_fail(sc, "silo", !gr_scene_find(sc, "silo", "height") ? "height"
                                      : !gr_scene_find(sc, "silo", "base") ? "base" : "orifice",
                          err, "[silo] needs 'height', 'base' and 'orifice'");
    if (s->orifice > s->width)
        return gr_scene_entry_fail(sc, "silo", "orifice", err, "the orifice is wider than the silo base");
    if (s->orifice_center - 0.5 * s->orifice < s->x0 || s->orifice_center + 0.5 * s->orifice > s->x0 + s->width)
        return gr_scene_entry_fail(sc, "silo", "orifice_center", err, "the orifice reaches past the silo walls");
    if (s->x0 - margin < 0 || s->x0 + s->width + margin > sc->width || s->base - margin < 0 ||
        s->base + s->height > sc->height)
        return gr_scene_entry_fail(sc, "silo", "width", err, "the silo (with its walls) does not fit in the domain");
    return GR_OK;
}

/* The hopper above the silo, the reinsertion band and the exit line;
 * d is the largest grain diameter. */
static int read_silo_flow(gr_scene *sc, double d, gr_err *err)
{
    gr_silo *s = &sc->silo;
    if (gr_scene_get_yesno(sc, "silo", "hopper", 0, &s->hopper, err) ||
        POSITIVE("silo", "hopper_outlet", 0.3 * s->width, &s->hopper_outlet) ||
        ANYNUM("silo", "hopper_bottom", s->base + s->height + 2 * d, &s->hopper_bottom) ||
        ANYNUM("silo", "hopper_top", s->hopper_bottom + 0.25 * s->width, &s->hopper_top) ||
        gr_scene_get_yesno(sc, "silo", "reinsert", 0, &s->reinsert, err) ||
        ANYNUM("silo", "reinsert_top", s->base + s->height - d, &s->reinsert_top) ||
        ANYNUM("silo", "reinsert_bottom", s->reinsert_top - 4 * d, &s->reinsert_bottom) ||
        ANYNUM("silo", "exit_below", s->base - 2 * d, &s->exit_below))
        return err->code;
    if (s->hopper) {
        if (s->hopper_outlet > s->width)
            return gr_scene_entry_fail(sc, "silo", "hopper_outlet", err, "the hopper outlet is wider than the silo");
        if (!(s->hopper_top > s->hopper_bottom) || s->hopper_top > sc->height)
            return gr_scene_entry_fail(sc, "silo", "hopper_top", err,
                              "the hopper rim must lie above its outlet and inside the domain");
    }
    if (s->reinsert && !(s->reinsert_top - s->reinsert_bottom >= d))
        return gr_scene_entry_fail(sc, "silo", "reinsert_bottom", err, "the reinsertion band must be at least one diameter tall");
    if (s->exit_below > s->base)
        return gr_scene_entry_fail(sc, "silo", "exit_below", err, "grains must leave below the silo base");
    return GR_OK;
}

/* The silo's side walls, base (the orifice piece opens at open_time)
 * and hopper as wall segments. */
static int add_silo_segments(gr_scene *sc, gr_err *err)
{
    const gr_silo *s = &sc->silo;
    double x0 = s->x0, x1 = s->x0 + s->width, y0 = s->base, y1 = s->base + s->height;
    double ol = s->orifice_center - 0.5 * s->orifice, orr = s->orifice_center + 0.5 * s->orifice;
    gr_segment segs[6] = {
        {x0, y0, x0, y1, INFINITY, 0, 0}, {x1, y0, x1, y1, INFINITY, 0, 0},
        {x0, y0, ol, y0, INFINITY, 0, 0}, {orr, y0, x1, y0, INFINITY, 0, 0},
        {ol, y0, orr, y0, s->open_time, 0, 0},
        {0, 0, 0, 0, 0, 0, 0}};
    int nseg = 5;
    for (int k = 0; k < nseg; k++) {
        /* Zero-length base pieces when the orifice touches a wall. */
        if (segs[k].x0 == segs[k].x1 && segs[k].y0 == segs[k].y1)
            continue;
        if (add_segment(sc, segs[k], err))
            return err->code;
    }
    if (s->hopper) {
        double c = s->orifice_center, h = 0.5 * s->hopper_outlet;
        gr_segment hl = {x0, s->hopper_top, c - h, s->hopper_bottom, INFINITY, 0, 0};
        gr_segment hr = {c + h, s->hopper_bottom, x1, s->hopper_top, INFINITY, 0, 0};
        if (add_segment(sc, hl, err) || add_segment(sc, hr, err))
            return err->code;
    }
    return GR_OK;
}

static int read_silo(gr_scene *sc, gr_err *err)
{
    gr_silo *s = &sc->silo;
    s->present = 0;
    for (size_t i = 0; i < sc->nentries; i++)
        s->present |= !strcmp(sc->entries[i].section, "silo");
    if (!s->present)
        return GR_OK;
    double d = gr_scene_max_diameter(sc);
    int v;
    if (gr_scene_get_choice(sc, "silo", "walls", walls_names, GR_WALLS_SEGMENTS, &v, err))
        return err->code;
    s->walls = (gr_wall_kind)v;
    double margin = s->walls == GR_WALLS_GRAINS ? d : 0.0;
    int rc = read_silo_box(sc, margin, err);
    if (!rc)
        rc = read_silo_flow(sc, d, err);
    if (rc || s->walls != GR_WALLS_SEGMENTS)
        return rc;
    return add_silo_segments(sc, err);
}

int gr_scene_read_geometry(gr_scene *sc, gr_err *err)
{
    if (read_floor(sc, err) || read_walls(sc, err) || read_silo(sc, err))
        return err->code;
    return GR_OK;
}
