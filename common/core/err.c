#include "err.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

int gr_fail(gr_err *e, int code, const char *fmt, ...)
{
    if (!e)
        return code;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(e->msg, sizeof e->msg, fmt, ap);
    va_end(ap);
    e->code = code;
    return code;
}

int gr_err_prefix(gr_err *e, const char *fmt, ...)
{
    if (!e)
        return GR_ERUN;
    char pre[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(pre, sizeof pre, fmt, ap);
    va_end(ap);
    size_t lp = strlen(pre), lm = strlen(e->msg);
    if (lp >= sizeof e->msg)
        lp = sizeof e->msg - 1;
    if (lp + lm >= sizeof e->msg)
        lm = sizeof e->msg - 1 - lp;
    memmove(e->msg + lp, e->msg, lm);
    memcpy(e->msg, pre, lp);
    e->msg[lp + lm] = '\0';
    return e->code;
}

void gr_err_clear(gr_err *e)
{
    if (e) {
        e->code = GR_OK;
        e->msg[0] = '\0';
    }
}
