/* Stop signals (TERM, INT, HUP) as a request that the long loops read at
 * their safe points: a run saves its state and says where it stopped, a
 * sweep ends its workers and keeps their finished parts. A second signal
 * ends the program at once (the handler resets itself). */
#ifndef GR_EXP_STOP_H
#define GR_EXP_STOP_H

/* Catch the stop signals; idempotent. */
void exp_stop_install(void);
/* The stop signal received (0: none). */
int exp_stop_signal(void);
/* A forked worker: the default dispositions again, for good (install does
 * nothing in it), and (Linux) ended by SIGTERM when its parent dies, even
 * by SIGKILL, so that no worker outlives the sweep. parent: the parent's
 * pid before fork. */
void exp_stop_worker(int parent);
/* "SIGTERM", "SIGINT", "SIGHUP" or "signal N". */
const char *exp_stop_name(int sig);
/* End the process as the signal would have (the exit status a shell
 * reads, 128 + sig), after the caller has said what it kept. */
void exp_stop_exit(int sig);

#endif
