/* grano silo-start's command line: its own options, the statistics of a
 * full and a quick run, the estimate printed before a full run, and the
 * sweep of the discharges (silo_start.c) and their report
 * (silo_start_report.c). */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmd.h"
#include "silo_cli.h"
#include "silo_start.h"
static void usage(FILE *f)
{
    fprintf(f,
        "usage: grano silo-start [options]\n\n"
        "The start of a silo discharge (thesis chapter 3) on the soft DEM backend:\n"
        "fill through a hopper and settle with the first orifice closed, once per\n"
        "realisation; then for each orifice branch that settled silo to the orifice\n"
        "(the packing settles again on the new base), open it, and follow the grains\n"
        "until the surface (its highest layer) has fallen two diameters and as many\n"
        "grains have left as filled them.\n"
        "Writes DIR/silo-start.h5, .dat tables and the figures fig3_1 ... fig3_6.\n\n"
        "options:\n"
        "  -D, --orifices LIST  orifice widths in d, comma separated (default 3.8,11)\n"
        "  -n, --realisations N independent discharges per orifice (default 20)\n"
        "  -s, --seed S         seed of realisation 0; realisation r uses S + r (default 1)\n"
        "  -j, --jobs N         discharges run at once, one process each (default 1)\n"
        "  -o, --out DIR        output directory (default results/silo-start)\n"
        "      --grains N       mobile grains (default 5000)\n"
        "      --width W        container width in d (default 50; height 2 W)\n"
        "      --hopper-outlet F the filling hopper's outlet, a fraction of the width\n"
        "                       (default " SILO_STR(SILO_OUTLET) ")\n"
        "      --max-steps N    stop a discharge after N steps at most\n"
        "      --subtract MODE  the mean flow subtracted from the window's displacements:\n"
        "                       columns (default: the mean of the grains that started\n"
        "                       in the same tenth of the window across x, the velocity\n"
        "                       profile), cells (a 5 x 5 grid over the window) or\n"
        "                       window (the whole window's mean)\n"
        "      --method M       the method (default dem); one without the silo's features\n"
        "                       (walls made of fixed grains, an orifice, ...) is refused.\n"
        "                       Steps stay dem's (1.25e-4 tau); cd runs its own dt\n"
        "                       (2.5e-3 tau, 20 steps) on rigid disks, mu 0.5, e = 0\n"
        "      --param K=V      a key of the method's section (repeatable), e.g. tol=1e-4\n"
        "      --material K=V   a key of [material] (repeatable), replacing the thesis's\n"
        "                       law (normal = hertz, tangential = regularised, kn = 1e5,\n"
        "                       gamma_n = 100, gamma_t = 300, mu = 0.5), e.g. mu=0.3\n"
        "  -Q, --quick          800 grains in a 20 d x 48 d silo filled without hopper,\n"
        "                       2 realisations, shorter runs: a smoke test in seconds\n"
        "  -f, --force          redo every part, even finished ones\n"
        "  -q, --quiet          no progress line\n"
        "  -h, --help           this help\n\n"
        "Each filling writes DIR/parts/fill-r<r>.part, each discharge\n"
        "DIR/parts/start-D<D>-r<r>.part when done; a run that is\n"
        "interrupted and started again with the same options redoes only the missing\n"
        "parts. Exit codes: 0 done, 1 a run failed, 2 bad input.\n");
}

/* Lags 1, 2, 3, 4, 6, 8, 11, ... frames (ratio about sqrt 2). */
static void make_lags(ss_ctx *c)
{
    c->nslots = 0;
    double l = 1;
    long last = 0;
    while (c->nslots < SS_MAX_SLOTS) {
        long v = lround(l);
        l *= M_SQRT2;
        if (v == last)
            continue;
        if (v * c->fs > c->max_steps)
            break;
        c->lag[c->nslots++] = last = v;
    }
}

static void make_times(ss_ctx *c)
{
    static const long extra[] = {2500, 4000, 16000, 25000, 40000, 63000, 100000, 160000,
                                 250000, 400000, 630000, 1000000};
    c->ntimes = 0;
    for (int i = 0; i < 6; i++)
        c->times[c->ntimes++] = ss_fig32_steps[i];
    for (size_t i = 0; i < sizeof extra / sizeof extra[0]; i++)
        if (extra[i] <= c->max_steps && c->ntimes < SS_MAX_TIMES)
            c->times[c->ntimes++] = extra[i];
    for (size_t i = 1; i < c->ntimes; i++)
        for (size_t j = i; j > 0 && c->times[j] < c->times[j - 1]; j--) {
            long t = c->times[j];
            c->times[j] = c->times[j - 1], c->times[j - 1] = t;
        }
}

static int ss_report_any(const void *ctx, char *const *parts, char *summary, size_t nsum, gr_err *err)
{
    return ss_report(ctx, parts, summary, nsum, err);
}

static const struct option ss_own_opts[] = {{"max-steps", required_argument, NULL, 'M'},
                                            {"subtract", required_argument, NULL, 'S'}, {NULL, 0, NULL, 0}};

/* silo-start's own options; a number not given is -1 */
typedef struct {
    long maxsteps;
    int subtract;
} ss_own;

static int ss_own_option(int ch, const char *arg, void *own);

/* A filling per realisation; a discharge: the branch (SILO_REBRANCH_STEPS
 * at the filling's own orifice, SILO_BRANCH_STEPS elsewhere), then the
 * time for the surface to fall 2 d through the outflow, within [min_steps,
 * max_steps]: measured 2.0e5 steps at 3.8 d and 5.2e4 at 11 d (means,
 * docs/experiments.md "Measured cost"), so D^-1.27 between them. */
static void ss_estimate(const void *ctx, double *pre, double *unit)
{
    const ss_ctx *c = ctx;
    double s = 0;
    for (size_t o = 0; o < c->norif; o++) {
        double run = 2.0e5 * pow(3.8 / c->orifice[o], 1.27);
        s += fmin((double)c->max_steps, fmax((double)c->min_steps, run));
        s += c->orifice[o] == c->fills.orifice ? SILO_REBRANCH_STEPS : SILO_BRANCH_STEPS;
    }
    *pre = silo_cpu_estimate(&c->base, SILO_FILL_STEPS);
    *unit = silo_cpu_estimate(&c->base, s / (double)c->norif);
}

static const silo_cli ss_cli = {
    .name = "silo-start", .usage = usage, .own = ss_own_opts, .own_short = "", .own_parse = ss_own_option,
    .orifices = "3.8,11", .quick_orifices = "3.8,11", .reinsert = 0,
    .prefix = "start", .progress_what = "discharges", .units_what = "discharges",
    .pre_unit = silo_fill_unit, .pre_label = silo_fill_label, .pre_key = silo_fill_key, .pre_prefix = "fill",
    .pre_what = "fillings", .unit = ss_unit, .label = ss_label, .key = ss_key, .report = ss_report_any, .estimate = ss_estimate};

/* --max-steps and --subtract into the ss_own at own */
static int ss_own_option(int ch, const char *arg, void *own)
{
    ss_own *w = own;
    if (ch == 'S') {
        static const char *const names[] = {"window", "columns", "cells"};
        for (int k = 0; k < 3; k++)
            if (!strcmp(arg, names[k]))
                return w->subtract = k, 0;
        return silo_bad(&ss_cli, "--subtract", arg, "window, columns or cells");
    }
    if (ch != 'M')
        return 1;
    return silo_parse_long(arg, 100, &w->maxsteps) ? silo_bad(&ss_cli, "--max-steps", arg, "an integer >= 100") : 0;
}

int cmd_silo_start(int argc, char **argv)
{
    silo_opts o;
    ss_own w = {-1, SS_SUB_COLUMNS};
    int rc = silo_cli_parse(&ss_cli, argc, argv, &o, &w);
    if (rc >= 0)
        return rc;
    ss_ctx c = {0};
    c.quick = o.quick;
    if ((rc = silo_cli_silo(&ss_cli, &o, &c.base, c.orifice, SS_MAX_ORIF, &c.norif)))
        return rc;
    int quick = o.quick;
    c.nreal = (int)(o.nreal > 0 ? o.nreal : quick ? 2 : 20);
    c.seed = (uint64_t)o.seed;
    c.fs = 20;
    c.min_steps = quick ? 4000 : 10000;
    c.max_steps = w.maxsteps > 0 ? w.maxsteps : quick ? 12000 : 800000;
    c.fall_stop = 2.0;
    c.window = quick ? 8 : 15;
    c.cell = quick ? 1 : 2;
    c.sample_cap = quick ? 4000 : 20000;
    c.subtract = w.subtract;
    make_lags(&c);
    make_times(&c);
    char dir[1024];
    c.dir = silo_cli_dir(&ss_cli, &o, dir, sizeof dir);
    /* filled with the first orifice closed: its discharges branch without a lift */
    c.fills = (silo_fills){&c.base, c.seed, c.dir, c.orifice[0]};
    return silo_cli_sweep(&ss_cli, &o, &c, &c.fills, (size_t)c.nreal, c.norif * (size_t)c.nreal, c.dir);
}
