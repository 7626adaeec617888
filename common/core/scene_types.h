/* The scene's plain types: the domain, walls, materials, species, initial
 * condition and run control as the scene reader fills them
 * (scene/scene.h). Here, below every other room, so that geometry, output
 * and checkpoints take a scene without reaching up to its reader. */
#ifndef GR_SCENE_TYPES_H
#define GR_SCENE_TYPES_H

#include <stddef.h>
#include <stdint.h>

enum { GR_LEFT = 0, GR_RIGHT = 1, GR_BOTTOM = 2, GR_TOP = 3 };
typedef enum { GR_BC_WALL = 0, GR_BC_PERIODIC, GR_BC_OPEN } gr_bc;

typedef enum { GR_NORMAL_LINEAR = 0, GR_NORMAL_HERTZ } gr_normal_law;
typedef enum {
    GR_TANG_NONE = 0,    /* frictionless */
    GR_TANG_COULOMB,     /* -mu|Fn| sign(vt), eq. 2.6 */
    GR_TANG_VISCOUS,     /* -gamma_t vt, eq. 2.8 */
    GR_TANG_REGULARISED, /* -min(mu|Fn|, gamma_t|vt|) sign(vt), eq. 2.9 */
    GR_TANG_SPRING       /* static friction, tangential spring zeta, eqs. 2.10-2.12 */
} gr_tang_law;

typedef struct {
    gr_normal_law normal;
    gr_tang_law tangential;
    double kn, gamma_n;     /* soft methods: stiffness, normal damping */
    double kt, gamma_t;     /* tangential spring and damping */
    double mu;              /* Coulomb friction coefficient */
    double restitution;     /* normal restitution for hard methods; NaN if unset */
    double tangential_restitution; /* beta in [-1, 1]; -1 = smooth; NaN if unset */
    double wall_restitution;       /* hard walls; NaN = same as restitution */
    int clip_attraction;    /* soft methods: no attractive normal force (default 1) */
} gr_material;

#define GR_MAX_SPECIES 4
typedef struct {
    char name[32];
    double diameter;       /* mean diameter */
    double polydispersity; /* diameters uniform in d(1 +- p) */
    double density;        /* areal: mass = density * pi d^2 / 4 */
    long count;            /* mobile grains of this species */
    double weight;         /* real grains each simulated particle stands for
                              (DSMC); 1 everywhere else */
} gr_species;

/* A wall segment of infinite mass. A gate (open_time finite) vanishes at
 * open_time; a vibrating segment moves vertically with the floor motion. */
typedef struct {
    double x0, y0, x1, y1;
    double open_time;  /* INFINITY: never opens */
    int vibrating;     /* follows the floor motion */
    int line;          /* scene-file line that made it, 0 if derived */
} gr_segment;

typedef enum {
    GR_FLOOR_FIXED = 0,
    GR_FLOOR_SINE,      /* y = A cos(omega t) */
    GR_FLOOR_SAWTOOTH,  /* y = A (1 - 2 frac(omega t / 2 pi)) ... see geom.h */
    GR_FLOOR_SINE_HF,   /* high-frequency limit: floor at y = 0, velocity A omega cos(random phase) */
    GR_FLOOR_SAWTOOTH_HF /* high-frequency limit: v' = 2 Vp - v */
} gr_floor_motion;

typedef struct {
    gr_floor_motion motion;
    double amplitude, omega;
} gr_floor;

typedef enum { GR_WALLS_SEGMENTS = 0, GR_WALLS_GRAINS } gr_wall_kind;

typedef struct {
    int present;
    double width, height;   /* container, inner size */
    double x0, base;        /* left inner edge and base height */
    double orifice;         /* width D of the orifice */
    double orifice_center;  /* x of its centre */
    double open_time;       /* the orifice opens at this time (INFINITY: closed) */
    gr_wall_kind walls;
    int hopper;             /* a filling hopper above the container */
    double hopper_outlet;   /* width of the hopper's outlet */
    double hopper_bottom, hopper_top; /* heights of its outlet and its rim */
    int reinsert;           /* grains that leave are reinserted at the top */
    double reinsert_bottom, reinsert_top; /* band where they are reinserted */
    double exit_below;      /* grains below this height have left */
} gr_silo;

/* GR_INIT_OCCUPATION: no grains; a lattice backend fills its channels at
 * random with the mean occupations below (docs/scene-format.md). */
typedef enum { GR_INIT_LATTICE = 0, GR_INIT_RANDOM, GR_INIT_FILE, GR_INIT_OCCUPATION } gr_init_kind;
/* Overlapping grains at the start (a soft packing read from a file): left
 * as they are (a hard method refuses them, naming the key), or pushed
 * apart (common/scene/init_overlap.c). */
typedef enum { GR_OVERLAP_REFUSE = 0, GR_OVERLAP_PUSH } gr_overlap_policy;
typedef enum { GR_VEL_ZERO = 0, GR_VEL_GAUSSIAN, GR_VEL_SPEED } gr_vel_kind;

typedef struct {
    gr_init_kind kind;
    double x0, y0, x1, y1;  /* region to fill */
    double spacing;         /* lattice pitch in units of the largest diameter */
    gr_vel_kind velocity;
    double v0;              /* gaussian: std per component; speed: modulus */
    char file[1024];        /* columns: x y [vx vy [diameter]] */
    gr_overlap_policy overlap;
    double occupation;      /* occupation: mean occupation of each moving channel */
    double rest_occupation; /* and of the rest channel */
} gr_init;

typedef struct {
    double x0, y0, x1, y1;
    int present;
} gr_window;

typedef struct {
    double until;           /* simulated time to run to */
    double output_every;    /* time between trajectory frames */
    double observe_every;   /* time between observable samples */
    double thermo_every;    /* time between thermo lines off a terminal, 0: none */
    double checkpoint_every;
    int field_nx, field_ny; /* coarse-graining grid, 0 = none */
    int contacts;           /* write the contact network with each frame */
    int stress;             /* write the contact stress with each frame */
    int strict;             /* a broken validity limit stops the run */
    double stall_steps;     /* steps (events) without the time advancing that, */
    double stall_seconds;   /* ... with as many wall seconds, stop a run */
    double max_cost_growth; /* steps per unit time over the first unit's that stop a run (0: none) */
} gr_runctl;

/* Scale limits (docs/reliability.md): a scene beyond them is refused up
 * front with the reason. */
#define GR_SCENE_MAX_GRAINS 10000000L
#define GR_SCENE_MAX_WALLS 100000
#define GR_SCENE_MAX_MAGNITUDE 1e100
#define GR_SCENE_MAX_BYTES (64 << 20)
#define GR_STR_(x) #x
#define GR_STR(x) GR_STR_(x)

/* One key = value of the file, kept for messages and for backends. */
typedef struct {
    char section[64], key[64];
    const char *value;      /* into the scene's parsed copy of the text */
    int line;
    int used;
} gr_scene_entry;

typedef struct gr_scene {
    char path[1024];
    char *text;             /* the whole file, stored in the output */
    char name[64];
    double width, height;   /* domain [0,width] x [0,height] */
    gr_bc side[4];
    double gravity;         /* acceleration along -y */
    gr_material mat;
    int nspecies;
    gr_species species[GR_MAX_SPECIES];
    int nsegments;
    gr_segment *segments;   /* user walls and the silo's, when made of segments */
    gr_floor floor;
    gr_silo silo;
    gr_init init;
    gr_window window;
    gr_runctl run;
    uint64_t seed;
    size_t nentries;
    gr_scene_entry *entries;
    char *parsed;           /* the text cut into the entries' values */
    size_t *index, index_cap; /* (section, key) -> entry + 1, open addressing */
    int set_line0;          /* line of the first --set in text, 0: none */
} gr_scene;

#endif
