/* Option values shared by the subcommands' parsers. */
#include "opts.h"

#include <math.h>
#include <stdlib.h>

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

