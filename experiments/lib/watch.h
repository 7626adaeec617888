/* A run's cost watched while it advances: the advance to each sample time
 * goes in chunks of steps (events), and after each chunk the simulated
 * time and the steps taken are compared with two bounds. A run whose time
 * stops advancing ([run] stall_steps steps and stall_seconds wall seconds
 * without moving by 1e-9 of the run's length: an inelastic collapse, a
 * Zeno sequence), or whose steps per unit time grow past [run]
 * max_cost_growth times those of its first unit of time (at least 10 per
 * grain), stops with a
 * diagnostic naming the cause and the keys. Chunks change nothing in the
 * run: a method's advance resumes where a step limit stopped it. */
#ifndef GR_EXP_WATCH_H
#define GR_EXP_WATCH_H

#include <stdint.h>

#include "err.h"
#include "method.h"
#include "progress.h"
#include "scene.h"

typedef struct {
    const char *unit;          /* "events" or "steps" (the counter read) */
    double span;               /* the span of the reference and of a window */
    double ref_rate;           /* steps per unit time over the first span, at least 10 per
                                  grain (0: not yet) */
    int ref_floor;             /* ref_rate is the floor, above the first span's rate */
    double t_moved, wall_moved;
    uint64_t s_moved;          /* steps at the last real advance of time */
    double t_win;
    uint64_t s_win;            /* start of the current window */
    double rate;               /* steps per unit time over the last whole window */
} exp_watch;

void exp_watch_init(exp_watch *w, gr_sim *st, const gr_runctl *rc);
/* Advance st to t_end as gr_sim_advance does, watched; the progress line
 * (pg, may be NULL) follows each chunk with the steps per unit time. A
 * stop signal (stop.h) returns GR_OK early, between two chunks, with the
 * state whole. */
int exp_watch_advance(exp_watch *w, gr_sim *st, const gr_scene *sc, double t_end, gr_progress *pg, gr_err *err);

#endif
