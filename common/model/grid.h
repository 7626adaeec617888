/* Uniform cell grid with linked lists (head per cell, next per particle),
 * shared by neighbour search, event-driven cells, DSMC cells and fields. */
#ifndef GR_GRID_H
#define GR_GRID_H

#include <stddef.h>

#include "err.h"

typedef struct {
    int nx, ny;
    double x0, y0, lx, ly;  /* covered region */
    double cx, cy;          /* cell size */
    int periodic_x, periodic_y;
    long *head;             /* nx*ny, -1 = empty */
    long *next;             /* per particle, -1 = end */
    size_t cap;
} gr_grid;

/* Cells at least min_cell wide covering [x0,x0+lx] x [y0,y0+ly]. */
gr_grid *gr_grid_create(double x0, double y0, double lx, double ly, double min_cell,
                        int periodic_x, int periodic_y, gr_err *err);
void gr_grid_free(gr_grid *g);
/* Cell index of a point; points outside are clamped to the border cells
 * (periodic directions wrap). */
long gr_grid_cell(const gr_grid *g, double x, double y);
/* Rebuild the lists from n positions; skip[i] != 0 leaves i out (may be NULL). */
int gr_grid_build(gr_grid *g, const double *x, const double *y, size_t n,
                  const unsigned char *skip, gr_err *err);
/* The up-to-9 distinct cells around cell c (itself first); returns count. */
int gr_grid_neighbours(const gr_grid *g, long c, long out[9]);
/* Call fn for every unordered pair i<j closer than rcut (minimum image on
 * periodic sides, periods lx, ly); fn returns non-zero to stop. */
typedef int (*gr_pair_fn)(size_t i, size_t j, double dx, double dy, void *user);
int gr_grid_pairs(const gr_grid *g, const double *x, const double *y, double rcut,
                  gr_pair_fn fn, void *user);

#endif
