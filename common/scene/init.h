/* Initial particles of a scene: the mobile grains (lattice, random without
 * overlap, or read from a file; velocities per [init]) followed by the
 * fixed wall grains of a silo whose walls are grains (gate grains over the
 * orifice flagged GR_PF_GATE). Deterministic from sc->seed. */
#ifndef GR_INIT_H
#define GR_INIT_H

#include "particles.h"
#include "scene.h"

int gr_init_particles(const gr_scene *sc, gr_particles *out, gr_err *err);

/* [init] kind = file (init_file.c): appends the grains of path to p, at the
 * density of species sp (and its diameter when the file gives none). The
 * format is told by the content: a LAMMPS data file (atom style sphere or
 * atomic, Velocities optional), the first frame of an extended XYZ file,
 * or plain columns x y [vx vy [diameter]]. */
int gr_init_read_file(const char *path, const gr_species *sp, gr_particles *p, gr_err *err);

/* [init] overlap = push (init_overlap.c): the grains of p moved apart
 * until no pair overlaps and none cuts a wall (fixed grains stay), or
 * GR_EINPUT naming the file, the grains, the overlap and the key when the
 * overlap is beyond a soft packing's (0.1 of the contact distance) or
 * does not vanish. */
typedef struct {
    double overlap;          /* the largest the file had (a length) */
    char where[200];         /* its grains (numbered as in the file) or grain and wall */
    double max_displacement; /* the largest move of a grain */
    int sweeps;              /* sweeps that moved grains */
} gr_init_relax_report;
int gr_init_push_apart(const gr_scene *sc, gr_particles *p, gr_init_relax_report *rep, gr_err *err);
/* gr_init_particles, saying in note (n bytes, "" when nothing was done;
 * NULL: not said) what overlap = push did. */
int gr_init_particles_noted(const gr_scene *sc, gr_particles *out, char *note, size_t n, gr_err *err);

/* Place grain radius r at the reinsertion band of the silo without overlap
 * with any of the n grains of p (positions x, y, radii), trying up to
 * `tries` random spots from rng; returns 1 and the spot, or 0 if none. */
struct gr_rng;
int gr_reinsert_spot(const gr_scene *sc, const gr_particles *p, double r,
                     struct gr_rng *rng, int tries, double *x, double *y);

#endif
