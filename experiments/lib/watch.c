/* The run's cost watched (watch.h). */
#include "watch.h"

#include "stop.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* Steps a chunk: small enough that a crawl shows within a fraction of a
 * second, large enough that the checks cost nothing. */
#define CHUNK 4096

/* The method's steps (events); unit NULL when it counts neither. */
static uint64_t steps_of(const gr_sim *st, const char **unit)
{
    uint64_t s = 0;
    *unit = gr_sim_counter(st, "events", &s) ? "events" : gr_sim_counter(st, "steps", &s) ? "steps" : NULL;
    return s;
}

void exp_watch_init(exp_watch *w, gr_sim *st, const gr_runctl *rc)
{
    uint64_t s = steps_of(st, &w->unit);
    double t = gr_sim_time(st), len = rc->until - t;
    w->t_moved = w->t_win = t;
    w->s_moved = w->s_win = s;
    /* the first unit of time, or a tenth of a shorter run */
    w->span = len > 10 ? 1.0 : len > 0 ? len / 10 : 1.0;
    w->ref_rate = w->rate = 0;
    w->wall_moved = gr_wall_seconds();
}

/* The key that names a method's remedy for a collapse, if it has one. */
static void remedy(const gr_sim *st, char *buf, size_t n)
{
    const gr_method_type *m = gr_sim_type(st);
    buf[0] = '\0';
    for (const gr_param *p = m->params; p && p->name; p++)
        if (!strcmp(p->name, "collapse")) {
            snprintf(buf, n, "; [%s] collapse chooses the inelastic-collapse model", m->name);
            return;
        }
}

/* The reference rate is at least this many steps per grain and unit
 * time: a run that starts in free fall (a silo filled from above, a bed
 * dropped from a lattice) has almost no events in its first unit, and any
 * packing's collisions would then count as a crawl. */
#define FLOOR_PER_GRAIN 10.0

/* After a chunk: s steps (events) so far at simulated time t. */
static int check(exp_watch *w, const gr_sim *st, const gr_scene *sc, uint64_t s, gr_err *err)
{
    const gr_runctl *rc = &sc->run;
    double t = gr_sim_time(st), now = gr_wall_seconds();
    char why[200];
    if (t - w->t_moved > 1e-9 * fmax(1.0, fabs(rc->until))) {
        w->t_moved = t, w->s_moved = s, w->wall_moved = now;
    } else if ((double)(s - w->s_moved) >= rc->stall_steps && now - w->wall_moved >= rc->stall_seconds) {
        remedy(st, why, sizeof why);
        return gr_fail(err, GR_ERUN,
                       "stalled at t = %.10g: %llu %s over %.0f s advanced the simulated time by %.3g, less than "
                       "1e-9 of the run (an inelastic collapse or a Zeno sequence of %s)%s; [run] stall_steps and "
                       "stall_seconds set this bound",
                       t, (unsigned long long)(s - w->s_moved), w->unit, now - w->wall_moved, t - w->t_moved,
                       w->unit, why);
    }
    if (t - w->t_win >= w->span) {
        w->rate = (double)(s - w->s_win) / (t - w->t_win);
        if (!(w->ref_rate > 0)) {
            double floor = FLOOR_PER_GRAIN * (double)gr_scene_count(sc);
            w->ref_floor = w->rate < floor;
            w->ref_rate = fmax(w->rate, floor);
        }
        w->t_win = t, w->s_win = s;
    }
    if (rc->max_cost_growth > 0 && w->ref_rate > 0) {
        /* the window so far counts too: a crawl shows before its span ends */
        double now_rate = t > w->t_win ? (double)(s - w->s_win) / (t - w->t_win) : w->rate;
        double grown = fmax(w->rate, (double)(s - w->s_win) >= 16 * CHUNK ? now_rate : 0) / w->ref_rate;
        if (grown > rc->max_cost_growth) {
            remedy(st, why, sizeof why);
            char ref[120];
            if (w->ref_floor)
                snprintf(ref, sizeof ref, "%.4g (%g per grain, more than the run's first %.3g had)", w->ref_rate,
                         FLOOR_PER_GRAIN, w->span);
            else
                snprintf(ref, sizeof ref, "%.4g of the run's first %.3g", w->ref_rate, w->span);
            return gr_fail(err, GR_ERUN,
                           "the cost grew past its bound at t = %.10g: %.4g %s per unit time, %.0f times the "
                           "%s (as when a bed comes to rest or collapses)%s; [run] max_cost_growth sets this "
                           "bound (0: none)",
                           t, w->ref_rate * grown, w->unit, grown, ref, why);
        }
    }
    return GR_OK;
}

int exp_watch_advance(exp_watch *w, gr_sim *st, const gr_scene *sc, double t_end, gr_progress *pg, gr_err *err)
{
    if (!w->unit)
        return gr_sim_advance(st, t_end, 0, err);
    uint64_t before = steps_of(st, &w->unit);
    for (;;) {
        if (gr_sim_advance(st, t_end, CHUNK, err))
            return err->code;
        uint64_t after = steps_of(st, &w->unit);
        if (check(w, st, sc, after, err))
            return err->code;
        gr_progress_cost(pg, gr_sim_time(st), w->unit, w->rate);
        /* a stop signal is the caller's to act on, between two chunks */
        if (exp_stop_signal())
            return GR_OK;
        /* fewer steps than asked: the end time was reached (or the counter
         * counts fewer than the steps; the caller's loop then asks again) */
        if (after - before < CHUNK || gr_sim_time(st) >= t_end)
            return GR_OK;
        before = after;
    }
}
