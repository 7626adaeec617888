/* Directories for results and part files. */
#include "files.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

int exp_mkdirs(const char *dir, gr_err *err)
{
    char buf[1024];
    snprintf(buf, sizeof buf, "%s", dir);
    for (char *s = buf + 1; *s; s++) {
        if (*s != '/')
            continue;
        *s = 0;
        if (mkdir(buf, 0777) && errno != EEXIST)
            return gr_fail(err, GR_EINPUT, "%s: cannot create directory: %s", buf, strerror(errno));
        *s = '/';
    }
    if (mkdir(buf, 0777) && errno != EEXIST)
        return gr_fail(err, GR_EINPUT, "%s: cannot create directory: %s", buf, strerror(errno));
    return GR_OK;
}
