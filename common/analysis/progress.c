#include "progress.h"

#include <inttypes.h>
#include <math.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>

struct gr_progress {
    FILE *out;
    int tty;
    double t0, t1, delay;
    double wall0, last_draw;
    int drawn;
    double thermo_every, thermo_next, thermo_wall; /* thermo lines */
    uint64_t thermo_steps;
    int thermo_lines;
    const char *label; /* name of the progress variable */
    const char *obs_name; /* the key observable last shown */
    double obs_value;
    const char *cost_unit; /* steps (events) per unit time, shown once known */
    double cost;
};

double gr_wall_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

gr_progress *gr_progress_create(FILE *out, double t_begin, double t_end, double delay)
{
    gr_progress *p = calloc(1, sizeof *p);
    if (!p)
        return NULL;
    p->out = out;
    p->tty = out && isatty(fileno(out));
    p->t0 = t_begin;
    p->t1 = t_end;
    p->delay = delay;
    p->wall0 = gr_wall_seconds();
    p->thermo_next = t_begin;
    p->label = "t";
    return p;
}

void gr_progress_label(gr_progress *p, const char *name)
{
    if (p)
        p->label = name;
}

void gr_progress_free(gr_progress *p)
{
    if (!p)
        return;
    gr_progress_finish(p);
    free(p);
}

static void fmt_duration(char *buf, size_t n, double s)
{
    if (s < 0 || s != s)
        snprintf(buf, n, "?");
    else if (s < 60)
        snprintf(buf, n, "%.0fs", s);
    else if (s < 3600)
        snprintf(buf, n, "%dm%02ds", (int)(s / 60), (int)s % 60);
    else
        snprintf(buf, n, "%dh%02dm", (int)(s / 3600), (int)(s / 60) % 60);
}

void gr_progress_update(gr_progress *p, double t_sim, const char *obs_name, double obs_value)
{
    if (!p || !p->tty)
        return;
    if (obs_name)
        p->obs_name = obs_name, p->obs_value = obs_value;
    double now = gr_wall_seconds(), el = now - p->wall0;
    if (el < p->delay || now - p->last_draw < 0.25)
        return;
    p->last_draw = now;
    double frac = (t_sim - p->t0) / (p->t1 - p->t0);
    double rem = frac > 0 ? el * (1 - frac) / frac : -1;
    char e[32], r[32];
    fmt_duration(e, sizeof e, el);
    fmt_duration(r, sizeof r, rem);
    fprintf(p->out, "\r\033[K%5.1f%%  %s = %-10.4g elapsed %s  remaining %s", 100 * frac, p->label, t_sim, e, r);
    if (p->obs_name)
        fprintf(p->out, "  %s = %.4g", p->obs_name, p->obs_value);
    if (p->cost_unit && p->cost > 0)
        fprintf(p->out, "  %s/tau = %.3g", p->cost_unit, p->cost);
    fflush(p->out);
    p->drawn = 1;
}

void gr_progress_cost(gr_progress *p, double t_sim, const char *unit, double per_time)
{
    if (!p)
        return;
    p->cost_unit = unit, p->cost = per_time;
    gr_progress_update(p, t_sim, NULL, 0);
}

void gr_progress_finish(gr_progress *p)
{
    if (p && p->drawn) {
        fprintf(p->out, "\r\033[K");
        fflush(p->out);
        p->drawn = 0;
    }
}

void gr_progress_thermo(gr_progress *p, double every)
{
    if (p)
        p->thermo_every = every;
}

/* Steps per wall-clock second since the previous line (0 on the first). */
static void thermo_line(gr_progress *p, const gr_obs *o)
{
    double now = gr_wall_seconds();
    double rate = p->thermo_lines && now > p->thermo_wall
                      ? (double)(o->steps - p->thermo_steps) / (now - p->thermo_wall) : 0.0;
    if (!p->thermo_lines)
        fprintf(p->out, "%12s %12s %12s %12s %12s %9s %10s\n", "Step", "Time", "KinEng", "PotEng", "Temp",
                "Outflow", "Steps/s");
    fprintf(p->out, "%12" PRIu64 " %12.6g %12.6g %12.6g %12.6g %9" PRIu64 " %10.4g\n", o->steps, o->t,
            o->ekin_trans + o->ekin_rot, o->epot_grav, o->temperature, o->outflow, rate);
    fflush(p->out);
    p->thermo_lines++;
    p->thermo_steps = o->steps;
    p->thermo_wall = now;
}

void gr_progress_obs(gr_progress *p, const gr_obs *o)
{
    if (!p)
        return;
    if (p->tty) {
        gr_progress_update(p, o->t, "E_kin", o->ekin_trans + o->ekin_rot);
        return;
    }
    if (!(p->thermo_every > 0))
        return;
    double eps = 1e-9 * (fabs(p->t1) > 1 ? fabs(p->t1) : 1);
    if (p->thermo_lines && o->t < p->thermo_next - eps && o->t < p->t1 - eps)
        return;
    thermo_line(p, o);
    while (p->thermo_next <= o->t + eps)
        p->thermo_next += p->thermo_every;
}
