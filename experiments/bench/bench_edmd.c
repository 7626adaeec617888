/* grano bench edmd: collisions per second of the event-driven backend for
 * elastic disks in a periodic box, against N and the packing fraction. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "clock.h"
#include "cmd.h"
#include "edmd/edmd.h"
#include "opts.h"
#include "order.h"
#include "init.h"
#include "scene.h"

static void usage(FILE *f)
{
    fprintf(f,
            "usage: grano bench edmd [--n N1,N2,...] [--eta E1,E2,...] [--equil C] [--measure C] [--arity 2|4]\n"
            "                        [--queue tree|calendar] [--cell C] [--sort S] [--quick] [--ratio R]\n\n"
            "Elastic disks (d = m = 1, V0 = 1) in a periodic square box at packing fraction eta, from a\n"
            "square lattice; C equilibration collisions per grain (default 20), then at least C\n"
            "measured collisions per grain (default 10, and at least 2e6 collisions in all).\n"
            "Defaults: --n 1000,10000,100000,1000000 --eta 0.3,0.6; --quick: --n 1000,10000.\n"
            "--arity: branching of the event tree ([edmd] tree_arity, default 2); --cell: minimum cell\n"
            "side ([edmd] cell, default the diameter); --queue: the event queue ([edmd] queue);\n"
            "--sort: collisions per grain between spatial re-sorts ([edmd] sort_every, default automatic).\n"
            "Prints per case: RESULT method=edmd n=N eta=E collisions_per_s=X\n"
            "--ratio R: instead, per eta, equilibrate the first and the last N of --n (default 1e3 and\n"
            "1e6) and time them in R alternating rounds of 2e6 collisions each, so that the host's\n"
            "drifting speed hits both alike; prints per round and in all the rate of the large system\n"
            "over that of the small one (the issue's criterion: at least 1/2), per CPU second.\n");
}

/* The scene as a file would give it: the common reader and initialiser. */
static gr_scene *bench_scene(long n, double eta, int arity, double cell, const char *queue, double sort,
                             gr_err *err)
{
    double L = sqrt(n * M_PI / 4.0 / eta);
    long side = (long)ceil(sqrt((double)n));
    double spacing = L / (side + 0.01);
    char text[1024];
    snprintf(text, sizeof text,
             "[scene]\nname = bench-edmd\nseed = 1\n"
             "[domain]\nwidth = %.17g\nheight = %.17g\nleft = periodic\nright = periodic\n"
             "bottom = periodic\ntop = periodic\n"
             "[material]\nrestitution = 1\n"
             "[species]\ndiameter = 1\ncount = %ld\n"
             "[init]\nkind = lattice\nspacing = %.17g\nvelocity = speed\nv0 = 1\n"
             "[edmd]\ntree_arity = %d\ncell = %.17g\nsort_every = %.17g\n%s%s\n",
             L, L, n, spacing, arity, cell, sort, queue ? "queue = " : "", queue ? queue : "");
    const char *extra[] = {"edmd", NULL};
    return gr_scene_parse(text, "(bench edmd)", extra, err);
}

/* An equilibrated bench system: equil collisions per grain from the lattice. */
static gr_edmd *bench_system(long n, double eta, int arity, double cell, const char *queue, double sort, double equil,
                             gr_err *err)
{
    gr_scene *sc = bench_scene(n, eta, arity, cell, queue, sort, err);
    gr_particles *p = sc ? gr_particles_create((size_t)n, err) : NULL;
    gr_edmd_params prm;
    gr_edmd *s = NULL;
    if (sc && p && !gr_init_particles(sc, p, err) && !gr_edmd_params_read(sc, &prm, err))
        (void)gr_edmd_create(sc, p, &prm, NULL, &s, err);
    gr_particles_free(p);
    gr_scene_free(sc);
    if (s && gr_edmd_advance(s, INFINITY, (uint64_t)(equil * n), err)) {
        gr_edmd_free(s);
        s = NULL;
    }
    return s;
}

/* Collisions per CPU second of one round of `want` collisions. */
static int bench_round(gr_edmd *s, double want, double *rate, gr_err *err)
{
    gr_edmd_counters c0, c1;
    gr_edmd_get_counters(s, &c0);
    double u0 = exp_cpu_seconds();
    int rc = gr_edmd_advance(s, INFINITY, (uint64_t)want, err);
    double u1 = exp_cpu_seconds();
    gr_edmd_get_counters(s, &c1);
    *rate = (double)(c1.pair - c0.pair) / (u1 - u0);
    return rc;
}

/* The two systems timed in turns: the ratio of their rates within each
 * round is immune to the host's speed drifting over minutes. */
static int bench_ratio(long n1, long n2, const double *etas, int ne, int rounds, int arity, double cell,
                       const char *queue, double sort, double equil)
{
    enum { RMAX = 64 };
    const double want = 2e6;
    for (int ie = 0; ie < ne; ie++) {
        gr_err err = {0};
        gr_edmd *a = bench_system(n1, etas[ie], arity, cell, queue, sort, equil, &err);
        gr_edmd *b = a ? bench_system(n2, etas[ie], arity, cell, queue, sort, equil, &err) : NULL;
        if (!b) {
            fprintf(stderr, "grano bench edmd: eta = %g: %s\n", etas[ie], err.msg);
            gr_edmd_free(a);
            return err.code ? err.code : 1;
        }
        double r[RMAX], sa = 0, sb = 0;
        printf("# eta %g: round, N = %ld coll/cpu_s, N = %ld coll/cpu_s, ratio\n", etas[ie], n1, n2);
        for (int k = 0; k < rounds; k++) {
            double ra, rb;
            if (bench_round(a, want, &ra, &err) || bench_round(b, want, &rb, &err)) {
                fprintf(stderr, "grano bench edmd: %s\n", err.msg);
                gr_edmd_free(a);
                gr_edmd_free(b);
                return err.code;
            }
            r[k] = rb / ra;
            sa += 1.0 / ra;
            sb += 1.0 / rb;
            printf("  %3d %12.4g %12.4g %7.3f\n", k + 1, ra, rb, r[k]);
            fflush(stdout);
        }
        gr_edmd_free(a);
        gr_edmd_free(b);
        qsort(r, (size_t)rounds, sizeof *r, exp_cmp_double);
        /* equal collisions per round: the overall rates are harmonic means */
        printf("RATIO method=edmd eta=%g n_small=%ld n_large=%ld rounds=%d ratio=%.3f median=%.3f min=%.3f "
               "max=%.3f\n",
               etas[ie], n1, n2, rounds, sa / sb, r[rounds / 2], r[0], r[rounds - 1]);
        fflush(stdout);
    }
    return 0;
}

/* The options of bench edmd. */
typedef struct {
    double ns[16], etas[8];
    int nn, ne;
    double equil, measure;
    int arity;
    double cell;
    const char *queue;
    double sort;
    int rounds;
} be_opts;

static int edmd_option(void *ctx, int id, const char *arg, gr_err *err)
{
    be_opts *o = ctx;
    long v;
    switch (id) {
    case 'Q': o->nn = 2; return 0;
    case 'n':
    case 'e': {
        size_t n;
        if (exp_parse_list(arg, id == 'n' ? o->ns : o->etas, id == 'n' ? 16 : 8, &n))
            return gr_fail(err, GR_EINPUT, "%s: '%s' is not a list of positive numbers", id == 'n' ? "--n" : "--eta",
                           arg);
        *(id == 'n' ? &o->nn : &o->ne) = (int)n;
        return 0;
    }
    case 'E': return exp_opt_double("--equil", arg, 0, 1e15, &o->equil, err);
    case 'M': return exp_opt_double("--measure", arg, 1e-300, 1e15, &o->measure, err);
    case 'r':
        if (exp_opt_long("--ratio", arg, 1, 64, &v, err))
            return err->code;
        o->rounds = (int)v;
        return 0;
    case 'a':
        if (exp_opt_long("--arity", arg, 2, 4, &v, err))
            return err->code;
        o->arity = (int)v;
        return 0;
    case 's': return exp_opt_double("--sort", arg, -1e300, 1e300, &o->sort, err);
    case 'q': o->queue = arg; return 0;
    case 'c': return exp_opt_double("--cell", arg, 0, 1e300, &o->cell, err);
    default: return gr_fail(err, GR_EINPUT, "unknown option");
    }
}

/* Parse argv into *o; -1 to go on, else the exit code (0 after --help). */
static int parse_args(int argc, char **argv, be_opts *o)
{
    static const struct option opts[] = {
        {"quick", no_argument, NULL, 'Q'},         {"n", required_argument, NULL, 'n'},
        {"eta", required_argument, NULL, 'e'},     {"equil", required_argument, NULL, 'E'},
        {"measure", required_argument, NULL, 'M'}, {"ratio", required_argument, NULL, 'r'},
        {"arity", required_argument, NULL, 'a'},   {"sort", required_argument, NULL, 's'},
        {"queue", required_argument, NULL, 'q'},   {"cell", required_argument, NULL, 'c'},
        {NULL, 0, NULL, 0}};
    *o = (be_opts){.ns = {1e3, 1e4, 1e5, 1e6}, .etas = {0.3, 0.6}, .nn = 4, .ne = 2, .equil = 20, .measure = 10,
                   .arity = 2, .cell = 0, .queue = NULL, .sort = -1.0, .rounds = 0};
    int first = 0;
    int rc = exp_getopt_main("bench edmd", argc, argv, opts, edmd_option, o, usage, 0, &first);
    if (rc >= 0)
        return rc;
    return -1;
}

/* One row of the table: N disks at packing eta, equilibrated first so
 * that the lattice start does not count, then timed over at least 2e6
 * collisions so that short runs are not all clock resolution. */
static int bench_one(const be_opts *o, long n, double eta)
{
    gr_err err = {0};
    gr_scene *sc = bench_scene(n, eta, o->arity, o->cell, o->queue, o->sort, &err);
    gr_particles *p = sc ? gr_particles_create((size_t)n, &err) : NULL;
    gr_edmd_params prm;
    gr_edmd *s = NULL;
    if (!sc || !p || gr_init_particles(sc, p, &err) || gr_edmd_params_read(sc, &prm, &err) ||
        gr_edmd_create(sc, p, &prm, NULL, &s, &err)) {
        fprintf(stderr, "grano bench edmd: N = %ld, eta = %g: %s\n", n, eta, err.msg);
        gr_particles_free(p);
        gr_scene_free(sc);
        return err.code ? err.code : 1;
    }
    gr_particles_free(p);
    if (gr_edmd_advance(s, INFINITY, (uint64_t)(o->equil * n), &err)) {
        fprintf(stderr, "grano bench edmd: %s\n", err.msg);
        gr_edmd_free(s);
        gr_scene_free(sc);
        return err.code;
    }
    gr_edmd_counters c0, c1;
    gr_edmd_get_counters(s, &c0);
    double want = o->measure * n > 2e6 ? o->measure * n : 2e6;
    double w0 = exp_wall_seconds(), u0 = exp_cpu_seconds();
    int rc = gr_edmd_advance(s, INFINITY, (uint64_t)want, &err);
    double w1 = exp_wall_seconds(), u1 = exp_cpu_seconds();
    gr_edmd_get_counters(s, &c1);
    gr_edmd_free(s);
    gr_scene_free(sc);
    if (rc) {
        fprintf(stderr, "grano bench edmd: %s\n", err.msg);
        return rc;
    }
    double coll = (double)(c1.pair - c0.pair);
    double ev = coll + (double)(c1.crossing - c0.crossing) + (double)(c1.stale - c0.stale);
    printf("  %9ld %5.2f %12.0f %9.3f %14.4g %14.4g %14.4g\n", n, eta, coll, w1 - w0, coll / (w1 - w0),
           coll / (u1 - u0), ev / (w1 - w0));
    printf("RESULT method=edmd n=%ld eta=%g collisions_per_s=%.4g cpu_collisions_per_s=%.4g\n", n, eta,
           coll / (w1 - w0), coll / (u1 - u0));
    fflush(stdout);
    return 0;
}

int bench_edmd(int argc, char **argv)
{
    be_opts o;
    int rc = parse_args(argc, argv, &o);
    if (rc >= 0)
        return rc;
    for (int i = 0; i < o.ne; i++)
        if (!(o.etas[i] > 0 && o.etas[i] <= 0.7)) {
            fprintf(stderr, "grano bench edmd: packing fraction %g outside (0, 0.7]\n", o.etas[i]);
            return 2;
        }
    printf("# elastic disks, periodic box, lattice start with speeds 1 in random directions\n");
    if (o.rounds)
        return bench_ratio((long)o.ns[0], (long)o.ns[o.nn - 1], o.etas, o.ne, o.rounds, o.arity, o.cell, o.queue,
                           o.sort, o.equil);
    printf("# %9s %5s %12s %9s %14s %14s %14s\n", "N", "eta", "collisions", "wall_s", "coll/s", "coll/cpu_s",
           "events/s");
    for (int ie = 0; ie < o.ne; ie++)
        for (int in = 0; in < o.nn; in++)
            if ((rc = bench_one(&o, (long)o.ns[in], o.etas[ie])))
                return rc;
    return 0;
}
