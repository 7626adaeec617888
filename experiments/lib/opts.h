/* Option values shared by the subcommands' parsers, and one getopt_long
 * loop for all of them: --name=VALUE and --name VALUE both work, numbers are
 * read whole and range-checked, --help and --version are always known. */
#ifndef GR_EXP_OPTS_H
#define GR_EXP_OPTS_H

#include <getopt.h>
#include <stddef.h>
#include <stdio.h>

#include "err.h"

/* Parse a comma-separated list of positive numbers (at most cap); 0 or -1. */
int exp_parse_list(const char *s, double *v, size_t cap, size_t *n);

/* The whole of s a number in [lo, hi]; GR_EINPUT naming flag otherwise. */
int exp_opt_double(const char *flag, const char *s, double lo, double hi, double *out, gr_err *err);
/* The same with each bound open or closed, as the message states it:
 * exp_opt_interval("--alpha", s, 0, 1, 1, 0, ...) takes (0, 1]. */
int exp_opt_interval(const char *flag, const char *s, double lo, int lo_open, double hi, int hi_open, double *out,
                     gr_err *err);
int exp_opt_long(const char *flag, const char *s, long lo, long hi, long *out, gr_err *err);

/* exp_getopt's answers besides GR_OK and GR_EINPUT. */
enum { EXP_OPT_HELP = -2, EXP_OPT_VERSION = -3 };
#define EXP_OPT_ID_HELP 'h'
#define EXP_OPT_ID_VERSION 0x7ffe

/* One option: id is the option's val (a printable val is also its short
 * letter), arg its value or NULL. 0 taken, else an error code (err set). */
typedef int (*exp_opt_fn)(void *ctx, int id, const char *arg, gr_err *err);

/* getopt_long over opts (NULL-name ended) plus --help/-h and --version.
 * GR_OK with argv[*first..argc) the positional arguments (options may
 * come after them); EXP_OPT_HELP or EXP_OPT_VERSION when asked (the caller
 * prints and exits 0); GR_EINPUT naming an unknown option, a missing value
 * or a value fn refused. */
int exp_getopt(int argc, char **argv, const struct option *opts, exp_opt_fn fn, void *ctx, int *first,
               gr_err *err);

/* exp_getopt for a subcommand's main: prints usage (--help) or the version
 * and returns 0 (exit 0); prints "grano CMD: ..." and returns 2 on a bad
 * option, or on positional arguments beyond max_pos; else -1 (go on) with
 * argv[*first..argc) the positional ones. */
int exp_getopt_main(const char *cmd, int argc, char **argv, const struct option *opts, exp_opt_fn fn, void *ctx,
                    void (*usage)(FILE *), int max_pos, int *first);

/* Print "grano CMD VERSION" to stdout. */
void exp_print_version(const char *cmd);

#endif
