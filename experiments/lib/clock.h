/* Clocks for the benchmarks: wall (monotonic) and this process's CPU time,
 * in seconds. */
#ifndef GR_EXP_CLOCK_H
#define GR_EXP_CLOCK_H

double exp_wall_seconds(void);
double exp_cpu_seconds(void);

#endif
