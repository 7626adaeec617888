/* grano advise SCENE [--tolerance X] [--from FILE]: which method, at which
 * setting, reaches the error a user accepts most cheaply, and the compare
 * row that says so (cmp_advise.c). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmd.h"
#include "cmp_advise.h"
#include "opts.h"

#define CMP_DEFAULT_FROM "compare-out/compare.h5"

static void usage(FILE *f)
{
    fprintf(f, "usage: grano advise SCENE [--tolerance X] [--from FILE]\n\n"
               "The cheapest method for SCENE at relative error X: SCENE is matched to the nearest case\n"
               "of grano compare; among the methods that model it, the compare row of that case that\n"
               "reaches X (error plus two error bars) at the least wall time per run is named, with\n"
               "its setting (docs/comparison.md). grano run SCENE --method auto runs it.\n\n"
               "options:\n"
               "  -t, --tolerance X    accepted relative error, as 0.05 or 5%% (default: the nearest\n"
               "                       case's own tolerance, compare.txt states it)\n"
               "  -F, --from FILE      a comparison's results (default " CMP_DEFAULT_FROM ", what\n"
               "                       grano compare writes by default)\n"
               "  -h, --help           this help;  --version: the version\n"
               "Exit code 0 with the advice on stdout; 2 when no method qualifies (the reason on\n"
               "stderr), for a bad scene or flag, or when FILE cannot be read.\n");
}

int cmp_parse_tolerance(const char *flag, const char *s, double *tol, gr_err *err)
{
    char buf[64];
    size_t n = strlen(s);
    int pct = n && s[n - 1] == '%';
    snprintf(buf, sizeof buf, "%.*s", (int)(n - (size_t)pct), s);
    if (exp_opt_interval(flag, buf, 0, 1, pct ? 1000 : 10, 0, tol, err))
        return err->code;
    if (pct)
        *tol /= 100;
    return GR_OK;
}

typedef struct {
    double tol;
    const char *from;
} advise_args;

static int one_option(void *ctx, int id, const char *arg, gr_err *err)
{
    advise_args *a = ctx;
    switch (id) {
    case 't': return cmp_parse_tolerance("--tolerance", arg, &a->tol, err);
    case 'F': a->from = arg; return 0;
    default: return gr_fail(err, GR_EINPUT, "unknown option");
    }
}

int cmd_advise(int argc, char **argv)
{
    static const struct option opts[] = {{"tolerance", required_argument, NULL, 't'},
                                         {"from", required_argument, NULL, 'F'},
                                         {NULL, 0, NULL, 0}};
    advise_args a = {0, CMP_DEFAULT_FROM};
    int first = 0;
    int rc = exp_getopt_main("advise", argc, argv, opts, one_option, &a, usage, 1, &first);
    if (rc >= 0)
        return rc;
    if (first >= argc) {
        fprintf(stderr, "grano advise: give a scene file (grano advise --help)\n");
        return 2;
    }
    const char *names[GR_MAX_METHODS + 1];
    gr_method_names(names, GR_MAX_METHODS + 1);
    gr_err err = {0};
    gr_scene *sc = gr_scene_load(argv[first], names, &err);
    cmp_advice adv;
    if (!sc || cmp_advise(sc, a.from, a.tol, &adv, &err)) {
        fprintf(stderr, "grano advise: %s\n", err.msg);
        gr_scene_free(sc);
        return 2;
    }
    printf("%s", adv.method);
    if (adv.setting)
        printf(" with %s = %s", adv.knob, adv.value);
    printf("\n  %s\n", adv.why);
    gr_scene_free(sc);
    return 0;
}
