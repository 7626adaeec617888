/* grano bench dsmc: particle moves per CPU second of the DSMC backend with
 * collisions, against N, in a dilute periodic box; the state's bytes per
 * particle; beside it, edmd on the same dilute cooling scene (CPU time to
 * the same simulated time, and the temperature each reaches); and the cost
 * of the random generators (--rng). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_rng.h"
#include "clock.h"
#include "cmd.h"
#include "dsmc/dsmc_int.h"
#include "init.h"
#include "method.h"
#include "opts.h"
#include "scene.h"

/* edmd's cell side in the dilute scenes (diameters): at packing 0.01 its
 * fastest, 4 times faster than its default of one diameter, which spends
 * its events on cell crossings (cells of 1, 3, 6, 12, 24, 48: CPU ratio
 * to dsmc 40, 16, 11, 9.5, 17, 35 at N = 2e4). */
#define EDMD_CELL 12.0


static void usage(FILE *f)
{
    fprintf(f,
            "usage: grano bench dsmc [--n N1,N2,...] [--eta E] [--dt F] [--ppc P] [--enskog] [--quick]\n"
            "       grano bench dsmc --compare [--n N1,...] [--rounds R] [--quick]\n"
            "       grano bench dsmc --threads T1,T2 [--n N1,...] [--rounds R] [--enskog]\n"
            "       grano bench dsmc --rng\n\n"
            "Throughput: disks (d = m = 1, T = 1) in a periodic square box at packing fraction E (default\n"
            "0.01), square lattice start with Gaussian velocities; dt = F mean free times (default 0.2),\n"
            "cells holding P particles on average (default 8, so the side stays below the mean free path).\n"
            "The Boltzmann rate, or with --enskog the Enskog mode (the method's default). Three steps warm\n"
            "the cells' speed bounds, then at least 5 steps and 2e7 moves are timed.\n"
            "Defaults: --n 1e3,1e4,1e5,1e6,1e7; --quick: --n 1e3,1e4,1e5. Prints per N:\n"
            "  RESULT method=dsmc n=N particle_moves_per_s=X collisions_per_particle_step=C bytes_per_particle=B\n"
            "--compare: the homogeneous cooling of disks with restitution 0.9 at packing 0.01 to a quarter\n"
            "of the initial temperature (Haff), on dsmc and on edmd, R rounds (default 3) alternating the\n"
            "two; prints each method's CPU seconds and final T / T0 per round and\n"
            "  RATIO method=dsmc peer=edmd n=N cpu_ratio=X t_ratio=Y\n"
            "(edmd's CPU time over dsmc's; dsmc's final temperature over edmd's). Defaults --n 1e4,1e5;\n"
            "--quick: --n 2000, one round.\n"
            "--sweep: speed against error on the cooling of --compare with N real grains (default 4e4,\n"
            "--quick 4000), edmd the reference, R seeds each (--rounds, default 3; --quick 2): dsmc with dt\n"
            "0.05 to 2 mean free times, cells of 0.25 to 4 mean free paths, weights W = 1 to 64; per row\n"
            "  SWEEP method=dsmc knob=K value=V n=N cpu_s=C T_over_T0=T stderr=S error=E\n"
            "--threads T1,T2: the throughput scene on T1 and on T2 threads (default --n 1e5,1e6), and T2\n"
            "independent one-thread runs of it at once (the machine's ceiling), advanced in R alternating\n"
            "rounds (default 3) of 1e7 moves each; wall seconds of each, the speedup, the ceiling's, the\n"
            "fraction of it, and whether the T1 and T2 states are the same bits (exit 1 if not):\n"
            "  SCALING method=dsmc n=N threads=T1,T2 speedup=X ceiling=C of_ceiling=F identical=1\n"
            "--rng: draws per second of the generators the backend could use (GSL's mt19937 and others\n"
            "through gsl_rng_uniform, Random123's Philox and Threefry).\n");
}

/* The bench scene as a file would give it: n simulated particles of
 * weight W at packing fraction eta of the real grains, dt and the cell
 * side (0: the method's default) in absolute units. */
static gr_scene *bench_scene(long n, double eta, double alpha, double dt, double cell, double W, int seed,
                             const char *enskog, gr_err *err)
{
    double L = sqrt((double)n * W * M_PI / 4.0 / eta);
    long side = (long)ceil(sqrt((double)n));
    double spacing = L / ((double)side + 0.01);
    char init[160], text[1400];
    /* a lattice is fastest to lay out; the scene format takes spacings up
     * to 10 d, beyond which random placement is as quick (dilute) */
    if (spacing <= 10)
        snprintf(init, sizeof init, "kind = lattice\nspacing = %.17g", spacing);
    else
        snprintf(init, sizeof init, "kind = random");
    snprintf(text, sizeof text,
             "[scene]\nname = bench-dsmc\nseed = %d\n"
             "[domain]\nwidth = %.17g\nheight = %.17g\nleft = periodic\nright = periodic\n"
             "bottom = periodic\ntop = periodic\n[material]\nrestitution = %.17g\n"
             "[species]\ndiameter = 1\ncount = %ld\nweight = %.17g\n"
             "[init]\n%s\nvelocity = gaussian\nv0 = 1\n"
             "[dsmc]\ndt = %.17g\ncell = %.17g\nenskog = %s\n[edmd]\ncell = %g\n",
             seed, L, L, alpha, n, W, init, dt, cell, enskog, EDMD_CELL);
    const char *extra[] = {"dsmc", "edmd", NULL};
    return gr_scene_parse(text, "(bench dsmc)", extra, err);
}

/* Mean free time and path of the real grains at packing eta, T = 1. */
static double tau_of(double eta) { return 1.0 / (2.0 * sqrt(M_PI) * eta * 4.0 / M_PI); }
static double lambda_of(double eta) { return 1.0 / (2.0 * M_SQRT2 * eta * 4.0 / M_PI); }

static gr_sim *bench_sim(const char *method, const gr_scene *sc, gr_err *err)
{
    const gr_method_type *m = gr_method_find(method);
    gr_particles *p = gr_particles_create(0, err);
    gr_sim *s = NULL;
    if (m && p && !gr_init_particles(sc, p, err))
        (void)gr_sim_create(m, sc, p, &s, err);
    gr_particles_free(p);
    return s;
}

static uint64_t counter(const gr_sim *s, const char *name)
{
    uint64_t v = 0;
    (void)gr_sim_counter(s, name, &v);
    return v;
}

static int throughput(long n, double eta, double dtf, double ppc, const char *ens)
{
    gr_err err = {0};
    double nd = eta * 4.0 / M_PI;
    gr_scene *sc = bench_scene(n, eta, 1.0, dtf * tau_of(eta), sqrt(ppc / nd), 1.0, 1, ens, &err);
    gr_sim *s = sc ? bench_sim("dsmc", sc, &err) : NULL;
    long steps = (long)fmax(5.0, ceil(2e7 / (double)n));
    int rc = !s || gr_sim_advance(s, INFINITY, 3, &err);
    uint64_t p0 = s ? counter(s, "pair_collisions") : 0;
    double c0 = exp_cpu_seconds(), w0 = exp_wall_seconds();
    rc = rc || gr_sim_advance(s, INFINITY, (uint64_t)steps, &err);
    double c1 = exp_cpu_seconds(), w1 = exp_wall_seconds();
    if (rc) {
        fprintf(stderr, "grano bench dsmc: N = %ld: %s\n", n, err.msg);
        gr_sim_free(s);
        gr_scene_free(sc);
        return err.code ? err.code : 1;
    }
    double moves = (double)n * (double)steps, coll = (double)(counter(s, "pair_collisions") - p0);
    const gr_dsmc *d = gr_sim_state(s);
    printf("  %9ld %6ld %9.3f %9.3f %12.4g %8.4f %6.1f %7.2f\n", n, steps, w1 - w0, c1 - c0, moves / (c1 - c0),
           2 * coll / moves, gr_dsmc_bytes_per_particle(d), (double)n / ((double)d->nx * d->ny));
    printf("RESULT method=dsmc n=%ld particle_moves_per_s=%.4g collisions_per_particle_step=%.4f "
           "bytes_per_particle=%.1f\n",
           n, moves / (c1 - c0), 2 * coll / moves, gr_dsmc_bytes_per_particle(d));
    fflush(stdout);
    gr_sim_free(s);
    gr_scene_free(sc);
    return 0;
}

/* The instance's particle state, bit for bit, and its counters, between
 * two runs of the same scene. */
static int same_state(const gr_dsmc *a, const gr_dsmc *b)
{
    size_t n = a->n;
    return a->n == b->n && !memcmp(a->x, b->x, n * sizeof *a->x) && !memcmp(a->y, b->y, n * sizeof *a->y) &&
           !memcmp(a->vx, b->vx, n * sizeof *a->vx) && !memcmp(a->vy, b->vy, n * sizeof *a->vy) &&
           !memcmp(a->rank, b->rank, n * sizeof *a->rank) && a->pairs == b->pairs && a->cand == b->cand &&
           a->stand_ins == b->stand_ins && a->virial == b->virial;
}

/* Threads: the same scene on T1 and on T2 threads, and, as the machine's
 * ceiling for T2 threads, T2 independent one-thread runs of it at once on
 * the same cores; advanced in alternating rounds (so that all see the same
 * load), wall seconds of each summed. The T1 and T2 states are compared
 * bit for bit at the end. */
enum { MAXC = 64 };

static int scaling(long n, double eta, double dtf, double ppc, const char *ens, int T1, int T2, int rounds)
{
    gr_err err = {0};
    double nd = eta * 4.0 / M_PI;
    gr_scene *sc = bench_scene(n, eta, 1.0, dtf * tau_of(eta), sqrt(ppc / nd), 1.0, 1, ens, &err);
    int nc = T2 < MAXC ? T2 : MAXC, ns = 2 + nc, rc = !sc;
    gr_sim *s[2 + MAXC] = {NULL};
    for (int k = 0; k < ns && !rc; k++)
        rc = !(s[k] = bench_sim("dsmc", sc, &err));
    long steps = (long)fmax(2.0, ceil(1e7 / (double)n));
    double wall[3] = {0, 0, 0};
    for (int k = 0; k < ns && !rc; k++) {
        ((gr_dsmc *)gr_sim_state(s[k]))->par.threads = k == 0 ? T1 : k == 1 ? T2 : 1;
        rc = gr_sim_advance(s[k], INFINITY, 3, &err);
    }
    for (int r = 0; r < rounds && !rc; r++) {
        for (int k = 0; k < 2 && !rc; k++) {
            double w0 = exp_wall_seconds();
            rc = gr_sim_advance(s[k], INFINITY, (uint64_t)steps, &err);
            wall[k] += exp_wall_seconds() - w0;
        }
        int bad = 0;
        double w0 = exp_wall_seconds();
#pragma omp parallel for num_threads(nc) schedule(static, 1) reduction(+ : bad)
        for (int k = 0; k < nc; k++) {
            gr_err e = {0};
            bad += gr_sim_advance(s[2 + k], INFINITY, (uint64_t)steps, &e) != 0;
        }
        wall[2] += exp_wall_seconds() - w0;
        rc = rc || bad;
    }
    if (rc)
        fprintf(stderr, "grano bench dsmc: N = %ld: %s\n", n, err.code ? err.msg : "a ceiling run failed");
    else {
        int same = same_state(gr_sim_state(s[0]), gr_sim_state(s[1]));
        double moves = (double)n * (double)steps * rounds, ceil_x = nc * wall[0] / wall[2];
        printf("  %9ld %6ld %3d %9.3f %12.4g %3d %9.3f %12.4g %7.3f %7.3f %6.2f %s\n", n, steps * rounds, T1,
               wall[0], moves / wall[0], T2, wall[1], moves / wall[1], wall[0] / wall[1], ceil_x,
               wall[0] / wall[1] / ceil_x, same ? "same" : "DIFFERENT");
        printf("SCALING method=dsmc n=%ld threads=%d,%d speedup=%.3f ceiling=%.3f of_ceiling=%.3f identical=%d\n", n,
               T1, T2, wall[0] / wall[1], ceil_x, wall[0] / wall[1] / ceil_x, same);
        rc = same ? 0 : 1;
    }
    fflush(stdout);
    for (int k = 0; k < ns; k++)
        gr_sim_free(s[k]);
    gr_scene_free(sc);
    return rc ? (err.code ? err.code : 1) : 0;
}

/* One cooling run (restitution 0.9, packing 0.01) to t_end, where Haff's
 * law gives T0/4: CPU seconds and T(t_end) / T(0). */
static int cool(const char *method, long n, double dt, double cell, double W, const char *enskog, int seed,
                double *cpu, double *tr, gr_err *err)
{
    const double alpha = 0.9, eta = 0.01;
    gr_scene *sc = bench_scene(n, eta, alpha, dt, cell, W, seed, enskog, err);
    gr_sim *s = sc ? bench_sim(method, sc, err) : NULL;
    gr_obs o0, o1;
    int rc = !s || gr_sim_observe(s, &o0, err);
    /* Haff: T = T0 / 4 at zeta0 t / 2 = 1, zeta0 = sqrt(pi) (1 - alpha^2) n sqrt(T0) */
    double nd = eta * 4.0 / M_PI, t_end = rc ? 0 : 2.0 / (sqrt(M_PI) * (1 - alpha * alpha) * nd * sqrt(o0.temperature));
    double c0 = exp_cpu_seconds();
    rc = rc || gr_sim_advance(s, t_end, 0, err) || gr_sim_observe(s, &o1, err);
    *cpu = exp_cpu_seconds() - c0;
    *tr = rc ? NAN : o1.temperature / o0.temperature;
    gr_sim_free(s);
    gr_scene_free(sc);
    return rc ? (err->code ? err->code : 1) : 0;
}

static int compare(const double *ns, size_t nn, int rounds)
{
    printf("# HCS, alpha 0.9, packing 0.01, to T0/4 (Haff): per round N, seed, CPU s and T/T0 of dsmc "
           "then edmd\n");
    for (size_t k = 0; k < nn; k++) {
        long n = (long)ns[k];
        double cd = 0, ce = 0, td = 0, te = 0;
        for (int r = 0; r < rounds; r++) {
            gr_err err = {0};
            double a, b, ta, tb;
            double dt = 0.2 * tau_of(0.01), cell = sqrt(8 / (0.01 * 4 / M_PI));
            if (cool("dsmc", n, dt, cell, 1, "no", 1 + r, &a, &ta, &err) ||
                cool("edmd", n, dt, cell, 1, "no", 1 + r, &b, &tb, &err)) {
                fprintf(stderr, "grano bench dsmc --compare: N = %ld: %s\n", n, err.msg);
                return err.code ? err.code : 1;
            }
            printf("  %8ld %3d %9.3f %8.5f %9.3f %8.5f\n", n, 1 + r, a, ta, b, tb);
            fflush(stdout);
            cd += a, ce += b, td += ta, te += tb;
        }
        printf("RATIO method=dsmc peer=edmd n=%ld rounds=%d cpu_ratio=%.3g t_ratio=%.4f\n", n, rounds, ce / cd,
               td / te);
        fflush(stdout);
    }
    return 0;
}

/* One knob setting: R seeds of dsmc, their mean T/T0 and CPU seconds. */
static int sweep_row(const char *knob, double value, long n, double dt, double cell, double W, const char *enskog,
                     int R, double ref)
{
    double cpu = 0, sum = 0, sum2 = 0;
    for (int r = 0; r < R; r++) {
        gr_err err = {0};
        double c, tr;
        if (cool("dsmc", n, dt, cell, W, enskog, 1 + r, &c, &tr, &err)) {
            fprintf(stderr, "grano bench dsmc --sweep: %s = %g: %s\n", knob, value, err.msg);
            return err.code ? err.code : 1;
        }
        cpu += c, sum += tr, sum2 += tr * tr;
    }
    double m = sum / R, se = R > 1 ? sqrt(fmax(0, sum2 / R - m * m) / (R - 1)) : NAN;
    double ppc = (double)n * cell * cell / (n * W * M_PI / 4 / 0.01);
    printf("SWEEP method=dsmc knob=%s value=%g enskog=%s n=%ld ppc=%.3g cpu_s=%.4g T_over_T0=%.5f stderr=%.5f "
           "error=%.4f\n",
           knob, value, enskog, n, ppc, cpu / R, m, se, fabs(m / ref - 1));
    fflush(stdout);
    return 0;
}

/* Speed against error: the cooling of --compare with N real grains, edmd
 * the reference (R seeds), then dsmc with one knob moved at a time from
 * dt = 0.2 mean free times, cells of half a mean free path, W = 1: dt in
 * mean free times, the cell side in mean free paths, the weight W (N / W
 * simulated particles). */
static int sweep(long n, int R)
{
    double tau = tau_of(0.01), lam = lambda_of(0.01), ref = 0, cref = 0;
    for (int r = 0; r < R; r++) {
        gr_err err = {0};
        double c, tr;
        if (cool("edmd", n, 1, 0, 1, "no", 1 + r, &c, &tr, &err)) {
            fprintf(stderr, "grano bench dsmc --sweep: edmd: %s\n", err.msg);
            return err.code ? err.code : 1;
        }
        ref += tr / R, cref += c / R;
    }
    printf("# HCS, alpha 0.9, packing 0.01, N = %ld, to Haff's T0/4; %d seeds per row; error = |T/T0 / edmd's - 1|\n",
           n, R);
    printf("SWEEP method=edmd knob=reference value=0 n=%ld cpu_s=%.4g T_over_T0=%.5f stderr=nan error=0\n", n, cref,
           ref);
    const double dts[] = {0.05, 0.1, 0.2, 0.5, 1.0, 2.0}, cells[] = {0.25, 0.5, 1, 2, 4}, ws[] = {1, 4, 16, 64};
    int rc = 0;
    /* both rates: Boltzmann's leaves out chi(0.01) = 1.016 of edmd's
     * hard disks, which sets its error floor; the Enskog mode has it */
    for (int e = 0; e < 2 && !rc; e++) {
        const char *ens = e ? "yes" : "no";
        for (int k = 0; k < 6 && !rc; k++)
            rc = sweep_row("dt", dts[k], n, dts[k] * tau, 0.5 * lam, 1, ens, R, ref);
        for (int k = 0; k < 5 && !rc; k++)
            rc = sweep_row("cell", cells[k], n, 0.2 * tau, cells[k] * lam, 1, ens, R, ref);
        /* W: N / W simulated particles, in cells kept at 8 of them on
         * average (a pair alone in its cell collides again and again) */
        for (int k = 0; k < 4 && !rc; k++) {
            double cell = sqrt(8.0 * n * M_PI / 4 / 0.01 / (n / ws[k]));
            rc = sweep_row("W", ws[k], (long)(n / ws[k]), 0.2 * tau, cell, ws[k], ens, R, ref);
        }
    }
    return rc;
}

int bench_dsmc(int argc, char **argv)
{
    double ns[16] = {1e3, 1e4, 1e5, 1e6, 1e7}, eta = 0.01, dtf = 0.2, ppc = 8;
    size_t nn = 5;
    double th[2] = {0, 0};
    size_t nth = 0;
    int quick = 0, cmp = 0, rounds = 3, given = 0;
    const char *ens = "no";
    for (int a = 1; a < argc; a++) {
        int ok = 1;
        if (!strcmp(argv[a], "--help") || !strcmp(argv[a], "-h")) {
            usage(stdout);
            return 0;
        } else if (!strcmp(argv[a], "--version")) {
            exp_print_version("bench dsmc");
            return 0;
        } else if (!strcmp(argv[a], "--quick")) {
            quick = 1;
        } else if (!strcmp(argv[a], "--compare")) {
            cmp = 1;
        } else if (!strcmp(argv[a], "--enskog")) {
            ens = "yes";
        } else if (!strcmp(argv[a], "--sweep")) {
            cmp = 2;
        } else if (!strcmp(argv[a], "--rng")) {
            return bench_rng_draws();
        } else if (a + 1 < argc && !strcmp(argv[a], "--n")) {
            ok = !exp_parse_list(argv[++a], ns, 16, &nn), given = 1;
        } else if (a + 1 < argc && !strcmp(argv[a], "--eta")) {
            eta = atof(argv[++a]), ok = eta > 0 && eta <= 0.5;
        } else if (a + 1 < argc && !strcmp(argv[a], "--dt")) {
            dtf = atof(argv[++a]), ok = dtf > 0;
        } else if (a + 1 < argc && !strcmp(argv[a], "--ppc")) {
            ppc = atof(argv[++a]), ok = ppc > 0;
        } else if (a + 1 < argc && !strcmp(argv[a], "--threads")) {
            ok = !exp_parse_list(argv[++a], th, 2, &nth) && nth == 2 && th[0] >= 1 && th[1] >= 1 && th[0] <= 256 &&
                 th[1] <= 256;
        } else if (a + 1 < argc && !strcmp(argv[a], "--rounds")) {
            rounds = atoi(argv[++a]), ok = rounds >= 1 && rounds <= 64;
        } else {
            ok = 0;
        }
        if (!ok) {
            fprintf(stderr, "grano bench dsmc: bad or incomplete option '%s'\n", argv[a]);
            usage(stderr);
            return 2;
        }
    }
    if (cmp == 2)
        return sweep(given ? (long)ns[0] : quick ? 4000 : 40000, quick ? 2 : rounds);
    if (cmp) {
        double cn[2] = {1e4, 1e5}, qn[1] = {2000};
        return given ? compare(ns, nn, quick ? 1 : rounds)
                     : quick ? compare(qn, 1, 1) : compare(cn, 2, rounds);
    }
    if (quick && !given)
        nn = 3;
    if (nth == 2) {
        double tn[2] = {1e5, 1e6};
        const double *list = given ? ns : tn;
        printf("# periodic box, packing %g, dt %g mean free times, %g particles per cell, enskog = %s; wall seconds, "
               "%d rounds\n", eta, dtf, ppc, ens, rounds);
        printf("# %9s %6s %3s %9s %12s %3s %9s %12s %7s %7s %6s %s\n", "N", "steps", "T1", "wall_s", "moves/s", "T2",
               "wall_s", "moves/s", "speedup", "ceiling", "of_it", "bits");
        for (size_t k = 0; k < (given ? nn : 2); k++) {
            int rc = scaling((long)list[k], eta, dtf, ppc, ens, (int)th[0], (int)th[1], rounds);
            if (rc)
                return rc;
        }
        return 0;
    }
    printf("# periodic box, packing %g, dt %g mean free times, %g particles per cell, enskog = %s\n", eta, dtf, ppc,
           ens);
    printf("# %9s %6s %9s %9s %12s %8s %6s %7s\n", "N", "steps", "wall_s", "cpu_s", "moves/cpu_s", "coll/p/s",
           "B/p", "ppc");
    for (size_t k = 0; k < nn; k++) {
        int rc = throughput((long)ns[k], eta, dtf, ppc, ens);
        if (rc)
            return rc;
    }
    return 0;
}
