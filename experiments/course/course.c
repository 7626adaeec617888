/* grano course: the three exercises of the lecture slides on event-driven
 * hard disks (docs/course.md), through the method interface: relaxation to
 * the Maxwell distribution, wall pressure against density and against V0,
 * homogeneous cooling. Each writes an HDF5 file, a plain table and PNG
 * figures; this file holds the command (course_common.c what they share). */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <gsl/gsl_errno.h>

#include "cmd.h"
#include "course.h"
#include "files.h"
#include "opts.h"
#include "init.h"

/* Refuse, before any output, a method that does not count disk-disk
 * collisions: a one-disk box is enough to ask it. */
static int require_pairs(const course_opts *o, const char *ex, gr_err *err)
{
    gr_scene *sc;
    gr_sim *s;
    if (course_sim("[domain]\nwidth = 4\nheight = 4\n[material]\nrestitution = 1\n[species]\ncount = 1\n"
                   "[init]\nkind = lattice\nvelocity = speed\nv0 = 1\n",
                   o, NULL, &sc, &s, err))
        return err->code;
    char who[64];
    snprintf(who, sizeof who, "the exercise%s", strcmp(ex, "all") ? "" : "s");
    uint64_t pairs;
    int rc = course_pairs(s, who, &pairs, err);
    gr_sim_free(s);
    gr_scene_free(sc);
    return rc;
}

static void usage(FILE *f)
{
    fprintf(f, "usage: grano course EXERCISE [--method M] [--quick] [--out DIR] [--naive|--tree] [--seed S]\n"
               "                    [--n N] [--eta ETA | --box L] [--alpha A] [--collisions C] [--time T]\n"
               "                    [--runs R] [--force] [--help] [--version]\n\n"
               "The exercises of the lecture slides on event-driven hard disks (docs/course.md):\n"
               "  maxwell    speed histograms after N/2, N, 2N, 3N, C N collisions against Maxwell's law\n"
               "             (--n, --eta or --box, --collisions C (> 3, default 10), --runs)\n"
               "  pressure   wall pressure against the density n = N/L^2 and against V0\n"
               "             (--box, --n of the sweep against V0, --time of the measurement)\n"
               "  cooling    homogeneous cooling of inelastic disks against Haff's law\n"
               "             (--n, --eta or --box, --alpha, --collisions)\n"
               "  all        the three in turn (each takes the flags it uses)\n"
               "--method M: the method (default edmd); every exercise counts disk-disk collisions, so\n"
               "the method must give the counter 'pair_collisions'. --out DIR: where the .h5, .dat\n"
               "and .png files go (default course-out); --quick: small runs for tests; --naive: the\n"
               "slides' algorithm v1.0 (edmd's algorithm = naive, the default for maxwell) instead\n"
               "of the event tree; --tree forces the tree; --seed S: the first start's seed.\n"
               "--n N: disks (2 .. 10^7); --eta ETA: packing fraction N pi d^2/(4 L^2) in (0, 0.75);\n"
               "--box L: the square box's side in d; --alpha A: restitution in (0, 1]; --collisions C:\n"
               "run length in collisions per disk; --time T: pressure's measurement in L/V0; --runs R:\n"
               "independent starts pooled. A flag an exercise does not use is refused by name.\n"
               "An exercise's existing result file DIR/EXERCISE.h5 is replaced only with --force.\n");
}

enum { O_QUICK = 'Q', O_NAIVE = 0x100, O_TREE, O_OUT = 'o', O_METHOD = 'm', O_ALPHA = 0x103, O_SEED = 's',
       O_FORCE = 'f', O_N = 0x110, O_ETA, O_BOX, O_COLL, O_TIME, O_RUNS };

typedef struct {
    course_opts *o;
    const char *method;
} parse_ctx;

/* The parameters' flags, their bits, and the exercises that use them. */
static const struct {
    const char *flag;
    unsigned bit;
    const char *used_by; /* space-separated exercises */
} params[] = {
    {"--n", COURSE_N, "maxwell pressure cooling"},       {"--eta", COURSE_ETA, "maxwell cooling"},
    {"--box", COURSE_BOX, "maxwell pressure cooling"},   {"--alpha", COURSE_ALPHA, "cooling"},
    {"--collisions", COURSE_COLLISIONS, "maxwell cooling"}, {"--time", COURSE_TIME, "pressure"},
    {"--runs", COURSE_RUNS, "maxwell"},
};
#define NPARAMS (sizeof params / sizeof params[0])

static const char *const ex_params[] = {
    "maxwell", "--n, --eta or --box, --collisions, --runs",
    "pressure", "--n, --box, --time",
    "cooling", "--n, --eta or --box, --alpha, --collisions",
};

static int real_opt(course_opts *o, unsigned bit, const char *flag, const char *arg, double lo, int lo_open,
                    double hi, int hi_open, double *v, gr_err *err)
{
    o->given |= bit;
    return exp_opt_interval(flag, arg, lo, lo_open, hi, hi_open, v, err);
}

static int int_opt(course_opts *o, unsigned bit, const char *flag, const char *arg, long lo, long hi, long *v,
                   gr_err *err)
{
    o->given |= bit;
    return exp_opt_long(flag, arg, lo, hi, v, err);
}

static int one_option(void *ctx, int id, const char *arg, gr_err *err)
{
    parse_ctx *c = ctx;
    course_opts *o = c->o;
    long seed;
    switch (id) {
    case O_QUICK: o->quick = 1; return 0;
    case O_NAIVE: o->naive = 1; return 0;
    case O_TREE: o->naive = 0; return 0;
    case O_FORCE: o->force = 1; return 0;
    case O_OUT: o->out = arg; return 0;
    case O_METHOD: c->method = arg; return 0;
    case O_ALPHA: return real_opt(o, COURSE_ALPHA, "--alpha", arg, 0, 1, 1, 0, &o->alpha, err);
    case O_ETA: return real_opt(o, COURSE_ETA, "--eta", arg, 0, 1, 0.75, 1, &o->eta, err);
    case O_BOX: return real_opt(o, COURSE_BOX, "--box", arg, 0, 1, 1e6, 0, &o->box, err);
    case O_COLL: return real_opt(o, COURSE_COLLISIONS, "--collisions", arg, 0, 1, 1e4, 0, &o->collisions, err);
    case O_TIME: return real_opt(o, COURSE_TIME, "--time", arg, 0, 1, 1e6, 0, &o->time, err);
    case O_N: return int_opt(o, COURSE_N, "--n", arg, 2, 10000000, &o->n, err);
    case O_RUNS: return int_opt(o, COURSE_RUNS, "--runs", arg, 1, 100000, &o->runs, err);
    case O_SEED:
        if (exp_opt_long("--seed", arg, 0, LONG_MAX, &seed, err))
            return err->code;
        o->seed = (unsigned long)seed;
        return 0;
    default: return gr_fail(err, GR_EINPUT, "unknown option");
    }
}

/* A parameter the exercise does not use is refused by name (with `all`,
 * one that none uses cannot be given). */
static int check_params(const course_opts *o, const char *ex)
{
    if ((o->given & COURSE_ETA) && (o->given & COURSE_BOX)) {
        fprintf(stderr, "grano course: --eta and --box both set the box; give one\n");
        return 2;
    }
    if (!strcmp(ex, "all"))
        return 0;
    for (size_t k = 0; k < NPARAMS; k++) {
        if (!(o->given & params[k].bit) || strstr(params[k].used_by, ex))
            continue;
        const char *mine = "";
        for (size_t e = 0; e < sizeof ex_params / sizeof *ex_params; e += 2)
            if (!strcmp(ex_params[e], ex))
                mine = ex_params[e + 1];
        fprintf(stderr, "grano course %s: %s is not a parameter of this exercise (%s takes %s, --seed, --method)\n",
                ex, params[k].flag, ex, mine);
        return 2;
    }
    return 0;
}

/* Options into o and the exercise; 0, -1 (help or version printed: exit
 * 0), or the exit code of a bad flag (reported here). */
static int parse(int argc, char **argv, course_opts *o, const char **ex)
{
    static const struct option opts[] = {
        {"quick", no_argument, NULL, O_QUICK},        {"naive", no_argument, NULL, O_NAIVE},
        {"tree", no_argument, NULL, O_TREE},          {"out", required_argument, NULL, O_OUT},
        {"method", required_argument, NULL, O_METHOD}, {"alpha", required_argument, NULL, O_ALPHA},
        {"seed", required_argument, NULL, O_SEED},    {"force", no_argument, NULL, O_FORCE},
        {"n", required_argument, NULL, O_N},          {"eta", required_argument, NULL, O_ETA},
        {"box", required_argument, NULL, O_BOX},      {"collisions", required_argument, NULL, O_COLL},
        {"time", required_argument, NULL, O_TIME},    {"runs", required_argument, NULL, O_RUNS},
        {NULL, 0, NULL, 0}};
    parse_ctx c = {o, "edmd"};
    gr_err err = {0};
    int first = 0;
    int rc = exp_getopt_main("course", argc, argv, opts, one_option, &c, usage, 1, &first);
    if (rc >= 0)
        return rc ? rc : -1;
    if (first >= argc) {
        fprintf(stderr, "grano course: missing EXERCISE\n");
        usage(stderr);
        return 2;
    }
    *ex = argv[first];
    if (gr_method_lookup(c.method, "--method", &o->m, &err)) {
        fprintf(stderr, "grano course: %s\n", err.msg);
        return 2;
    }
    if (o->naive >= 0 && strcmp(o->m->name, "edmd")) {
        fprintf(stderr, "grano course: --%s selects edmd's algorithm, which method '%s' does not have\n",
                o->naive ? "naive" : "tree", o->m->name);
        return 2;
    }
    return 0;
}

/* An exercise's result file is replaced only with --force. */
static int check_results(const course_opts *o, const char *ex, int all)
{
    static const char *const names[] = {"maxwell", "pressure", "cooling"};
    for (int k = 0; k < 3; k++) {
        if (!all && strcmp(ex, names[k]))
            continue;
        char path[1200];
        snprintf(path, sizeof path, "%s/%s.h5", o->out, names[k]);
        gr_err e = {0};
        if (exp_check_writable(path, "--out", o->force, &e)) {
            fprintf(stderr, "grano course: %s\n", e.msg);
            return 2;
        }
    }
    return 0;
}

int cmd_course(int argc, char **argv)
{
    const char *ex = NULL;
    course_opts o = {.out = "course-out", .quick = 0, .naive = -1, .alpha = 0.9, .seed = 1};
    int rc = parse(argc, argv, &o, &ex);
    if (rc)
        return rc < 0 ? 0 : rc;
    int all = !strcmp(ex, "all");
    if (!all && strcmp(ex, "maxwell") && strcmp(ex, "pressure") && strcmp(ex, "cooling")) {
        fprintf(stderr, "grano course: unknown exercise '%s'\n", ex);
        usage(stderr);
        return 2;
    }
    if ((rc = check_params(&o, ex)))
        return rc;
    gsl_set_error_handler_off();
    gr_err err = {0};
    if ((rc = require_pairs(&o, ex, &err))) {
        fprintf(stderr, "grano course %s: %s\n", ex, err.msg);
        return rc;
    }
    if (exp_mkdirs(o.out, &err)) {
        fprintf(stderr, "grano course: --out %s\n", err.msg);
        return 2;
    }
    if ((rc = check_results(&o, ex, all)))
        return rc;
    int naive = o.naive;
    if (!rc && (all || !strcmp(ex, "maxwell"))) {
        /* the first exercise is the slides' v1.0 */
        o.naive = naive < 0 ? !strcmp(o.m->name, "edmd") : naive;
        o.pg = gr_progress_create(stderr, 0, 1, 1.0);
        rc = course_maxwell(&o, &err);
        gr_progress_free(o.pg);
    }
    o.naive = naive < 0 ? 0 : naive;
    if (!rc && (all || !strcmp(ex, "pressure"))) {
        o.pg = gr_progress_create(stderr, 0, 1, 1.0);
        rc = course_pressure(&o, &err);
        gr_progress_free(o.pg);
    }
    if (!rc && (all || !strcmp(ex, "cooling"))) {
        o.pg = gr_progress_create(stderr, 0, 1, 1.0);
        rc = course_cooling(&o, &err);
        gr_progress_free(o.pg);
    }
    if (rc) {
        fprintf(stderr, "grano course %s: %s\n", ex, err.msg);
        return rc;
    }
    return 0;
}
