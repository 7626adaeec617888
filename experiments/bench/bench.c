/* grano bench METHOD [...]: every registered method is benchable. A method
 * with a bench of its own (which may use its backend's internals) runs
 * that; any other runs the generic bench through gr_sim. */
#include <stdio.h>
#include <string.h>

#include "bench_generic.h"
#include "cmd.h"
#include "opts.h"

/* The benches of their own, keyed by the backend's table (no name is
 * written twice: the registry names the methods). */
extern const gr_method_type gr_cd_method, gr_dem_method, gr_dsmc_method, gr_edmd_method, gr_lgca_method;
typedef struct {
    const gr_method_type *method;
    int (*main)(int argc, char **argv);
} bench_entry;
static const bench_entry own[] = {
    {&gr_cd_method, bench_cd},     {&gr_dem_method, bench_dem},   {&gr_dsmc_method, bench_dsmc},
    {&gr_edmd_method, bench_edmd}, {&gr_lgca_method, bench_lgca}, {NULL, NULL},
};

static void usage(FILE *f)
{
    fprintf(f, "usage: grano bench METHOD [options]   (grano bench METHOD --help)\n"
               "       grano bench --generic METHOD [options]\n\n"
               "Throughput and speed-against-error benchmarks. Methods:");
    const gr_method_type *const *all = gr_method_all();
    for (size_t i = 0; all[i]; i++)
        fprintf(f, " %s", all[i]->name);
    fprintf(f, "\n--generic: the same box of grains through the method interface alone, for any method\n"
               "(what a method without a bench of its own runs).\n");
}

int cmd_bench(int argc, char **argv)
{
    if (argc < 2 || !strcmp(argv[1], "--help") || !strcmp(argv[1], "-h")) {
        usage(argc < 2 ? stderr : stdout);
        return argc < 2 ? 2 : 0;
    }
    if (!strcmp(argv[1], "--version")) {
        exp_print_version("bench");
        return 0;
    }
    int generic = !strcmp(argv[1], "--generic");
    if (generic && argc < 3) {
        fprintf(stderr, "grano bench: --generic needs a METHOD\n");
        usage(stderr);
        return 2;
    }
    const gr_method_type *m;
    gr_err err = {0};
    if (gr_method_lookup(argv[1 + generic], "grano bench", &m, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        usage(stderr);
        return 2;
    }
    for (size_t i = 0; own[i].method && !generic; i++)
        if (own[i].method == m)
            return own[i].main(argc - 1, argv + 1);
    return bench_generic(m, argc - 1 - generic, argv + 1 + generic);
}
