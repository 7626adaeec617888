/* grano bench lgca: site updates per second (one node, one step) of the
 * lattice gas on periodic square lattices, on 1 and 2 threads. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_c2c.h"
#include "clock.h"
#include "cmd.h"
#include "init.h"
#include "lgca/lgca_int.h"
#include "method.h"
#include "opts.h"
#include "order.h"

static void usage(FILE *f)
{
    fprintf(f,
            "usage: grano bench lgca [--size N1,N2,...] [--threads T1,T2,...] [--rules fhp3|granular]\n"
            "                        [--p P] [--updates U] [--quick] [--ratio R]\n\n"
            "A periodic lattice of N x N nodes at occupation 1/4 per channel; each case runs at least\n"
            "U site updates (default 2e9; --quick: 2e8) after one warm-up step. Defaults: --size\n"
            "256,1024,4096,8192 --threads 1,2 --rules fhp3 (granular with --p P > 0 adds the\n"
            "dissipation bits). Prints per case:\n"
            "  RESULT method=lgca nx=NX ny=NY threads=T site_updates_per_s=X cpu_site_updates_per_s=Y ...\n"
            "(Y: per second of CPU time of all threads).\n"
            "--ratio R: for the first size, R alternating rounds of 1 thread, 2 threads and two\n"
            "independent 1-thread runs at once (the node's ceiling for 2 threads), printing the\n"
            "speed-up of each round and of all (the host's drift hits both alike), and the median of\n"
            "the rounds' own fractions of the ceiling (of_ceiling_median).\n");
}

static gr_sim *make(long n, int threads, const char *rules, double p, gr_scene **scp, gr_err *e)
{
    char text[1024];
    double h = sqrt(3.0) / 2;
    snprintf(text, sizeof text,
             "[scene]\nname = bench-lgca\nseed = 1\n[domain]\nwidth = %.17g\nheight = %.17g\n"
             "left = periodic\nright = periodic\nbottom = periodic\ntop = periodic\n"
             "[init]\nkind = occupation\noccupation = 0\n[lgca]\ndt = 1\nrules = %s\np = %.17g\nthreads = %d\n",
             (double)n * h * (1 + 1e-12), (double)n * (1 + 1e-12), rules, p, threads);
    const char *extra[] = {"lgca", NULL};
    gr_scene *sc = gr_scene_parse(text, "bench-lgca", extra, e);
    if (!sc)
        return NULL;
    gr_particles *q = gr_particles_create(0, e);
    gr_sim *s = NULL;
    if (q)
        gr_sim_create(gr_method_find("lgca"), sc, q, &s, e);
    gr_particles_free(q);
    if (!s) {
        gr_scene_free(sc);
        return NULL;
    }
    /* occupation 1/4: the AND of two random words (a bench needs no
     * statistics, only a typical mix of collisions) */
    lgca *L = gr_sim_state(s);
    size_t nw = (size_t)L->nw;
    for (size_t j = 0; j < (size_t)L->nj; j++)
        for (size_t c = 0; c < LGCA_CH; c++)
            for (size_t w = 0; w < nw; w++) {
                uint64_t k = (j * LGCA_CH + c) * nw + w;
                L->lane[j][c * nw + w] = lgca_rand_word(L->key, k, 60, 0) & lgca_rand_word(L->key, k, 61, 0) & L->valid[w];
            }
    *scp = sc;
    return s;
}

/* Site updates per second of wall time over at least `updates` updates;
 * *cpu: per second of the process's CPU time (all threads), which a
 * host shared with other jobs distorts less. */
static double timed(gr_sim *s, long n, double updates, double *cpu, gr_err *e)
{
    long steps = (long)ceil(updates / ((double)n * (double)n));
    if (gr_sim_step(s, e))
        return NAN;
    double t0 = exp_wall_seconds(), c0 = exp_cpu_seconds();
    if (gr_sim_advance(s, gr_sim_time(s) + (double)steps * 1.0, 0, e))
        return NAN;
    double done = (double)steps * (double)n * (double)n;
    if (cpu)
        *cpu = done / (exp_cpu_seconds() - c0);
    return done / (exp_wall_seconds() - t0);
}

static int run_case(long n, int threads, const char *rules, double p, double updates)
{
    gr_err e = {0};
    gr_scene *sc;
    gr_sim *s = make(n, threads, rules, p, &sc, &e);
    if (!s) {
        fprintf(stderr, "grano bench lgca: %s\n", e.msg);
        return 1;
    }
    lgca *L = gr_sim_state(s);
    double cpu = NAN, rate = timed(s, n, updates, &cpu, &e);
    double bytes = (double)((LGCA_CH + 1) * (size_t)L->nw * 8 * (size_t)L->nj) / ((double)L->ni * L->nj);
    printf("RESULT method=lgca nx=%d ny=%d threads=%d site_updates_per_s=%.4g cpu_site_updates_per_s=%.4g "
           "rules=%s bytes_per_node=%.3f\n",
           L->nj, L->ni, threads, rate, cpu, rules, bytes);
    fflush(stdout);
    gr_sim_free(s);
    gr_scene_free(sc);
    return isnan(rate) ? 1 : 0;
}

/* Wall seconds for two one-thread lattices advanced at once, one per
 * core: the node's own ceiling for two threads (they share the memory and
 * the caches the two threads of one run share). */
static double pair_seconds(gr_sim *c[2], long n, double updates, gr_err *e)
{
    int bad = 0;
    double t0 = exp_wall_seconds();
#pragma omp parallel for num_threads(2) schedule(static, 1) reduction(+ : bad)
    for (int k = 0; k < 2; k++) {
        gr_err ek = {0};
        bad += isnan(timed(c[k], n, updates, NULL, &ek));
    }
    double t = exp_wall_seconds() - t0;
    if (bad)
        gr_fail(e, GR_ERUN, "a ceiling run failed");
    return bad ? NAN : t;
}

static int run_ratio(long n, int rounds, const char *rules, double p, double updates)
{
    gr_err e = {0};
    gr_scene *sc[4] = {NULL};
    gr_sim *s[4] = {NULL};
    int ok = 1;
    for (int k = 0; k < 4 && ok; k++)
        ok = (s[k] = make(n, k == 1 ? 2 : 1, rules, p, &sc[k], &e)) != NULL;
    double ta = 0, tb = 0, tc = 0, c2c0 = bench_c2c_ns(2000), frac[64];
    for (int r = 0; r < rounds && ok; r++) {
        double ra = timed(s[0], n, updates, NULL, &e), rb = timed(s[1], n, updates, NULL, &e);
        double pc = pair_seconds(s + 2, n, updates, &e);
        ok = !isnan(ra) && !isnan(rb) && !isnan(pc);
        ta += updates / ra, tb += updates / rb, tc += pc;
        frac[r] = rb * pc / (2 * updates);
        printf("round %d: 1 thread %.4g, 2 threads %.4g site updates/s, speed-up %.3f; two 1-thread runs at once "
               "%.4g together (ceiling %.3f)\n",
               r + 1, ra, rb, rb / ra, 2 * updates / pc, 2 * updates / pc / ra);
    }
    /* the host may move the guest's CPUs between rounds (the c2c figure
     * changes): each round's own fraction, and their median, hold anyway */
    if (ok) {
        qsort(frac, (size_t)rounds, sizeof *frac, exp_cmp_double);
        double med = rounds % 2 ? frac[rounds / 2] : 0.5 * (frac[rounds / 2 - 1] + frac[rounds / 2]);
        printf("RESULT method=lgca nx=%ld ny=%ld rules=%s speedup_2_threads=%.3f ceiling=%.3f of_ceiling=%.3f "
               "of_ceiling_median=%.3f rounds=%d c2c_ns=%.0f,%.0f\n",
               n, n, rules, ta / tb, 2 * ta / tc, ta / tb / (2 * ta / tc), med, rounds, c2c0, bench_c2c_ns(2000));
    }
    else
        fprintf(stderr, "grano bench lgca: %s\n", e.msg);
    for (int k = 0; k < 4; k++)
        gr_sim_free(s[k]), gr_scene_free(sc[k]);
    return ok ? 0 : 1;
}

typedef struct {
    long sizes[16], threads[8];
    int ns, nt, rounds;
    double updates, p;
    const char *rules;
} bl_opts;

/* A comma list of positive whole numbers into out (at most cap). */
static int int_list(const char *flag, const char *arg, long *out, size_t cap, int *n, gr_err *err)
{
    double v[16];
    size_t k;
    if (exp_parse_list(arg, v, cap, &k))
        return gr_fail(err, GR_EINPUT, "%s: '%s' is not a list of at most %zu positive numbers", flag, arg, cap);
    for (size_t i = 0; i < k; i++) {
        if (v[i] != floor(v[i]) || v[i] > 1e9)
            return gr_fail(err, GR_EINPUT, "%s: '%s' is not a list of whole numbers", flag, arg);
        out[i] = (long)v[i];
    }
    *n = (int)k;
    return GR_OK;
}

static int lgca_option(void *ctx, int id, const char *arg, gr_err *err)
{
    bl_opts *o = ctx;
    long v;
    switch (id) {
    case 'Q': o->updates = 2e8, o->ns = 2, o->sizes[0] = 256, o->sizes[1] = 1024; return 0;
    case 's': return int_list("--size", arg, o->sizes, 16, &o->ns, err);
    case 't': return int_list("--threads", arg, o->threads, 8, &o->nt, err);
    case 'R':
        if (strcmp(arg, "fhp3") && strcmp(arg, "granular"))
            return gr_fail(err, GR_EINPUT, "--rules: '%s' is not fhp3 or granular", arg);
        o->rules = arg;
        return 0;
    case 'p': return exp_opt_double("--p", arg, 0, 1, &o->p, err);
    case 'u': return exp_opt_double("--updates", arg, 1, 1e15, &o->updates, err);
    case 'r':
        if (exp_opt_long("--ratio", arg, 1, 64, &v, err))
            return err->code;
        o->rounds = (int)v;
        return 0;
    default: return gr_fail(err, GR_EINPUT, "unknown option");
    }
}

int bench_lgca(int argc, char **argv)
{
    static const struct option opts[] = {
        {"quick", no_argument, NULL, 'Q'},         {"size", required_argument, NULL, 's'},
        {"threads", required_argument, NULL, 't'}, {"rules", required_argument, NULL, 'R'},
        {"p", required_argument, NULL, 'p'},       {"updates", required_argument, NULL, 'u'},
        {"ratio", required_argument, NULL, 'r'},   {NULL, 0, NULL, 0}};
    bl_opts o = {.sizes = {256, 1024, 4096, 8192}, .threads = {1, 2}, .ns = 4, .nt = 2, .updates = 2e9,
                 .rules = "fhp3"};
    int first;
    int rc = exp_getopt_main("bench lgca", argc, argv, opts, lgca_option, &o, usage, 0, &first);
    if (rc >= 0)
        return rc;
    const long *sizes = o.sizes, *threads = o.threads;
    int ns = o.ns, nt = o.nt, rounds = o.rounds;
    double updates = o.updates, p = o.p;
    const char *rules = o.rules;
    if (p > 0 && !strcmp(rules, "fhp3")) {
        fprintf(stderr, "grano bench lgca: --p needs --rules granular\n");
        return 2;
    }
    if (rounds)
        return run_ratio(sizes[0], rounds, rules, p, updates);
    for (int i = 0; i < ns; i++)
        for (int t = 0; t < nt; t++)
            if (run_case(sizes[i], (int)threads[t], rules, p, updates))
                return 1;
    return 0;
}
