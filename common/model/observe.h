/* Observables: what a method measures of its state, sample by sample.
 * gr_obs holds one sample; a method declares which of its members it gives
 * (a gr_obs_def table in its type, methods/method.h), and a result file
 * holds exactly those. The common particle set below is the default of
 * particle methods. */
#ifndef GR_OBSERVE_H
#define GR_OBSERVE_H

#include <stddef.h>
#include <stdint.h>

#include "particles.h"

/* Declared observables of one method at most; also the size of the slots a
 * method fills by its declaration's position (count[], extra[]). */
#define GR_OBS_MAX 32

typedef struct {
    double t;
    uint64_t steps;         /* time steps, or events for event-driven methods */
    uint64_t n_mobile;
    double ekin_trans, ekin_rot; /* totals over mobile grains */
    double epot_grav;            /* m g y summed over mobile grains */
    double temperature;     /* granular temperature: <m |v - <v>|^2> / 2 per grain */
    double px, py;          /* total momentum of mobile grains (adjacent: one 2-vector) */
    uint64_t outflow;       /* grains that left through the orifice since t = 0 */
    double wall_pressure;   /* average since the last window reset; NaN while the window is empty */
    double max_overlap;     /* soft methods, in diameters */
    /* By the position k of its declaration: a counter (GR_OBS_COUNTER, filled
     * by gr_sim_observe from the method's counter of the same name) or a
     * quantity of the method's own (GR_OBS_EXTRA, filled by its observe). */
    uint64_t count[GR_OBS_MAX];
    double extra[GR_OBS_MAX][2];
} gr_obs;

/* Where a declared observable's value is in a gr_obs. */
typedef enum {
    GR_OBS_FIELD = 0, /* the member at off: a double (ncomp of them) or, integer, a uint64_t */
    GR_OBS_COUNTER,   /* count[k]: the method's counter of the same name */
    GR_OBS_EXTRA      /* extra[k][0 .. ncomp-1] */
} gr_obs_src;

typedef struct {
    const char *name;  /* observables/<name> */
    const char *unit;  /* H5MD unit string ("1": a pure number) */
    int ncomp;         /* 1, or 2 (x, y) */
    int integer;       /* a count: int64 in the file */
    gr_obs_src src;
    size_t off;        /* GR_OBS_FIELD: offsetof(gr_obs, member) */
    const char *doc;   /* its meaning, one line */
    /* A validity limit: the counter counts the steps that broke it, and
     * key ("section.key") is what changes the limit. NULL otherwise. */
    const char *key;
    /* GR_OBS_NEEDS_*: what a scene must have for the quantity to exist; a
     * run of a scene without it does not write it (a frictionless scene
     * has no rotation, a scene without walls no wall pressure). */
    unsigned needs;
} gr_obs_def;

enum { GR_OBS_NEEDS_ROTATION = 1u, GR_OBS_NEEDS_WALLS = 2u, GR_OBS_NEEDS_ORIFICE = 4u };

/* Initialisers of the common particle set, for a method's table. */
#define GR_OBS_DEF_F(name, unit, member, nc, doc) GR_OBS_DEF_FN(name, unit, member, nc, doc, 0)
#define GR_OBS_DEF_FN(name, unit, member, nc, doc, needs) \
    {name, unit, nc, 0, GR_OBS_FIELD, offsetof(gr_obs, member), doc, NULL, needs}
#define GR_OBS_DEF_U(name, member, doc, needs) {name, "1", 1, 1, GR_OBS_FIELD, offsetof(gr_obs, member), doc, NULL, needs}
#define GR_OBS_N_MOBILE GR_OBS_DEF_U("n_mobile", n_mobile, "grains that move (not fixed, not gone)", 0)
#define GR_OBS_EKIN_TRANS GR_OBS_DEF_F("ekin_trans", "m d+2 tau-2", ekin_trans, 1, "translational kinetic energy of the mobile grains")
#define GR_OBS_EKIN_ROT GR_OBS_DEF_FN("ekin_rot", "m d+2 tau-2", ekin_rot, 1, "rotational kinetic energy of the mobile grains", GR_OBS_NEEDS_ROTATION)
#define GR_OBS_EPOT_GRAV GR_OBS_DEF_F("epot_grav", "m d+2 tau-2", epot_grav, 1, "gravitational potential energy m g y")
#define GR_OBS_TEMPERATURE GR_OBS_DEF_F("temperature", "m d+2 tau-2", temperature, 1, "granular temperature per grain, m <(v - <v>)^2> / 2")
#define GR_OBS_MOMENTUM GR_OBS_DEF_F("momentum", "m d tau-1", px, 2, "total momentum of the mobile grains")
#define GR_OBS_OUTFLOW GR_OBS_DEF_U("outflow", outflow, "grains that left through the orifice since t = 0", GR_OBS_NEEDS_ORIFICE)
#define GR_OBS_WALL_PRESSURE GR_OBS_DEF_FN("wall_pressure", "m tau-2", wall_pressure, 1, "force per unit length on the walls, averaged since the previous sample", GR_OBS_NEEDS_WALLS)
#define GR_OBS_MAX_OVERLAP GR_OBS_DEF_F("max_overlap", "d", max_overlap, 1, "largest overlap of two grains (or a grain and a wall)")
/* A counter or a quantity of the method's own, at position k of its table. */
#define GR_OBS_DEF_COUNTER(name, doc) {name, "1", 1, 1, GR_OBS_COUNTER, 0, doc, NULL, 0}
#define GR_OBS_DEF_LIMIT(name, key, doc) {name, "1", 1, 1, GR_OBS_COUNTER, 0, doc, key, 0}
#define GR_OBS_DEF_EXTRA(name, unit, nc, doc) {name, unit, nc, 0, GR_OBS_EXTRA, 0, doc, NULL, 0}
#define GR_OBS_DEF_END {NULL, NULL, 0, 0, GR_OBS_FIELD, 0, NULL, NULL, 0}

/* The common particle set, NULL-name ended: what a particle method without
 * a table of its own declares. */
extern const gr_obs_def gr_obs_particle_set[];

/* How many entries a table has before its end. */
size_t gr_obs_count(const gr_obs_def *defs);
/* The value of defs[k] in o: ncomp doubles, or one uint64_t if integer. */
const void *gr_obs_value(const gr_obs *o, const gr_obs_def *defs, size_t k);

/* Fill the kinematic observables from a particle snapshot; leaves t, steps,
 * outflow, wall_pressure, max_overlap untouched. */
void gr_obs_from_particles(const gr_particles *p, double gravity, gr_obs *o);
void gr_obs_clear(gr_obs *o);

#endif
