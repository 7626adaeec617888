/* grano bench dem: throughput of the soft DEM backend on a dense settled
 * bed (Hertz, regularised friction, the thesis's constants) against N, the
 * same bed in LAMMPS when asked (--peer lammps), and the speed-against-error
 * sweep (--accuracy). */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "bench_c2c.h"
#include "clock.h"
#include "cmd.h"
#include "dem/dem.h"
#include "init.h"
#include "opts.h"
#include "plot.h"
#include "table.h"

static gr_scene *bench_dem_scene(const char *text, gr_err *err)
{
    static const char *const ext[] = {"dem", NULL};
    return gr_scene_parse(text, "bench-dem", ext, err);
}

/* A hexagonal bed of n unit grains, about as wide as tall, in a box of
 * fixed grains (bottom row and two side columns), shifted by 2 so that the
 * domain's own walls stay clear. */
static gr_particles *make_bed(long n, double *width, double *height, gr_err *err)
{
    gr_particles *p = gr_particles_create((size_t)n + 4096, err);
    if (!p)
        return NULL;
    long cols = (long)ceil(sqrt((double)n * 1.1547));
    long rows = (n + cols - 1) / cols;
    double s = 1.0 + 1e-4, h = 0.5 * sqrt(3.0) * s, o = 2.0;
    double xr = 1.0 + (double)(cols - 1) * s + 0.5 * s + 1.0;
    double top = 1.0 + (double)rows * h + 2.0;
    long k = 0;
    for (long r = 0; r < rows && k < n; r++)
        for (long c = 0; c < cols && k < n; c++, k++)
            if (gr_particles_push(p, o + 1.0 + (double)c * s + (r % 2 ? 0.5 * s : 0.0),
                                  o + 1.0 + (double)r * h, 0.5, 1.0, 0, 0, err) < 0)
                goto fail;
    long nb = (long)ceil(xr);
    for (long c = 0; c <= nb; c++)
        if (gr_particles_push(p, o + xr * (double)c / (double)nb, o, 0.5, 1.0, GR_PF_FIXED, 0, err) < 0)
            goto fail;
    for (double y = 1.0; y <= top; y += 1.0)
        if (gr_particles_push(p, o, o + y, 0.5, 1.0, GR_PF_FIXED, 0, err) < 0 ||
            gr_particles_push(p, o + xr, o + y, 0.5, 1.0, GR_PF_FIXED, 0, err) < 0)
            goto fail;
    for (size_t i = 0; i < p->n; i++)
        p->id[i] = (int64_t)i;
    *width = xr + 2 * o;
    *height = top + 2 * o;
    return p;
fail:
    gr_particles_free(p);
    return NULL;
}

/* The bed's state after the settling steps, in id order. */
typedef struct {
    long n;
    double rate;          /* mobile particle-steps per second */
    double seconds;
    double cpu_rate;      /* per second of CPU time */
    double bytes_per_grain;
    double lammps_rate;
    double lammps_seconds;
    double lammps_cpu_rate;
    double rate1;         /* --scaling: one thread, timed interleaved with T */
    double c2c[2];        /* --scaling: the threads' round trip before and after, ns */
} bed_result;

static int lammps_run(const gr_particles *p, double width, double height, long steps, double skin,
                      const char *dir, bed_result *r, gr_err *err)
{
    char data[1200], in[1200], log[1200], cmd[4096];
    snprintf(data, sizeof data, "%s/bed-%ld.data", dir, r->n);
    snprintf(in, sizeof in, "%s/bed-%ld.in", dir, r->n);
    snprintf(log, sizeof log, "%s/bed-%ld.log", dir, r->n);
    FILE *f = fopen(data, "w");
    if (!f)
        return gr_fail(err, GR_EINPUT, "%s: %s", data, strerror(errno));
    size_t live = 0;
    for (size_t i = 0; i < p->n; i++)
        live += !(p->flags[i] & GR_PF_GONE);
    fprintf(f, "grano dense bed, %ld mobile grains (grano bench dem)\n\n%zu atoms\n2 atom types\n\n"
               "0 %.17g xlo xhi\n0 %.17g ylo yhi\n-0.5 0.5 zlo zhi\n\nAtoms # sphere\n\n",
            r->n, live, width, height);
    /* diameter, and a density giving m = 1 for a unit sphere: masses are
     * then set to 1 in the input, since the data file's density is 3D */
    for (size_t i = 0; i < p->n; i++)
        if (!(p->flags[i] & GR_PF_GONE))
            fprintf(f, "%zu %d %.17g %.17g %.17g %.17g 0\n", i + 1, p->flags[i] & GR_PF_FIXED ? 2 : 1,
                    2 * p->radius[i], 6.0 / M_PI, p->x[i], p->y[i]);
    fprintf(f, "\nVelocities\n\n");
    for (size_t i = 0; i < p->n; i++)
        if (!(p->flags[i] & GR_PF_GONE))
            fprintf(f, "%zu %.17g %.17g 0 0 0 %.17g\n", i + 1, p->vx[i], p->vy[i], p->omega[i]);
    fclose(f);
    f = fopen(in, "w");
    if (!f)
        return gr_fail(err, GR_EINPUT, "%s: %s", in, strerror(errno));
    fprintf(f,
            "# The bed of grano bench dem: Hertz kn = 1e5 (LAMMPS scales by sqrt(R_eff) = 1/2),\n"
            "# gamma_n = 100, regularised friction gamma_t = 300, mu = 0.5, dt = 1.25e-4.\n"
            "units lj\ndimension 2\natom_style sphere\nboundary f f p\ncomm_modify vel yes\n"
            "read_data %s\nset group all mass 1.0\n"
            "group mobile type 1\ngroup wall type 2\n"
            "pair_style granular\n"
            "pair_coeff * * hertz 2.0e5 100.0 damping velocity tangential linear_nohistory 3.0 0.5\n"
            "neighbor %.17g bin\nneigh_modify delay 0 every 1 check yes exclude type 2 2\n"
            "fix 1 mobile nve/sphere disc\nfix 2 all enforce2d\nfix 3 mobile gravity 1.0 vector 0 -1 0\n"
            "timestep 1.25e-4\nthermo %ld\nrun %ld\n",
            data, skin, steps, steps);
    fclose(f);
    snprintf(cmd, sizeof cmd, "OMP_NUM_THREADS=1 lmp -in '%s' -log '%s' -screen none > /dev/null 2>&1", in, log);
    int rc = system(cmd);
    if (rc != 0)
        return gr_fail(err, GR_ERUN, "lmp failed (exit %d); its log is %s (is Debian's lammps installed?)", rc, log);
    f = fopen(log, "r");
    if (!f)
        return gr_fail(err, GR_ERUN, "%s: %s", log, strerror(errno));
    char line[1024];
    double loop = -1, cpu_pct = 100;
    long st = 0, atoms = 0;
    while (fgets(line, sizeof line, f)) {
        double tl, pc;
        int procs;
        if (sscanf(line, "Loop time of %lf on %d procs for %ld steps with %ld atoms", &tl, &procs, &st, &atoms) == 4)
            loop = tl;
        if (sscanf(line, "%lf%% CPU use", &pc) == 1)
            cpu_pct = pc;
    }
    fclose(f);
    if (loop <= 0 || st != steps)
        return gr_fail(err, GR_ERUN, "%s: no 'Loop time' line for %ld steps", log, steps);
    r->lammps_seconds = loop;
    r->lammps_rate = (double)r->n * (double)steps / loop;
    r->lammps_cpu_rate = r->lammps_rate * 100.0 / cpu_pct;
    return GR_OK;
}

/* One thread and T threads timed in alternating rounds on the same bed, so
 * that a change of machine load hits both alike (the runs are bit-identical
 * whatever the thread count, so switching mid-run changes nothing else).
 * The rounds go 1, T, T, 1, 1, T, ...: a cost that drifts through the run
 * (the flowing silo's rises as it fills: 98 list builds in its first 16000
 * timed steps, 145 in the next) hits both alike, where 1, T, 1, T gave T
 * always the later, dearer round. */
static int time_scaling(gr_dem *d, long steps, long threads, bed_result *r, gr_err *err)
{
    enum { ROUNDS = 4 };
    double sec[2] = {0, 0};
    long per = steps / ROUNDS > 0 ? steps / ROUNDS : 1;
    r->c2c[0] = bench_c2c_ns(2000);
    for (int k = 0; k < ROUNDS; k++) {
        for (int j = 0; j < 2; j++) {
            int v = j ^ (k & 1);
            d->par.threads = v ? threads : 1;
            double t0 = exp_wall_seconds();
            if (gr_dem_advance(d, INFINITY, (uint64_t)per, err))
                return err->code;
            sec[v] += exp_wall_seconds() - t0;
        }
    }
    d->par.threads = threads;
    r->c2c[1] = bench_c2c_ns(2000);
    r->seconds = sec[1];
    r->rate = (double)d->nmobile * (double)(per * ROUNDS) / sec[1];
    r->rate1 = (double)d->nmobile * (double)(per * ROUNDS) / sec[0];
    return GR_OK;
}

/* The flowing silo of grano silo-flow (thesis section 3.1), simplified: n
 * grains on a lattice (pitch 1.05) in a box of wall grains W wide and 2 W
 * tall, the orifice D = 8 open from the start and the grains that leave
 * reinserted at the top, so that after the settling steps the flow is
 * steady. W from n as silo-flow's 50 for 5000. */
static void silo_text(long n, long threads, double skin, char *text, size_t cap)
{
    double W = round(50.0 * sqrt((double)n / 5000.0)), H = 2 * W, b = 5, D = 8;
    long per_row = (long)floor((W - 0.1) / 1.05), rows = (n + per_row - 1) / per_row + 1;
    double r0 = b + 0.05, r1 = r0 + (double)rows * 1.05 + 0.5;
    snprintf(text, cap,
             "[scene]\nseed = 1\n[domain]\nwidth = %.17g\nheight = %.17g\nbottom = open\ngravity = 1\n"
             "[material]\nnormal = hertz\ntangential = regularised\nkn = 1e5\ngamma_n = 100\n"
             "gamma_t = 300\nmu = 0.5\n[species]\ndiameter = 1\ncount = %ld\n"
             "[silo]\nwidth = %.17g\nheight = %.17g\nbase = %.17g\norifice = %.17g\nopen_time = 0\n"
             "walls = grains\nexit_below = %.17g\nreinsert = yes\n"
             "[init]\nkind = lattice\nregion = 1 %.17g %.17g %.17g\nspacing = 1.05\nvelocity = gaussian\nv0 = 1\n"
             "[dem]\ndt = 1.25e-4\nthreads = %ld\nskin = %.17g\nmax_overlap = 0.25\n",
             W + 2, fmax(b + H + 2, r1 + 1), n, W, H, b, D, b - 1.5, r0, W + 1, r1, threads, skin);
}

static int bed(long n, long steps, long settle, long threads, int scaling, int silo, double skin,
               const char *peer, const char *dir, bed_result *r, gr_err *err)
{
    double width = 0, height = 0;
    char text[2048];
    gr_particles *p;
    gr_scene *sc = NULL;
    if (silo) {
        silo_text(n, threads, skin, text, sizeof text);
        p = gr_particles_create(0, err);
        if (p && (!(sc = bench_dem_scene(text, err)) || gr_init_particles(sc, p, err))) {
            gr_scene_free(sc);
            gr_particles_free(p);
            return err->code;
        }
    } else {
        p = make_bed(n, &width, &height, err);
        snprintf(text, sizeof text,
                 "[domain]\nwidth = %.17g\nheight = %.17g\ngravity = 1\n"
                 "[material]\nnormal = hertz\ntangential = regularised\nkn = 1e5\ngamma_n = 100\n"
                 "gamma_t = 300\nmu = 0.5\n"
                 /* the grains come from make_bed, not from the scene's [init] */
                 "[species]\ncount = 1\n"
                 "[dem]\ndt = 1.25e-4\nthreads = %ld\nskin = %.17g\n",
                 width, height, threads, skin);
        if (p)
            sc = bench_dem_scene(text, err);
    }
    if (!p)
        return err->code;
    gr_dem *d = NULL;
    int rc = GR_OK;
    gr_dem_params par;
    if (!sc || gr_dem_params_read(sc, &par, err) || gr_dem_check_dt(sc, p, &par, err) ||
        gr_dem_create(sc, p, &par, NULL, &d, err)) {
        rc = err->code;
        goto done;
    }
    /* settle (untimed), then time the steps, as a run takes them */
    if (settle > 0)
        rc = gr_dem_advance(d, INFINITY, (uint64_t)settle, err);
    if (rc)
        goto done;
    if (scaling) {
        r->n = n;
        r->bytes_per_grain = gr_dem_memory(d) / (double)d->n;
        rc = time_scaling(d, steps, threads, r, err);
        goto done;
    }
    uint64_t b0 = d->builds;
    double t0 = exp_wall_seconds(), c0 = exp_cpu_seconds();
    rc = gr_dem_advance(d, INFINITY, (uint64_t)steps, err);
    double t1 = exp_wall_seconds(), c1 = exp_cpu_seconds();
    if (rc)
        goto done;
    r->n = n;
    r->seconds = t1 - t0;
    r->rate = (double)d->nmobile * (double)steps / (t1 - t0);
    r->cpu_rate = (double)d->nmobile * (double)steps / (c1 - c0) * (double)threads;
    r->bytes_per_grain = gr_dem_memory(d) / (double)d->n;
    fprintf(stderr, "dem n=%ld: %.3f s for %ld steps, %llu list builds, %.2f list pairs per grain, largest overlap %.4f d\n",
            n, r->seconds, steps, (unsigned long long)(d->builds - b0),
            d->nb_start ? (double)d->nb_start[d->n] / (double)d->n : 0.0, d->max_ovl);
    if (peer) {
        if ((rc = gr_dem_snapshot(d, p, err)))
            goto done;
        rc = lammps_run(p, width, height, steps, skin, dir, r, err);
    }
done:
    gr_dem_free(d);
    gr_scene_free(sc);
    gr_particles_free(p);
    return rc;
}

/* ---- speed against error ---------------------------------------------- */

static const char *const integ_names[] = {"verlet", "gear", "euler"};

static gr_dem *acc_create(const char *text, const gr_particles *p, gr_err *err)
{
    gr_scene *sc = bench_dem_scene(text, err);
    if (!sc)
        return NULL;
    gr_dem_params par;
    gr_dem *d = NULL;
    gr_particles *init = (gr_particles *)p;
    if (!init) {
        init = gr_particles_create(0, err);
        if (!init || gr_init_particles(sc, init, err)) {
            gr_particles_free(init);
            gr_scene_free(sc);
            return NULL;
        }
    }
    if (!gr_dem_params_read(sc, &par, err) && !gr_dem_check_dt(sc, init, &par, err))
        gr_dem_create(sc, init, &par, NULL, &d, err);
    if (init != p)
        gr_particles_free(init);
    gr_scene_free(sc);
    return d;
}

/* Two unit disks approaching at speed 1, Hertz with the thesis's damping:
 * restitution and contact time. The contact starts between two steps, at
 * a phase th of a step; the force jumps there (damping), an O(dt) error
 * that cancels over equally spaced phases, so each point averages nph
 * phases. The reference (CVODE) is sampled every h and the crossings of
 * zero overlap interpolated. */
static int collision_once(const char *text, double dt, double h, double th, int cv, double *e, double *tc,
                          long *steps, gr_err *err)
{
    double gap = dt * (1.0 + th);
    gr_particles *p = gr_particles_create(2, err);
    if (!p)
        return err->code;
    gr_particles_push(p, 9.5 - 0.5 * gap, 10, 0.5, 1.0, 0, 0, err);
    gr_particles_push(p, 10.5 + 0.5 * gap, 10, 0.5, 1.0, 0, 0, err);
    p->vx[0] = 0.5;
    p->vx[1] = -0.5;
    gr_dem *d = acc_create(text, p, err);
    gr_particles_free(p);
    if (!d)
        return err->code;
    int rc = GR_OK;
    double xi_prev = -gap, t_prev = 0, t_on = -1, t_off = -1;
    while (t_off < 0 && d->t < 1.0 && !rc) {
        rc = cv ? gr_dem_advance(d, d->t + h, 0, err) : gr_dem_step(d, err);
        long i0 = gr_dem_index(d, 0), i1 = gr_dem_index(d, 1);
        double xi = 1.0 - (d->f[F_X][d->cur][i1] - d->f[F_X][d->cur][i0]);
        if (xi_prev <= 0 && xi > 0 && t_on < 0)
            t_on = t_prev + (d->t - t_prev) * (-xi_prev) / (xi - xi_prev);
        if (xi_prev > 0 && xi <= 0)
            t_off = t_prev + (d->t - t_prev) * xi_prev / (xi_prev - xi);
        xi_prev = xi;
        t_prev = d->t;
    }
    if (!rc && !cv)
        rc = gr_dem_step(d, err);
    if (!rc) {
        long i0 = gr_dem_index(d, 0), i1 = gr_dem_index(d, 1);
        *e = d->f[F_VX][d->cur][i1] - d->f[F_VX][d->cur][i0];
        *tc = t_off - t_on;
        *steps = (long)d->step;
    }
    gr_dem_free(d);
    return rc;
}

static int collision(const char *integ, double dt, double h, int nph, double *e, double *tc, double *secs,
                     long *steps, gr_err *err)
{
    char text[1024];
    snprintf(text, sizeof text,
             "[domain]\nwidth = 20\nheight = 20\n"
             "[material]\nnormal = hertz\nkn = 1e5\ngamma_n = 100\n[species]\ncount = 2\n"
             "[dem]\ndt = %.17g\ndt_fraction = 1\nintegrator = %s\nneighbour = brute\nv_impact = 1\n"
             "cvode_rtol = 1e-12\ncvode_atol = 1e-14\n", dt, integ);
    int cv = !strcmp(integ, "cvode");
    double c0 = exp_cpu_seconds();
    *e = *tc = 0;
    *steps = 0;
    for (int k = 0; k < nph; k++) {
        double ek, tk;
        long sk;
        if (collision_once(text, dt, h, (k + 0.5) / nph, cv, &ek, &tk, &sk, err))
            return err->code;
        *e += ek / nph;
        *tc += tk / nph;
        *steps += sk;
    }
    *secs = exp_cpu_seconds() - c0;
    return GR_OK;
}

/* Forty grains falling in a small box for one tau (Hertz, regularised
 * friction, the thesis's constants): positions by id at the end. */
static int packing(const char *integ, double dt, double T, int n, double *xy, double *secs, long *steps,
                   gr_err *err)
{
    char text[1024];
    snprintf(text, sizeof text,
             "[scene]\nseed = 17\n[domain]\nwidth = 8\nheight = 16\ngravity = 1\n"
             "[material]\nnormal = hertz\ntangential = regularised\nkn = 1e5\ngamma_n = 100\n"
             "gamma_t = 300\nmu = 0.5\n[species]\ncount = %d\n"
             "[init]\nkind = random\nregion = 0 0 8 16\nvelocity = gaussian\nv0 = 0.5\n"
             "[dem]\ndt = %.17g\ndt_fraction = 1\nintegrator = %s\nneighbour = brute\n"
             "cvode_rtol = 1e-11\ncvode_atol = 1e-13\n", n, dt, integ);
    double c0 = exp_cpu_seconds();
    gr_dem *d = acc_create(text, NULL, err);
    if (!d)
        return err->code;
    int rc = gr_dem_advance(d, T, 0, err);
    if (!rc) {
        for (size_t i = 0; i < d->n; i++) {
            xy[2 * d->tag[i]] = d->f[F_X][d->cur][i];
            xy[2 * d->tag[i] + 1] = d->f[F_Y][d->cur][i];
        }
        *steps = (long)d->step;
    }
    *secs = exp_cpu_seconds() - c0;
    gr_dem_free(d);
    return rc;
}

/* The two-disk collision at dt = t_c/10 ... t_c/(10 2^(nk-1)) for each
 * integrator: one block of the table each, so that gnuplot's `index`
 * picks an integrator. */
static void accuracy_collisions(FILE *f, double tc0, double e_ref, double tc_ref, int nk, int quick)
{
    for (int g = 0; g < 3; g++) {
        for (int k = 0; k < nk; k++) {
            double dt = tc0 / 10 / pow(2, k), e, tc, secs = 0;
            long steps;
            gr_err e2 = {0};
            if (collision(integ_names[g], dt, 0, quick ? 4 : 8, &e, &tc, &secs, &steps, &e2)) {
                printf("collision %s dt=%.4g: failed (%s)\n", integ_names[g], dt, e2.msg);
                continue;
            }
            double ee = fabs(e / e_ref - 1), et = fabs(tc / tc_ref - 1);
            fprintf(f, "collision %s %.6g %ld %.6g %.6g %.6g nan\n", integ_names[g], dt, steps, secs, ee, et);
            printf("collision %-6s dt = t_c/%-5.0f: e error %.3e, t_c error %.3e, %.3g s\n", integ_names[g],
                   tc0 / dt, ee, et, secs);
        }
        fprintf(f, "\n\n");
    }
}

/* The settling packing of n grains to time T for each integrator, the
 * largest position error against xref; xy is room for 2 n numbers. */
static void accuracy_packing(FILE *f, int n, double T, const double *xref, double *xy, int nk)
{
    for (int g = 0; g < 3; g++) {
        for (int k = 0; k < nk; k++) {
            double dt = 4e-4 / pow(2, k), secs;
            long steps;
            gr_err e2 = {0};
            if (packing(integ_names[g], dt, T, n, xy, &secs, &steps, &e2)) {
                printf("packing %s dt=%.4g: failed (%s)\n", integ_names[g], dt, e2.msg);
                continue;
            }
            double worst = 0;
            for (int i = 0; i < 2 * n; i++)
                worst = fmax(worst, fabs(xy[i] - xref[i]));
            fprintf(f, "packing %s %.6g %ld %.6g nan nan %.6g\n", integ_names[g], dt, steps, secs, worst);
            printf("packing   %-6s dt = %-9.4g: position error %.3e d, %.3g s\n", integ_names[g], dt, worst, secs);
        }
        fprintf(f, "\n\n");
    }
}

/* Error against CPU time, the figure of the accuracy sweep in dat. */
static int accuracy_plot(const char *dat, const char *png, int n, double T, gr_err *err)
{
    FILE *gp = gr_plot_open(png, 1100, 480, err);
    if (!gp)
        return err->code;
    fprintf(gp, "set multiplot layout 1,2\nset logscale xy\nset format y '10^{%%L}'\nset grid\n"
                "set key bottom left\nset xlabel 'CPU seconds'\n"
                "set title 'two-disk collision (Hertz, {/Symbol g}_n = 100, v = 1; phase-averaged)'\n"
                "set ylabel 'relative error against CVODE'\n"
                "plot for [g=0:2] '%s' index g using 5:6 with linespoints title word('verlet gear euler', g+1).' e', "
                "for [g=0:2] '%s' index g using 5:7 with linespoints dashtype 2 title word('verlet gear euler', g+1).' t_c'\n"
                "set title 'settling packing (%d grains, t = %g)'\nset ylabel 'largest position error / d'\n"
                "plot for [g=3:5] '%s' index g using 5:8 with linespoints title word('verlet gear euler', g-2)\n"
                "unset multiplot\n",
            dat, dat, n, T, dat);
    if (gr_plot_close(gp, png, err))
        return err->code;
    return GR_OK;
}

static int bench_dem_accuracy(const char *dir, int quick, gr_err *err)
{
    char dat[1200], png[1200];
    snprintf(dat, sizeof dat, "%s/dem_accuracy.dat", dir);
    snprintf(png, sizeof png, "%s/dem_accuracy.png", dir);
    double tc0 = 3.21 * pow(0.5 / 1e5, 0.4); /* eq. 2.5 at v = 1 */
    double e_ref, tc_ref, sref;
    long st;
    printf("# reference: CVODE (Adams), rtol 1e-12 (collision), 1e-11 (packing)\n");
    if (collision("cvode", tc0 / 100, tc0 / 20000, 1, &e_ref, &tc_ref, &sref, &st, err))
        return err->code;
    int n = quick ? 12 : 40;
    double T = quick ? 0.3 : 1.0;
    double *xref = malloc(sizeof(double) * 2 * (size_t)n), *xy = malloc(sizeof(double) * 2 * (size_t)n);
    if (!xref || !xy) {
        free(xref), free(xy);
        return gr_fail(err, GR_ERUN, "out of memory");
    }
    double pref_secs;
    if (packing("cvode", 1e-4, T, n, xref, &pref_secs, &st, err)) {
        free(xref), free(xy);
        return err->code;
    }
    printf("# collision reference: e = %.12f, t_c = %.12f (eq. 2.5: %.6f); packing of %d grains to t = %g: %.3g s\n",
           e_ref, tc_ref, tc0, n, T, pref_secs);
    FILE *f = exp_dat_open(dat, err);
    if (!f) {
        free(xref), free(xy);
        return err->code;
    }
    fprintf(f, "# grano bench dem --accuracy: error against the CVODE reference and cost\n"
               "# problem integrator dt steps cpu_seconds err_restitution err_contact_time err_position\n");
    int nk = quick ? 3 : 6;
    accuracy_collisions(f, tc0, e_ref, tc_ref, nk, quick);
    accuracy_packing(f, n, T, xref, xy, nk);
    free(xref), free(xy);
    if (exp_dat_close(f, dat, err) || accuracy_plot(dat, png, n, T, err))
        return err->code;
    printf("wrote %s and %s\n", dat, png);
    return GR_OK;
}

static void usage(FILE *f)
{
    fprintf(f,
            "usage: grano bench dem [--n N[,N...]] [--steps S] [--settle S] [--threads T] [--skin S]\n"
            "                       [--scaling] [--silo] [--peer lammps] [--dir DIR]\n"
            "       grano bench dem --accuracy [--quick] [--dir DIR]\n\n"
            "Throughput (mobile particle-steps per second) on a dense settled bed of unit\n"
            "grains in a box of wall grains: Hertz kn = 1e5, gamma_n = 100, regularised\n"
            "friction gamma_t = 300, mu = 0.5, dt = 1.25e-4 (the thesis). Defaults: N =\n"
            "5000,20000,80000, 2000 timed steps after 1000 settling steps, 1 thread, skin 0.2.\n"
            "--peer lammps runs the same bed in Debian's lmp and prints the ratio.\n"
            "--scaling times 1 and T threads in alternating rounds on the same bed and\n"
            "prints the speedup (T from --threads, default 2 with --scaling).\n"
            "--silo times a flowing silo instead of the bed: N grains in a box of wall grains\n"
            "50 (N/5000)^1/2 wide and twice as tall, orifice 8 open from the start, the\n"
            "grains that leave reinserted at the top (settle at least 16000 steps to reach\n"
            "the steady flow).\n"
            "--accuracy sweeps dt for each integrator against the CVODE reference and writes\n"
            "DIR/dem_accuracy.dat and DIR/dem_accuracy.png (default DIR: .).\n");
}

/* The options of bench dem. */
typedef struct {
    long ns[16];
    int nn;
    long steps, settle, threads;
    double skin;
    const char *peer, *dir;
    int accuracy, quick, scaling, threads_given, silo;
} bd_opts;

static int dem_option(void *ctx, int id, const char *arg, gr_err *err)
{
    bd_opts *o = ctx;
    switch (id) {
    case 'A': o->accuracy = 1; return 0;
    case 'C': o->scaling = 1; return 0;
    case 'F': o->silo = 1; return 0;
    case 'Q': o->quick = 1; return 0;
    case 'n':
        o->nn = 0;
        for (const char *s = arg; *s && o->nn < 16;) {
            char *end;
            o->ns[o->nn++] = strtol(s, &end, 10);
            if (end == s || o->ns[o->nn - 1] < 1 || (*end && *end != ','))
                return gr_fail(err, GR_EINPUT, "--n: '%s' is not positive integers separated by commas", arg);
            s = *end ? end + 1 : end;
        }
        return 0;
    case 's': return exp_opt_long("--steps", arg, 1, LONG_MAX, &o->steps, err);
    case 'S': return exp_opt_long("--settle", arg, 0, LONG_MAX, &o->settle, err);
    case 't':
        o->threads_given = 1;
        return exp_opt_long("--threads", arg, 1, 1024, &o->threads, err);
    case 'k': return exp_opt_double("--skin", arg, 0, 1e6, &o->skin, err);
    case 'p':
        if (strcmp(arg, "lammps"))
            return gr_fail(err, GR_EINPUT, "--peer: unknown peer '%s' (known: lammps)", arg);
        o->peer = arg;
        return 0;
    case 'd': o->dir = arg; return 0;
    default: return gr_fail(err, GR_EINPUT, "unknown option");
    }
}

/* Parse argv into *o; -1 to go on, else the exit code (0 after --help). */
static int parse_args(int argc, char **argv, bd_opts *o)
{
    static const struct option opts[] = {
        {"accuracy", no_argument, NULL, 'A'},     {"scaling", no_argument, NULL, 'C'},
        {"silo", no_argument, NULL, 'F'},
        {"quick", no_argument, NULL, 'Q'},        {"n", required_argument, NULL, 'n'},
        {"steps", required_argument, NULL, 's'},  {"settle", required_argument, NULL, 'S'},
        {"threads", required_argument, NULL, 't'}, {"skin", required_argument, NULL, 'k'},
        {"peer", required_argument, NULL, 'p'},   {"dir", required_argument, NULL, 'd'},
        {NULL, 0, NULL, 0}};
    *o = (bd_opts){.ns = {5000, 20000, 80000}, .nn = 3, .steps = 2000, .settle = 1000, .threads = 1, .skin = 0.2,
                   .peer = NULL, .dir = "."};
    int first = 0;
    int rc = exp_getopt_main("bench dem", argc, argv, opts, dem_option, o, usage, 0, &first);
    if (rc >= 0)
        return rc;
    return -1;
}

/* The options that make sense only together; 0 or the exit code 2. */
static int check_args(bd_opts *o)
{
    if (o->steps < 1 || o->settle < 0 || o->threads < 1 || !(o->skin >= 0)) {
        fprintf(stderr, "grano bench dem: --steps and --threads must be positive, --settle and --skin not negative\n");
        return 2;
    }
    if (o->scaling && !o->threads_given)
        o->threads = 2;
    if (o->silo && o->peer) {
        fprintf(stderr, "grano bench dem: --silo has no --peer (grano silo-flow --peer lammps runs the silo in LAMMPS)\n");
        return 2;
    }
    if (o->scaling && (o->threads < 2 || o->peer)) {
        fprintf(stderr, "grano bench dem: --scaling compares 1 thread with --threads T >= 2, without --peer\n");
        return 2;
    }
    if (mkdir(o->dir, 0777) && errno != EEXIST) {
        fprintf(stderr, "grano bench dem: cannot create %s: %s\n", o->dir, strerror(errno));
        return 2;
    }
    return 0;
}

/* One bed's lines: the human one and the RESULT line the checks read. */
static void print_bed(const bd_opts *o, const bed_result *r)
{
    if (o->scaling) {
        printf("dem n=%ld: %.4g particle-steps/s on 1 thread, %.4g on %ld (alternating rounds)\n", r->n, r->rate1,
               r->rate, o->threads);
        printf("RESULT method=dem n=%ld steps=%ld particle_steps_per_s=%.6g threads=%ld speedup=%.3f "
               "c2c_ns=%.0f,%.0f\n",
               r->n, o->steps, r->rate, o->threads, r->rate / r->rate1, r->c2c[0], r->c2c[1]);
        fflush(stdout);
        return;
    }
    printf("dem n=%ld threads=%ld: %.4g s, %.4g particle-steps/s (%.4g per CPU-second x threads), %.1f bytes per grain\n",
           r->n, o->threads, r->seconds, r->rate, r->cpu_rate, r->bytes_per_grain);
    if (o->peer)
        printf("lammps n=%ld: %.4g s, %.4g particle-steps/s (%.4g per CPU-second; CPU-time ratio %.3f)\n", r->n,
               r->lammps_seconds, r->lammps_rate, r->lammps_cpu_rate, r->cpu_rate / r->lammps_cpu_rate);
    printf("RESULT method=dem n=%ld steps=%ld particle_steps_per_s=%.6g", r->n, o->steps, r->rate);
    if (o->peer)
        printf(" lammps_particle_steps_per_s=%.6g ratio=%.3f", r->lammps_rate, r->rate / r->lammps_rate);
    printf("\n");
    fflush(stdout);
}

int bench_dem(int argc, char **argv)
{
    bd_opts o;
    int rc = parse_args(argc, argv, &o);
    if (rc >= 0 || (rc = check_args(&o)))
        return rc;
    gr_err err = {0};
    if (o.accuracy) {
        rc = bench_dem_accuracy(o.dir, o.quick, &err);
        if (rc)
            fprintf(stderr, "grano bench dem: %s\n", err.msg);
        return rc;
    }
    for (int k = 0; k < o.nn; k++) {
        bed_result r = {0};
        if (bed(o.ns[k], o.steps, o.settle, o.threads, o.scaling, o.silo, o.skin, o.peer, o.dir, &r, &err)) {
            fprintf(stderr, "grano bench dem: n = %ld: %s\n", o.ns[k], err.msg);
            return err.code;
        }
        print_bed(&o, &r);
    }
    return 0;
}
