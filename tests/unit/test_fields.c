/* Coarse-grained fields, window displacements and mean square displacement
 * on configurations whose answers are known. */
#include "test.h"

#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_randist.h>

#include "fields.h"
#include "rng.h"
#include "stats.h"

/* ---------------------------------------------------- disk-rectangle area */

typedef struct {
    double xc, yc, r, y1, y2;
} chord_par;

/* Length of the disk's vertical chord at x inside [y1, y2]. */
static double chord_in(double x, void *vp)
{
    const chord_par *p = vp;
    double dx = x - p->xc;
    if (fabs(dx) >= p->r)
        return 0.0;
    double h = sqrt(p->r * p->r - dx * dx);
    return fmax(0.0, fmin(p->yc + h, p->y2) - fmax(p->yc - h, p->y1));
}

/* The closed form against numerical quadrature, on random rectangles of
 * every size and position relative to the disk; and over a tiling the
 * pieces sum to pi r^2. */
static void disk_rect_area_is_exact(void **state)
{
    (void)state;
    gr_err e = {0};
    gr_rng *r = gr_rng_create(21, 0, &e);
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(2000);
    for (int t = 0; t < 300; t++) {
        chord_par p = {gr_rng_uniform(r), gr_rng_uniform(r), 0.2 + gr_rng_uniform(r), 0, 0};
        double x1 = 3.0 * gr_rng_uniform(r) - 1.5, x2 = x1 + 2.0 * gr_rng_uniform(r);
        p.y1 = 3.0 * gr_rng_uniform(r) - 1.5;
        p.y2 = p.y1 + 2.0 * gr_rng_uniform(r);
        gsl_function F = {chord_in, &p};
        double ref = 0.0, abserr;
        double lo = fmax(x1, p.xc - p.r), hi = fmin(x2, p.xc + p.r);
        /* break points where the chord ends cross y1 or y2 (kinks) */
        double pts[6] = {lo};
        size_t np = 1;
        for (int k = 0; k < 2; k++) {
            double dy = (k ? p.y2 : p.y1) - p.yc;
            if (fabs(dy) < p.r)
                for (int sgn = -1; sgn <= 1; sgn += 2) {
                    double xk = p.xc + sgn * sqrt(p.r * p.r - dy * dy);
                    if (xk > lo && xk < hi)
                        pts[np++] = xk;
                }
        }
        pts[np++] = hi;
        for (size_t u = 1; u < np; u++) /* insertion sort */
            for (size_t v = u; v > 0 && pts[v - 1] > pts[v]; v--) {
                double tmp = pts[v];
                pts[v] = pts[v - 1];
                pts[v - 1] = tmp;
            }
        if (hi > lo)
            assert_int_equal(gsl_integration_qagp(&F, pts, np, 1e-13, 1e-11, 2000, w, &ref, &abserr), 0);
        assert_close(gr_disk_rect_area(p.xc, p.yc, p.r, x1, x2, p.y1, p.y2), ref, 1e-9);
    }
    gsl_integration_workspace_free(w);
    /* simple cases */
    assert_close(gr_disk_rect_area(0, 0, 1, -2, 2, -2, 2), M_PI, 1e-15);
    assert_close(gr_disk_rect_area(0, 0, 1, 0, 2, -2, 2), M_PI / 2, 1e-15);
    assert_close(gr_disk_rect_area(0, 0, 1, 0, 2, 0, 2), M_PI / 4, 1e-15);
    assert_close(gr_disk_rect_area(0, 0, 1, 2, 3, 0, 2), 0.0, 0);
    /* tiling with cells smaller than the disk */
    for (int t = 0; t < 50; t++) {
        double xc = gr_rng_uniform(r), yc = gr_rng_uniform(r), rad = 0.5;
        double cell = 0.1 + 0.5 * gr_rng_uniform(r), s = 0.0;
        for (int i = -20; i < 20; i++) /* covers [-2, 2]^2 */
            for (int j = -20; j < 20; j++)
                s += gr_disk_rect_area(xc, yc, rad, i * cell, (i + 1) * cell, j * cell,
                                       (j + 1) * cell);
        assert_close(s, M_PI * rad * rad, 1e-13);
    }
    gr_rng_free(r);
}

/* ------------------------------------------------------------------ fields */

/* Triangular lattice of unit disks, spacing a, filling [0, L] x [0, L]. */
static gr_particles *hex_lattice(double a, double L)
{
    gr_err e = {0};
    gr_particles *p = gr_particles_create(0, &e);
    double h = a * sqrt(3.0) / 2.0;
    for (int j = 0; (j + 0.5) * h < L; j++)
        for (int i = 0; (i + 0.5 + 0.5 * (j & 1)) * a < L; i++)
            assert_true(gr_particles_push(p, (i + 0.5 + 0.5 * (j & 1)) * a, (j + 0.5) * h, 0.5,
                                          1.0, 0, 0, &e) >= 0);
    return p;
}

static void lattice_packing_fraction(void **state)
{
    (void)state;
    gr_err e = {0};
    double a = 1.05, L = 60.0, phi0 = M_PI / 4.0 / (a * a * sqrt(3.0) / 2.0);
    gr_particles *p = hex_lattice(a, L);
    /* cells of 5 x 5, the grid reaching one cell beyond the packing */
    gr_field *f = gr_field_create(14, 14, -5.0, -5.0, 5.0, 5.0, &e);
    assert_non_null(f);
    assert_int_equal(gr_field_add(f, p, GR_PF_FIXED, 1.0, &e), GR_OK);
    double phi[196], sum = 0.0, worst = 0.0;
    gr_field_packing(f, phi);
    for (int c = 0; c < 196; c++) {
        sum += phi[c] * 25.0;
        int ix = c % 14, iy = c / 14;
        if (ix >= 2 && ix <= 11 && iy >= 2 && iy <= 11)
            worst = fmax(worst, fabs(phi[c] / phi0 - 1.0));
    }
    print_message("# hex lattice phi0 = %.4f, exact binning: worst interior cell %.2f %%\n", phi0,
                  100 * worst);
    assert_true(worst < 0.015);
    /* every disk is inside the grid: the areas add up to N pi r^2 */
    assert_rel(sum, (double)p->n * M_PI * 0.25, 1e-12);
    /* a grid that cuts the packing counts only the part inside it: one
     * cell [0, 0.5) x [0, 0.6) over the corner disk centred (0.5, 0.5) */
    gr_field *cut = gr_field_create(1, 1, 0.0, 0.0, 0.5, 0.6, &e);
    gr_particles *one = gr_particles_create(1, &e);
    gr_particles_push(one, 0.5, 0.5, 0.5, 1.0, 0, 0, &e);
    assert_int_equal(gr_field_add(cut, one, 0, 1.0, &e), GR_OK);
    gr_field_packing(cut, phi);
    assert_close(phi[0] * 0.3, gr_disk_rect_area(0.5, 0.5, 0.5, 0.0, 0.5, 0.0, 0.6), 1e-15);
    assert_true(phi[0] * 0.3 < M_PI / 4 * 0.5 + 1e-12 && phi[0] * 0.3 > M_PI / 16);
    gr_particles_free(one);
    gr_field_free(cut);

    /* centre binning: a cell can gain or lose a lattice row (5 disks of
     * 26), only the mean over cells is right */
    gr_field *g = gr_field_create(14, 14, -5.0, -5.0, 5.0, 5.0, &e);
    g->packing_mode = GR_FIELD_CENTRES;
    assert_int_equal(gr_field_add(g, p, 0, 1.0, &e), GR_OK);
    gr_field_packing(g, phi);
    double mean = 0.0, worst_c = 0.0;
    for (int c = 0; c < 196; c++) {
        int ix = c % 14, iy = c / 14;
        if (ix >= 2 && ix <= 11 && iy >= 2 && iy <= 11) {
            mean += phi[c] / 100.0;
            worst_c = fmax(worst_c, fabs(phi[c] / phi0 - 1.0));
        }
    }
    print_message("# centre binning: mean interior %.4f, worst cell %.1f %%\n", mean,
                  100 * worst_c);
    assert_rel(mean, phi0, 0.01);
    assert_true(worst_c < 0.2 && worst_c > worst);

    /* number per cell and per area */
    double nc[196], na[196];
    gr_field_number(g, nc, na);
    assert_close(na[5 * 14 + 5], nc[5 * 14 + 5] / 25.0, 1e-15);
    double ntot = 0.0;
    for (int c = 0; c < 196; c++)
        ntot += nc[c];
    assert_close(ntot, (double)p->n, 1e-9);
    gr_field_free(g);

    /* fixed grains are left out, and the average over snapshots holds */
    for (size_t i = 0; i < p->n; i += 2)
        p->flags[i] |= GR_PF_FIXED;
    gr_field_clear(f);
    assert_int_equal(gr_field_add(f, p, GR_PF_FIXED, 1.0, &e), GR_OK);
    assert_int_equal(gr_field_add(f, p, GR_PF_FIXED, 3.0, &e), GR_OK);
    gr_field_packing(f, phi);
    sum = 0.0;
    for (int c = 0; c < 196; c++)
        sum += phi[c] * 25.0;
    assert_rel(sum, (double)(p->n / 2) * M_PI * 0.25, 1e-12);
    assert_int_equal(gr_field_add(f, p, 0, 0.0, &e), GR_EINPUT);
    /* a non-finite grain is refused and leaves the sums untouched */
    p->vx[7] = NAN;
    assert_int_equal(gr_field_add(f, p, 0, 1.0, &e), GR_ERUN);
    gr_field_packing(f, phi);
    double sum2 = 0.0;
    for (int c = 0; c < 196; c++)
        sum2 += phi[c] * 25.0;
    assert_close(sum2, sum, 0);
    gr_field_free(f);
    gr_particles_free(p);
}

static void velocity_and_temperature(void **state)
{
    (void)state;
    gr_err e = {0};
    gr_particles *p = hex_lattice(1.05, 20.0);
    gr_field *f = gr_field_create(4, 4, 0.0, 0.0, 5.0, 5.0, &e);
    for (size_t i = 0; i < p->n; i++) {
        p->vx[i] = 0.3;
        p->vy[i] = -1.2;
        p->mass[i] = 2.0;
    }
    assert_int_equal(gr_field_add(f, p, 0, 1.0, &e), GR_OK);
    double vx[16], vy[16], T[16];
    gr_field_velocity(f, vx, vy);
    gr_field_temperature(f, T);
    for (int c = 0; c < 16; c++) {
        assert_close(vx[c], 0.3, 1e-14);
        assert_close(vy[c], -1.2, 1e-14);
        assert_close(T[c], 0.0, 1e-13);
    }
    /* a second snapshot at another uniform velocity: V is the mean and
     * T = m |v1 - v2|^2 / 8 per grain */
    for (size_t i = 0; i < p->n; i++) {
        p->vx[i] = 0.7;
        p->vy[i] = -0.2;
    }
    assert_int_equal(gr_field_add(f, p, 0, 1.0, &e), GR_OK);
    gr_field_velocity(f, vx, vy);
    gr_field_temperature(f, T);
    double v2[32];
    gr_field_velocity_xy(f, v2);
    for (int c = 0; c < 16; c++) {
        assert_close(v2[2 * c], vx[c], 0);
        assert_close(v2[2 * c + 1], vy[c], 0);
        assert_close(vx[c], 0.5, 1e-14);
        assert_close(vy[c], -0.7, 1e-14);
        assert_close(T[c], 2.0 * (0.16 + 1.0) / 8.0, 1e-13);
    }
    /* merge equals accumulating both into one */
    gr_field *g = gr_field_create(4, 4, 0.0, 0.0, 5.0, 5.0, &e);
    assert_int_equal(gr_field_merge(g, f, &e), GR_OK);
    assert_int_equal(gr_field_merge(g, f, &e), GR_OK);
    double T2[16];
    gr_field_temperature(g, T2);
    assert_close(T2[5], T[5], 1e-14);
    gr_field *h = gr_field_create(4, 5, 0.0, 0.0, 5.0, 5.0, &e);
    assert_int_equal(gr_field_merge(h, f, &e), GR_EINPUT);
    gr_field_free(h);
    gr_field_free(g);

    /* thermal velocities of sd s per component: T = m s^2 */
    gr_rng *r = gr_rng_create(22, 0, &e);
    gr_field *one = gr_field_create(1, 1, 0.0, 0.0, 20.0, 20.0, &e);
    for (int snap = 0; snap < 10; snap++) {
        for (size_t i = 0; i < p->n; i++) {
            p->vx[i] = 1.0 + gr_rng_gaussian(r, 0.3);
            p->vy[i] = gr_rng_gaussian(r, 0.3);
        }
        assert_int_equal(gr_field_add(one, p, 0, 1.0, &e), GR_OK);
    }
    gr_field_temperature(one, T);
    gr_field_velocity(one, vx, vy);
    print_message("# thermal cell (%zu grains x 10): T = %.4f (expected %.4f), vx = %.4f\n", p->n,
                  T[0], 2.0 * 0.09, vx[0]);
    assert_rel(T[0], 2.0 * 0.09, 0.03);
    assert_close(vx[0], 1.0, 0.01);
    /* an empty cell has no velocity */
    gr_field *far = gr_field_create(1, 1, 100.0, 100.0, 1.0, 1.0, &e);
    gr_field_add(far, p, 0, 1.0, &e);
    gr_field_velocity(far, vx, NULL);
    gr_field_temperature(far, T);
    assert_true(isnan(vx[0]) && isnan(T[0]));
    assert_int_equal(gr_field_cell(far, 99.0, 100.5), -1);
    gr_field_free(far);
    gr_field_free(one);
    gr_rng_free(r);
    gr_field_free(f);
    gr_particles_free(p);
    assert_null(gr_field_create(0, 3, 0, 0, 1, 1, &e));
    assert_int_equal(e.code, GR_EINPUT);
}

/* ----------------------------------------------------------- displacements */

static double jx(size_t i) { return 0.001 * sin((double)i); }
static double jy(size_t i) { return 0.002 * cos(3.0 * (double)i); }

/* Grains on a 50 x 100 square lattice move by a known shear flow plus a
 * known jitter; the window is 15 x 15 around the centre. */
static void window_displacements(void **state)
{
    (void)state;
    gr_err e = {0};
    size_t n = 5000;
    gr_particles *a = gr_particles_create(n, &e), *b = gr_particles_create(n, &e);
    for (size_t i = 0; i < n; i++) {
        double x = (double)(i % 50) + 0.5, y = (double)(i / 50) + 0.5;
        gr_particles_push(a, x, y, 0.5, 1.0, 0, 0, &e);
        gr_particles_push(b, x + jx(i), y - 0.5 - 0.01 * x + jy(i), 0.5, 1.0, 0, 0, &e);
    }
    double *dx = malloc(n * sizeof *dx), *dy = malloc(n * sizeof *dy);
    size_t m;
    gr_disp_opts o = {.x0 = 17.5, .x1 = 32.5, .y0 = 42.5, .y1 = 57.5};
    assert_int_equal(gr_disp_particles(a, b, &o, dx, dy, &m, &e), GR_OK);
    assert_int_equal(m, 225);
    /* first selected grain: x = 17.5, y = 42.5, index 42 * 50 + 17 */
    assert_close(dx[0], jx(42 * 50 + 17), 1e-12);
    assert_close(dy[0], -0.5 - 0.175 + jy(42 * 50 + 17), 1e-12);

    /* the mean vertical flow subtracted */
    o.subtract_y = 1;
    o.subtract_x = 1;
    assert_int_equal(gr_disp_particles(a, b, &o, dx, dy, &m, &e), GR_OK);
    double sx = 0, sy = 0, vy_mean = 0;
    for (size_t k = 0; k < m; k++) {
        sx += dx[k];
        sy += dy[k];
        vy_mean += dy[k] * dy[k];
    }
    assert_close(sx, 0.0, 1e-13);
    assert_close(sy, 0.0, 1e-12);
    double sd_window = sqrt(vy_mean / m);

    /* per column: the shear is removed, the jitter stays */
    o.subtract_y = 15;
    assert_int_equal(gr_disp_particles(a, b, &o, dx, dy, &m, &e), GR_OK);
    double s2 = 0;
    for (size_t k = 0; k < m; k++)
        s2 += dy[k] * dy[k];
    double sd_col = sqrt(s2 / m);
    print_message("# dy sd: window mean removed %.4f, column means removed %.5f\n", sd_window,
                  sd_col);
    assert_close(sd_window, 0.01 * sqrt((15.0 * 15.0 - 1.0) / 12.0), 2e-4);
    assert_true(sd_col < 0.0016 && sd_col > 0.001);

    /* reordered, one grain gone, one reinserted far away, one fixed */
    gr_particles *c = gr_particles_create(n, &e);
    for (size_t j = n; j-- > 0;) {
        if (j == 45 * 50 + 20) /* in the window, missing from c */
            continue;
        long k = gr_particles_push(c, b->x[j], b->y[j], 0.5, 1.0, 0, 0, &e);
        c->id[k] = b->id[j];
        if (j == 46 * 50 + 20)
            c->y[k] = 99.0; /* reinserted at the top */
        if (j == 47 * 50 + 20)
            c->flags[k] = GR_PF_FIXED;
    }
    o = (gr_disp_opts){.x0 = 17.5, .x1 = 32.5, .y0 = 42.5, .y1 = 57.5, .max_jump = 5.0,
                       .skip_flags = GR_PF_FIXED};
    assert_int_equal(gr_disp_particles(a, c, &o, dx, dy, &m, &e), GR_OK);
    assert_int_equal(m, 222);
    assert_close(dx[0], jx(42 * 50 + 17), 1e-12); /* still in index order of a */

    /* periodic side: a grain crossing x = 50 moves by +0.2, not -49.8 */
    double xa[1] = {49.9}, ya[1] = {1.0}, xb[1] = {0.1}, yb[1] = {1.0};
    o = (gr_disp_opts){.x0 = 0, .x1 = 50, .y0 = 0, .y1 = 2, .period_x = 50.0};
    assert_int_equal(gr_disp_window(xa, ya, xb, yb, NULL, 1, &o, dx, dy, &m, &e), GR_OK);
    assert_int_equal(m, 1);
    assert_close(dx[0], 0.2, 1e-12);
    o.x1 = o.x0;
    assert_int_equal(gr_disp_window(xa, ya, xb, yb, NULL, 1, &o, dx, dy, &m, &e), GR_EINPUT);

    free(dx);
    free(dy);
    gr_particles_free(a);
    gr_particles_free(b);
    gr_particles_free(c);
}

/* --------------------------------------------- mean square displacement */

/* Displacements of sd sqrt(2 t^alpha) per component: the log-log fit of
 * the accumulated MSD returns alpha; kappa is 0 for Gaussian steps and 1
 * for Laplace steps. */
static void msd_exponent_and_kappa(void **state)
{
    (void)state;
    gr_err e = {0};
    gr_rng *r = gr_rng_create(23, 0, &e);
    size_t nl = 8, n = 4000;
    gr_msd *s = gr_msd_create(nl, &e), *half = gr_msd_create(nl, &e);
    double *dx = malloc(n * sizeof *dx), *dy = malloc(n * sizeof *dy);
    for (int origin = 0; origin < 2; origin++)
        for (size_t k = 0; k < nl; k++) {
            double t = pow(2.0, (double)k), sd = sqrt(2.0 * pow(t, 1.4));
            for (size_t i = 0; i < n; i++) {
                dx[i] = gr_rng_gaussian(r, sd);
                dy[i] = gsl_ran_laplace(gr_rng_gsl(r), sd / sqrt(2.0));
            }
            assert_int_equal(gr_msd_add(s, k, t, dx, dy, n, &e), GR_OK);
            if (origin == 0)
                assert_int_equal(gr_msd_add(half, k, t, dx, dy, n, &e), GR_OK);
        }
    double mx[8], my[8], ex[8], ey[8], kx[8], ky[8];
    gr_msd_result(s, mx, my, ex, ey, kx, ky);
    gr_fit f;
    assert_int_equal(gr_fit_loglog(s->lag, mx, ex, nl, &f, &e), GR_OK);
    print_message("# MSD x: exponent %.4f +- %.4f, prefactor %.3f; kappa x %.3f y %.3f\n", f.p[1],
                  f.err[1], f.p[0], kx[3], ky[3]);
    assert_close(f.p[1], 1.4, 4.0 * f.err[1]);
    assert_true(f.err[1] < 0.01);
    assert_close(f.p[0], 2.0, 4.0 * f.err[0]);
    assert_int_equal(gr_fit_loglog(s->lag, my, ey, nl, &f, &e), GR_OK);
    assert_close(f.p[1], 1.4, 4.0 * f.err[1]);
    /* sd of kappa from 8000 samples: sqrt(24/8000)/3 = 0.018 (Gauss), about
     * 50/sqrt(8000)/3 = 0.19 (Laplace; 0.07 for the mean of 8 lags) */
    double kmean = 0.0;
    for (size_t k = 0; k < nl; k++) {
        assert_close(kx[k], 0.0, 0.1);
        kmean += ky[k] / (double)nl;
    }
    assert_close(kmean, 1.0, 0.3);
    /* merging the first origin twice into a copy: same counts as s */
    gr_msd *m2 = gr_msd_create(nl, &e);
    assert_int_equal(gr_msd_merge(m2, half, &e), GR_OK);
    assert_int_equal(gr_msd_merge(m2, half, &e), GR_OK);
    assert_close(m2->n[4], s->n[4], 0);
    assert_close(m2->lag[4], 16.0, 0);
    assert_int_equal(gr_msd_add(s, 2, 5.0, dx, dy, 1, &e), GR_EINPUT);
    assert_int_equal(gr_msd_add(s, 8, 5.0, dx, dy, 1, &e), GR_EINPUT);
    gr_msd *other = gr_msd_create(3, &e);
    assert_int_equal(gr_msd_merge(m2, other, &e), GR_EINPUT);
    gr_msd_free(other);
    gr_msd_free(m2);
    gr_msd_free(half);
    gr_msd_free(s);
    gr_msd_free(NULL);
    free(dx);
    free(dy);
    gr_rng_free(r);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(disk_rect_area_is_exact),
        cmocka_unit_test(lattice_packing_fraction),
        cmocka_unit_test(velocity_and_temperature),
        cmocka_unit_test(window_displacements),
        cmocka_unit_test(msd_exponent_and_kappa),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
