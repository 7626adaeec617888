/* A free spot for a grain reinserted at the top of the silo: random spots
 * of the band, tried in turn, the first that overlaps no grain.
 *
 * A try against every grain of the band costs tries x grains: with the
 * band full, dem's flowing silo spent 260-340 us of serial time on a grain
 * that found no spot (1000 tries against some 300 grains), while the other
 * thread of the step waited. The grains near the band are binned once per
 * call on cells as wide as the reach of a contact, so a try looks at its
 * nine cells; the spot found (or none) is the same, as a try is refused by
 * the same test on the same grains, those within reach. */
#include <math.h>
#include <stdlib.h>

#include "init.h"
#include "rng.h"

typedef struct {
    double x0, y0, h;
    int nx, ny;
    int32_t *start, *idx; /* grains of cell c: idx[start[c] .. start[c + 1] - 1] */
} band_cells;

static int overlaps(const gr_particles *p, size_t j, double r, double cx, double cy)
{
    double dx = cx - p->x[j], dy = cy - p->y[j], rr = r + p->radius[j];
    return !(dx * dx + dy * dy >= rr * rr);
}

static int cell_of(const band_cells *b, double x, double y, int *ix, int *iy)
{
    *ix = (int)floor((x - b->x0) / b->h), *iy = (int)floor((y - b->y0) / b->h);
    return *ix >= 0 && *ix < b->nx && *iy >= 0 && *iy < b->ny;
}

/* The grains of p within reach of the band, binned; 0 when not worth it or
 * out of memory (the caller then tries against every grain). */
static int bin_band(const gr_silo *s, const gr_particles *p, double reach, band_cells *b)
{
    reach *= 1.01; /* no grain within reach is lost to the rounding of its cell */
    b->x0 = s->x0 - reach, b->y0 = s->reinsert_bottom - reach, b->h = reach;
    double w = s->width + 2 * reach, hgt = s->reinsert_top - s->reinsert_bottom + 2 * reach;
    /* cells no more than some grains' worth: grow them if the reach is tiny */
    while (ceil(w / b->h) * ceil(hgt / b->h) > 4.0 * (double)p->n + 64.0)
        b->h *= 2.0;
    b->nx = (int)ceil(w / b->h), b->ny = (int)ceil(hgt / b->h);
    size_t nc = (size_t)b->nx * (size_t)b->ny;
    b->start = calloc(nc + 1, sizeof *b->start);
    b->idx = malloc((p->n + 1) * sizeof *b->idx);
    if (!b->start || !b->idx)
        return 0;
    int ix, iy;
    for (size_t j = 0; j < p->n; j++)
        if (!(p->flags[j] & GR_PF_GONE) && cell_of(b, p->x[j], p->y[j], &ix, &iy))
            b->start[(size_t)iy * (size_t)b->nx + (size_t)ix + 1]++;
    for (size_t c = 0; c < nc; c++)
        b->start[c + 1] += b->start[c];
    for (size_t j = 0; j < p->n; j++)
        if (!(p->flags[j] & GR_PF_GONE) && cell_of(b, p->x[j], p->y[j], &ix, &iy))
            b->idx[b->start[(size_t)iy * (size_t)b->nx + (size_t)ix]++] = (int32_t)j;
    for (size_t c = nc; c > 0; c--) /* the fill moved each start to the next cell's */
        b->start[c] = b->start[c - 1];
    b->start[0] = 0;
    return 1;
}

static int free_in_cells(const band_cells *b, const gr_particles *p, double r, double cx, double cy)
{
    int ix, iy;
    cell_of(b, cx, cy, &ix, &iy);
    for (int y = iy - 1; y <= iy + 1; y++)
        for (int x = ix - 1; x <= ix + 1; x++) {
            if (x < 0 || x >= b->nx || y < 0 || y >= b->ny)
                continue;
            size_t c = (size_t)y * (size_t)b->nx + (size_t)x;
            for (int32_t k = b->start[c]; k < b->start[c + 1]; k++)
                if (overlaps(p, (size_t)b->idx[k], r, cx, cy))
                    return 0;
        }
    return 1;
}

static int free_all(const gr_particles *p, double r, double cx, double cy)
{
    for (size_t j = 0; j < p->n; j++)
        if (!(p->flags[j] & GR_PF_GONE) && overlaps(p, j, r, cx, cy))
            return 0;
    return 1;
}

int gr_reinsert_spot(const gr_scene *sc, const gr_particles *p, double r,
                     struct gr_rng *rng, int tries, double *x, double *y)
{
    const gr_silo *s = &sc->silo;
    double rmax = 0.0;
    for (size_t j = 0; j < p->n; j++)
        rmax = p->radius[j] > rmax ? p->radius[j] : rmax;
    band_cells b = {0};
    /* a few grains: binning costs more than it saves */
    int binned = p->n > 32 && bin_band(s, p, r + rmax, &b);
    int found = 0;
    for (int t = 0; t < tries && !found; t++) {
        double cx = s->x0 + r + (s->width - 2 * r) * gr_rng_uniform(rng);
        double cy = s->reinsert_bottom + r + (s->reinsert_top - s->reinsert_bottom - 2 * r) * gr_rng_uniform(rng);
        if (binned ? free_in_cells(&b, p, r, cx, cy) : free_all(p, r, cx, cy))
            *x = cx, *y = cy, found = 1;
    }
    free(b.start), free(b.idx);
    return found;
}
