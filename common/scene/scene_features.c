/* Which features a scene uses, and where in the file each was asked for. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "scene.h"

typedef struct {
    unsigned bit;
    const char *name;
    const char *section, *key; /* the key that brings it in */
} feature_info;

static const feature_info features[GR_FEAT_COUNT] = {
    {GR_FEAT_GRAVITY, "gravity", "domain", "gravity"},
    {GR_FEAT_FRICTION, "friction (tangential forces or rough collisions)", "material", "tangential"},
    {GR_FEAT_CONTACT_HISTORY, "static friction with a tangential spring (contact history)", "material", "tangential"},
    {GR_FEAT_PERIODIC, "periodic sides", "domain", "left"},
    {GR_FEAT_OPEN_SIDE, "open sides", "domain", "bottom"},
    {GR_FEAT_SEGMENTS, "wall segments", "silo", "walls"},
    {GR_FEAT_WALL_GRAINS, "walls made of fixed grains", "silo", "walls"},
    {GR_FEAT_ORIFICE, "an orifice that opens at a time", "silo", "open_time"},
    {GR_FEAT_VIBRATING_FLOOR, "a vibrating floor", "floor", "motion"},
    {GR_FEAT_REINSERT, "reinsertion of grains that leave", "silo", "reinsert"},
    {GR_FEAT_POLYDISPERSE, "polydisperse grains", "species", "polydispersity"},
    {GR_FEAT_MIXTURE, "several species", "species", "diameter"},
    {GR_FEAT_HERTZ, "the Hertz normal force", "material", "normal"},
    {GR_FEAT_HF_FLOOR, "a high-frequency floor limit", "floor", "motion"},
    {GR_FEAT_WEIGHTS, "particle weights (a simulated particle standing for several grains)", "species", "weight"},
    {GR_FEAT_RESTITUTION, "a normal restitution coefficient", "material", "restitution"},
    {GR_FEAT_LATTICE, "a lattice state (initial condition given as channel occupations)", "init", "kind"},
    {GR_FEAT_SOFT_TANGENTIAL, "a viscous or regularised tangential force (a soft-contact law)", "material",
     "tangential"},
};

unsigned gr_scene_features(const gr_scene *sc)
{
    unsigned f = 0;
    const gr_material *m = &sc->mat;
    if (sc->gravity > 0)
        f |= GR_FEAT_GRAVITY;
    if (m->tangential != GR_TANG_NONE || (!isnan(m->tangential_restitution) && m->tangential_restitution != -1.0))
        f |= GR_FEAT_FRICTION;
    if (m->tangential == GR_TANG_SPRING)
        f |= GR_FEAT_CONTACT_HISTORY;
    if (m->tangential == GR_TANG_VISCOUS || m->tangential == GR_TANG_REGULARISED)
        f |= GR_FEAT_SOFT_TANGENTIAL;
    for (int s = 0; s < 4; s++) {
        if (sc->side[s] == GR_BC_PERIODIC)
            f |= GR_FEAT_PERIODIC;
        if (sc->side[s] == GR_BC_OPEN)
            f |= GR_FEAT_OPEN_SIDE;
    }
    if (sc->nsegments > 0)
        f |= GR_FEAT_SEGMENTS;
    for (int i = 0; i < sc->nsegments; i++)
        if (isfinite(sc->segments[i].open_time))
            f |= GR_FEAT_ORIFICE;
    if (sc->silo.present) {
        if (sc->silo.walls == GR_WALLS_GRAINS)
            f |= GR_FEAT_WALL_GRAINS;
        if (isfinite(sc->silo.open_time))
            f |= GR_FEAT_ORIFICE;
        if (sc->silo.reinsert)
            f |= GR_FEAT_REINSERT;
    }
    if (sc->floor.motion == GR_FLOOR_SINE || sc->floor.motion == GR_FLOOR_SAWTOOTH)
        f |= GR_FEAT_VIBRATING_FLOOR;
    if (sc->floor.motion == GR_FLOOR_SINE_HF || sc->floor.motion == GR_FLOOR_SAWTOOTH_HF)
        f |= GR_FEAT_HF_FLOOR;
    for (int k = 0; k < sc->nspecies; k++)
        if (sc->species[k].polydispersity > 0)
            f |= GR_FEAT_POLYDISPERSE;
    if (sc->nspecies > 1)
        f |= GR_FEAT_MIXTURE;
    for (int k = 0; k < sc->nspecies; k++)
        if (sc->species[k].weight != 1.0)
            f |= GR_FEAT_WEIGHTS;
    if (m->normal == GR_NORMAL_HERTZ)
        f |= GR_FEAT_HERTZ;
    if (!isnan(m->restitution) || !isnan(m->wall_restitution))
        f |= GR_FEAT_RESTITUTION;
    if (sc->init.kind == GR_INIT_OCCUPATION)
        f |= GR_FEAT_LATTICE;
    return f;
}

const char *gr_feature_name(unsigned bit)
{
    for (int i = 0; i < GR_FEAT_COUNT; i++)
        if (features[i].bit == bit)
            return features[i].name;
    return "an unknown feature";
}

int gr_feature_known(unsigned bit)
{
    for (int i = 0; i < GR_FEAT_COUNT; i++)
        if (features[i].bit == bit && features[i].name)
            return 1;
    return 0;
}

/* The first entry of the file that brings the feature in. */
static const gr_scene_entry *feature_entry(const gr_scene *sc, unsigned bit)
{
    const gr_scene_entry *e = NULL;
    switch (bit) {
    case GR_FEAT_PERIODIC:
    case GR_FEAT_OPEN_SIDE: {
        static const char *const sides[] = {"left", "right", "bottom", "top"};
        const char *want = bit == GR_FEAT_PERIODIC ? "periodic" : "open";
        for (int s = 0; s < 4 && !e; s++) {
            const gr_scene_entry *c = gr_scene_find(sc, "domain", sides[s]);
            if (c && !strcmp(c->value, want))
                e = c;
        }
        return e;
    }
    case GR_FEAT_FRICTION:
        e = gr_scene_find(sc, "material", "tangential");
        return e ? e : gr_scene_find(sc, "material", "tangential_restitution");
    case GR_FEAT_RESTITUTION:
        e = gr_scene_find(sc, "material", "restitution");
        return e ? e : gr_scene_find(sc, "material", "wall_restitution");
    case GR_FEAT_POLYDISPERSE:
    case GR_FEAT_MIXTURE:
    case GR_FEAT_WEIGHTS:
        for (size_t i = 0; i < sc->nentries && !e; i++)
            if (!strncmp(sc->entries[i].section, "species", 7) &&
                !strcmp(sc->entries[i].key, bit == GR_FEAT_MIXTURE  ? "count"
                                            : bit == GR_FEAT_WEIGHTS ? "weight"
                                                                     : "polydispersity"))
                e = &sc->entries[i];
        return e;
    case GR_FEAT_SEGMENTS:
        for (size_t i = 0; i < sc->nentries && !e; i++)
            if (!strncmp(sc->entries[i].section, "wall.", 5))
                e = &sc->entries[i];
        return e ? e : gr_scene_find(sc, "silo", "walls") ? gr_scene_find(sc, "silo", "walls")
                                                          : gr_scene_find(sc, "silo", "orifice");
    case GR_FEAT_ORIFICE:
        e = gr_scene_find(sc, "silo", "open_time");
        for (size_t i = 0; i < sc->nentries && !e; i++)
            if (!strncmp(sc->entries[i].section, "wall.", 5) && !strcmp(sc->entries[i].key, "open_time"))
                e = &sc->entries[i];
        return e;
    default:
        for (int i = 0; i < GR_FEAT_COUNT; i++)
            if (features[i].bit == bit)
                return gr_scene_find(sc, features[i].section, features[i].key);
        return NULL;
    }
}

void gr_scene_feature_where(const gr_scene *sc, unsigned bit, char *buf, size_t n)
{
    const gr_scene_entry *e = feature_entry(sc, bit);
    if (e)
        snprintf(buf, n, "%s:%d: [%s] key '%s'", sc->path, e->line, e->section, e->key);
    else
        snprintf(buf, n, "%s", sc->path);
}

/* All of them at once: a user learns in one attempt everything a method
 * lacks for this scene. */
int gr_scene_refuse_features(const gr_scene *sc, unsigned missing, const char *who, gr_err *err)
{
    int n = 0;
    for (unsigned b = 0; b < GR_FEAT_COUNT; b++)
        n += (missing >> b) & 1u;
    if (!n)
        return GR_OK;
    if (n == 1) {
        unsigned b = 0;
        while (!(missing & (1u << b)))
            b++;
        char where[900];
        gr_scene_feature_where(sc, 1u << b, where, sizeof where);
        return gr_fail(err, GR_EINPUT, "%s: %s does not support %s", where, who, gr_feature_name(1u << b));
    }
    char list[900] = "";
    size_t len = 0;
    for (unsigned b = 0; b < GR_FEAT_COUNT && len < sizeof list; b++) {
        if (!(missing & (1u << b)))
            continue;
        char where[600];
        gr_scene_feature_where(sc, 1u << b, where, sizeof where);
        len += (size_t)snprintf(list + len, sizeof list - len, "\n  %s: %s", where, gr_feature_name(1u << b));
    }
    return gr_fail(err, GR_EINPUT, "%s: %s does not support %d feature%s of this scene:%s", sc->path, who, n,
                   n > 1 ? "s" : "", list);
}
