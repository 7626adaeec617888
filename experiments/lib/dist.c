/* MPI distribution of a sweep's units (see dist.h). */
#include "dist.h"

#include <stdlib.h>
#include <string.h>

#ifdef GRANO_MPI
#include <mpi.h>
#endif

int exp_dist_available(void)
{
#ifdef GRANO_MPI
    return 1;
#else
    return 0;
#endif
}

void exp_dist_begin(exp_dist *d)
{
    *d = (exp_dist){0, 1, 0};
#ifdef GRANO_MPI
    /* only under a launcher: a singleton MPI_Init would start a daemon */
    if (!getenv("OMPI_COMM_WORLD_SIZE") && !getenv("PMIX_RANK") && !getenv("PMI_RANK"))
        return;
    if (MPI_Init(NULL, NULL) != MPI_SUCCESS)
        return;
    d->mpi = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &d->rank);
    MPI_Comm_size(MPI_COMM_WORLD, &d->size);
#endif
}

void exp_dist_end(exp_dist *d)
{
#ifdef GRANO_MPI
    if (d->mpi)
        MPI_Finalize();
#endif
    d->mpi = 0;
}

/* This rank's units as a sweep of their own: local unit k is global unit
 * rank + k * size. */
typedef struct {
    exp_unit_fn fn;
    exp_label_fn label, key;
    void *ctx;
    size_t rank, size;
} share;

static size_t global(const share *s, size_t k)
{
    return s->rank + k * s->size;
}

static int share_unit(size_t k, const char *part, const char *key, void *ctx, volatile double *progress,
                      gr_err *err)
{
    share *s = ctx;
    return s->fn(global(s, k), part, key, s->ctx, progress, err);
}

static void share_label(size_t k, void *ctx, char *buf, size_t n)
{
    share *s = ctx;
    s->label(global(s, k), s->ctx, buf, n);
}

static void share_key(size_t k, void *ctx, char *buf, size_t n)
{
    share *s = ctx;
    s->key(global(s, k), s->ctx, buf, n);
}

int exp_dist_sweep(const exp_dist *d, const exp_sweep *sw, exp_unit_fn fn, exp_label_fn label,
                   exp_label_fn key, void *ctx, gr_err *err)
{
    size_t rank = (size_t)d->rank, size = (size_t)d->size;
    share s = {fn, label, key, ctx, rank, size};
    exp_sweep mine = *sw;
    mine.nunits = sw->nunits > rank ? (sw->nunits - rank + size - 1) / size : 0;
    mine.progress = sw->progress && rank == 0;
    char **paths = calloc(mine.nunits + 1, sizeof *paths);
    size_t reused = 0;
    int rc = paths ? GR_OK : gr_fail(err, GR_ERUN, "out of memory");
    if (!rc && mine.nunits)
        rc = exp_sweep_run(&mine, share_unit, share_label, share_key, &s, paths, &reused, err);
    for (size_t k = 0; paths && k < mine.nunits; k++)
        free(paths[k]);
    free(paths);
#ifdef GRANO_MPI
    if (d->mpi) {
        int worst = 0;
        MPI_Allreduce(&rc, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
        if (worst && !rc)
            rc = gr_fail(err, worst, "a unit failed on another rank (its message is on that rank's stderr)");
    }
#endif
    return rc;
}
