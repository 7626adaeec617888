/* grano methods: every registered backend with its representation, the
 * scene features it supports, its optional operations and its parameter
 * table, all read from the registry. */
#include <stdio.h>
#include <string.h>

#include "cmd.h"
#include "method.h"
#include "opts.h"

static void usage(FILE *f)
{
    fprintf(f, "usage: grano methods [NAME] [--help] [--version]\n\n"
               "Each registered method (or only NAME): what it represents, the scene features\n"
               "it supports (a scene asking for another is refused), its optional operations,\n"
               "and the keys of its scene section with type, default, range, unit and meaning.\n");
}

static void print_method(const gr_method_type *m)
{
    printf("%s: %s\n", m->name, m->summary);
    printf("  represents: %s\n", m->repr == GR_REPR_PARTICLES ? "particles (snapshots)" : "a lattice (node occupations)");
    printf("  features:");
    int first = 1;
    for (unsigned b = 0; b < GR_FEAT_COUNT; b++) {
        if (m->features & (1u << b)) {
            printf("%s %s", first ? "" : ";", gr_feature_name(1u << b));
            first = 0;
        }
    }
    printf("\n  not supported:");
    first = 1;
    for (unsigned b = 0; b < GR_FEAT_COUNT; b++) {
        if (!(m->features & (1u << b)) && gr_feature_known(1u << b)) {
            printf("%s %s", first ? "" : ";", gr_feature_name(1u << b));
            first = 0;
        }
    }
    printf("%s\n  operations of its own:", first ? " none" : "");
    unsigned ops = gr_method_ops(m);
    for (unsigned b = 0; b < GR_OP_COUNT; b++)
        if (ops & (1u << b))
            printf(" %s;", gr_op_name(1u << b));
    printf("\n  observables (observables/NAME in a result; a validity limit names the key that changes it):\n");
    const gr_obs_def *d = gr_method_observables(m);
    for (size_t k = 0; d[k].name; k++)
        printf("    %-18s %-12s %-8s %s%s%s%s\n", d[k].name, d[k].unit,
               d[k].ncomp == 2 ? "vector" : d[k].integer ? "count" : "scalar", d[k].doc,
               d[k].key ? " [validity limit: " : "", d[k].key ? d[k].key : "", d[k].key ? "]" : "");
    printf("  [%s] parameters:\n", m->name);
    printf("    %-14s %-6s %-10s %-22s %-6s %s\n", "key", "type", "default", "range", "unit", "meaning");
    gr_params_print(stdout, m->params);
}

static int no_option(void *ctx, int id, const char *arg, gr_err *err)
{
    (void)ctx, (void)id, (void)arg;
    return gr_fail(err, GR_EINPUT, "unknown option");
}

int cmd_methods(int argc, char **argv)
{
    static const struct option none[] = {{NULL, 0, NULL, 0}};
    int first = 0;
    int prc = exp_getopt_main("methods", argc, argv, none, no_option, NULL, usage, 1, &first);
    if (prc >= 0)
        return prc;
    if (argc - first > 1) {
        usage(stderr);
        return 2;
    }
    if (argc - first == 1) {
        const gr_method_type *m;
        gr_err err = {0};
        if (gr_method_lookup(argv[first], "grano methods", &m, &err)) {
            fprintf(stderr, "grano: %s\n", err.msg);
            return 2;
        }
        print_method(m);
        return 0;
    }
    const gr_method_type *const *all = gr_method_all();
    for (size_t i = 0; all[i]; i++) {
        if (i)
            printf("\n");
        print_method(all[i]);
    }
    return 0;
}
