#include "particles.h"

#include <stdlib.h>
#include <string.h>

#define GR_PARTICLE_FIELDS(X)                                                  \
    X(double, x) X(double, y) X(double, vx) X(double, vy) X(double, omega)     \
    X(double, radius) X(double, mass) X(double, inertia) X(uint32_t, flags)    \
    X(int64_t, id) X(int32_t, species)

gr_particles *gr_particles_create(size_t cap, gr_err *err)
{
    gr_particles *p = calloc(1, sizeof *p);
    if (!p) {
        gr_fail(err, GR_ERUN, "out of memory for the particle store");
        return NULL;
    }
    if (gr_particles_reserve(p, cap ? cap : 16, err)) {
        gr_particles_free(p);
        return NULL;
    }
    return p;
}

void gr_particles_free(gr_particles *p)
{
    if (!p)
        return;
#define FREE_FIELD(T, f) free(p->f);
    GR_PARTICLE_FIELDS(FREE_FIELD)
#undef FREE_FIELD
    free(p);
}

int gr_particles_reserve(gr_particles *p, size_t cap, gr_err *err)
{
    if (cap <= p->cap)
        return GR_OK;
    /* Grow every array before publishing the new capacity, so a failure
     * leaves the store consistent. */
#define GROW_FIELD(T, f)                                                       \
    {                                                                          \
        T *q = realloc(p->f, cap * sizeof(T));                                 \
        if (!q)                                                                \
            return gr_fail(err, GR_ERUN, "out of memory for %zu particles", cap); \
        memset(q + p->cap, 0, (cap - p->cap) * sizeof(T));                     \
        p->f = q;                                                              \
    }
    GR_PARTICLE_FIELDS(GROW_FIELD)
#undef GROW_FIELD
    p->cap = cap;
    return GR_OK;
}

long gr_particles_push(gr_particles *p, double x, double y, double radius,
                       double mass, uint32_t flags, int32_t species, gr_err *err)
{
    if (p->n == p->cap && gr_particles_reserve(p, 2 * p->cap + 16, err))
        return -1;
    size_t i = p->n++;
    p->x[i] = x;
    p->y[i] = y;
    p->vx[i] = p->vy[i] = p->omega[i] = 0.0;
    p->radius[i] = radius;
    p->mass[i] = mass;
    p->inertia[i] = gr_disk_inertia(mass, radius);
    p->flags[i] = flags;
    p->id[i] = (int64_t)i;
    p->species[i] = species;
    return (long)i;
}

int gr_particles_copy(gr_particles *dst, const gr_particles *src, gr_err *err)
{
    if (gr_particles_reserve(dst, src->n, err))
        return err ? err->code : GR_ERUN;
#define COPY_FIELD(T, f) if (src->n) memcpy(dst->f, src->f, src->n * sizeof(T));
    GR_PARTICLE_FIELDS(COPY_FIELD)
#undef COPY_FIELD
    dst->n = src->n;
    return GR_OK;
}

void gr_particles_copy_one(gr_particles *dst, size_t j, const gr_particles *src, size_t i)
{
#define COPY_ONE(T, f) dst->f[j] = src->f[i];
    GR_PARTICLE_FIELDS(COPY_ONE)
#undef COPY_ONE
}

size_t gr_particles_count_mobile(const gr_particles *p)
{
    size_t m = 0;
    for (size_t i = 0; i < p->n; i++)
        m += !(p->flags[i] & (GR_PF_FIXED | GR_PF_GONE));
    return m;
}

static int cmp_id_index(const void *a, const void *b)
{
    const gr_id_index *x = a, *y = b;
    if (x->id != y->id)
        return x->id < y->id ? -1 : 1;
    return (x->i > y->i) - (x->i < y->i);
}

void gr_id_index_sort(const int64_t *id, size_t n, gr_id_index *ix)
{
    for (size_t k = 0; k < n; k++)
        ix[k] = (gr_id_index){id[k], k};
    if (n > 1)
        qsort(ix, n, sizeof *ix, cmp_id_index);
}

const gr_id_index *gr_id_index_find(const gr_id_index *ix, size_t n, int64_t id)
{
    size_t lo = 0, hi = n;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (ix[mid].id < id)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < n && ix[lo].id == id ? &ix[lo] : NULL;
}

int64_t gr_id_index_duplicate(const gr_id_index *ix, size_t n)
{
    for (size_t k = 1; k < n; k++)
        if (ix[k].id == ix[k - 1].id)
            return ix[k].id;
    return -1;
}
