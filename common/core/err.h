/* Status codes and error messages: library functions fill a gr_err and
 * return its code; only main() prints and exits. */
#ifndef GR_ERR_H
#define GR_ERR_H

#include <stddef.h>

enum {
    GR_OK = 0,
    GR_ERUN = 1,   /* a run failed (instability, I/O) */
    GR_EINPUT = 2  /* bad input: scene file, flag, output path */
};

typedef struct {
    int code;
    char msg[1024];
} gr_err;

/* Set the message (printf style) and return code; code 0 is not allowed. */
int gr_fail(gr_err *e, int code, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* Prefix the existing message with more context ("while X: "). */
int gr_err_prefix(gr_err *e, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

void gr_err_clear(gr_err *e);

#endif
