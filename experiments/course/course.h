/* Shared by the exercises of `grano course` (docs/course.md): their
 * options, the instance on a scene text, collision counting and the result
 * file. Each exercise is one file. */
#ifndef GR_COURSE_H
#define GR_COURSE_H

#include <stdint.h>

#include "err.h"
#include "h5md.h"
#include "method.h"
#include "particles.h"
#include "progress.h"
#include "scene.h"

/* The flags that set an exercise's parameters, as bits of course_opts.given:
 * an exercise refuses by name a flag it does not use. */
enum {
    COURSE_N = 1u << 0,
    COURSE_ETA = 1u << 1,
    COURSE_BOX = 1u << 2,
    COURSE_ALPHA = 1u << 3,
    COURSE_COLLISIONS = 1u << 4,
    COURSE_TIME = 1u << 5,
    COURSE_RUNS = 1u << 6
};

typedef struct {
    const char *out;
    int quick;
    int naive;     /* [edmd] algorithm = naive (v1.0 of the slides) instead of the tree */
    unsigned long seed;
    int force;     /* replace existing result files */
    const gr_method_type *m;
    gr_progress *pg; /* the exercise's progress line on a terminal (NULL: none) */
    unsigned given;  /* COURSE_* bits of the flags given; the values below */
    long n;          /* --n: disks (pressure: of the sweep against V0) */
    double eta;      /* --eta: packing fraction N pi d^2 / (4 L^2) */
    double box;      /* --box: side L of the square box / d */
    double alpha;    /* --alpha: restitution (cooling) */
    double collisions; /* --collisions: run length in collisions per disk */
    double time;     /* --time: pressure's measurement window in L / V0 */
    long runs;       /* --runs: independent starts pooled (maxwell) */
} course_opts;

/* The scene of text (the keys of a scene file) with the method's section,
 * and an instance on it starting from init (NULL: the scene's [init]). The
 * scene outlives the instance: free it after. */
int course_sim(const char *text, const course_opts *o, const gr_particles *init, gr_scene **psc,
               gr_sim **ps, gr_err *err);

/* Disk-disk collisions so far (the counter "pair_collisions"); GR_EINPUT
 * naming the counter and `who` when the method does not count them. */
int course_pairs(const gr_sim *s, const char *who, uint64_t *pairs, gr_err *err);
/* Run until `target` disk-disk collisions have happened. */
int course_advance_pairs(gr_sim *s, uint64_t target, gr_err *err);

/* How the method runs, for the first line of an exercise's report:
 * "algorithm tree" for edmd, the method's name for the others. */
const char *course_how(const course_opts *o);

/* The pitch of the square lattice the exercises start n disks on: it
 * fills 0.99 of a box of side L. */
double course_spacing(long n, double L);
/* The side of a square box of n disks: --box, or from --eta, or from the
 * exercise's packing fraction eta0; GR_EINPUT naming the flag when the
 * disks do not fit on the starting square lattice (spacing below 1 d). */
int course_box(const course_opts *o, long n, double eta0, double *L, gr_err *err);

/* The exercise's HDF5 result file <out>/<name>, labelled with the method:
 * written as <name>.part and renamed by course_h5_close once whole (rc: the
 * writes' status; on a failure the part is removed), so that a killed
 * exercise leaves no half-written result under its name. */
gr_h5md *course_h5(const course_opts *o, const char *name, const gr_scene *sc, gr_err *err);
int course_h5_close(gr_h5md *h, const course_opts *o, const char *name, int rc, gr_err *err);

/* Whether a cooling gas is still homogeneous (course_hcs.c): its box
 * against the shear instability's length L_c, and the momentum and number
 * density modes of wavelength above L_c (the first shell when L < L_c)
 * against a homogeneous gas's (1 each). */
typedef struct {
    double lc;      /* L_c / d */
    int modes;      /* wave vectors averaged over */
    double flow;    /* <|j_k|^2> / (2 N T): vortices when well above 1 */
    double density; /* <|rho_k|^2> / N: clusters when well above 1 */
} course_hcs;
double course_hcs_lc(double n, double chi, double alpha);
int course_hcs_measure(const gr_particles *p, double L, double alpha, double chi, course_hcs *h);
/* The number density of cells as a map, their mean velocities as arrows. */
int course_hcs_plot(const char *png, const gr_particles *p, double L, double t, const char *title, gr_err *err);

int course_maxwell(const course_opts *o, gr_err *err);
int course_pressure(const course_opts *o, gr_err *err);
int course_cooling(const course_opts *o, gr_err *err);

#endif
