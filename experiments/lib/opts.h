/* Option values shared by the subcommands' parsers. */
#ifndef GR_EXP_OPTS_H
#define GR_EXP_OPTS_H

#include <stddef.h>

/* Parse a comma-separated list of positive numbers (at most cap); 0 or -1. */
int exp_parse_list(const char *s, double *v, size_t cap, size_t *n);

#endif
