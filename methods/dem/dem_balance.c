/* How the strips of a force evaluation are cut into one run per thread,
 * balanced by their measured cost. Below the evaluation (which cuts every
 * colour) and the one-barrier step (which cuts the whole step). */
#include "dem.h"
#include "dem_eval.h"

/* Cut the m strips first, first + step, ... into nth contiguous runs of
 * about equal cost (the measured times once every one of them has one,
 * the grain counts before): b[t] is the index, in that sequence, of the
 * first strip of run t, b[nth] = m. */
void gr_dem_cut_runs(const gr_dem *d, const struct gr_dem_eval *ev, int first, int step, int m,
                     int nth, int *b)
{
    const int32_t *i0 = d->strips.i0;
    int timed = 1;
    double total = 0.0, acc = 0.0;
    for (int k = 0; k < m; k++)
        timed &= ev->st[first + k * step].stime > 0;
#define WEIGHT(s) (timed ? ev->st[s].stime : (double)(i0[(s) + 1] - i0[s]) + 1.0)
    for (int k = 0; k < m; k++)
        total += WEIGHT(first + k * step);
    int t = 1;
    b[0] = 0;
    for (int k = 0; k < m && t < nth; k++) {
        double w = WEIGHT(first + k * step);
        /* cut before strip k when that lands nearer the target */
        while (t < nth && acc + 0.5 * w >= total * t / nth)
            b[t++] = k;
        acc += w;
    }
#undef WEIGHT
    while (t <= nth)
        b[t++] = m;
}

/* Each colour ends at a barrier, so each is balanced on its own (one cut
 * for all colours left a thread idle at every colour). */
void gr_dem_split_strips(const gr_dem *d, struct gr_dem_eval *ev, int nth)
{
    int ns = ev->ns, ncol = ev->c.ncol;
    for (int col = 0; col < ncol; col++)
        gr_dem_cut_runs(d, ev, col, ncol, (ns - col + ncol - 1) / ncol, nth, ev->split + col * (nth + 1));
}
