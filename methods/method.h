/* The backend interface, version 2 (docs/interface.md).
 *
 * A backend is a const table of functions (GSL's step types are the model)
 * with optional operations whose defaults are documented below (SUNDIALS's
 * ops tables are the model). Programs never hold a backend's state: they
 * hold a gr_sim, made by gr_sim_create, and call gr_sim_* functions, which
 * apply the defaults and refuse, by name, what a backend cannot give. */
#ifndef GR_METHOD_H
#define GR_METHOD_H

#include <stddef.h>
#include <stdint.h>

#include "ckpt.h"
#include "contacts.h"
#include "err.h"
#include "fields.h"
#include "observe.h"
#include "params.h"
#include "particles.h"
#include "rng.h"
#include "scene.h"

/* What a backend's state is made of. Both kinds give observables and
 * coarse-grained fields on the common grid; only particles give snapshots. */
typedef enum { GR_REPR_PARTICLES = 0, GR_REPR_LATTICE = 1 } gr_repr;

/* A named event count (collisions, events, iterations, ...). */
typedef struct {
    const char *name;
    uint64_t value;
} gr_counter;
#define GR_MAX_COUNTERS 16
/* Copy at most cap of the n counters into out; returns how many (for a
 * backend's counters operation). */
size_t gr_counters_put(gr_counter *out, size_t cap, const gr_counter *all, size_t n);

/* What create is handed besides the initial particles: the scene, the
 * values of the method's section (checked against its table), and the
 * instance, from which random streams are drawn (gr_sim_stream). */
typedef struct gr_sim gr_sim;
typedef struct {
    const gr_scene *scene;
    const gr_param_values *params;
    gr_sim *sim;
} gr_method_ctx;

typedef struct gr_method_type {
    const char *name;     /* "dem", "edmd", ...: also its scene section */
    const char *summary;  /* one line */
    gr_repr repr;
    unsigned features;    /* GR_FEAT_* the backend supports */
    const gr_param *params; /* its section's table, ended by a NULL name */
    /* What it measures, ended by a NULL name (common/observe.h): a run
     * writes exactly these, `grano methods NAME` lists them. Each counter
     * is declared (GR_OBS_DEF_COUNTER or, for a validity limit,
     * GR_OBS_DEF_LIMIT, at the position k its value takes in gr_obs.count).
     * [NULL: the common particle set, for a particle method] */
    const gr_obs_def *observables;

    /* ---- mandatory ---- */
    /* Build a state. Features outside `features` were refused and the
     * section checked against `params` before this is called. init holds
     * the scene's initial grains (a lattice backend may read occupations
     * from it; it is never NULL). */
    int (*create)(const gr_method_ctx *ctx, const gr_particles *init, void **state, gr_err *err);
    double (*time)(const void *state);
    /* Full state: load into a state created from the same scene continues
     * bit for bit as the uninterrupted run. Random streams handed out by
     * gr_sim_stream are saved by the instance, not here. */
    int (*save)(const void *state, gr_ckpt *ck, gr_err *err);
    int (*load)(void *state, gr_ckpt *ck, gr_err *err);
    void (*free)(void *state);

    /* ---- optional (NULL: the default in brackets) ---- */
    /* Advance until the time reaches t_end or max_steps steps (events) were
     * done, whichever is first; max_steps 0 = no limit. [step while
     * time < t_end - dt / 1e6: needs step and dt] */
    int (*advance)(void *state, double t_end, uint64_t max_steps, gr_err *err);
    /* Pure: observing twice gives the same numbers. Window quantities
     * (wall_pressure) are averages since the last reset_window. [particles:
     * the kinematic set from the snapshot, t from time, steps from the
     * counter "steps" (or "events"), outflow from the counter "outflow"] */
    int (*observe)(void *state, gr_obs *obs, gr_err *err);
    /* The fixed time step [none: event-driven, or advance of its own]. */
    double (*dt)(const void *state);
    /* Every grain in id order at time() [mandatory for GR_REPR_PARTICLES;
     * a lattice backend has none, and gr_sim_snapshot refuses by name]. */
    int (*snapshot)(void *state, gr_particles *out, gr_err *err);
    /* Accumulate the current state into f with weight w [particles: the
     * snapshot's mobile grains through gr_field_add]. */
    int (*fields)(void *state, gr_field *f, double w, gr_err *err);
    /* Fill at most cap counters, return how many [none]. */
    size_t (*counters)(const void *state, gr_counter *out, size_t cap);
    /* Start new averaging windows [nothing accumulates]. */
    void (*reset_window)(void *state);
    /* One time step or event [advance(t = inf, max_steps = 1)]. */
    int (*step)(void *state, gr_err *err);
    /* The contact network at time(): every contact that carries a force
     * (common/contacts.h) [none: `[run] contacts = yes` is refused]. */
    int (*contacts)(void *state, gr_contacts *out, gr_err *err);
    /* The stress averaged over the window since the previous call, which
     * starts a new one (reset on read): kinetic plus collisional, for a
     * method whose collisions are instantaneous and leave no contact
     * network (common/stress.h, gr_stress_acc). global[4] (xx, xy, yx, yy,
     * m tau-2, compression positive) is the mean of nx x ny cells tiling
     * the domain, given in cells[(iy * nx + ix) * 4 + c] when cells is not
     * NULL. The first call, or one on another grid, starts the window and
     * gives NaN. [none: `[run] stress = yes` needs contact networks] */
    int (*stress)(void *state, int nx, int ny, double global[4], double *cells, gr_err *err);
    /* What broke the validity limit counted by the declared counter `name`:
     * the value measured and the limit, in a phrase ("the mean of particles
     * per cell is 1.3, below 2") [the limit's description]. */
    void (*diagnose)(const void *state, const char *name, char *msg, size_t n);
} gr_method_type;

/* Optional operations, for gr_sim_require and `grano methods`. */
enum {
    GR_OP_SNAPSHOT = 1u << 0,
    GR_OP_FIELDS = 1u << 1,
    GR_OP_COUNTERS = 1u << 2,
    GR_OP_RESET_WINDOW = 1u << 3,
    GR_OP_STEP = 1u << 4,
    GR_OP_CONTACTS = 1u << 5,
    GR_OP_STRESS = 1u << 6,
    GR_OP_ADVANCE = 1u << 7,
    GR_OP_OBSERVE = 1u << 8
};
#define GR_OP_COUNT 9
/* Operations the backend implements itself (not by a default). */
unsigned gr_method_ops(const gr_method_type *m);
const char *gr_op_name(unsigned op_bit);

/* ---- registry (methods/registry.c) ---- */
const gr_method_type *gr_method_find(const char *name);
/* NULL-ended list of registered backends. */
const gr_method_type *const *gr_method_all(void);
/* Their names, NULL ended, for gr_scene_load's extra sections: fills at
 * most cap entries including the NULL. */
void gr_method_names(const char **names, size_t cap);
#define GR_MAX_METHODS 16
/* By name, or GR_EINPUT naming the nearest registered one; `who` is the
 * flag or key that asked ("--method"). */
int gr_method_lookup(const char *name, const char *who, const gr_method_type **out, gr_err *err);

/* ---- the instance (methods/sim.c) ---- */
/* Refuse scene features the backend lacks (naming the feature, and the
 * file, line and key that asked for it), read its section through its
 * parameter table, then create. */
int gr_sim_create(const gr_method_type *m, const gr_scene *sc, const gr_particles *init,
                  gr_sim **out, gr_err *err);
void gr_sim_free(gr_sim *s);

const gr_method_type *gr_sim_type(const gr_sim *s);
const gr_scene *gr_sim_scene(const gr_sim *s);
/* What create derived from the scene for the user to see (a hard method's
 * restitution from gamma_n, the soft DEM's gamma_n from a restitution):
 * create adds one phrase per derivation; the run prints them and keeps
 * them in the result's parameters/derived. "" when nothing was derived. */
void gr_sim_note(gr_sim *s, const char *phrase);
const char *gr_sim_notes(const gr_sim *s);
/* The note of a hard method's restitution (gr_scene_restitution), if any. */
void gr_sim_note_restitution(gr_sim *s, const gr_particles *init);
/* The backend's state: for its own per-method bench and tests only. */
void *gr_sim_state(gr_sim *s);

int gr_sim_advance(gr_sim *s, double t_end, uint64_t max_steps, gr_err *err);
int gr_sim_step(gr_sim *s, gr_err *err);
double gr_sim_time(const gr_sim *s);
int gr_sim_observe(gr_sim *s, gr_obs *obs, gr_err *err);
void gr_sim_reset_window(gr_sim *s);
int gr_sim_snapshot(gr_sim *s, gr_particles *out, gr_err *err);
int gr_sim_fields(gr_sim *s, gr_field *f, double w, gr_err *err);
size_t gr_sim_counters(const gr_sim *s, gr_counter *out, size_t cap);
/* The counter of that name: 1 and its value, or 0 when the method has none. */
int gr_sim_counter(const gr_sim *s, const char *name, uint64_t *value);
int gr_sim_contacts(gr_sim *s, gr_contacts *out, gr_err *err);
/* The backend's window-averaged stress (see the table), or GR_EINPUT
 * naming the method if it has none. */
int gr_sim_stress(gr_sim *s, int nx, int ny, double global[4], double *cells, gr_err *err);
/* The observables the method declares (its table, or the particle set). */
const gr_obs_def *gr_method_observables(const gr_method_type *m);
const gr_obs_def *gr_sim_observables(const gr_sim *s);
/* Bit k: observable k does not exist in this scene (GR_OBS_NEEDS_*). */
uint64_t gr_sim_obs_skip(const gr_sim *s);

/* A validity limit broken during the run: the declared limit counter
 * `name`, the key that changes it, how many steps broke it, and what the
 * method measured. */
typedef struct {
    size_t index;   /* its position among the declared observables */
    const char *name, *key, *doc;
    uint64_t count;
    char detail[256];
} gr_diag;
/* The broken limits (count > 0), at most cap of them. */
size_t gr_sim_diagnostics(gr_sim *s, gr_diag *out, size_t cap);

/* GR_EINPUT if the backend lacks any of ops (GR_OP_*): "<who> needs <op>,
 * which method '<name>' does not give". */
int gr_sim_require(const gr_method_type *m, unsigned ops, const char *who, gr_err *err);
/* GR_EINPUT if the backend lacks any of features (GR_FEAT_*), naming the
 * first one and `who`. */
int gr_method_require_features(const gr_method_type *m, unsigned features, const char *who,
                               gr_err *err);

/* Random stream k of the backend (k < 0x10000), from the scene seed and
 * GR_STREAM_METHOD_BASE + k. Owned by the instance, saved and restored
 * with it. */
gr_rng *gr_sim_stream(gr_sim *s, uint64_t id, gr_err *err);
/* The stream of the common table (rng.h) with that id, owned and saved
 * likewise: for a backend whose stream predates its numbering (dem's
 * reinsertion, edmd's floor and reinsertion), so its draws stay the same. */
gr_rng *gr_sim_stream_id(gr_sim *s, uint64_t id, gr_err *err);

/* Full state: the parameter values (a load compares them and names the
 * first that differs), the random streams, then the backend's save. */
int gr_sim_save(const gr_sim *s, gr_ckpt *ck, gr_err *err);
int gr_sim_load(gr_sim *s, gr_ckpt *ck, gr_err *err);

#endif
