#include "movie_enc.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

static volatile sig_atomic_t caught;
static const int catch_signals[] = {SIGINT, SIGTERM, SIGHUP};

static void on_signal(int sig)
{
    caught = sig;
}

void mv_catch(void)
{
    struct sigaction sa = {0};
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    for (size_t k = 0; k < sizeof catch_signals / sizeof *catch_signals; k++)
        sigaction(catch_signals[k], &sa, NULL);
}

int mv_caught(void)
{
    return caught != 0;
}

void mv_release(void)
{
    for (size_t k = 0; k < sizeof catch_signals / sizeof *catch_signals; k++)
        signal(catch_signals[k], SIG_DFL);
    if (caught)
        raise(caught);
}

/* The last non-empty line of a log, for an error message. */
static void last_line(const char *log, char *buf, size_t n)
{
    buf[0] = '\0';
    FILE *f = fopen(log, "r");
    char line[384];
    while (f && fgets(line, sizeof line, f)) {
        line[strcspn(line, "\n")] = '\0';
        if (line[0])
            snprintf(buf, n, "%s", line);
    }
    if (f)
        fclose(f);
}

int mv_run(char *const argv[], const char *log, gr_err *err)
{
    fflush(stdout);
    fflush(stderr);
    pid_t pid = fork();
    if (pid < 0)
        return gr_fail(err, GR_ERUN, "cannot start %s: %s", argv[0], strerror(errno));
    if (pid == 0) {
        int fd = open(log, O_WRONLY | O_CREAT | O_TRUNC, 0644), in = open("/dev/null", O_RDONLY);
        if (fd >= 0)
            dup2(fd, 1), dup2(fd, 2);
        if (in >= 0)
            dup2(in, 0);
        execvp(argv[0], argv);
        _exit(127);
    }
    int st, told = 0;
    while (waitpid(pid, &st, 0) < 0) {
        if (errno != EINTR)
            return gr_fail(err, GR_ERUN, "%s: lost: %s", argv[0], strerror(errno));
        if (caught && !told++)
            kill(pid, SIGTERM);
    }
    if (caught)
        return gr_fail(err, GR_ERUN, "interrupted");
    if (WIFEXITED(st) && WEXITSTATUS(st) == 0)
        return GR_OK;
    char why[400];
    last_line(log, why, sizeof why);
    if (WIFEXITED(st))
        return gr_fail(err, GR_ERUN, "%s failed (exit %d%s%s)", argv[0], WEXITSTATUS(st), why[0] ? ": " : "", why);
    return gr_fail(err, GR_ERUN, "%s was killed (signal %d)", argv[0], WIFSIGNALED(st) ? WTERMSIG(st) : 0);
}

int mv_tmpdir(const char *out, char *dir, size_t n, gr_err *err)
{
    if (snprintf(dir, n, "%s.frames-XXXXXX", out) >= (int)n || !mkdtemp(dir)) {
        gr_fail(err, GR_ERUN, "cannot make a folder for the frames beside %s: %s", out, strerror(errno));
        dir[0] = '\0';
        return err->code;
    }
    return GR_OK;
}

void mv_rmdir(const char *dir)
{
    if (!dir[0])
        return;
    DIR *d = opendir(dir);
    struct dirent *e;
    char p[1400];
    while (d && (e = readdir(d)))
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) {
            snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
            unlink(p);
        }
    if (d)
        closedir(d);
    rmdir(dir);
}

int mv_encode_mp4(const char *dir, long fps, const char *part, gr_err *err)
{
    char rate[32], in[1300], log[1300];
    snprintf(rate, sizeof rate, "%ld", fps);
    snprintf(in, sizeof in, "%s/f%%06d.png", dir);
    snprintf(log, sizeof log, "%s/ffmpeg.log", dir);
    /* H.264 in 4:2:0 (what every player plays) needs even sides */
    char *argv[] = {"ffmpeg", "-nostdin", "-y", "-loglevel", "error", "-framerate", rate, "-i", in,
                    "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2:color=white", "-c:v", "libx264",
                    "-pix_fmt", "yuv420p", "-movflags", "+faststart", "-f", "mp4", (char *)part, NULL};
    return mv_run(argv, log, err);
}
