/* Stop signals as a request (stop.h). The flag is the program's one
 * static state: a signal handler can only pass a value through a volatile
 * sig_atomic_t. A worker marks itself so, and catches nothing: its parent
 * ends it with SIGTERM and it should die at once. */
#include "stop.h"

#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>
#ifdef __linux__
#include <sys/prctl.h>
#endif

static volatile sig_atomic_t stop_sig, is_worker;

static void on_stop(int sig) { stop_sig = sig; }

static const int sigs[] = {SIGTERM, SIGINT, SIGHUP};

void exp_stop_install(void)
{
    if (is_worker)
        return;
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_stop;
    sigemptyset(&sa.sa_mask);
    /* a second signal finds the default: the program ends at once */
    sa.sa_flags = SA_RESETHAND;
    for (size_t k = 0; k < sizeof sigs / sizeof *sigs; k++)
        sigaction(sigs[k], &sa, NULL);
}

int exp_stop_signal(void) { return stop_sig; }

void exp_stop_worker(int parent)
{
    for (size_t k = 0; k < sizeof sigs / sizeof *sigs; k++)
        signal(sigs[k], SIG_DFL);
    stop_sig = 0;
    is_worker = 1;
#ifdef __linux__
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    /* the parent may have died before prctl */
    if (getppid() != (pid_t)parent)
        _exit(1);
#else
    (void)parent;
#endif
}

const char *exp_stop_name(int sig)
{
    switch (sig) {
    case SIGTERM: return "SIGTERM";
    case SIGINT: return "SIGINT";
    case SIGHUP: return "SIGHUP";
    default: return "a signal";
    }
}

void exp_stop_exit(int sig)
{
    fflush(NULL);
    signal(sig, SIG_DFL);
    raise(sig);
    _exit(128 + sig);
}
