/* Option values shared by the subcommands' parsers. */
#include "opts.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int exp_parse_list(const char *s, double *v, size_t cap, size_t *n)
{
    *n = 0;
    while (*s) {
        char *end;
        double x = strtod(s, &end);
        if (end == s || !(x > 0) || !isfinite(x) || *n >= cap)
            return -1;
        v[(*n)++] = x;
        s = end;
        if (*s == ',')
            s++;
        else if (*s)
            return -1;
    }
    return *n ? 0 : -1;
}


int exp_opt_double(const char *flag, const char *s, double lo, double hi, double *out, gr_err *err)
{
    return exp_opt_interval(flag, s, lo, 0, hi, 0, out, err);
}

int exp_opt_interval(const char *flag, const char *s, double lo, int lo_open, double hi, int hi_open, double *out,
                     gr_err *err)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end || errno || !isfinite(v) || v < lo || v > hi || (lo_open && v == lo) ||
        (hi_open && v == hi))
        return gr_fail(err, GR_EINPUT, "%s: '%s' is not a number in %c%g, %g%c", flag, s, lo_open ? '(' : '[', lo,
                       hi, hi_open ? ')' : ']');
    *out = v;
    return GR_OK;
}

int exp_opt_long(const char *flag, const char *s, long lo, long hi, long *out, gr_err *err)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (end == s || *end || errno || v < lo || v > hi)
        return gr_fail(err, GR_EINPUT, "%s: '%s' is not an integer in [%ld, %ld]", flag, s, lo, hi);
    *out = v;
    return GR_OK;
}

#define EXP_MAX_OPTS 64

int exp_getopt(int argc, char **argv, const struct option *opts, exp_opt_fn fn, void *ctx, int *first,
               gr_err *err)
{
    struct option all[EXP_MAX_OPTS + 3];
    char shorts[3 * EXP_MAX_OPTS + 8] = ":h";
    size_t k = 0, ns = strlen(shorts);
    for (const struct option *p = opts; p && p->name && k < EXP_MAX_OPTS; p++) {
        all[k++] = *p;
        if (p->val > ' ' && p->val < 127 && p->val != 'h') {
            shorts[ns++] = (char)p->val;
            if (p->has_arg == required_argument)
                shorts[ns++] = ':';
        }
    }
    shorts[ns] = '\0';
    all[k++] = (struct option){"help", no_argument, NULL, EXP_OPT_ID_HELP};
    all[k++] = (struct option){"version", no_argument, NULL, EXP_OPT_ID_VERSION};
    all[k] = (struct option){NULL, 0, NULL, 0};
    opterr = 0;
    optind = 1;
    int ch;
    while ((ch = getopt_long(argc, argv, shorts, all, NULL)) != -1) {
        if (ch == EXP_OPT_ID_HELP)
            return EXP_OPT_HELP;
        if (ch == EXP_OPT_ID_VERSION)
            return EXP_OPT_VERSION;
        if (ch == ':')
            return gr_fail(err, GR_EINPUT, "option '%s' needs a value", argv[optind - 1]);
        if (ch == '?')
            return gr_fail(err, GR_EINPUT, "unknown option '%s'", argv[optind - 1]);
        int rc = fn(ctx, ch, optarg, err);
        if (rc)
            return rc;
    }
    *first = optind;
    return GR_OK;
}

void exp_print_version(const char *cmd)
{
    printf("grano %s %s\n", cmd, GRANO_VERSION);
}

int exp_getopt_main(const char *cmd, int argc, char **argv, const struct option *opts, exp_opt_fn fn, void *ctx,
                    void (*usage)(FILE *), int max_pos, int *first)
{
    gr_err err = {0};
    int rc = exp_getopt(argc, argv, opts, fn, ctx, first, &err);
    if (rc == EXP_OPT_HELP || rc == EXP_OPT_VERSION) {
        if (rc == EXP_OPT_HELP)
            usage(stdout);
        else
            exp_print_version(cmd);
        return 0;
    }
    if (!rc && argc - *first > max_pos)
        rc = gr_fail(&err, GR_EINPUT, "unexpected argument '%s'", argv[*first + max_pos]);
    if (rc) {
        fprintf(stderr, "grano %s: %s (see grano %s --help)\n", cmd, err.msg, cmd);
        return 2;
    }
    return -1;
}
