/* What the lattice shows: populations, momentum, energy, and the fields
 * coarse-grained onto a grid. Every particle has the grain's mass m and
 * speed a/dt along its channel (0 at rest); particles in wall nodes, which
 * are being reflected, count where they are. */
#include <math.h>

#include "lgca_int.h"

void lgca_populations(const lgca *L, uint64_t *moving, uint64_t *resting)
{
    size_t nw = (size_t)L->nw;
    *moving = *resting = 0;
    for (size_t j = 0; j < (size_t)L->nj; j++)
        for (size_t c = 0; c < LGCA_CH; c++) {
            const uint64_t *x = L->lane[j] + c * nw;
            uint64_t n = 0;
            for (size_t w = 0; w < nw; w++)
                n += (uint64_t)__builtin_popcountll(x[w]);
            *(c == LGCA_REST ? resting : moving) += n;
        }
}

/* Per lane and channel: the count and the sum of row indices. */
void lgca_observe(const lgca *L, gr_obs *o)
{
    size_t nw = (size_t)L->nw;
    double c = L->a / L->par.dt, m = L->mass;
    uint64_t n[LGCA_CH] = {0};
    double ysum = 0;
    for (size_t j = 0; j < (size_t)L->nj; j++)
        for (size_t k = 0; k < LGCA_CH; k++) {
            const uint64_t *x = L->lane[j] + k * nw;
            for (size_t w = 0; w < nw; w++)
                for (uint64_t b = x[w]; b; b &= b - 1) {
                    int i = (int)(w * 64) + __builtin_ctzll(b);
                    ysum += (i + 0.25 + 0.5 * (double)(j & 1)) * L->a;
                    n[k]++;
                }
        }
    uint64_t total = 0, moving = 0;
    double px = 0, py = 0;
    for (int k = 0; k < LGCA_CH; k++) {
        total += n[k];
        if (k < 6) {
            moving += n[k];
            double ux, uy;
            lgca_unit_velocity(k, &ux, &uy);
            px += (double)n[k] * ux;
            py += (double)n[k] * uy;
        }
    }
    o->t = (double)L->step * L->par.dt;
    o->steps = L->step;
    o->n_mobile = total;
    o->ekin_trans = 0.5 * m * c * c * (double)moving;
    o->ekin_rot = 0;
    o->epot_grav = m * L->sc->gravity * ysum;
    o->px = m * c * px;
    o->py = m * c * py;
    double M = m * (double)total;
    o->temperature = total ? (2 * o->ekin_trans - (o->px * o->px + o->py * o->py) / M) / (2.0 * (double)total) : 0;
    o->outflow = L->outflow;
    o->wall_pressure = NAN;
    o->max_overlap = NAN;
}

/* The node's share of the plane, the h x a rectangle around it (these tile
 * the plane), spread over the cells it overlaps. */
static void add_area(gr_field *f, double x, double y, double hw, double hh, double area)
{
    double x0 = x - hw, x1 = x + hw, y0 = y - hh, y1 = y + hh, inv = area / (4 * hw * hh);
    int ia = (int)floor((x0 - f->x0) / f->cx), ib = (int)floor((x1 - f->x0) / f->cx);
    int ja = (int)floor((y0 - f->y0) / f->cy), jb = (int)floor((y1 - f->y0) / f->cy);
    for (int iy = ja < 0 ? 0 : ja; iy <= jb && iy < f->ny; iy++)
        for (int ix = ia < 0 ? 0 : ia; ix <= ib && ix < f->nx; ix++) {
            double cx0 = f->x0 + ix * f->cx, cy0 = f->y0 + iy * f->cy;
            double ox = fmin(x1, cx0 + f->cx) - fmax(x0, cx0), oy = fmin(y1, cy0 + f->cy) - fmax(y0, cy0);
            if (ox > 0 && oy > 0)
                f->area[(size_t)iy * (size_t)f->nx + (size_t)ix] += ox * oy * inv;
        }
}

/* Each particle counts in the cell of its node: number, mass, momentum,
 * m v^2; and an area of one seventh of the node's rectangle, spread over
 * the cells it overlaps (so the packing field is the fraction of occupied
 * channels, 1 on a full lattice, without the aliasing of lanes 0.866 d
 * apart on cells of another width). */
int lgca_fields(const lgca *L, gr_field *f, double w, gr_err *err)
{
    if (!(w > 0))
        return gr_fail(err, GR_EINPUT, "field weight must be > 0");
    size_t nw = (size_t)L->nw;
    double c = L->a / L->par.dt, m = L->mass, share = L->a * L->h / LGCA_CH;
    for (int j = 0; j < L->nj; j++)
        for (size_t wd = 0; wd < nw; wd++) {
            uint64_t any = 0;
            const uint64_t *lane = L->lane[j];
            for (int k = 0; k < LGCA_CH; k++)
                any |= lane[(size_t)k * nw + wd];
            for (; any; any &= any - 1) {
                int i = (int)(wd * 64) + __builtin_ctzll(any);
                double x, y;
                lgca_node_xy(L, i, j, &x, &y);
                long cell = gr_field_cell(f, x, y);
                int n = 0, moving = 0;
                double vx = 0, vy = 0;
                for (int k = 0; k < LGCA_CH; k++)
                    if (lane[(size_t)k * nw + wd] >> (i & 63) & 1u) {
                        n++;
                        if (k < 6) {
                            double ux, uy;
                            lgca_unit_velocity(k, &ux, &uy);
                            moving++, vx += ux * c, vy += uy * c;
                        }
                    }
                add_area(f, x, y, 0.5 * L->h, 0.5 * L->a, w * n * share);
                if (cell < 0)
                    continue;
                f->num[cell] += w * n;
                f->mass[cell] += w * n * m;
                f->px[cell] += w * m * vx;
                f->py[cell] += w * m * vy;
                f->mv2[cell] += w * m * c * c * moving;
            }
        }
    f->wsum += w;
    return GR_OK;
}
