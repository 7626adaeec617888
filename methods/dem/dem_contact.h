/* The contact law of one pair (or grain and wall), inlined into the force
 * loops. Sign conventions (docs/methods/dem.md): n points from i to j,
 * t = perp(n); dv = v_j - v_i; the force returned acts on j, -F on i;
 * both torques are -Ft R. A wall is grain i with v = wall velocity, R = 0. */
#ifndef GR_DEM_CONTACT_H
#define GR_DEM_CONTACT_H

#include <math.h>
#include <stdint.h>

#include "dem.h"

#define DEM_INLINE static inline __attribute__((always_inline))

typedef struct {
    double kn, gn, kt, gt, mu, dt;
    int clip;
} dem_law;

/* Grain at (px, py) of radius r against the segment from (ax, ay) along
 * (ex, ey): 0 when apart, else 1 with the overlap and the unit normal from
 * the segment to the grain (the segment's own normal when the centre lies
 * on it). One geometry for the force loop and the contact network. */
DEM_INLINE int dem_seg_contact(double ax, double ay, double ex, double ey, double px, double py,
                               double r, double *xi, double *nx, double *ny)
{
    double l2 = ex * ex + ey * ey;
    double u = l2 > 0 ? ((px - ax) * ex + (py - ay) * ey) / l2 : 0.0;
    u = u < 0 ? 0 : u > 1 ? 1 : u;
    double dx = px - (ax + u * ex), dy = py - (ay + u * ey);
    double d2 = dx * dx + dy * dy;
    if (d2 >= r * r)
        return 0;
    double dist = sqrt(d2);
    if (dist > 0) {
        *nx = dx / dist;
        *ny = dy / dist;
    } else {
        double le = sqrt(l2);
        *nx = -ey / le;
        *ny = ex / le;
    }
    *xi = r - dist;
    return 1;
}

/* History slot lookup for the pair (owner index, partner key) at the force
 * evaluation numbered E; returns the slot or -1 when the table is full. */
DEM_INLINE long dem_hist_slot(gr_dem_hist *h, size_t own, int32_t key, uint64_t E, int *fresh)
{
    int cap = h->cap;
    size_t base = own * (size_t)cap;
    int32_t *P = h->partner + base;
    uint64_t *St = h->stamp + base;
    long freek = -1;
    for (int k = 0; k < cap; k++) {
        if (P[k] == key && St[k] + 1 == E) {
            *fresh = 0;
            return (long)(base + (size_t)k);
        }
        if (freek < 0 && (P[k] < 0 || St[k] + 1 < E))
            freek = k;
    }
    *fresh = 1;
    return freek < 0 ? -1 : (long)(base + (size_t)freek);
}

/* Write slot s at evaluation E, keeping its previous content for undo. */
DEM_INLINE void dem_hist_write(gr_dem_hist *h, long s, int32_t key, double z, uint64_t E)
{
    if (h->stamp[s] != E) {
        h->partner_old[s] = h->partner[s];
        h->z_old[s] = h->z[s];
        h->stamp_old[s] = h->stamp[s];
    }
    h->partner[s] = key;
    h->z[s] = z;
    h->stamp[s] = E;
}

/* Normal and tangential force for overlap xi along unit n (nx, ny), with
 * relative velocity dv and rotation term wsum = w_i R_i + w_j R_j. zeta is
 * the spring's stretch (in/out, TL == spring only), integ its time step;
 * energy receives the normal spring's elastic energy. */
DEM_INLINE void dem_law_eval(const dem_law *L, const int NL, const int TL, double xi,
                             double nx, double ny, double dvx, double dvy, double wsum,
                             double *zeta, double integ, double *Fx, double *Fy, double *Ft,
                             double *energy)
{
    double vn = dvx * nx + dvy * ny;
    double el = NL == GR_NORMAL_HERTZ ? L->kn * xi * sqrt(xi) : L->kn * xi;
    /* elastic energy kn xi^(p+1) / (p+1), for the energy-jump check */
    *energy = el * xi * (NL == GR_NORMAL_HERTZ ? 0.4 : 0.5);
    double fn = el - L->gn * vn;
    if (L->clip && fn < 0.0)
        fn = 0.0;
    double ft = 0.0;
    if (TL != GR_TANG_NONE) {
        double vt = -dvx * ny + dvy * nx - wsum;
        double afn = fabs(fn);
        if (TL == GR_TANG_COULOMB) {
            ft = vt > 0 ? -L->mu * afn : vt < 0 ? L->mu * afn : 0.0;
        } else if (TL == GR_TANG_VISCOUS) {
            ft = -L->gt * vt;
        } else if (TL == GR_TANG_REGULARISED) {
            double a = L->gt * fabs(vt), b = L->mu * afn;
            double m = a < b ? a : b;
            ft = vt > 0 ? -m : vt < 0 ? m : 0.0;
        } else {
            double z = *zeta + integ * vt;
            double fs = -(L->kt * z + L->gt * vt);
            double cap = L->mu * afn;
            if (fabs(fs) > cap) {
                ft = fs > 0 ? cap : -cap;
                z = -(ft + L->gt * vt) / L->kt;
            } else {
                ft = fs;
            }
            *zeta = z;
        }
    }
    *Fx = fn * nx - ft * ny;
    *Fy = fn * ny + ft * nx;
    *Ft = ft;
}

#endif
