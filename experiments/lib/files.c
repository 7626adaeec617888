/* Directories for results and part files. */
#include "files.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

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

int exp_check_writable(const char *path, const char *flag, int force, gr_err *err)
{
    struct stat st;
    if (!path[0])
        return gr_fail(err, GR_EINPUT, "%s: an empty file name", flag);
    if (stat(path, &st) == 0) {
        if (!S_ISREG(st.st_mode))
            return gr_fail(err, GR_EINPUT, "%s: '%s' is %s, not a regular file; it is never replaced", flag,
                           path, S_ISDIR(st.st_mode) ? "a directory" : "a device or special file");
        if (!force)
            return gr_fail(err, GR_EINPUT, "%s: '%s' already exists; use --force to replace it", flag, path);
        if (access(path, W_OK))
            return gr_fail(err, GR_EINPUT, "%s: '%s' is not writable: %s", flag, path, strerror(errno));
        return GR_OK;
    }
    char dir[1024];
    const char *slash = strrchr(path, '/');
    if (slash)
        snprintf(dir, sizeof dir, "%.*s", (int)(slash - path) + (slash == path), path);
    else
        snprintf(dir, sizeof dir, ".");
    if (access(dir, W_OK | X_OK))
        return gr_fail(err, GR_EINPUT, "%s: cannot create '%s': %s", flag, path, strerror(errno));
    return GR_OK;
}

int exp_remove_stale(const char *path)
{
    struct stat st;
    if (lstat(path, &st) || !S_ISREG(st.st_mode))
        return 0;
    return unlink(path) == 0;
}
