/* Internal to the neighbour search: the spatial sort's table of per-grain
 * arrays and the list builder's pieces, defined in dem_neigh.c and used by
 * the rebuild on the threads of a team (dem_team.c). */
#ifndef GR_DEM_SORTLIST_H
#define GR_DEM_SORTLIST_H

#include <stddef.h>
#include <stdint.h>

#include "dem.h"

/* What a run of grains' list is built into: their pairs and segments
 * (then copied to their place in the list), and, for one thread's share
 * of a rebuild on a team (dem_team.c), kept across rebuilds, the sort's
 * scratch array. */
typedef struct {
    int32_t *j, *s;
    size_t capj, caps, nj, ns, offj, offs;
    void *tmp;
    size_t captmp;
    int fail;
    char pad[64]; /* threads write their own entries: no shared cache line */
} dem_listbuf;

/* A per-grain array to reorder: esz bytes per grain. */
typedef struct {
    void *a;
    size_t esz;
} perm_arr;

enum { PERM_MAX = 2 * F_NFIELDS + 20 };

/* The arrays a sort reorders, their number, the largest grain entry. */
int gr_dem_perm_table(gr_dem *d, int live, perm_arr *e, size_t *emax);
/* Slots [k0, k1) of one array in the new order, into out. */
void gr_dem_perm_gather(const perm_arr *e, const int32_t *perm, size_t k0, size_t k1, void *out);
/* *a grown to hold need entries (1 when out of memory). */
int gr_dem_grow_i32(int32_t **a, size_t *cap, size_t need);
/* The list rows of grains [i0, i1) into b (1 when out of memory). */
int gr_dem_list_run(gr_dem *d, const double *x, const double *y, size_t i0, size_t i1, int sorted, dem_listbuf *b);
/* The owner of each list pair of grains [i0, i1). */
void gr_dem_list_owners(gr_dem *d, size_t i0, size_t i1, int32_t end);
/* nb_start and sg_start sized for the grains. */
int gr_dem_list_starts(gr_dem *d, gr_err *err);
/* Each strip's first grain, from the cells (after a binning). */
void gr_dem_strips_index(gr_dem *d);
/* The list's ends, owners' array and strips, once its rows are in. */
int gr_dem_list_finish(gr_dem *d, size_t cnt, size_t scnt, gr_err *err);

#endif
