#include "grid.h"

#include <math.h>
#include <stdlib.h>

#include "geom.h"

gr_grid *gr_grid_create(double x0, double y0, double lx, double ly, double min_cell,
                        int periodic_x, int periodic_y, gr_err *err)
{
    if (!(lx > 0) || !(ly > 0) || !(min_cell > 0)) {
        gr_fail(err, GR_EINPUT, "grid: sizes must be positive (lx %g, ly %g, cell %g)", lx, ly, min_cell);
        return NULL;
    }
    gr_grid *g = calloc(1, sizeof *g);
    if (!g) {
        gr_fail(err, GR_ERUN, "out of memory for the cell grid");
        return NULL;
    }
    /* Counted in double: the int cast of a huge ratio is undefined. */
    double fx = fmax(1.0, floor(lx / min_cell)), fy = fmax(1.0, floor(ly / min_cell));
    if (fx * fy > 1e8) {
        gr_fail(err, GR_EINPUT, "grid: %.3g x %.3g cells is too many (at most 1e8)", fx, fy);
        free(g);
        return NULL;
    }
    g->nx = (int)fx;
    g->ny = (int)fy;
    g->x0 = x0, g->y0 = y0, g->lx = lx, g->ly = ly;
    g->cx = lx / g->nx, g->cy = ly / g->ny;
    g->periodic_x = periodic_x, g->periodic_y = periodic_y;
    g->head = malloc((size_t)g->nx * g->ny * sizeof *g->head);
    if (!g->head) {
        gr_fail(err, GR_ERUN, "out of memory for the cell grid");
        gr_grid_free(g);
        return NULL;
    }
    return g;
}

void gr_grid_free(gr_grid *g)
{
    if (!g)
        return;
    free(g->head);
    free(g->next);
    free(g);
}

static int cell_coord(double u, double u0, double c, int n, int periodic)
{
    int i = (int)floor((u - u0) / c);
    if (periodic) {
        i %= n;
        if (i < 0)
            i += n;
    } else {
        i = i < 0 ? 0 : i >= n ? n - 1 : i;
    }
    return i;
}

long gr_grid_cell(const gr_grid *g, double x, double y)
{
    int i = cell_coord(x, g->x0, g->cx, g->nx, g->periodic_x);
    int j = cell_coord(y, g->y0, g->cy, g->ny, g->periodic_y);
    return (long)j * g->nx + i;
}

int gr_grid_build(gr_grid *g, const double *x, const double *y, size_t n,
                  const unsigned char *skip, gr_err *err)
{
    if (n > g->cap) {
        long *q = realloc(g->next, n * sizeof *q);
        if (!q)
            return gr_fail(err, GR_ERUN, "out of memory for the cell lists");
        g->next = q;
        g->cap = n;
    }
    for (long c = 0; c < (long)g->nx * g->ny; c++)
        g->head[c] = -1;
    /* Insert in reverse so each cell lists its particles in index order. */
    for (size_t k = n; k-- > 0;) {
        if (skip && skip[k])
            continue;
        long c = gr_grid_cell(g, x[k], y[k]);
        g->next[k] = g->head[c];
        g->head[c] = (long)k;
    }
    return GR_OK;
}

int gr_grid_neighbours(const gr_grid *g, long c, long out[9])
{
    int ci = (int)(c % g->nx), cj = (int)(c / g->nx), m = 0;
    out[m++] = c;
    for (int dj = -1; dj <= 1; dj++) {
        for (int di = -1; di <= 1; di++) {
            if (!di && !dj)
                continue;
            int i = ci + di, j = cj + dj;
            if (g->periodic_x)
                i = (i + g->nx) % g->nx;
            if (g->periodic_y)
                j = (j + g->ny) % g->ny;
            if (i < 0 || i >= g->nx || j < 0 || j >= g->ny)
                continue;
            long nc = (long)j * g->nx + i;
            int dup = 0;
            for (int k = 0; k < m; k++)
                dup |= out[k] == nc;
            if (!dup)
                out[m++] = nc;
        }
    }
    return m;
}

int gr_grid_pairs(const gr_grid *g, const double *x, const double *y, double rcut,
                  gr_pair_fn fn, void *user)
{
    double Lx = g->periodic_x ? g->lx : 0, Ly = g->periodic_y ? g->ly : 0;
    double rc2 = rcut * rcut;
    long nc = (long)g->nx * g->ny;
    for (long c = 0; c < nc; c++) {
        long nb[9];
        int m = gr_grid_neighbours(g, c, nb);
        for (long i = g->head[c]; i >= 0; i = g->next[i]) {
            for (int k = 0; k < m; k++) {
                /* Each unordered pair once: by cell index, then particle index. */
                if (nb[k] < c)
                    continue;
                for (long j = nb[k] == c ? g->next[i] : g->head[nb[k]]; j >= 0; j = g->next[j]) {
                    double dx = gr_min_image(x[j] - x[i], Lx), dy = gr_min_image(y[j] - y[i], Ly);
                    if (dx * dx + dy * dy < rc2) {
                        int rc = i < j ? fn((size_t)i, (size_t)j, dx, dy, user)
                                       : fn((size_t)j, (size_t)i, -dx, -dy, user);
                        if (rc)
                            return rc;
                    }
                }
            }
        }
    }
    return 0;
}
