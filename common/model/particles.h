/* Particle store: structure of arrays. Grains of a wall are particles
 * flagged fixed; ids are stable across reorderings and restarts. */
#ifndef GR_PARTICLES_H
#define GR_PARTICLES_H

#include <stddef.h>
#include <stdint.h>

#include "err.h"

enum {
    GR_PF_FIXED = 1u << 0, /* never moves: wall grain */
    GR_PF_GATE = 1u << 1,  /* fixed grain closing the orifice until it opens */
    GR_PF_GONE = 1u << 2   /* left the domain and was not reinserted */
};

typedef struct {
    size_t n, cap;
    double *x, *y, *vx, *vy, *omega;
    double *radius, *mass, *inertia;
    uint32_t *flags;
    int64_t *id;
    int32_t *species;
} gr_particles;

gr_particles *gr_particles_create(size_t cap, gr_err *err);
void gr_particles_free(gr_particles *p);
int gr_particles_reserve(gr_particles *p, size_t cap, gr_err *err);
/* Append one grain at rest; returns its index or -1 (err filled). */
long gr_particles_push(gr_particles *p, double x, double y, double radius,
                       double mass, uint32_t flags, int32_t species, gr_err *err);
/* Copy every field of src into dst (resized). */
int gr_particles_copy(gr_particles *dst, const gr_particles *src, gr_err *err);
/* Copy grain i of src to slot j of dst (both must exist). */
void gr_particles_copy_one(gr_particles *dst, size_t j, const gr_particles *src, size_t i);
size_t gr_particles_count_mobile(const gr_particles *p);
/* Grains sorted by id: entry k holds the k-th smallest id and its index in
 * the array it came from. One helper for every id-order pass (snapshots,
 * matching two snapshots, duplicate checks), so none keeps its own sort. */
typedef struct {
    int64_t id;
    size_t i;
} gr_id_index;
/* Fill ix[0..n) sorted by id (ties by index, so the order is total). */
void gr_id_index_sort(const int64_t *id, size_t n, gr_id_index *ix);
/* The entry of id in a sorted index, or NULL. */
const gr_id_index *gr_id_index_find(const gr_id_index *ix, size_t n, int64_t id);
/* An id present twice in a sorted index, or -1 when all are distinct
 * (ids are never negative). */
int64_t gr_id_index_duplicate(const gr_id_index *ix, size_t n);
/* Disk inertia 1/2 m r^2. */
static inline double gr_disk_inertia(double mass, double radius) { return 0.5 * mass * radius * radius; }

#endif
