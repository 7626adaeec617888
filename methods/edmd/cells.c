/* The cells of the event-driven scheme: which cell a point is in, and
 * the singly linked lists of the grains in each. */
#include <math.h>

#include "edmd_int.h"

int edmd_cell_of(const gr_edmd *s, double x, double y)
{
    int ix = (int)floor(x / s->cw), iy = (int)floor((y - s->ybot) / s->ch);
    if (s->periodic_x)
        ix = ((ix % s->nx) + s->nx) % s->nx;
    if (s->periodic_y)
        iy = ((iy % s->ny) + s->ny) % s->ny;
    ix = ix < 0 ? 0 : ix >= s->nx ? s->nx - 1 : ix;
    iy = iy < 0 ? 0 : iy >= s->ny ? s->ny - 1 : iy;
    return ix + s->nx * iy;
}

/* Cell lists are singly linked: a grain's predecessor is found from the
 * head (a cell holds about one grain, and its head and grains are in cache
 * by then), where a back link would cost a random line per change. */
void edmd_cell_remove(gr_edmd *s, int32_t i)
{
    edmd_p *p = &s->p[i];
    int32_t *link = &s->chead[p->cell];
    while (*link != i)
        link = &s->p[*link].cnext;
    *link = p->cnext;
}

void edmd_cell_insert(gr_edmd *s, int32_t i, int c)
{
    edmd_p *p = &s->p[i];
    p->cell = c;
    p->cnext = s->chead[c];
    s->chead[c] = i;
}
