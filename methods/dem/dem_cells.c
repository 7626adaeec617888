/* Cells: the grid (no smaller than the neighbour cutoff), the wall
 * segments near each cell, the grains binned by cell (CSR by counting
 * sort, row-major so that a sort by cell is also a spatial sort for cache
 * locality), and the strips of rows that the threaded force loop colours.
 * Below the spatial sort and the Verlet lists (dem_neigh.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dem.h"

static void cells_free(gr_dem_cells *g)
{
    free(g->start);
    free(g->idx);
    free(g->cell);
    free(g->cell_seg_start);
    free(g->cell_seg);
    memset(g, 0, sizeof *g);
}

double gr_dem_seg_dist(double ax, double ay, double bx, double by, double px, double py)
{
    double ex = bx - ax, ey = by - ay, l2 = ex * ex + ey * ey;
    double u = l2 > 0 ? ((px - ax) * ex + (py - ay) * ey) / l2 : 0.0;
    u = u < 0 ? 0 : u > 1 ? 1 : u;
    return hypot(px - ax - u * ex, py - ay - u * ey);
}

double gr_dem_seg_margin(const gr_dem *d)
{
    /* a vibrating segment moves by up to the amplitude either way */
    return 2.0 * fabs(d->sc.floor.amplitude);
}

/* The grid's box (grains, walls, a margin; the period when periodic) and
 * cell counts for cells no smaller than cutoff. */
static int grid_size(gr_dem *d, double cutoff, gr_err *err)
{
    gr_dem_cells *g = &d->cells;
    double xmin = 0, xmax = d->sc.width, ymin = 0, ymax = d->sc.height;
    double *x = d->f[F_X][d->cur], *y = d->f[F_Y][d->cur];
    for (size_t i = 0; i < d->n; i++) {
        xmin = fmin(xmin, x[i]), xmax = fmax(xmax, x[i]);
        ymin = fmin(ymin, y[i]), ymax = fmax(ymax, y[i]);
    }
    for (int k = 0; k < d->nseg; k++) {
        const gr_dem_seg *s = &d->seg[k];
        xmin = fmin(xmin, fmin(s->x0, s->x1)), xmax = fmax(xmax, fmax(s->x0, s->x1));
        ymin = fmin(ymin, fmin(s->y0, s->y1)), ymax = fmax(ymax, fmax(s->y0, s->y1));
    }
    double m = d->rmax + gr_dem_seg_margin(d);
    xmin -= m, xmax += m, ymin -= m, ymax += m;
    g->px = d->Lx > 0;
    g->py = d->Ly > 0;
    if (g->px)
        xmin = 0, xmax = d->Lx;
    if (g->py)
        ymin = 0, ymax = d->Ly;
    double lx = xmax - xmin, ly = ymax - ymin;
    long nx = (long)floor(lx / cutoff), ny = (long)floor(ly / cutoff);
    if (nx < 1) nx = 1;
    if (ny < 1) ny = 1;
    if ((g->px && nx < 3) || (g->py && ny < 3))
        return gr_fail(err, GR_EINPUT,
                       "periodic domain %g x %g is narrower than 3 neighbour cells of %g (largest diameter plus skin)",
                       d->sc.width, d->sc.height, cutoff);
    /* Keep the grid a few cells per grain at most; a periodic direction
     * keeps its cells (they tile the period), so stop once nothing can
     * shrink: a long periodic strip looped here for ever. */
    while ((double)nx * (double)ny > 4.0 * (double)(d->ntag + 64)) {
        long nx2 = nx > 3 && !g->px ? (nx + 1) / 2 : nx, ny2 = ny > 3 && !g->py ? (ny + 1) / 2 : ny;
        if (nx2 == nx && ny2 == ny)
            break;
        nx = nx2, ny = ny2;
    }
    if ((double)nx * (double)ny > 1e8) {
        char where[1200];
        gr_scene_where(&d->sc, "domain", "width", where, sizeof where);
        return gr_fail(err, GR_EINPUT, "%s: domain %g x %g needs %ld x %ld neighbour cells of %g, more than 1e8",
                       where, d->sc.width, d->sc.height, nx, ny, cutoff);
    }
    g->nx = (int)nx;
    g->ny = (int)ny;
    g->x0 = xmin;
    g->y0 = ymin;
    g->cx = lx / (double)nx;
    g->cy = ly / (double)ny;
    g->icx = 1.0 / g->cx;
    g->icy = 1.0 / g->cy;
    return GR_OK;
}

/* Segments near each cell (CSR): centre distance below half the diagonal
 * plus the reach of a grain. Counts on the first pass, fills on the
 * second. */
static int cell_segments(gr_dem *d, gr_err *err)
{
    gr_dem_cells *g = &d->cells;
    size_t nc = (size_t)g->nx * (size_t)g->ny;
    double reach = 0.5 * hypot(g->cx, g->cy) + d->rmax + d->par.skin + gr_dem_seg_margin(d);
    size_t cnt = 0;
    for (int pass = 0; pass < 2; pass++) {
        cnt = 0;
        for (size_t c = 0; c < nc; c++) {
            double ccx = g->x0 + ((double)(c % (size_t)g->nx) + 0.5) * g->cx;
            double ccy = g->y0 + ((double)(c / (size_t)g->nx) + 0.5) * g->cy;
            if (pass)
                g->cell_seg_start[c] = (int32_t)cnt;
            for (int k = 0; k < d->nseg; k++) {
                const gr_dem_seg *s = &d->seg[k];
                if (gr_dem_seg_dist(s->x0, s->y0, s->x1, s->y1, ccx, ccy) < reach) {
                    if (pass)
                        g->cell_seg[cnt] = k;
                    cnt++;
                }
            }
        }
        if (!pass) {
            g->cell_seg = malloc((cnt + 1) * sizeof *g->cell_seg);
            if (!g->cell_seg)
                return gr_fail(err, GR_ERUN, "out of memory for wall cells");
        }
    }
    g->cell_seg_start[nc] = (int32_t)cnt;
    return GR_OK;
}

int gr_dem_cells_setup(gr_dem *d, double cutoff, gr_err *err)
{
    gr_dem_cells *g = &d->cells;
    cells_free(g);
    if (grid_size(d, cutoff, err))
        return err->code;
    size_t nc = (size_t)g->nx * (size_t)g->ny;
    g->start = calloc(nc + 1, sizeof *g->start);
    g->cell_seg_start = calloc(nc + 1, sizeof *g->cell_seg_start);
    if (!g->start || !g->cell_seg_start)
        return gr_fail(err, GR_ERUN, "out of memory for %zu cells", nc);
    if (cell_segments(d, err))
        return err->code;
    gr_dem_make_strips(d);
    return GR_OK;
}

static int cells_reserve(gr_dem_cells *g, size_t n, gr_err *err)
{
    if (n <= g->cap)
        return GR_OK;
    size_t cap = n + n / 2 + 16;
    int32_t *a = realloc(g->idx, cap * sizeof *a);
    if (!a)
        return gr_fail(err, GR_ERUN, "out of memory for the cell lists");
    g->idx = a;
    a = realloc(g->cell, cap * sizeof *a);
    if (!a)
        return gr_fail(err, GR_ERUN, "out of memory for the cell lists");
    g->cell = a;
    g->cap = cap;
    return GR_OK;
}

int gr_dem_bin(gr_dem *d, const double *x, const double *y, gr_err *err)
{
    gr_dem_cells *g = &d->cells;
    size_t n = d->n, nc = (size_t)g->nx * (size_t)g->ny;
    if (cells_reserve(g, n, err))
        return err->code;
    memset(g->start, 0, (nc + 1) * sizeof *g->start);
    for (size_t i = 0; i < n; i++) {
        double fx = floor((x[i] - g->x0) * g->icx), fy = floor((y[i] - g->y0) * g->icy);
        long cx = fx < 0 ? 0 : fx >= g->nx ? g->nx - 1 : (long)fx;
        long cy = fy < 0 ? 0 : fy >= g->ny ? g->ny - 1 : (long)fy;
        int32_t c = (int32_t)(cy * g->nx + cx);
        g->cell[i] = c;
        g->start[c + 1]++;
    }
    for (size_t c = 0; c < nc; c++)
        g->start[c + 1] += g->start[c];
    /* stable placement: grains keep their relative order within a cell */
    int32_t *fill = malloc((nc + 1) * sizeof *fill);
    if (!fill)
        return gr_fail(err, GR_ERUN, "out of memory for the cell lists");
    memcpy(fill, g->start, (nc + 1) * sizeof *fill);
    for (size_t i = 0; i < n; i++)
        g->idx[fill[g->cell[i]]++] = (int32_t)i;
    free(fill);
    return GR_OK;
}

void gr_dem_make_strips(gr_dem *d)
{
    gr_dem_cells *g = &d->cells;
    gr_dem_strips *s = &d->strips;
    int ny = g->ny;
    /* a fixed rule in the grid only: the strips (and so the sums) do not
     * depend on the number of threads */
    int rps = ny / 48 > 1 ? ny / 48 : 1;
    int ns = ny / rps, ncol = gr_dem_colours(d);
    ns -= ns % ncol;
    if (ns < ncol)
        ns = 1;
    free(s->row0);
    free(s->i0);
    s->row0 = malloc((size_t)(ns + 1) * sizeof *s->row0);
    s->i0 = calloc((size_t)(ns + 1), sizeof *s->i0);
    s->n = ns;
    for (int k = 0; k <= ns; k++)
        s->row0[k] = (int32_t)((long)k * ny / ns);
}
