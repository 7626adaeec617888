/* The sweep runner: independent units of work (realisations, orifice sizes)
 * spread over local cores with fork(), one part file per unit, so that an
 * interrupted sweep resumes without redoing finished parts. */
#include "sweep.h"

#include <errno.h>
#include <signal.h>
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
#include "stop.h"

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

/* Each unit's part path and key (sealed with this build's hash); a part
 * whose key matches is reused
 * (unless --force) and counted in *done_before, the others are marked in
 * todo. Returns how many are to run. A unit whose path or key could not
 * be allocated is to run, and fails there with "out of memory". */
static size_t plan_units(const exp_sweep *sw, exp_label_fn label, exp_label_fn keyf, void *ctx, char **paths,
                         char **keys, unit_slot *slot, unsigned char *todo, size_t *done_before)
{
    size_t ntodo = 0;
    uint64_t bin = exp_binary_hash();
    for (size_t u = 0; u < sw->nunits; u++) {
        char lab[256];
        label(u, ctx, lab, sizeof lab);
        paths[u] = malloc(strlen(sw->dir) + strlen(sw->prefix) + strlen(lab) + 16);
        keys[u] = malloc(2048);
        if (!paths[u] || !keys[u])
            continue;
        sprintf(paths[u], "%s/%s-%s.part", sw->dir, sw->prefix, lab);
        keyf(u, ctx, keys[u], 2048);
        exp_key_seal(keys[u], 2048, bin);
        if (!sw->force && exp_part_key_is(paths[u], keys[u])) {
            slot[u].progress = 1;
            (*done_before)++;
        } else {
            todo[u] = 1;
            ntodo++;
        }
    }
    return ntodo;
}

/* Fork unit u: the child runs it, leaves its status and message in the
 * shared slot (the parent reads them, the child's memory being gone) and
 * exits. Returns the child's pid, or -1 with errno. */
static pid_t start_unit(exp_unit_fn fn, size_t u, char **paths, char **keys, void *ctx, unit_slot *slot)
{
    fflush(NULL);
    pid_t me = getpid(), c = fork();
    if (c != 0)
        return c;
    exp_stop_worker(me);
    gr_err e = {0};
    int st = paths[u] && keys[u] ? fn(u, paths[u], keys[u], ctx, &slot[u].progress, &e)
                                 : gr_fail(&e, GR_ERUN, "out of memory");
    slot[u].status = st;
    snprintf(slot[u].msg, sizeof slot[u].msg, "%.590s", e.msg);
    _exit(st ? 1 : 0);
}

/* Unit u has ended with wait status `status`: a failure, or a success
 * without its part, becomes the error rc if none came first (the first
 * failure is the one reported); returns rc. */
static int reap_unit(size_t u, int status, exp_label_fn label, void *ctx, char **paths, unit_slot *slot, int rc,
                     gr_err *err)
{
    char lab[256];
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        if (!rc) {
            label(u, ctx, lab, sizeof lab);
            rc = gr_fail(err, GR_ERUN, "unit %s failed: %s", lab,
                         slot[u].msg[0] ? slot[u].msg : (WIFSIGNALED(status) ? "killed by a signal" : "no message"));
        }
    } else if (access(paths[u], F_OK) != 0) {
        if (!rc) {
            label(u, ctx, lab, sizeof lab);
            rc = gr_fail(err, GR_ERUN, "unit %s ended without writing %s", lab, paths[u]);
        }
    } else
        slot[u].progress = 1;
    return rc;
}

/* The summed progress of the units that run (each from 0 to 1). */
static double todo_progress(const unit_slot *slot, const unsigned char *todo, size_t n)
{
    double sum = 0;
    for (size_t u = 0; u < n; u++)
        if (todo[u])
            sum += slot[u].progress;
    return sum;
}

/* The run's own memory; the paths belong to the caller. */
static void free_run(unit_slot *slot, pid_t *pid, char **keys, unsigned char *todo, size_t n)
{
    for (size_t u = 0; u < n; u++)
        free(keys[u]);
    free(keys), free(pid), free(todo);
    munmap(slot, (n + 1) * sizeof *slot);
}

/* A stop signal: the running workers are ended (a part is written whole
 * or not at all, so theirs are simply missing) and waited for; the
 * finished parts stay for the same command to resume from. */
static int stop_workers(const exp_sweep *sw, pid_t *pid, size_t n, size_t finished, size_t ntodo, gr_err *err)
{
    size_t stopped = 0;
    for (size_t u = 0; u < n; u++)
        if (pid[u] > 0)
            kill(pid[u], SIGTERM), stopped++;
    for (size_t u = 0; u < n; u++)
        if (pid[u] > 0) {
            int status;
            waitpid(pid[u], &status, 0);
            pid[u] = 0;
        }
    return gr_fail(err, GR_ERUN,
                   "stopped by %s: %zu of the %zu units to run finished (their parts kept in %s), %zu workers "
                   "ended; the same command resumes the sweep from the finished parts",
                   exp_stop_name(exp_stop_signal()), finished, ntodo, sw->dir, stopped);
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

/* The first unit, and a quarter, a half and three quarters of them. */
static int paced_at(size_t finished, size_t ntodo)
{
    if (finished == 1)
        return 1;
    for (size_t k = 1; k < 4; k++)
        if (finished == (k * ntodo + 3) / 4)
            return 1;
    return 0;
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
    size_t ntodo = plan_units(sw, label, keyf, ctx, paths, keys, slot, todo, done_before);
    exp_stop_install();
    gr_progress *pg = sw->progress && ntodo ? gr_progress_create(stderr, 0, (double)ntodo, 1.0) : NULL;
    gr_progress_label(pg, "units");
    size_t next = 0, running = 0, finished = 0;
    double t0 = gr_wall_seconds();
    int rc = GR_OK;
    int jobs = sw->jobs > 0 ? sw->jobs : 1;
    while (finished < ntodo) {
        if (exp_stop_signal()) {
            rc = stop_workers(sw, pid, n, finished, ntodo, err);
            break;
        }
        while (running < (size_t)jobs && next < n) {
            if (!todo[next]) {
                next++;
                continue;
            }
            pid_t c = start_unit(fn, next, paths, keys, ctx, slot);
            if (c < 0) {
                rc = gr_fail(err, GR_ERUN, "fork: %s", strerror(errno));
                break;
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
                rc = reap_unit(u, status, label, ctx, paths, slot, rc, err);
                if (!rc && sw->paced && finished < ntodo && paced_at(finished, ntodo))
                    sw->paced(sw->paced_ctx, gr_wall_seconds() - t0, finished, ntodo - finished, jobs);
            }
            continue;
        }
        if (w < 0 && running)
            running = 0; /* no children left: should not happen */
        gr_progress_update(pg, todo_progress(slot, todo, n), "units done", (double)finished);
        sleep_ms(200);
    }
    gr_progress_finish(pg);
    gr_progress_free(pg);
    free_run(slot, pid, keys, todo, n);
    return rc;
}
