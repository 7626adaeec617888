/* The command line that `grano silo-start` and `grano silo-flow` share:
 * the common options (--orifices, --realisations, --seed, --jobs, --out,
 * --grains, --width, --hopper-outlet, --method, --material, --param, --quick, --force, --quiet, --help), the
 * base silo and orifice list they describe, and the run of the sweep with
 * its closing line. Each command describes itself in a silo_cli and keeps
 * only its own options and its own parameters of the units. */
#ifndef GR_SILO_CLI_H
#define GR_SILO_CLI_H

#include <getopt.h>
#include <stddef.h>
#include <stdio.h>

#include "silo_common.h"
#include "sweep.h"

/* The values of the common options; a number not given is -1. */
typedef struct {
    const char *orif, *out, *method;
    long nreal, jobs, seed, grains;
    double width, outlet;
    int quick, force, quiet;
    char params[SILO_PARAMS]; /* --param lines, "key = value\n" */
    char material[SILO_PARAMS]; /* --material lines */
} silo_opts;

/* One of the command's own options: 0 taken, 2 a bad value (said). */
typedef int (*silo_own_fn)(int ch, const char *arg, void *own);

typedef struct {
    const char *name;                /* "silo-flow": messages, default DIR */
    void (*usage)(FILE *f);
    const struct option *own;        /* its own long options, {NULL} ended */
    const char *own_short;           /* their short letters for getopt ("b:") */
    silo_own_fn own_parse;
    const char *orifices;            /* the default --orifices */
    const char *quick_orifices;      /* ... under --quick */
    long quick_n;                    /* the quick silo's grains; 0: silo_cfg_quick's */
    double quick_width;              /* its width (height 2 W); 0: silo_cfg_quick's */
    int reinsert;                    /* the units reinsert the grains that leave */
    const char *prefix;              /* part files: DIR/parts/<prefix>-<label>.part */
    const char *progress_what;       /* the progress line's label */
    const char *units_what;          /* the closing line's word for the units */
    exp_unit_fn unit;
    exp_label_fn label, key;
    exp_report_fn report;
    /* units run first (NULL: none), whose parts <pre_prefix>-<label>.part
       the units read: the fillings, one per realisation */
    exp_unit_fn pre_unit;
    exp_label_fn pre_label, pre_key;
    const char *pre_prefix, *pre_what;
    /* CPU seconds of a first unit and of a unit, printed as the estimated
       time before a full (not --quick) run; NULL: none */
    void (*estimate)(const void *ctx, double *pre, double *unit);
} silo_cli;

/* The label of unit `unit` of a sweep over orifices x nreal realisations
 * (realisation fastest): "D<D>-r<r>", the name of its part file. */
void silo_unit_label(const double *orifice, int nreal, size_t unit, char *buf, size_t n);

/* "grano <cmd>: <opt>: '<val>' is not <what>" on stderr; returns 2. */
int silo_bad(const silo_cli *cli, const char *opt, const char *val, const char *what);
/* A decimal integer >= lo into *out; 0, or -1 leaving *out. */
int silo_parse_long(const char *s, long lo, long *out);

/* Parse argv into *o, the command's own options through cli->own_parse.
 * Returns -1 to go on, else the exit code (0 after --help, 2 bad input). */
int silo_cli_parse(const silo_cli *cli, int argc, char **argv, silo_opts *o, void *own);

/* The base silo of the options (quick or thesis size, --grains, --width,
 * --method checked on the silo the units will open) and the orifices
 * (at most cap); 0, or 2 after saying why. */
int silo_cli_silo(const silo_cli *cli, const silo_opts *o, silo_cfg *base, double *orifice, size_t cap,
                  size_t *norif);

/* The output directory: --out, else results/<name>[-quick]; returns dir. */
const char *silo_cli_dir(const silo_cli *cli, const silo_opts *o, char *dir, size_t n);

/* Run (or reuse) the npre first units (cli->pre_unit, context pre_ctx),
 * then the nunits units of ctx into dir/parts, then the report; the
 * closing line unless --quiet. Returns the exit code. */
int silo_cli_sweep(const silo_cli *cli, const silo_opts *o, void *ctx, void *pre_ctx, size_t npre, size_t nunits,
                   const char *dir);

#endif
