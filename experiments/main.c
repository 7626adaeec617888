/* grano: one program, one file per subcommand. */
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "cmd.h"
#include "h5md.h"
#include "stop.h"

typedef struct {
    const char *name;
    const char *summary;
    int (*main)(int argc, char **argv);
} subcommand;

static const subcommand commands[] = {
    {"run", "run a scene with one method, writing H5MD", cmd_run},
    {"methods", "the methods: features, operations, parameter tables", cmd_methods},
    {"info", "describe what a grano result file holds", cmd_info},
    {"bench", "throughput and speed-against-error benchmarks", cmd_bench},
    {"silo-start", "start of a silo discharge (thesis chapter 3)", cmd_silo_start},
    {"silo-flow", "silo outflow against orifice size (thesis chapter 4)", cmd_silo_flow},
    {"course", "the event-driven course exercises (Maxwell, pressure, cooling)", cmd_course},
    {"plot", "a picture of one frame of a result: grains coloured by a quantity, or a field", cmd_plot},
    {"movie", "a result's frames as a movie (MP4 through ffmpeg, or GIF)", cmd_movie},
    {"export", "a result's trajectory for LAMMPS, OVITO, VMD, ASE (dump, extxyz, csv)", cmd_export},
    {"compare", "the same scenes on every method: speed against error", cmd_compare},
    {"advise", "the cheapest method for a scene at an accepted error, from compare's results", cmd_advise},
};
#define NCOMMANDS (sizeof commands / sizeof commands[0])

static void usage(FILE *f)
{
    fprintf(f, "usage: grano COMMAND [options]   (grano COMMAND --help for each)\n\n"
               "Numerical methods for dry granular media in two dimensions.\n\n"
               "commands:\n");
    for (size_t i = 0; i < NCOMMANDS; i++)
        fprintf(f, "  %-12s %s\n", commands[i].name, commands[i].summary);
}

/* Results on standard output must reach it: a full disk is a failure
 * (exit 1), not a silent truncation; a closed pipe ends the program by
 * SIGPIPE, as it does any filter. */
static int stdout_checked(int rc)
{
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "grano: error writing standard output: %s\n", strerror(errno));
        return rc ? rc : 1;
    }
    return rc;
}

int main(int argc, char **argv)
{
    /* GSL's default handler aborts; grano checks every status instead. */
    gsl_set_error_handler_off();
    gr_h5_no_exit_handler();
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
        usage(stdout);
        return stdout_checked(0);
    }
    if (!strcmp(argv[1], "--version")) {
        printf("grano %s\n", GRANO_VERSION);
        return stdout_checked(0);
    }
    for (size_t i = 0; i < NCOMMANDS; i++)
        if (!strcmp(argv[1], commands[i].name)) {
            int rc = stdout_checked(commands[i].main(argc - 1, argv + 1));
            /* a command that caught a stop signal has said what it kept;
             * the program then ends as the signal would have ended it */
            if (exp_stop_signal())
                exp_stop_exit(exp_stop_signal());
            return rc;
        }
    fprintf(stderr, "grano: unknown command '%s'\n", argv[1]);
    usage(stderr);
    return 2;
}
