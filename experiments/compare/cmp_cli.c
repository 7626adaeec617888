/* grano compare [--quick] [--cases LIST] [--methods LIST] [--out DIR] [-j N] [--resume]:
 * the command (docs/comparison.md): options, the plan of runs, the sweep. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <gsl/gsl_errno.h>

#include "cmd.h"
#include "cmp.h"
#include "cmp_own.h"
#include "opts.h"
#include "progress.h"
#include "sweep.h"

#ifndef GRANO_COMPARE_SCENES
#define GRANO_COMPARE_SCENES "experiments/scenes/compare"
#endif

static void usage(FILE *f)
{
    fprintf(f, "usage: grano compare [--quick] [--cases LIST] [--methods LIST] [--out DIR] [-j N] [--resume]\n"
               "       grano compare SCENE.ini [--methods LIST] [--observable NAME] [--until T] [--reference M]\n"
               "                     [--seeds N] [--tolerance X] [--out DIR] [-j N] [--resume]\n\n"
               "The same scenes on every method that models them, each at several settings of its\n"
               "accuracy knob: wall time against the error of the case's measured quantity\n"
               "(docs/comparison.md). Writes DIR/compare.h5, DIR/compare.txt, DIR/<case>.png and\n"
               "DIR/summary.png (each with its gnuplot script, .gp). With a scene file: that scene on\n"
               "every method that models it, each method's time step from its default for the scene\n"
               "down to a quarter, against the finest run of the most accurate method.\n\n"
               "options:\n"
               "  -q, --quick          small runs and fewer settings (the meson test), ~1 minute\n"
               "  -c, --cases LIST     comma-separated cases (default all):");
    for (const cmp_case *c = cmp_cases(); c->name; c++)
        fprintf(f, " %s", c->name);
    fprintf(f, "\n"
               "  -m, --methods LIST   comma-separated methods (default all registered)\n"
               "  -o, --out DIR        results folder (default compare-out); runs are kept in\n"
               "                       DIR/parts and reused by a later call with the same settings\n"
               "  -j, --jobs N         runs at once (default 1); results do not depend on N\n"
               "  -s, --scenes DIR     the case scenes (default %s)\n"
               "  -f, --force          redo every run\n"
               "  -r, --resume         continue an interrupted comparison in DIR: its finished runs\n"
               "                       are kept (exit 2 if DIR holds none)\n"
               "      --no-progress    no progress line\n"
               "with SCENE.ini:\n"
               "      --observable NAME  the quantity compared (default epot_grav under gravity, else\n"
               "                       temperature; grano methods lists each method's), mean over the\n"
               "                       second half of the run\n"
               "      --until T        [run] until of every run (default the scene's)\n"
               "      --reference M    the method whose finest run is the reference (default edmd\n"
               "                       when the scene gives a restitution, else dem)\n"
               "      --seeds N        realisations (default 3)\n"
               "      --tolerance X    the relative error each outcome is told against (default 0.05)\n"
               "  -h, --help           this help;  --version: the version\n"
               "Exit code 0 (also without gnuplot: the tables are written, the figures not, and it says\n"
               "so); 1 when a run or a check failed; 2 for bad arguments.\n",
            GRANO_COMPARE_SCENES);
}

typedef struct {
    const char *cases, *methods;
    int resume;
    cmp_own_opts own; /* own.scene set: a user's scene */
} cmp_sel;

/* Every entry of list names a case (or a method): else exit code 2. */
static int check_list(const char *flag, const char *list, int cases)
{
    char buf[512];
    snprintf(buf, sizeof buf, "%s", list);
    for (char *save = NULL, *s = strtok_r(buf, ",", &save); s; s = strtok_r(NULL, ",", &save)) {
        int ok = 0;
        if (cases) {
            for (const cmp_case *c = cmp_cases(); c->name; c++)
                ok |= !strcmp(c->name, s);
        } else
            ok = gr_method_find(s) != NULL;
        if (!ok) {
            fprintf(stderr, "grano compare: %s: unknown %s '%s' (grano compare --help lists them)\n", flag,
                    cases ? "case" : "method", s);
            return 2;
        }
    }
    return 0;
}

enum { O_QUICK = 'q', O_CASES = 'c', O_METHODS = 'm', O_OUT = 'o', O_JOBS = 'j', O_SCENES = 's', O_FORCE = 'f',
       O_RESUME = 'r', O_NOPROGRESS = 0x100, O_OBS, O_UNTIL, O_REF, O_SEEDS, O_TOL };

typedef struct {
    cmp_plan *pl;
    cmp_sel *sel;
} parse_ctx;

static int one_option(void *ctx, int id, const char *arg, gr_err *err)
{
    parse_ctx *c = ctx;
    long jobs;
    switch (id) {
    case O_QUICK: c->pl->quick = 1; return 0;
    case O_CASES: c->sel->cases = arg; return 0;
    case O_METHODS: c->sel->methods = arg; return 0;
    case O_OUT: c->pl->out = arg; return 0;
    case O_SCENES: c->pl->scenes = arg; return 0;
    case O_FORCE: c->pl->force = 1; return 0;
    case O_RESUME: c->sel->resume = 1; return 0;
    case O_OBS: c->sel->own.observable = arg; return 0;
    case O_REF: c->sel->own.reference = arg; return 0;
    case O_UNTIL: return exp_opt_interval("--until", arg, 0, 1, 1e12, 0, &c->sel->own.until, err);
    case O_TOL: return exp_opt_interval("--tolerance", arg, 0, 1, 10, 0, &c->sel->own.tolerance, err);
    case O_SEEDS:
        if (exp_opt_long("--seeds", arg, 1, 1000, &jobs, err))
            return err->code;
        c->sel->own.seeds = (int)jobs;
        return 0;
    case O_NOPROGRESS: c->pl->progress = 0; return 0;
    case O_JOBS:
        if (exp_opt_long("-j", arg, 1, 256, &jobs, err))
            return err->code;
        c->pl->jobs = (int)jobs;
        return 0;
    default: return gr_fail(err, GR_EINPUT, "unknown option");
    }
}

/* Options into pl and sel: 0, -1 (help or version printed: exit 0), or the
 * exit code of a bad flag (reported here). */
static int parse(int argc, char **argv, cmp_plan *pl, cmp_sel *sel)
{
    static const struct option opts[] = {
        {"quick", no_argument, NULL, O_QUICK},       {"cases", required_argument, NULL, O_CASES},
        {"methods", required_argument, NULL, O_METHODS}, {"out", required_argument, NULL, O_OUT},
        {"jobs", required_argument, NULL, O_JOBS},   {"scenes", required_argument, NULL, O_SCENES},
        {"force", no_argument, NULL, O_FORCE},       {"no-progress", no_argument, NULL, O_NOPROGRESS},
        {"resume", no_argument, NULL, O_RESUME},     {"observable", required_argument, NULL, O_OBS},
        {"until", required_argument, NULL, O_UNTIL}, {"reference", required_argument, NULL, O_REF},
        {"seeds", required_argument, NULL, O_SEEDS}, {"tolerance", required_argument, NULL, O_TOL},
        {NULL, 0, NULL, 0}};
    parse_ctx c = {pl, sel};
    int first = 0;
    int rc = exp_getopt_main("compare", argc, argv, opts, one_option, &c, usage, 1, &first);
    if (rc >= 0)
        return rc ? rc : -1;
    sel->own.scene = first < argc ? argv[first] : NULL;
    sel->own.methods = sel->methods;
    const char *own_flag = sel->own.observable ? "--observable" : sel->own.reference ? "--reference"
                         : sel->own.until > 0 ? "--until" : sel->own.seeds ? "--seeds"
                         : sel->own.tolerance > 0 ? "--tolerance" : NULL;
    if (!sel->own.scene && own_flag) {
        fprintf(stderr, "grano compare: %s is for a scene of your own (grano compare SCENE.ini %s ...)\n", own_flag,
                own_flag);
        return 2;
    }
    if (sel->own.scene && sel->cases) {
        fprintf(stderr, "grano compare: --cases picks built-in cases; with a scene file (%s) give none\n",
                sel->own.scene);
        return 2;
    }
    if ((sel->cases && check_list("--cases", sel->cases, 1)) ||
        (sel->methods && check_list("--methods", sel->methods, 0)))
        return 2;
    if (sel->resume && pl->force) {
        fprintf(stderr, "grano compare: --resume keeps the finished runs, --force redoes them: give one\n");
        return 2;
    }
    char parts[2048];
    snprintf(parts, sizeof parts, "%s/parts", pl->out);
    if (sel->resume && access(parts, F_OK)) {
        fprintf(stderr, "grano compare: --resume: %s holds no runs to continue (no %s)\n", pl->out, parts);
        return 2;
    }
    return 0;
}

int cmd_compare(int argc, char **argv)
{
    cmp_plan pl = {.jobs = 1, .out = "compare-out", .scenes = GRANO_COMPARE_SCENES, .progress = 1};
    cmp_sel sel = {.own = {.tolerance = 0}};
    int rc = parse(argc, argv, &pl, &sel);
    if (rc)
        return rc < 0 ? 0 : rc;
    gsl_set_error_handler_off();
    pl.progress = pl.progress && isatty(STDERR_FILENO);
    gr_err err = {0};
    cmp_own *own = NULL;
    if (sel.own.scene) {
        if (!(sel.own.tolerance > 0))
            sel.own.tolerance = 0.05;
        own = malloc(sizeof *own);
        if (!own || cmp_own_build(&sel.own, own, &err)) {
            fprintf(stderr, "%sgrano compare: %s\n", own ? own->notes : "", own ? err.msg : "out of memory");
            free(own);
            return own && err.code != GR_EINPUT ? 1 : 2;
        }
        pl.cases = own->c;
        pl.scenes = own->dir;
        snprintf(pl.notes, sizeof pl.notes, "%s", own->notes);
    }
    if (cmp_plan_build(&pl, sel.cases, sel.methods, &err)) {
        fprintf(stderr, "%sgrano compare: %s\n", pl.notes, err.msg);
        free(pl.units);
        free(own);
        return err.code == GR_EINPUT ? 2 : 1;
    }
    char parts_dir[2048];
    snprintf(parts_dir, sizeof parts_dir, "%s/parts", pl.out);
    exp_sweep sw = {.nunits = pl.nunits, .jobs = pl.jobs, .dir = parts_dir, .prefix = "run",
                    .progress = pl.progress, .what = "runs", .force = pl.force};
    char **parts = calloc(pl.nunits, sizeof *parts);
    size_t reused = 0;
    int drawn = 0;
    printf("grano compare%s: %zu runs, %d at once, into %s\n%s", pl.quick ? " --quick" : "", pl.nunits, pl.jobs,
           pl.out, pl.notes);
    fflush(stdout);
    double t0 = gr_wall_seconds();
    rc = !parts ? gr_fail(&err, GR_ERUN, "out of memory")
                : exp_sweep_run(&sw, cmp_run_unit, cmp_unit_label, cmp_unit_key, &pl, parts, &reused, &err);
    if (!rc) {
        printf("%zu runs in %.1f s (%zu reused from %s)\n", pl.nunits, gr_wall_seconds() - t0, reused, parts_dir);
        rc = cmp_report(&pl, parts, &drawn, &err);
    }
    for (size_t u = 0; parts && u < pl.nunits; u++)
        free(parts[u]);
    free(parts);
    free(pl.units);
    free(own);
    if (rc) {
        fprintf(stderr, "grano compare: %s\n", err.msg);
        return rc == GR_EINPUT ? 2 : 1;
    }
    if (drawn)
        printf("wrote %s/compare.{h5,txt}, %s/<case>.png and %s/summary.png (gnuplot scripts beside)\n", pl.out,
               pl.out, pl.out);
    else
        fprintf(stderr, "grano compare: wrote %s/compare.{h5,txt}; no figures: gnuplot is not on PATH (install "
                        "it with 'apt-get install gnuplot-nox', then rerun: the runs are reused)\n", pl.out);
    return 0;
}
