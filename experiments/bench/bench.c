/* grano bench METHOD [...]: dispatch to the backend's benchmark program. */
#include <stdio.h>
#include <string.h>

#include "cmd.h"
#include "opts.h"

typedef struct {
    const char *method;
    int (*main)(int argc, char **argv);
} bench_entry;

/* One line per backend benchmark. */
static const bench_entry benches[] = {
    {"cd", bench_cd},
    {"dem", bench_dem},
    {"dsmc", bench_dsmc},
    {"edmd", bench_edmd},
    {"lgca", bench_lgca},
    {NULL, NULL},
};

static void usage(FILE *f)
{
    fprintf(f, "usage: grano bench METHOD [options]   (grano bench METHOD --help)\n\n"
               "Throughput and speed-against-error benchmarks. Methods:");
    for (size_t i = 0; benches[i].method; i++)
        fprintf(f, " %s", benches[i].method);
    fprintf(f, "\n");
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
    for (size_t i = 0; benches[i].method; i++)
        if (!strcmp(argv[1], benches[i].method))
            return benches[i].main(argc - 1, argv + 1);
    fprintf(stderr, "grano bench: no benchmark for method '%s'\n", argv[1]);
    usage(stderr);
    return 2;
}
