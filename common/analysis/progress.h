/* Progress of a long run on a terminal: elapsed, estimated remaining,
 * simulated time and one key observable, redrawn on one line a few times a
 * second. Off a terminal: nothing, or, once gr_progress_thermo is set,
 * thermo lines in the manner of LAMMPS's log (step, time, energies,
 * temperature, outflow, throughput) every so much simulated time. */
#ifndef GR_PROGRESS_H
#define GR_PROGRESS_H

#include <stdio.h>

#include "observe.h"

typedef struct gr_progress gr_progress;

/* Shows nothing until `delay` seconds have passed (short runs stay quiet). */
gr_progress *gr_progress_create(FILE *out, double t_begin, double t_end, double delay);
void gr_progress_free(gr_progress *p);
/* The name of the progress variable on the line ("t" by default, for a
 * simulated time; "units" where it counts units of work). */
void gr_progress_label(gr_progress *p, const char *name);
void gr_progress_update(gr_progress *p, double t_sim, const char *obs_name, double obs_value);
/* Off a terminal, a thermo line at the first sample, then at the first
 * sample at or after each multiple of every (> 0) and at t_end. */
void gr_progress_thermo(gr_progress *p, double every);
/* One observation: the progress line (key observable E_kin) on a terminal,
 * a thermo line off one when due. */
void gr_progress_obs(gr_progress *p, const gr_obs *o);
/* The run's cost, steps (events) per unit of simulated time, shown on the
 * line from now on, and the line redrawn at t_sim: between samples the
 * line follows the advance, so a crawl shows. */
void gr_progress_cost(gr_progress *p, double t_sim, const char *unit, double per_time);
/* Clear the line, if anything was drawn. */
void gr_progress_finish(gr_progress *p);
/* Monotonic wall-clock seconds. */
double gr_wall_seconds(void);

#endif
