/* The command line shared by the silo commands (silo_cli.h). */
#include "silo_cli.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dist.h"
#include "opts.h"
#include "plot.h"
#include "progress.h"

/* a long option without a short one */
#define OPT_METHOD 0x100
#define OPT_PARAM 0x101
#define OPT_VERSION 0x102
#define OPT_OUTLET 0x103
#define OPT_MATERIAL 0x104
/* room for the common options, the command's own and the end mark */
#define MAX_OPTS 24

static const struct option common_opts[] = {
    {"orifices", required_argument, NULL, 'D'}, {"realisations", required_argument, NULL, 'n'},
    {"seed", required_argument, NULL, 's'},     {"jobs", required_argument, NULL, 'j'},
    {"out", required_argument, NULL, 'o'},      {"grains", required_argument, NULL, 'G'},
    {"width", required_argument, NULL, 'W'},    {"method", required_argument, NULL, OPT_METHOD},
    {"param", required_argument, NULL, OPT_PARAM},   {"hopper-outlet", required_argument, NULL, OPT_OUTLET},
    {"material", required_argument, NULL, OPT_MATERIAL},
    {"quick", no_argument, NULL, 'Q'},          {"force", no_argument, NULL, 'f'},
    {"quiet", no_argument, NULL, 'q'},          {"help", no_argument, NULL, 'h'},
    {"version", no_argument, NULL, OPT_VERSION}, {NULL, 0, NULL, 0}};

void silo_unit_label(const double *orifice, int nreal, size_t unit, char *buf, size_t n)
{
    size_t o = unit / (size_t)nreal, r = unit % (size_t)nreal;
    snprintf(buf, n, "D%g-r%02zu", orifice[o], r);
}

int silo_bad(const silo_cli *cli, const char *opt, const char *val, const char *what)
{
    fprintf(stderr, "grano %s: %s: '%s' is not %s\n", cli->name, opt, val ? val : "", what);
    return 2;
}

int silo_parse_long(const char *s, long lo, long *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (*end || end == s || errno || v < lo)
        return -1;
    *out = v;
    return 0;
}

/* --param (--material) KEY=VALUE as a line "KEY = VALUE" of the method's
 * section ([material]) in lines. */
static int add_line(const silo_cli *cli, const char *opt, const char *arg, char *lines, size_t cap)
{
    if (!arg)
        return silo_bad(cli, opt, "", "KEY=VALUE");
    const char *eq = strchr(arg, '=');
    size_t used = strlen(lines), klen = eq ? (size_t)(eq - arg) : 0;
    if (!eq || !klen || !eq[1] || strchr(arg, '\n') || strspn(arg, "abcdefghijklmnopqrstuvwxyz_") != klen)
        return silo_bad(cli, opt, arg, "KEY=VALUE");
    int w = snprintf(lines + used, cap - used, "%.*s = %s\n", (int)klen, arg, eq + 1);
    if (w < 0 || (size_t)w >= cap - used)
        return silo_bad(cli, opt, arg, "within the room for parameters");
    return 0;
}

/* One common option into *o: 0 taken, 2 a bad value, 1 not a common one. */
static int common_option(const silo_cli *cli, int ch, const char *arg, silo_opts *o)
{
    char *end;
    switch (ch) {
    case 'D': o->orif = arg; return 0;
    case 'n': return silo_parse_long(arg, 1, &o->nreal) ? silo_bad(cli, "--realisations", arg, "a positive integer") : 0;
    case 's': return silo_parse_long(arg, 0, &o->seed) ? silo_bad(cli, "--seed", arg, "a non-negative integer") : 0;
    case 'j':
        if (silo_parse_long(arg, 1, &o->jobs) || o->jobs > 256)
            return silo_bad(cli, "--jobs", arg, "an integer in 1..256");
        return 0;
    case 'o': o->out = arg; return 0;
    case 'G': return silo_parse_long(arg, 10, &o->grains) ? silo_bad(cli, "--grains", arg, "an integer >= 10") : 0;
    case 'W':
        o->width = strtod(arg, &end);
        if (*end || !(o->width >= 8) || !isfinite(o->width))
            return silo_bad(cli, "--width", arg, "a width >= 8");
        return 0;
    case OPT_OUTLET:
        o->outlet = strtod(arg, &end);
        if (*end || end == arg || !(o->outlet > 0 && o->outlet < 1))
            return silo_bad(cli, "--hopper-outlet", arg, "a fraction of the width between 0 and 1");
        return 0;
    case OPT_METHOD: o->method = arg; return 0;
    case OPT_PARAM: return add_line(cli, "--param", arg, o->params, sizeof o->params);
    case OPT_MATERIAL: return add_line(cli, "--material", arg, o->material, sizeof o->material);
    case 'Q': o->quick = 1; return 0;
    case 'f': o->force = 1; return 0;
    case 'q': o->quiet = 1; return 0;
    default: return 1;
    }
}

/* The long options and short letters getopt sees: the common ones and the
 * command's own, in one table because getopt_long takes only one. */
static void option_table(const silo_cli *cli, struct option *opts, char *shorts, size_t nshort)
{
    size_t k = 0;
    for (const struct option *p = common_opts; p->name; p++)
        opts[k++] = *p;
    for (const struct option *p = cli->own; p && p->name && k + 1 < MAX_OPTS; p++)
        opts[k++] = *p;
    opts[k] = (struct option){NULL, 0, NULL, 0};
    snprintf(shorts, nshort, ":D:n:s:j:o:%sQfqh", cli->own_short ? cli->own_short : "");
}

int silo_cli_parse(const silo_cli *cli, int argc, char **argv, silo_opts *o, void *own)
{
    *o = (silo_opts){NULL, NULL, "dem", -1, 1, 1, -1, -1, -1, 0, 0, 0, "", ""};
    struct option opts[MAX_OPTS];
    char shorts[64];
    option_table(cli, opts, shorts, sizeof shorts);
    int ch;
    opterr = 0;
    optind = 1;
    while ((ch = getopt_long(argc, argv, shorts, opts, NULL)) != -1) {
        if (ch == 'h') {
            cli->usage(stdout);
            return 0;
        }
        if (ch == OPT_VERSION) {
            exp_print_version(cli->name);
            return 0;
        }
        if (ch == ':') {
            fprintf(stderr, "grano %s: option '%s' needs a value\n", cli->name, argv[optind - 1]);
            return 2;
        }
        int rc = common_option(cli, ch, optarg, o);
        if (rc == 1 && ch != '?' && cli->own_parse)
            rc = cli->own_parse(ch, optarg, own);
        if (rc == 1 || ch == '?') {
            fprintf(stderr, "grano %s: unknown option '%s' (see grano %s --help)\n", cli->name, argv[optind - 1],
                    cli->name);
            return 2;
        }
        if (rc)
            return rc;
    }
    if (optind != argc) {
        fprintf(stderr, "grano %s: unexpected argument '%s'\n", cli->name, argv[optind]);
        return 2;
    }
    return -1;
}

int silo_cli_silo(const silo_cli *cli, const silo_opts *o, silo_cfg *base, double *orifice, size_t cap,
                  size_t *norif)
{
    if (o->quick) {
        silo_cfg_quick(base, 1);
        if (cli->quick_n > 0)
            base->n = cli->quick_n;
        if (cli->quick_width > 0)
            base->width = cli->quick_width;
    } else
        silo_cfg_thesis(base, 1);
    if (o->grains > 0)
        base->n = o->grains;
    if (o->width > 0)
        base->width = o->width, base->height = 2 * o->width;
    if (o->outlet > 0) {
        if (!base->hopper) {
            fprintf(stderr, "grano %s: --hopper-outlet: the quick silo fills without a hopper\n", cli->name);
            return 2;
        }
        char v[32];
        snprintf(v, sizeof v, "%g", o->outlet);
        if (o->outlet * base->width < 5)
            return silo_bad(cli, "--hopper-outlet", v, "an outlet of 5 d or more at this width");
        base->outlet = o->outlet;
    }
    if (exp_parse_list(o->orif ? o->orif : o->quick ? cli->quick_orifices : cli->orifices, orifice, cap, norif))
        return silo_bad(cli, "--orifices", o->orif, "a comma-separated list of positive widths");
    for (size_t i = 0; i < *norif; i++)
        if (orifice[i] >= base->width - 2)
            return silo_bad(cli, "--orifices", o->orif, "narrower than the silo");
    memcpy(base->params, o->params, sizeof base->params);
    memcpy(base->material, o->material, sizeof base->material);
    gr_err me = {0};
    /* the silo as the units will open it */
    silo_cfg probe = *base;
    probe.orifice = orifice[0];
    probe.reinsert = cli->reinsert;
    if (silo_choose_method(&probe, o->method, &me)) {
        fprintf(stderr, "grano %s: %s\n", cli->name, me.msg);
        return 2;
    }
    base->method = probe.method;
    return 0;
}

const char *silo_cli_dir(const silo_cli *cli, const silo_opts *o, char *dir, size_t n)
{
    if (o->out)
        snprintf(dir, n, "%s", o->out);
    else
        snprintf(dir, n, "results/%s%s", cli->name, o->quick ? "-quick" : "");
    return dir;
}

/* A wall time as minutes, or seconds under two minutes. */
static const char *wall_text(double seconds, char *buf, size_t n)
{
    if (seconds < 120)
        snprintf(buf, n, "%.0f s", seconds);
    else
        snprintf(buf, n, "%.0f min", seconds / 60);
    return buf;
}

/* "estimated ..." before a full run: the units' CPU seconds (the
 * command's estimate at the rate measured unloaded) spread over the
 * workers, phase by phase. */
static void print_estimate(const silo_cli *cli, double pre, double unit, size_t npre, size_t nunits, int workers)
{
    if (!isfinite(pre) || !isfinite(unit))
        return;
    size_t w = workers > 0 ? (size_t)workers : 1;
    double wall = (double)((npre + w - 1) / w) * pre + (double)((nunits + w - 1) / w) * unit;
    char first[96] = "";
    if (npre)
        snprintf(first, sizeof first, "%s: %zu of ~%.0f CPU s, then ", cli->pre_what, npre, pre);
    char t[32];
    fprintf(stderr,
            "grano %s: estimated %s wall on %zu worker%s: %s%s: %zu of ~%.0f CPU s (at the rate measured "
            "on an idle core; a loaded machine is slower)\n",
            cli->name, wall_text(wall, t, sizeof t), w, w > 1 ? "s" : "", first, cli->units_what, nunits, unit);
}

/* The estimate calibrated on this machine as a phase's units finish (the
 * first, then each quarter): the wall time a unit took a worker so far,
 * against the estimate's, sets the pace of what is left (the later
 * phase's units included). */
typedef struct {
    const silo_cli *cli;
    const char *what;      /* the phase's units */
    double est, est_after; /* the estimate's CPU s of a unit of this phase and of the next */
    size_t n_after;        /* the next phase's units (0: none) */
} silo_pace;

static void paced(void *ctx, double elapsed, size_t finished, size_t left, int jobs)
{
    const silo_pace *p = ctx;
    size_t w = jobs > 0 ? (size_t)jobs : 1;
    /* the first w units ran side by side: one took the elapsed time */
    double unit = elapsed / (double)((finished + w - 1) / w);
    if (!(p->est > 0) || !(unit > 0))
        return;
    double pace = p->est / unit;
    double wall = unit * (double)left / (double)w + (double)((p->n_after + w - 1) / w) * p->est_after / pace;
    char t[32], e[32];
    fprintf(stderr,
            "grano %s: %zu of the %zu %s done in %s wall (~%.0f s a unit a worker, estimated ~%.0f CPU s: this "
            "machine runs at %.2f of the estimate's pace); estimated %s wall left on %zu worker%s\n",
            p->cli->name, finished, finished + left, p->what, wall_text(elapsed, e, sizeof e), unit, p->est, pace,
            wall_text(wall, t, sizeof t), w, w > 1 ? "s" : "");
}

int silo_cli_sweep(const silo_cli *cli, const silo_opts *o, void *ctx, void *pre_ctx, size_t npre, size_t nunits,
                   const char *dir)
{
    exp_dist d;
    exp_dist_begin(&d);
    char pdir[1100];
    snprintf(pdir, sizeof pdir, "%s/parts", dir);
    gr_err e = {0};
    /* one process per rank under MPI: mpirun places the ranks on the cores */
    int jobs = d.size > 1 ? 1 : (int)o->jobs;
    size_t reused = 0;
    double est_pre = NAN, est_unit = NAN;
    if (cli->estimate)
        cli->estimate(ctx, &est_pre, &est_unit);
    if (d.rank == 0 && !o->quiet && !o->quick && cli->estimate)
        print_estimate(cli, est_pre, est_unit, npre, nunits, jobs * d.size);
    int calibrate = d.size == 1 && !o->quiet && !o->quick && cli->estimate;
    silo_pace pace_pre = {cli, cli->pre_what, est_pre, est_unit, nunits};
    silo_pace pace_units = {cli, cli->units_what, est_unit, 0, 0};
    double t0 = gr_wall_seconds();
    int rc = GR_OK;
    if (npre && cli->pre_unit) {
        exp_sweep pre = {npre, jobs, pdir, cli->pre_prefix, !o->quiet, cli->pre_what, o->force,
                         calibrate ? paced : NULL, &pace_pre};
        rc = exp_dist_sweep(&d, &pre, cli->pre_unit, cli->pre_label, cli->pre_key, pre_ctx, &e);
    }
    exp_sweep sw = {nunits, jobs, pdir, cli->prefix, !o->quiet, cli->progress_what, o->force,
                    calibrate ? paced : NULL, &pace_units};
    if (!rc && d.size > 1) {
        rc = exp_dist_sweep(&d, &sw, cli->unit, cli->label, cli->key, ctx, &e);
        sw.force = 0; /* rank 0 reads the parts every rank wrote */
    }
    char summary[4096] = "";
    double t_units = 0;
    if (!rc && d.rank == 0)
        rc = exp_sweep_and_report(&sw, cli->unit, cli->label, cli->key, cli->report, ctx, summary,
                                   sizeof summary, &t_units, &reused, &e);
    t_units = gr_wall_seconds() - t0;
    if (rc)
        fprintf(stderr, "grano %s: %s\n", cli->name, e.msg);
    else if (d.rank == 0) {
        /* Results on standard output, messages on standard error. */
        if (!o->quiet)
            fprintf(stderr, "grano %s: %zu %s (%zu reused) in %.1f s wall with %d job%s%s; wrote %s/\n", cli->name,
                    nunits, cli->units_what, d.size > 1 ? (size_t)0 : reused, t_units, jobs * d.size,
                    jobs * d.size > 1 ? "s" : "", d.size > 1 ? " (MPI ranks)" : "", dir);
        fputs(summary, stdout);
        if (!gr_plot_have_gnuplot())
            fprintf(stderr, "grano %s: the data are written in %s/ (HDF5 and .dat tables); no figures: gnuplot "
                            "is not on PATH (install it with 'apt-get install gnuplot-nox', then rerun: the "
                            "runs are reused)\n", cli->name, dir);
    }
    exp_dist_end(&d);
    return rc;
}
