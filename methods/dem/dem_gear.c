/* The integrators other than velocity Verlet: Gear's 6-value predictor
 * and corrector and explicit Euler, and the kinetic energy summed over the
 * grains (Verlet's comes from its kick). Each writes into the other buffer,
 * so that a refused step leaves the last good state in place. */
#include <stddef.h>

#include "dem.h"
#include "geom.h"

double gr_dem_kinetic(gr_dem *d, int q)
{
    double ek = 0;
    for (size_t i = 0; i < d->n; i++) {
        double vx = d->f[F_VX][q][i], vy = d->f[F_VY][q][i];
        ek += (d->im[i] != 0) * 0.5 * d->mass[i] * (vx * vx + vy * vy);
        if (d->rot)
            ek += (d->iI[i] != 0) * 0.5 * d->inertia[i] * d->f[F_W][q][i] * d->f[F_W][q][i];
    }
    return ek;
}

void gr_dem_predict_euler(gr_dem *d, int p, int q)
{
    double dt = d->par.dt;
    for (size_t i = 0; i < d->n; i++) {
        double ax = d->f[F_FX][p][i] * d->im[i], ay = d->f[F_FY][p][i] * d->im[i] - d->gf[i];
        d->f[F_X][q][i] = gr_wrap(d->f[F_X][p][i] + dt * d->f[F_VX][p][i], d->Lx);
        d->f[F_Y][q][i] = gr_wrap(d->f[F_Y][p][i] + dt * d->f[F_VY][p][i], d->Ly);
        d->f[F_VX][q][i] = d->f[F_VX][p][i] + dt * ax;
        d->f[F_VY][q][i] = d->f[F_VY][p][i] + dt * ay;
        if (d->rot)
            d->f[F_W][q][i] = d->f[F_W][p][i] + dt * d->f[F_TQ][p][i] * d->iI[i];
    }
}

/* Gear, 6 values (Allen & Tildesley, app. E), scaled derivatives b_k;
 * c0 = 3/16 because the forces depend on velocities. */
static const double gear_c[6] = {3.0 / 16.0, 251.0 / 360.0, 1.0, 11.0 / 18.0, 1.0 / 6.0, 1.0 / 60.0};

/* Per degree of freedom (x, y, angle): the position, velocity and b_2..b_5
 * fields, shared by the predictor and the corrector. */
static const int gear_q0[3] = {F_X, F_Y, F_TH}, gear_qv[3] = {F_VX, F_VY, F_W};
static const int gear_qb[3][4] = {{F_B2X, F_B3X, F_B4X, F_B5X}, {F_B2Y, F_B3Y, F_B4Y, F_B5Y},
                                  {F_B2T, F_B3T, F_B4T, F_B5T}};

void gr_dem_predict_gear(gr_dem *d, int p, int q)
{
    double dt = d->par.dt;
    int ndof = d->rot ? 3 : 2;
    for (int c = 0; c < ndof; c++) {
        double *r0 = d->f[gear_q0[c]][p], *v = d->f[gear_qv[c]][p];
        const int *k = gear_qb[c];
        double *b2 = d->f[k[0]][p], *b3 = d->f[k[1]][p], *b4 = d->f[k[2]][p], *b5 = d->f[k[3]][p];
        double *R0 = d->f[gear_q0[c]][q], *V = d->f[gear_qv[c]][q];
        double *B2 = d->f[k[0]][q], *B3 = d->f[k[1]][q], *B4 = d->f[k[2]][q], *B5 = d->f[k[3]][q];
        double L = c == 0 ? d->Lx : c == 1 ? d->Ly : 0.0;
        for (size_t i = 0; i < d->n; i++) {
            double b1 = dt * v[i];
            R0[i] = gr_wrap(r0[i] + b1 + b2[i] + b3[i] + b4[i] + b5[i], L);
            double B1 = b1 + 2 * b2[i] + 3 * b3[i] + 4 * b4[i] + 5 * b5[i];
            B2[i] = b2[i] + 3 * b3[i] + 6 * b4[i] + 10 * b5[i];
            B3[i] = b3[i] + 4 * b4[i] + 10 * b5[i];
            B4[i] = b4[i] + 5 * b5[i];
            B5[i] = b5[i];
            V[i] = B1 / dt;
        }
    }
}

void gr_dem_correct_gear(gr_dem *d, int q)
{
    double dt = d->par.dt, h2 = 0.5 * dt * dt;
    int ndof = d->rot ? 3 : 2;
    for (int c = 0; c < ndof; c++) {
        const int *k = gear_qb[c];
        double *R0 = d->f[gear_q0[c]][q], *V = d->f[gear_qv[c]][q];
        double *B2 = d->f[k[0]][q], *B3 = d->f[k[1]][q], *B4 = d->f[k[2]][q], *B5 = d->f[k[3]][q];
        const double *F = d->f[c == 0 ? F_FX : c == 1 ? F_FY : F_TQ][q];
        const double *inv = c == 2 ? d->iI : d->im;
        double L = c == 0 ? d->Lx : c == 1 ? d->Ly : 0.0;
        for (size_t i = 0; i < d->n; i++) {
            double a = F[i] * inv[i] - (c == 1 ? d->gf[i] : 0.0);
            double del = h2 * a - B2[i];
            R0[i] = gr_wrap(R0[i] + gear_c[0] * del, L);
            V[i] += gear_c[1] * del / dt;
            B2[i] += gear_c[2] * del;
            B3[i] += gear_c[3] * del;
            B4[i] += gear_c[4] * del;
            B5[i] += gear_c[5] * del;
        }
    }
}
