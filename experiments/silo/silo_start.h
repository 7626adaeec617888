/* grano silo-start (thesis chapter 3): the unit of work (one discharge) and
 * the report over all of them, shared by silo_start.c and
 * silo_start_report.c. */
#ifndef GR_SILO_START_H
#define GR_SILO_START_H

#include <stddef.h>
#include <stdint.h>

#include "silo_common.h"
#include "silo_fill.h"
#include "fields.h"
#include "stats.h"

#define SS_MAX_ORIF 16
#define SS_MAX_SLOTS 64
#define SS_MAX_TIMES 32

/* The mean flow subtracted from the window's displacements: the window's
 * mean, the mean of each of SS_SUB_N columns across x (the profile
 * v(x) at the window's height), or of each cell of a 5 x 5 grid over the
 * window (cells of 3 d at full size, about 10 grains each). */
enum { SS_SUB_WINDOW, SS_SUB_COLUMNS, SS_SUB_CELLS };
#define SS_SUB_N 10

typedef struct {
    silo_cfg base;          /* size; orifice and seed set per unit */
    int quick;
    double orifice[SS_MAX_ORIF];
    size_t norif;
    int nreal;
    uint64_t seed;
    long fs;                /* frame interval, steps */
    long min_steps, max_steps;
    double fall_stop;       /* stop once the surface has fallen this far, and as
                               many grains have left as filled that height */
    double window;          /* side of the displacement window */
    double cell;            /* velocity field cells */
    size_t nslots;
    long lag[SS_MAX_SLOTS]; /* lags in frames */
    size_t ntimes;
    long times[SS_MAX_TIMES]; /* velocity field times, steps after opening */
    size_t sample_cap;      /* displacement samples kept per slot and unit */
    int subtract;           /* the local mean flow subtracted: SS_SUB_* */
    const char *dir;
    silo_fills fills;       /* one per realisation, branched to each orifice */
} ss_ctx;

/* The thesis's six panels of fig. 3.2, in steps after opening. */
extern const long ss_fig32_steps[6];

#define NB 48     /* histogram bins on [-UMAX, UMAX] standard deviations */
#define UMAX 6.0

/* Everything the report derives for one orifice. */
typedef struct {
    double D;
    size_t ns;
    double lag[SS_MAX_SLOTS], fall[SS_MAX_SLOTS];
    double mx[SS_MAX_SLOTS], my[SS_MAX_SLOTS], ex[SS_MAX_SLOTS], ey[SS_MAX_SLOTS];
    double kx[SS_MAX_SLOTS], ky[SS_MAX_SLOTS];
    gr_msd *msd;
    int sel[2];               /* slots of the short (0.01 d) and long (2 d) lags */
    double *pool[2][2];       /* [short/long][x/y] normalised samples */
    size_t npool[2];
    double stats[2][10];      /* per lag: time, fall, sd_x, sd_y, ks eq34 x, gauss x, eq34 y, gauss y, kappa x, y */
    double pdf[2][NB][5];
    gr_fit fit[2];
    int fit_ok[2];
    double fit_range[2];
    double *vy;               /* ntimes x ncells */
    double *wsum;
    double grid[6];
    double cost[5];           /* mean wall/CPU seconds of the branch and the run, steps */
    double branch[4];         /* means: branch's settling time, lift, filling's CPU s, kinetic energy at opening */
} ss_res;

/* Figures and tables (silo_start_figs.c). */
int ss_fig_velocity(const char *png, const ss_ctx *c, const ss_res *r, const long *steps,
                    size_t nsteps, gr_err *err);
int ss_fig_pdf(const char *png, const ss_res *res, size_t nr, int w, int vert_first,
               const char *title, gr_err *err);
int ss_fig_msd(const char *png, const ss_res *res, size_t nr, gr_err *err);
int ss_fig_kurtosis(const char *png, const ss_res *res, size_t nr, gr_err *err);
/* table: nr x ntimes x 3 (step, discharges, relative change; NaN: none). */
int ss_fig_stationarity(const char *png, const ss_ctx *c, const ss_res *res, size_t nr, const double *table,
                        gr_err *err);
/* The silo snapshot (end of the first discharge of orifice o) and fig. 3.1. */
int ss_pictures(const ss_ctx *c, char *const *parts, size_t o, gr_err *err);

void ss_label(size_t unit, void *ctx, char *buf, size_t n);
void ss_key(size_t unit, void *ctx, char *buf, size_t n);
int ss_unit(size_t unit, const char *part, const char *key, void *ctx, volatile double *progress,
            gr_err *err);

/* Read every part, average, fit, write <dir>/silo-start.h5, the .dat
 * tables and the figures. Fills a short summary for the terminal. */
int ss_report(const ss_ctx *c, char *const *parts, char *summary, size_t n, gr_err *err);

#endif
