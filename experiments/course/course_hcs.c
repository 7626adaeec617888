/* Whether a cooling gas is still homogeneous. The homogeneous cooling
 * state of inelastic disks is unstable in a box longer than
 * L_c = 2 pi / (n d sqrt(pi chi (1 - alpha^2))): there the shear mode's
 * viscous damping, nu k^2 with the dilute kinematic viscosity
 * nu = sqrt(T / (pi m)) / (2 n d), is slower than the thermal speed's decay
 * (1 - alpha^2) nu_E / 4 with Enskog's collision frequency nu_E, so vortices
 * grow, then clusters (Goldhirsch & Zanetti, Phys. Rev. Lett. 70, 1619
 * (1993); Brey, Ruiz-Montero & Cubero, Phys. Rev. E 54, 3664 (1996)). The
 * test: the Fourier modes of the momentum and number densities at
 * wavelengths above L_c, against their size in a homogeneous gas. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "course.h"
#include "plot.h"

/* At most this many modes: the smallest wave vectors first. */
#define MAXMODES 200

double course_hcs_lc(double n, double chi, double alpha)
{
    double a = 1 - alpha * alpha;
    return a > 0 ? 2 * M_PI / (n * sqrt(M_PI * chi * a)) : INFINITY;
}

/* The half plane of integer wave vectors (a, b) with 0 < a^2 + b^2 <= r2,
 * nearest first (at least the four of the first shell). */
static int modes(double r2, int (*ab)[2])
{
    int m = 0;
    int R = (int)ceil(sqrt(r2 < 1 ? 1 : r2));
    for (int s = 1; s <= 2 * R * R && m < MAXMODES; s++) {
        if (s > r2 && m >= 2)
            break;
        for (int a = 0; a <= R && m < MAXMODES; a++)
            for (int b = -R; b <= R && m < MAXMODES; b++)
                if (a * a + b * b == s && (a > 0 || b > 0))
                    ab[m][0] = a, ab[m][1] = b, m++;
    }
    return m;
}

int course_hcs_measure(const gr_particles *p, double L, double alpha, double chi, course_hcs *h)
{
    size_t N = p->n;
    double ux = 0, uy = 0;
    for (size_t i = 0; i < N; i++)
        ux += p->vx[i], uy += p->vy[i];
    ux /= (double)N, uy /= (double)N;
    double T = 0;
    for (size_t i = 0; i < N; i++)
        T += (p->vx[i] - ux) * (p->vx[i] - ux) + (p->vy[i] - uy) * (p->vy[i] - uy);
    T /= 2.0 * (double)N;
    double n = (double)N / (L * L);
    h->lc = course_hcs_lc(n, chi, alpha);
    int ab[MAXMODES][2];
    double r = L / h->lc;
    h->modes = modes(r * r, ab);
    double sj = 0, sr = 0;
    for (int k = 0; k < h->modes; k++) {
        double kx = 2 * M_PI * ab[k][0] / L, ky = 2 * M_PI * ab[k][1] / L;
        double rc = 0, rs = 0, jxc = 0, jxs = 0, jyc = 0, jys = 0;
        for (size_t i = 0; i < N; i++) {
            double ph = kx * p->x[i] + ky * p->y[i], c = cos(ph), s = sin(ph);
            double vx = p->vx[i] - ux, vy = p->vy[i] - uy;
            rc += c, rs += s, jxc += vx * c, jxs += vx * s, jyc += vy * c, jys += vy * s;
        }
        sr += rc * rc + rs * rs;
        sj += jxc * jxc + jxs * jxs + jyc * jyc + jys * jys;
    }
    /* a homogeneous gas: <|rho_k|^2> = N S(k) (S near 1 when dilute),
     * <|j_k|^2> = 2 N T (uncorrelated velocities) */
    h->density = sr / ((double)N * h->modes);
    h->flow = T > 0 ? sj / (2.0 * (double)N * T * h->modes) : 0;
    return GR_OK;
}

/* The number density and the mean velocity on a grid of m x m cells. */
static void coarse(const gr_particles *p, double L, int m, double *rho, double *u, double *v)
{
    for (int c = 0; c < m * m; c++)
        rho[c] = u[c] = v[c] = 0;
    for (size_t i = 0; i < p->n; i++) {
        int cx = (int)(p->x[i] / L * m), cy = (int)(p->y[i] / L * m);
        cx = cx < 0 ? 0 : cx >= m ? m - 1 : cx, cy = cy < 0 ? 0 : cy >= m ? m - 1 : cy;
        rho[cy * m + cx] += 1, u[cy * m + cx] += p->vx[i], v[cy * m + cx] += p->vy[i];
    }
    for (int c = 0; c < m * m; c++)
        if (rho[c] > 0)
            u[c] /= rho[c], v[c] /= rho[c];
}

/* The density map on cells of about 40 disks (8 to 40 a side), the flow
 * as arrows on cells three times wider: the long-wave structure the
 * instability grows, above the noise of a few disks a cell. */
int course_hcs_plot(const char *png, const gr_particles *p, double L, double t, const char *title, gr_err *err)
{
    int m = (int)sqrt((double)p->n / 40);
    m = m < 8 ? 8 : m > 40 ? 40 : m;
    int ma = m / 3 < 6 ? 6 : m / 3;
    double *rho = malloc(3 * (size_t)(m * m) * sizeof *rho), *fl = malloc(3 * (size_t)(ma * ma) * sizeof *fl);
    if (!rho || !fl) {
        free(rho), free(fl);
        return gr_fail(err, GR_ERUN, "out of memory for the %d x %d cells of %s", m, m, png);
    }
    double *u = fl + ma * ma, *v = u + ma * ma, c = L / m, ca = L / ma, mean = (double)p->n / (m * m), umax = 0;
    coarse(p, L, m, rho, rho + m * m, rho + 2 * m * m);
    coarse(p, L, ma, fl, u, v);
    for (int k = 0; k < ma * ma; k++)
        umax = fmax(umax, hypot(u[k], v[k]));
    FILE *gp = gr_plot_open(png, 760, 700, err);
    if (!gp) {
        free(rho), free(fl);
        return err->code;
    }
    fprintf(gp, "$rho << EOD\n");
    for (int k = 0; k < m * m; k++)
        fprintf(gp, "%.6g %.6g %.4g\n", (k % m + 0.5) * c, (k / m + 0.5) * c, rho[k] / mean);
    fprintf(gp, "EOD\n$u << EOD\n");
    /* arrows centred on their cells, the longest 0.9 of a cell */
    double sc = umax > 0 ? 0.9 * ca / umax : 0;
    for (int k = 0; k < ma * ma; k++)
        fprintf(gp, "%.6g %.6g %.4g %.4g\n", (k % ma + 0.5) * ca - 0.5 * sc * u[k],
                (k / ma + 0.5) * ca - 0.5 * sc * v[k], sc * u[k], sc * v[k]);
    char full[256], q[600];
    snprintf(full, sizeof full, "%s, t = %.4g", title, t);
    gr_plot_quote(full, q, sizeof q);
    fprintf(gp, "EOD\nset title %s\nset size ratio -1\nset xrange [0:%.8g]\nset yrange [0:%.8g]\n"
                "set xlabel 'x / d     (arrows: mean velocity of %d x %d cells, the longest %.3g V_0)'\n"
                "set ylabel 'y / d'\nset cblabel 'number density of %d x %d cells / its mean'\n"
                "set palette defined (0 'white', 1 '#9ecae1', 2 '#3182bd', 4 '#08306b')\nset cbrange [0:*]\n"
                "plot $rho u 1:2:3 w image notitle, $u u 1:2:3:4 w vectors head filled size %.3g,20 lw 2 "
                "lc 'black' notitle\n",
            q, L, L, ma, ma, umax, m, m, 0.2 * ca);
    free(rho), free(fl);
    return gr_plot_close(gp, png, err);
}
