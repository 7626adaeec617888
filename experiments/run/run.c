/* grano run SCENE: one scene, one method, H5MD out, checkpoints, restart. */
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cmd.h"
#include "fields.h"
#include "files.h"
#include "h5md.h"
#include "init.h"
#include "method.h"
#include "opts.h"
#include "plot.h"
#include "progress.h"
#include "runio.h"
#include "compare/cmp_advise.h"

static void usage(FILE *f)
{
    fprintf(f,
        "usage: grano run SCENE [options]\n\n"
        "Run SCENE (an INI scene file, see docs/scene-format.md) with one method and\n"
        "write its trajectory, observables and fields as H5MD (docs/output-format.md).\n\n"
        "options:\n"
        "  -m, --method M       backend: ");
    const gr_method_type *const *all = gr_method_all();
    for (size_t i = 0; all[i]; i++)
        fprintf(f, "%s%s", i ? ", " : "", all[i]->name);
    fprintf(f, " (default dem); auto: the cheapest\n"
        "                       that reaches --tolerance on the nearest case of a comparison\n"
        "                       (grano advise; its setting applied unless --set gives it)\n"
        "      --tolerance X    for --method auto: accepted relative error (default: the\n"
        "                       nearest case's own tolerance)\n"
        "      --from FILE      for --method auto: the comparison's compare.h5 (default\n"
        "                       compare-out/compare.h5)\n"
        "  -u, --until T        simulated time to run to (default: [run] until)\n"
        "  -s, --seed S         seed of every random stream (default: [scene] seed)\n"
        "  -o, --out FILE       result file (default results/<scene>-<method>.h5)\n"
        "  -f, --force          replace an existing result file and its checkpoint\n"
        "  -r, --restart CKPT   continue from a checkpoint written by a run of SCENE;\n"
        "                       an existing --out is continued (frames after CKPT dropped);\n"
        "                       SCENE's [run] and [measure] may differ from the checkpoint's\n"
        "      --branch         with --restart: a new --out from the checkpoint's state, where\n"
        "                       physical parameters (and --seed) may differ too\n"
        "      --snapshot PNG   a picture of the final state, grains coloured by speed (a lattice\n"
        "                       method: its density field, cells of about one diameter), on the\n"
        "                       scale of the 2nd to 98th percentile; grano plot draws any frame\n"
        "      --set S.K=V      set key K of section S as a scene line would (repeatable)\n"
        "  -q, --quiet          no progress line (terminal) or thermo lines (otherwise)\n"
        "  -h, --help           this help\n"
        "      --version        grano's version\n\n"
        "A checkpoint <out>.ckpt is written every [run] checkpoint_every and at the end;\n"
        "a run that goes unstable stops with a diagnostic, exit code 1, and its\n"
        "checkpoint holds the last good state. Bad input exits with code 2.\n");
}

typedef struct {
    const char *scene, *method, *out, *restart, *snapshot, *from;
    double tol;
    char auto_method[32], auto_set[200]; /* --method auto's choice and its setting */
    const char *sets[64];
    size_t nsets;
    double until;
    long long seed;
    int force, quiet, branch;
} run_args;

static int parse_args(int argc, char **argv, run_args *a)
{
    static const struct option opts[] = {
        {"method", required_argument, NULL, 'm'}, {"until", required_argument, NULL, 'u'},
        {"seed", required_argument, NULL, 's'},   {"out", required_argument, NULL, 'o'},
        {"force", no_argument, NULL, 'f'},        {"restart", required_argument, NULL, 'r'},
        {"snapshot", required_argument, NULL, 'P'}, {"quiet", no_argument, NULL, 'q'},
        {"help", no_argument, NULL, 'h'},         {"set", required_argument, NULL, 'S'},
        {"version", no_argument, NULL, 'V'},    {"branch", no_argument, NULL, 'B'},
        {"tolerance", required_argument, NULL, 'T'}, {"from", required_argument, NULL, 'F'},
        {NULL, 0, NULL, 0}};
    *a = (run_args){.method = "dem", .until = NAN, .seed = -1, .tol = 0, .from = "compare-out/compare.h5"};
    int c;
    opterr = 0;
    optind = 1;
    while ((c = getopt_long(argc, argv, ":m:u:s:o:fr:qh", opts, NULL)) != -1) {
        char *end;
        switch (c) {
        case 'm': a->method = optarg; break;
        case 'u':
            a->until = strtod(optarg, &end);
            if (*end || !(a->until > 0) || !isfinite(a->until)) {
                fprintf(stderr, "grano run: --until: '%s' is not a positive finite time\n", optarg);
                return 2;
            }
            break;
        case 's':
            errno = 0;
            a->seed = strtoll(optarg, &end, 10);
            if (end == optarg || *end || a->seed < 0 || errno) {
                fprintf(stderr, "grano run: --seed: '%s' is not a non-negative integer\n", optarg);
                return 2;
            }
            break;
        case 'o': a->out = optarg; break;
        case 'T': {
            gr_err te = {0};
            if (cmp_parse_tolerance("--tolerance", optarg, &a->tol, &te)) {
                fprintf(stderr, "grano run: %s\n", te.msg);
                return 2;
            }
            break;
        }
        case 'F': a->from = optarg; break;
        case 'f': a->force = 1; break;
        case 'r': a->restart = optarg; break;
        case 'P': a->snapshot = optarg; break;
        case 'q': a->quiet = 1; break;
        case 'S':
            if (a->nsets == sizeof a->sets / sizeof a->sets[0]) {
                fprintf(stderr, "grano run: --set: at most %zu settings\n", a->nsets);
                return 2;
            }
            a->sets[a->nsets++] = optarg;
            break;
        case 'h': usage(stdout); exit(0);
        case 'V': exp_print_version("run"); exit(0);
        case 'B': a->branch = 1; break;
        case ':':
            fprintf(stderr, "grano run: option '%s' needs a value\n", argv[optind - 1]);
            return 2;
        default:
            fprintf(stderr, "grano run: unknown option '%s' (see grano run --help)\n", argv[optind - 1]);
            return 2;
        }
    }
    if (optind != argc - 1) {
        fprintf(stderr, optind >= argc ? "grano run: missing SCENE\n" : "grano run: one SCENE expected\n");
        usage(stderr);
        return 2;
    }
    a->scene = argv[optind];
    return 0;
}

/* The result, its checkpoint and the snapshot: never a directory or a
 * device; an existing one only with --force (a restart continues its own);
 * partial files of a killed run are removed and said so. */
static int check_outputs(const run_args *a, const char *out, const char *ckpt, gr_err *e)
{
    const char *tails[2] = {".tmp", ".part"};
    const char *bases[2] = {ckpt, out};
    for (int k = 0; k < 2; k++) {
        char stale[1400];
        snprintf(stale, sizeof stale, "%s%s", bases[k], tails[k]);
        if (exp_remove_stale(stale) && !a->quiet)
            fprintf(stderr, "grano run: removed %s, a partial file left by an interrupted run\n", stale);
    }
    int cont = a->restart != NULL && !a->branch;
    if (exp_check_writable(out, "--out", a->force || cont, e) ||
        exp_check_writable(ckpt, "--out (its checkpoint)", a->force || cont, e) ||
        (a->snapshot && exp_check_writable(a->snapshot, "--snapshot", 1, e)))
        return e->code;
    return GR_OK;
}

/* An interval longer than the run is legal (--until may shorten a scene)
 * but not silent: it samples only the start or the end. */
static void warn_intervals(const gr_scene *sc, int quiet)
{
    const char *keys[3] = {"observe_every", "output_every", "checkpoint_every"};
    const double every[3] = {sc->run.observe_every, sc->run.output_every, sc->run.checkpoint_every};
    for (int j = 0; j < 3 && !quiet; j++) {
        if (every[j] > sc->run.until && gr_scene_find(sc, "run", keys[j])) {
            char where[1200];
            gr_scene_where(sc, "run", keys[j], where, sizeof where);
            fprintf(stderr, "grano run: warning: %s: %g is longer than the run (until = %g)\n", where, every[j],
                    sc->run.until);
        }
    }
}

static void warn_line(void *ctx, const char *msg)
{
    (void)ctx;
    fprintf(stderr, "grano run: warning: %s\n", msg);
}

static void note_line(void *ctx, const char *msg)
{
    (void)ctx;
    fprintf(stderr, "grano run: derived: %s\n", msg);
}

/* --method auto: the advice of grano advise for the scene, told on
 * stderr; its setting joins the --set list unless one sets that key. */
static int choose_method(run_args *a)
{
    cmp_advice adv;
    char *set = a->auto_set;
    const char *names[GR_MAX_METHODS + 1];
    gr_method_names(names, GR_MAX_METHODS + 1);
    gr_err e = {0};
    gr_scene *sc = gr_scene_load_set(a->scene, names, a->sets, a->nsets, &e);
    if (!sc || cmp_advise(sc, a->from, a->tol, &adv, &e)) {
        fprintf(stderr, "grano run: --method auto: %s\n", e.msg);
        gr_scene_free(sc);
        return 2;
    }
    gr_scene_free(sc);
    snprintf(a->auto_method, sizeof a->auto_method, "%s", adv.method);
    a->method = a->auto_method;
    int own_key = adv.setting;
    for (size_t i = 0; own_key && i < a->nsets; i++)
        own_key = strncmp(a->sets[i], adv.knob, strlen(adv.knob)) || a->sets[i][strlen(adv.knob)] != '=';
    if (own_key && a->nsets < sizeof a->sets / sizeof a->sets[0]) {
        snprintf(set, sizeof a->auto_set, "%s=%s", adv.knob, adv.value);
        a->sets[a->nsets++] = set;
    }
    fprintf(stderr, "grano run: --method auto: %s%s%s: %s\n", adv.method, own_key ? " with " : "", own_key ? set : "",
            adv.why);
    return 0;
}

static int fail_msg(const gr_err *e)
{
    fprintf(stderr, "grano run: %s\n", e->msg);
    return e->code ? e->code : 1;
}

int cmd_run(int argc, char **argv)
{
    run_args a;
    int rc = parse_args(argc, argv, &a);
    if (rc)
        return rc;
    gr_err e = {0};
    const gr_method_type *m;
    if (!strcmp(a.method, "auto") && (rc = choose_method(&a)))
        return rc;
    if (gr_method_lookup(a.method, "grano run: --method", &m, &e)) {
        fprintf(stderr, "%s\n", e.msg);
        return 2;
    }
    const char *names[GR_MAX_METHODS + 1];
    gr_method_names(names, GR_MAX_METHODS + 1);
    gr_scene *sc = gr_scene_load_set(a.scene, names, a.sets, a.nsets, &e);
    if (!sc)
        return fail_msg(&e);
    if (a.seed >= 0)
        sc->seed = (uint64_t)a.seed;
    if (!isnan(a.until))
        sc->run.until = a.until;

    warn_intervals(sc, a.quiet);
    char out[1200], ckpt[1300];
    if (a.out)
        snprintf(out, sizeof out, "%s", a.out);
    else {
        mkdir("results", 0777);
        snprintf(out, sizeof out, "results/%s-%s.h5", sc->name, m->name);
    }
    gr_run_ckpt_path(out, ckpt, sizeof ckpt);
    /* Refuse before any work, so bad input writes nothing. A restart
     * continues its output and checkpoint in place. */
    if ((rc = check_outputs(&a, out, ckpt, &e))) {
        gr_scene_free(sc);
        return fail_msg(&e);
    }
    if (a.branch && !a.restart) {
        gr_scene_free(sc);
        fprintf(stderr, "grano run: --branch needs --restart CKPT\n");
        return 2;
    }
    char notes[2048] = "";
    gr_run_opts ro = {.out = out, .ckpt = ckpt, .restart = a.restart, .force = a.force,
                      .progress = !a.quiet, .snapshot = a.snapshot, .branch = a.branch,
                      .notes = notes, .notes_cap = sizeof notes, .warn = warn_line,
                      .note = a.quiet ? NULL : note_line};
    rc = gr_run_scene(sc, m, &ro, &e);
    gr_scene_name_sets(sc, a.sets, a.nsets, &e);
    if (notes[0] && !a.quiet)
        fprintf(stderr, "grano run: %s from %s with these differences (%s): %s\n",
                a.branch ? "branched" : "restarted", a.restart,
                a.branch ? "--branch allows any" : "[run] and [measure] may differ", notes);
    if (rc)
        fail_msg(&e);
    else if (!a.quiet)
        fprintf(stderr, "grano run: wrote %s (checkpoint %s)%s%s\n", out, ckpt,
                a.snapshot ? ", snapshot " : "", a.snapshot ? a.snapshot : "");
    gr_scene_free(sc);
    return rc;
}
