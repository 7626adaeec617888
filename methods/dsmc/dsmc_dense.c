/* Whether the particles still form a gas: the packing fraction of bins of
 * about 32 grains (as the cells' density is measured at create), the
 * densest against [dsmc] gas_eta_max. A settling bed, a cluster or a jammed
 * outlet packs beyond the Boltzmann-Enskog gas; the limit limit_dense
 * counts the steps it does, and says where. */
#include <math.h>
#include <stdlib.h>

#include "dsmc_int.h"

double *gr_dsmc_bins(const gr_dsmc *d, int *bx, int *by, size_t *live)
{
    size_t n = 0;
    for (size_t i = 0; i < d->n; i++)
        n += !(d->rank[i] & GR_DSMC_GONE);
    *live = n;
    double side = sqrt(32.0 * d->Lx * d->Ly / (double)(n ? n : 1));
    *bx = (int)fmax(1.0, fmin(256.0, floor(d->Lx / side))), *by = (int)fmax(1.0, fmin(256.0, floor(d->Ly / side)));
    double *cnt = calloc((size_t)*bx * (size_t)*by, sizeof *cnt);
    if (!cnt)
        return NULL;
    for (size_t i = 0; i < d->n; i++)
        if (!(d->rank[i] & GR_DSMC_GONE)) {
            int x = (int)fmin(*bx - 1, fmax(0.0, floor(d->x[i] / d->Lx * *bx)));
            int y = (int)fmin(*by - 1, fmax(0.0, floor(d->y[i] / d->Ly * *by)));
            cnt[(size_t)y * (size_t)*bx + (size_t)x]++;
        }
    return cnt;
}

void gr_dsmc_dense_check(gr_dsmc *d)
{
    int bx, by;
    size_t live;
    double *cnt = gr_dsmc_bins(d, &bx, &by, &live);
    if (!cnt || live < 32) {
        free(cnt);
        return;
    }
    size_t best = 0;
    for (size_t b = 1; b < (size_t)bx * (size_t)by; b++)
        if (cnt[b] > cnt[best])
            best = b;
    double ab = d->Lx * d->Ly / ((double)bx * by), eta = cnt[best] * d->W * M_PI * d->sigma * d->sigma / 4 / ab;
    free(cnt);
    if (eta <= d->par.gas_eta_max)
        return;
    d->dense_steps += GR_DSMC_DENSE_EVERY;
    if (eta > d->dense[0]) {
        int x = (int)(best % (size_t)bx), y = (int)(best / (size_t)bx);
        double w = d->Lx / bx, h = d->Ly / by;
        d->dense[0] = eta, d->dense[1] = x * w, d->dense[2] = y * h, d->dense[3] = (x + 1) * w,
        d->dense[4] = (y + 1) * h;
    }
}
