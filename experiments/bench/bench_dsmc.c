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

static void usage(FILE *f)
{
    fprintf(f,
            "usage: grano bench dsmc [--n N1,N2,...] [--eta E] [--dt F] [--ppc P] [--quick]\n"
            "       grano bench dsmc --compare [--n N1,...] [--rounds R] [--quick]\n"
            "       grano bench dsmc --rng\n\n"
            "Throughput: disks (d = m = 1, T = 1) in a periodic square box at packing fraction E (default\n"
            "0.01), square lattice start with Gaussian velocities; dt = F mean free times (default 0.2),\n"
            "cells holding P particles on average (default 8, so the side stays below the mean free path).\n"
            "Three steps warm the cells' speed bounds, then at least 5 steps and 2e7 moves are timed.\n"
            "Defaults: --n 1e3,1e4,1e5,1e6,1e7; --quick: --n 1e3,1e4,1e5. Prints per N:\n"
            "  RESULT method=dsmc n=N particle_moves_per_s=X collisions_per_particle_step=C bytes_per_particle=B\n"
            "--compare: the homogeneous cooling of disks with restitution 0.9 at packing 0.01 to a quarter\n"
            "of the initial temperature (Haff), on dsmc and on edmd, R rounds (default 3) alternating the\n"
            "two; prints each method's CPU seconds and final T / T0 per round and\n"
            "  RATIO method=dsmc peer=edmd n=N cpu_ratio=X t_ratio=Y\n"
            "(edmd's CPU time over dsmc's; dsmc's final temperature over edmd's). Defaults --n 1e4,1e5;\n"
            "--quick: --n 2000, one round.\n"
            "--rng: draws per second of the generators the backend could use (GSL's mt19937 and others\n"
            "through gsl_rng_uniform, Random123's Philox and Threefry).\n");
}

/* The bench scene as a file would give it. */
static gr_scene *bench_scene(long n, double eta, double alpha, double dtf, double ppc, int seed, gr_err *err)
{
    double L = sqrt((double)n * M_PI / 4.0 / eta), nd = (double)n / (L * L);
    double tau = 1.0 / (2.0 * sqrt(M_PI) * nd), cell = sqrt(ppc / nd);
    long side = (long)ceil(sqrt((double)n));
    char text[1400];
    snprintf(text, sizeof text,
             "[scene]\nname = bench-dsmc\nseed = %d\n"
             "[domain]\nwidth = %.17g\nheight = %.17g\nleft = periodic\nright = periodic\n"
             "bottom = periodic\ntop = periodic\n[material]\nrestitution = %.17g\n"
             "[species]\ndiameter = 1\ncount = %ld\n"
             "[init]\nkind = lattice\nspacing = %.17g\nvelocity = gaussian\nv0 = 1\n"
             "[dsmc]\ndt = %.17g\ncell = %.17g\n",
             seed, L, L, alpha, n, L / ((double)side + 0.01), dtf * tau, cell);
    const char *extra[] = {"dsmc", "edmd", NULL};
    return gr_scene_parse(text, "(bench dsmc)", extra, err);
}

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

static int throughput(long n, double eta, double dtf, double ppc)
{
    gr_err err = {0};
    gr_scene *sc = bench_scene(n, eta, 1.0, dtf, ppc, 1, &err);
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

/* One cooling run to t_end: CPU seconds and T(t_end) / T(0). */
static int cool(const char *method, long n, int seed, double *cpu, double *tr, gr_err *err)
{
    const double alpha = 0.9, eta = 0.01;
    gr_scene *sc = bench_scene(n, eta, alpha, 0.2, 8, seed, err);
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
            if (cool("dsmc", n, 1 + r, &a, &ta, &err) || cool("edmd", n, 1 + r, &b, &tb, &err)) {
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

int bench_dsmc(int argc, char **argv)
{
    double ns[16] = {1e3, 1e4, 1e5, 1e6, 1e7}, eta = 0.01, dtf = 0.2, ppc = 8;
    size_t nn = 5;
    int quick = 0, cmp = 0, rounds = 3, given = 0;
    for (int a = 1; a < argc; a++) {
        int ok = 1;
        if (!strcmp(argv[a], "--help") || !strcmp(argv[a], "-h")) {
            usage(stdout);
            return 0;
        } else if (!strcmp(argv[a], "--quick")) {
            quick = 1;
        } else if (!strcmp(argv[a], "--compare")) {
            cmp = 1;
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
    if (cmp) {
        double cn[2] = {1e4, 1e5}, qn[1] = {2000};
        return given ? compare(ns, nn, quick ? 1 : rounds)
                     : quick ? compare(qn, 1, 1) : compare(cn, 2, rounds);
    }
    if (quick && !given)
        nn = 3;
    printf("# periodic box, packing %g, dt %g mean free times, %g particles per cell\n", eta, dtf, ppc);
    printf("# %9s %6s %9s %9s %12s %8s %6s %7s\n", "N", "steps", "wall_s", "cpu_s", "moves/cpu_s", "coll/p/s",
           "B/p", "ppc");
    for (size_t k = 0; k < nn; k++) {
        int rc = throughput((long)ns[k], eta, dtf, ppc);
        if (rc)
            return rc;
    }
    return 0;
}
