/* The sweep runner: independent units of work (realisations, orifice sizes)
 * spread over local cores with fork(), one part file per unit, so that an
 * interrupted sweep resumes without redoing finished parts. */
#include "sweep.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "files.h"
#include "parts.h"
#include "progress.h"

/* Shared with the children (mmap'd before fork): their progress and, on
 * failure, their message. */
typedef struct {
    double progress;
    int status;
    char msg[600];
} unit_slot;

static void sleep_ms(long ms)
{
    struct timespec ts = {ms / 1000, (ms % 1000) * 1000000L};
    nanosleep(&ts, NULL);
}

int exp_sweep_run(const exp_sweep *sw, exp_unit_fn fn, exp_label_fn label,
                   exp_label_fn keyf, void *ctx, char **paths, size_t *done_before, gr_err *err)
{
    size_t n = sw->nunits;
    *done_before = 0;
    if (exp_mkdirs(sw->dir, err))
        return err->code;
    unit_slot *slot = mmap(NULL, (n + 1) * sizeof *slot, PROT_READ | PROT_WRITE,
                           MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (slot == MAP_FAILED)
        return gr_fail(err, GR_ERUN, "mmap: %s", strerror(errno));
    pid_t *pid = calloc(n + 1, sizeof *pid);
    char **keys = calloc(n + 1, sizeof *keys);
    unsigned char *todo = calloc(n + 1, 1);
    if (!pid || !keys || !todo) {
        munmap(slot, (n + 1) * sizeof *slot);
        free(pid), free(keys), free(todo);
        return gr_fail(err, GR_ERUN, "out of memory");
    }
    size_t ntodo = 0;
    for (size_t u = 0; u < n; u++) {
        char lab[256];
        label(u, ctx, lab, sizeof lab);
        paths[u] = malloc(strlen(sw->dir) + strlen(sw->prefix) + strlen(lab) + 16);
        keys[u] = malloc(2048);
        if (!paths[u] || !keys[u])
            continue;
        sprintf(paths[u], "%s/%s-%s.part", sw->dir, sw->prefix, lab);
        keyf(u, ctx, keys[u], 2048);
        if (!sw->force && exp_part_key_matches(paths[u], keys[u])) {
            slot[u].progress = 1;
            (*done_before)++;
        } else {
            todo[u] = 1;
            ntodo++;
        }
    }
    gr_progress *pg = sw->progress && ntodo ? gr_progress_create(stderr, 0, (double)ntodo, 1.0) : NULL;
    size_t next = 0, running = 0, finished = 0;
    int rc = GR_OK;
    int jobs = sw->jobs > 0 ? sw->jobs : 1;
    while (finished < ntodo) {
        while (running < (size_t)jobs && next < n) {
            if (!todo[next]) {
                next++;
                continue;
            }
            fflush(NULL);
            pid_t c = fork();
            if (c < 0) {
                rc = gr_fail(err, GR_ERUN, "fork: %s", strerror(errno));
                break;
            }
            if (c == 0) {
                gr_err e = {0};
                int st = paths[next] && keys[next]
                             ? fn(next, paths[next], keys[next], ctx, &slot[next].progress, &e)
                             : gr_fail(&e, GR_ERUN, "out of memory");
                slot[next].status = st;
                snprintf(slot[next].msg, sizeof slot[next].msg, "%.590s", e.msg);
                _exit(st ? 1 : 0);
            }
            pid[next] = c;
            running++;
            next++;
        }
        if (rc && !running)
            break;
        int status;
        pid_t w = waitpid(-1, &status, WNOHANG);
        if (w > 0) {
            for (size_t u = 0; u < n; u++) {
                if (pid[u] != w)
                    continue;
                pid[u] = 0;
                running--;
                finished++;
                if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
                    if (!rc) {
                        char lab[256];
                        label(u, ctx, lab, sizeof lab);
                        rc = gr_fail(err, GR_ERUN, "unit %s failed: %s", lab,
                                     slot[u].msg[0] ? slot[u].msg
                                                    : (WIFSIGNALED(status) ? "killed by a signal" : "no message"));
                    }
                } else if (access(paths[u], F_OK) != 0) {
                    if (!rc) {
                        char lab[256];
                        label(u, ctx, lab, sizeof lab);
                        rc = gr_fail(err, GR_ERUN, "unit %s ended without writing %s", lab, paths[u]);
                    }
                } else
                    slot[u].progress = 1;
            }
            continue;
        }
        if (w < 0 && running)
            running = 0; /* no children left: should not happen */
        double sum = 0;
        for (size_t u = 0; u < n; u++)
            if (todo[u])
                sum += slot[u].progress;
        gr_progress_update(pg, sum, "units done", (double)finished);
        sleep_ms(200);
    }
    gr_progress_finish(pg);
    gr_progress_free(pg);
    for (size_t u = 0; u < n; u++)
        free(keys[u]);
    free(keys), free(pid), free(todo);
    munmap(slot, (n + 1) * sizeof *slot);
    return rc;
}

int exp_sweep_and_report(const exp_sweep *sw, exp_unit_fn fn, exp_label_fn label,
                          exp_label_fn key, exp_report_fn report, void *ctx, char *summary,
                          size_t nsum, double *seconds, size_t *reused, gr_err *err)
{
    char **parts = calloc(sw->nunits, sizeof *parts);
    if (!parts)
        return gr_fail(err, GR_ERUN, "out of memory");
    double t0 = gr_wall_seconds();
    int rc = exp_sweep_run(sw, fn, label, key, ctx, parts, reused, err);
    *seconds = gr_wall_seconds() - t0;
    if (!rc)
        rc = report(ctx, parts, summary, nsum, err);
    for (size_t u = 0; u < sw->nunits; u++)
        free(parts[u]);
    free(parts);
    return rc;
}
