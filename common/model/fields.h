/* Coarse-grained fields on a rectangular grid of cells (packing fraction,
 * number, velocity, granular temperature) accumulated over snapshots;
 * displacement statistics in a window; mean square displacement against
 * lag. Method independent: everything is computed from gr_particles. */
#ifndef GR_FIELDS_H
#define GR_FIELDS_H

#include <stddef.h>
#include <stdint.h>

#include "err.h"
#include "particles.h"

/* ------------------------------------------------------------------ fields */

enum {
    GR_FIELD_EXACT = 0,  /* packing: exact area of each disk inside each cell */
    GR_FIELD_CENTRES = 1 /* packing: the whole disk area to its centre's cell */
};

/* Cell (ix, iy) covers [x0 + ix cx, x0 + (ix+1) cx) x [y0 + iy cy, ...);
 * arrays are row-major, index c = iy nx + ix. Sums are weighted by the
 * snapshot weight w (1 for plain snapshots, the time interval for time
 * averages of event-driven runs). */
typedef struct {
    int nx, ny;
    double x0, y0, cx, cy;
    int packing_mode;  /* GR_FIELD_EXACT (default) or GR_FIELD_CENTRES */
    double wsum;       /* sum of snapshot weights */
    double *area;      /* sum w * disk area inside the cell */
    double *num;       /* sum w * grains whose centre is in the cell */
    double *mass;      /* sum w m */
    double *px, *py;   /* sum w m v */
    double *mv2;       /* sum w m |v|^2 */
} gr_field;

gr_field *gr_field_create(int nx, int ny, double x0, double y0, double cx, double cy,
                          gr_err *err);
void gr_field_free(gr_field *f);
void gr_field_clear(gr_field *f);
static inline size_t gr_field_ncells(const gr_field *f) { return (size_t)f->nx * (size_t)f->ny; }
/* Cell of a point, or -1 outside the grid. */
long gr_field_cell(const gr_field *f, double x, double y);
void gr_field_cell_centre(const gr_field *f, long c, double *x, double *y);

/* Accumulate one snapshot with weight w > 0; grains with any of skip_flags
 * (typically GR_PF_FIXED | GR_PF_GONE) are left out. Velocity and
 * temperature are binned by the grain's centre; packing per packing_mode
 * (disks partly outside the grid contribute only their part inside). */
int gr_field_add(gr_field *f, const gr_particles *p, uint32_t skip_flags, double w,
                 gr_err *err);
/* dst += src (same grid), e.g. over independent realisations. */
int gr_field_merge(gr_field *dst, const gr_field *src, gr_err *err);

/* Results, arrays of gr_field_ncells(f) (any may be NULL). Averages are
 * over the accumulated snapshots (weights). Where a cell never held a grain
 * centre, velocity and temperature are NaN.
 * packing: covered area / cell area. number: mean grains per cell, and per
 * unit area. velocity: mass-weighted mean. temperature: the granular
 * temperature of observe.h, T = <m |v - V|^2> / 2 per grain (in 2D the
 * fluctuating kinetic energy per grain equals kT), with V the cell's
 * time-averaged velocity: fluctuations of the cell velocity between
 * snapshots count as temperature. */
void gr_field_packing(const gr_field *f, double *phi);
void gr_field_number(const gr_field *f, double *per_cell, double *per_area);
void gr_field_velocity(const gr_field *f, double *vx, double *vy);
/* Interleaved (vx, vy) per cell, 2 ncells values: the layout of a vector
 * field in gr_h5md_write_field (ncomp = 2, same cell order and origin). */
void gr_field_velocity_xy(const gr_field *f, double *v);
void gr_field_temperature(const gr_field *f, double *T);

/* Area of the disk of radius r centred at (xc, yc) inside the rectangle
 * [x1, x2] x [y1, y2], exact (circular segments and corners). */
double gr_disk_rect_area(double xc, double yc, double r, double x1, double x2, double y1,
                         double y2);

/* ----------------------------------------------------------- displacements */

typedef struct {
    double x0, y0, x1, y1;     /* window on the start positions, [x0,x1) x [y0,y1) */
    uint32_t skip_flags;       /* leave out grains with these flags (either time) */
    int subtract_x;            /* 1: subtract the mean dx of the selection */
    int subtract_y;            /* 0: none; 1: subtract the mean dy of the window
                                  (the mean flow); k > 1: the mean dy of each of
                                  k columns of the window (start x), for a flow
                                  whose speed varies across the window */
    double max_jump;           /* > 0: leave out |d| > max_jump (reinserted grains) */
    double period_x, period_y; /* > 0: minimum image along a periodic side */
} gr_disp_opts;

/* Grain i at (xa[i], ya[i]) then (xb[i], yb[i]); flags may be NULL. The
 * displacements of the m selected grains go to dx, dy (room for n each),
 * in index order, with the requested means subtracted. */
int gr_disp_window(const double *xa, const double *ya, const double *xb, const double *yb,
                   const uint32_t *flags, size_t n, const gr_disp_opts *o, double *dx,
                   double *dy, size_t *m, gr_err *err);
/* The same from two snapshots, grains matched by id (a grain missing from
 * b is left out); dx, dy need room for a->n. */
int gr_disp_particles(const gr_particles *a, const gr_particles *b, const gr_disp_opts *o,
                      double *dx, double *dy, size_t *m, gr_err *err);

/* --------------------------------------------- mean square displacement */

/* Per lag slot: the number of displacements and the sums of dx^2, dx^4,
 * dy^2, dy^4, from any number of time origins and realisations. */
typedef struct {
    size_t nlag;
    double *lag;          /* lag of each slot; NaN until its first add */
    double *n, *sx2, *sx4, *sy2, *sy4;
} gr_msd;

gr_msd *gr_msd_create(size_t nlag, gr_err *err);
void gr_msd_free(gr_msd *s);
/* Add n displacements at lag `lag` to slot k; a slot keeps one lag (a
 * different lag, relative difference above 1e-9, is GR_EINPUT). */
int gr_msd_add(gr_msd *s, size_t k, double lag, const double *dx, const double *dy, size_t n,
               gr_err *err);
int gr_msd_merge(gr_msd *dst, const gr_msd *src, gr_err *err);
/* Per slot (arrays of nlag, any may be NULL; NaN for empty slots):
 * <dx^2>, <dy^2>, their standard errors sqrt((<d^4> - <d^2>^2) / n) for
 * independent samples (grains moving together make this an underestimate:
 * compare realisations), and kappa = <d^4> / (3 <d^2>^2) - 1. Fit the
 * exponent with gr_fit_loglog(lag, msd, ...). */
void gr_msd_result(const gr_msd *s, double *msd_x, double *msd_y, double *err_x,
                   double *err_y, double *kappa_x, double *kappa_y);

#endif
