/* How the threads share a velocity Verlet step: cost-balanced runs of
 * strips, the kick fused into the colours, the drift by the thread that
 * kicked, and the one-barrier step (gr_dem_eval_flow). */
#include <math.h>
#include <string.h>

#include "dem.h"
#include "dem_eval.h"

#ifdef _OPENMP
#include <omp.h>
#endif

/* Cut each colour's strips into nth contiguous runs of about equal cost:
 * the measured times once every strip of the colour has one, the grain
 * counts before. Each colour ends at a barrier, so each is balanced on its
 * own (one cut for all colours left a thread idle at every colour). */
void gr_dem_split_strips(const gr_dem *d, struct gr_dem_eval *ev, int nth)
{
    int ns = ev->ns, ncol = ev->c.ncol;
    const int32_t *i0 = d->strips.i0;
    for (int col = 0; col < ncol; col++) {
        int *b = ev->split + col * (nth + 1);
        int m = (ns - col + ncol - 1) / ncol, timed = 1;
        double total = 0.0, acc = 0.0;
        for (int k = 0; k < m; k++)
            timed &= ev->stime[col + k * ncol] > 0;
        for (int k = 0; k < m; k++) {
            int s = col + k * ncol;
            total += timed ? ev->stime[s] : (double)(i0[s + 1] - i0[s]) + 1.0;
        }
        int t = 1;
        b[0] = 0;
        for (int k = 0; k < m && t < nth; k++) {
            int s = col + k * ncol;
            double w = timed ? ev->stime[s] : (double)(i0[s + 1] - i0[s]) + 1.0;
            /* cut before strip k when that lands nearer the target */
            while (t < nth && acc + 0.5 * w >= total * t / nth)
                b[t++] = k;
            acc += w;
        }
        while (t <= nth)
            b[t++] = m;
    }
}

int gr_dem_eval_fuse_kick(gr_dem *d, int p)
{
    struct gr_dem_eval *ev = d->ev;
    int ns = ev->ns, ncol = ev->c.ncol;
    const int32_t *i0 = d->strips.i0;
    ev->c.kick = 0;
    /* external forces join at the end of the evaluation, after any kick */
    if (ev->mode != GR_DEM_NB_VERLET || d->ext_fx || ns < 1 || i0[0] != 0 || (size_t)i0[ns] != d->n)
        return 0;
    /* a strip's pushes come from itself, the strip below, and (periodic in
     * y) strip 0 for the last one: the last of these colours kicks it */
    for (int r = 0; r < ns; r++) {
        int k = r;
        if (r >= 1 && (r - 1) % ncol > k % ncol)
            k = r - 1;
        ev->kicker[r] = k;
    }
    /* the thread that will kick a strip drifts it at the next step */
    int nth = ev->c.nth;
    for (int r = 0; r < ns; r++) {
        int k = ev->kicker[r], col = k % ncol, j = k / ncol, t = 0;
        if (nth > 1 && ns > 1)
            while (t + 1 < nth && j >= ev->split[col * (nth + 1) + t + 1])
                t++;
        ev->powner[r] = t;
        ev->kin[r] = 0.0;
    }
    ev->c.kin = ev->kin, ev->c.kicker = ev->kicker;
    ev->c.kick = 1, ev->c.kick_p = p;
    return 1;
}

void gr_dem_eval_drift(gr_dem *d, int p, int q, int track)
{
    const struct gr_dem_eval *ev = d->ev;
    int t = omp_get_thread_num(), T = omp_get_num_threads(), ns = ev->ns;
    for (int r = 0; r < ns; r++)
        if (T == 1 || T != ev->c.nth ? r % T == t : ev->powner[r] == t)
            gr_dem_drift(d, p, q, track, (size_t)d->strips.i0[r], (size_t)d->strips.i0[r + 1], ev->smove + 2 * r);
#pragma omp barrier
}

double gr_dem_eval_moved(const gr_dem *d)
{
    const struct gr_dem_eval *ev = d->ev;
    double m1 = 0, m2 = 0;
    for (int k = 0; k < 2 * ev->ns; k++) {
        double s2 = ev->smove[k];
        if (s2 > m2) {
            if (s2 > m1) {
                m2 = m1;
                m1 = s2;
            } else {
                m2 = s2;
            }
        }
    }
    return sqrt(m1) + sqrt(m2);
}

double gr_dem_eval_kinetic(const gr_dem *d)
{
    double ek = 0.0;
    for (int s = 0; s < d->ev->ns; s++)
        ek += d->ev->kin[s];
    return ek;
}

