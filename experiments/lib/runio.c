#include "runio.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/statvfs.h>

#include "ckpt.h"
#include "fields.h"
#include "h5md.h"
#include "init.h"
#include "plot.h"
#include "progress.h"
#include "stress.h"
#include "restart.h"
#include "stop.h"
#include "watch.h"

void gr_run_ckpt_path(const char *out, char *buf, size_t n)
{
    size_t l = strlen(out);
    if (l > 3 && !strcmp(out + l - 3, ".h5"))
        snprintf(buf, n, "%.*s.ckpt", (int)(l - 3), out);
    else
        snprintf(buf, n, "%s.ckpt", out);
}

int gr_run_save(const char *path, gr_sim *sim, const uint64_t counters[3], gr_err *err)
{
    const gr_scene *sc = gr_sim_scene(sim);
    const gr_method_type *m = gr_sim_type(sim);
    gr_ckpt *ck = gr_ckpt_create(path, err);
    if (!ck)
        return err->code;
    int rc = gr_ckpt_put_bytes(ck, "run_scene_text", sc->text, strlen(sc->text), err);
    if (!rc)
        rc = gr_ckpt_put_bytes(ck, "run_method", m->name, strlen(m->name), err);
    uint64_t seed = sc->seed;
    if (!rc)
        rc = gr_ckpt_put_u64(ck, "run_seed", &seed, 1, err);
    if (!rc)
        rc = gr_ckpt_put_u64(ck, "run_counters", counters, 3, err);
    if (!rc)
        rc = gr_sim_save(sim, ck, err);
    if (!rc && m->snapshot) {
        /* The H5MD part makes a checkpoint readable by grano info, h5py and
         * grano export; its frame carries the time and, as the result's
         * frames do, the method's steps (events for an event-driven one). */
        gr_particles *p = gr_particles_create(0, err);
        gr_h5md_opts ho = {.method = m->name, .seed = sc->seed, .version = GRANO_VERSION};
        uint64_t step = 0;
        if (!gr_sim_counter(sim, "steps", &step) && !gr_sim_counter(sim, "events", &step))
            step = 0;
        rc = !p ? GR_ERUN : gr_sim_snapshot(sim, p, err);
        if (!rc)
            rc = gr_ckpt_put_h5md(ck, sc, &ho, step, gr_sim_time(sim), p, err);
        gr_particles_free(p);
    }
    if (rc) {
        /* Never let a partial checkpoint replace the last good one. */
        gr_ckpt_discard(ck);
        return rc;
    }
    return gr_ckpt_close(ck, err);
}

/* A stored string must equal the expected one. */
static int check_text(gr_ckpt *ck, const char *name, const char *want, const char *path,
                      const char *what, gr_err *err)
{
    size_t n;
    if (gr_ckpt_len(ck, name, &n, err))
        return gr_fail(err, GR_EINPUT, "%s: not a grano run checkpoint (no %s)", path, name);
    char *s = calloc(n + 1, 1);
    if (!s)
        return gr_fail(err, GR_ERUN, "out of memory");
    int rc = gr_ckpt_get_bytes(ck, name, s, n, err);
    if (!rc && strcmp(s, want))
        rc = gr_fail(err, GR_EINPUT, "--restart: %s was written for a different %s", path, what);
    free(s);
    return rc;
}

/* The stored scene text, allocated. */
static char *stored_text(gr_ckpt *ck, const char *path, gr_err *err)
{
    size_t n;
    if (gr_ckpt_len(ck, "run_scene_text", &n, err)) {
        gr_fail(err, GR_EINPUT, "%s: not a grano run checkpoint (no run_scene_text)", path);
        return NULL;
    }
    char *s = calloc(n + 1, 1);
    if (!s)
        gr_fail(err, GR_ERUN, "out of memory");
    else if (gr_ckpt_get_bytes(ck, "run_scene_text", s, n, err)) {
        free(s);
        s = NULL;
    }
    return s;
}

int gr_run_load(const char *path, gr_sim *sim, uint64_t counters[3], const gr_run_opts *o, gr_runctl *old_run,
                gr_err *err)
{
    const gr_scene *sc = gr_sim_scene(sim);
    const gr_method_type *m = gr_sim_type(sim);
    gr_ckpt *ck = gr_ckpt_open(path, err);
    if (!ck)
        return err->code;
    uint64_t seed;
    *old_run = sc->run;
    char *text = stored_text(ck, path, err);
    int rc = text ? GR_OK : err->code;
    if (!rc && strcmp(text, sc->text))
        rc = gr_restart_compare(sc, text, path, o->branch, o->notes, o->notes_cap, old_run, err);
    free(text);
    if (!rc)
        rc = check_text(ck, "run_method", m->name, path, "method", err);
    if (!rc && !(rc = gr_ckpt_get_u64(ck, "run_seed", &seed, 1, err)) && seed != sc->seed && !o->branch)
        rc = gr_fail(err, GR_EINPUT, "--restart: %s was written with seed %llu, not %llu (--branch starts a new output with the new seed)",
                     path, (unsigned long long)seed, (unsigned long long)sc->seed);
    if (!rc)
        rc = gr_ckpt_get_u64(ck, "run_counters", counters, 3, err);
    if (!rc)
        rc = gr_sim_load(sim, ck, err);
    gr_err ignore = {0};
    gr_ckpt_close(ck, &ignore);
    return rc;
}

/* Room left for a file: the free space of its filesystem and, under a
 * file-size limit (ulimit -f), what the limit leaves. A write that fails
 * half-way leaves an HDF5 file unreadable, so the run stops before one
 * that might not fit: twice the largest growth seen, and a margin. */
typedef struct {
    const char *path;
    double last, grow;
} room;

static int room_check(room *r, double more, gr_err *err)
{
    struct stat st;
    struct statvfs vs;
    if (stat(r->path, &st) || statvfs(r->path, &vs))
        return GR_OK; /* not created yet: its writer reports any failure */
    double size = (double)st.st_size, left = (double)vs.f_bavail * (double)vs.f_frsize;
    if (r->last > 0 && size - r->last > r->grow)
        r->grow = size - r->last;
    r->last = size;
    struct rlimit rl;
    if (!getrlimit(RLIMIT_FSIZE, &rl) && rl.rlim_cur != RLIM_INFINITY && (double)rl.rlim_cur - size < left)
        left = (double)rl.rlim_cur - size;
    double need = 2 * (r->grow > more ? r->grow : more) + 131072;
    if (left < need)
        return gr_fail(err, GR_ERUN, "%s: the disk is nearly full (%.3g MB left, the next write needs up to %.3g MB); stopped before writing so that the file stays readable",
                       r->path, left / 1e6, need / 1e6);
    return GR_OK;
}

typedef struct {
    room out_room, ckpt_room;
    uint64_t warned;   /* the validity limits already told, by declaration position */
    int strict_stop;   /* stopped by [run] strict = yes: the state is not a good one */
    int stopped;       /* the stop signal that ended the loop (0: none) */
    exp_watch watch;   /* the run's cost between samples */
    double last_frame; /* time of this run's last frame (-1: none yet) */
    gr_h5md *h;
    gr_field *field;
    gr_particles *snap;
    gr_contacts *net;  /* [run] contacts = yes or stress = yes */
    double *buf;
    double *sbuf;      /* [run] stress = yes: nx * ny * 4 on the field grid */
} run_io;

/* [run] stress = yes: over the domain (fields/stress_global, one cell) and
 * on the field grid, with each frame: the contact stress of the frame's
 * network for a method that has one, else the method's window-averaged
 * stress (kinetic plus collisional) since the previous frame. */
static int write_stress(run_io *io, const gr_scene *sc, gr_sim *st, uint64_t step, double t, gr_err *err)
{
    double g[4];
    int nx = sc->run.field_nx, ny = sc->run.field_ny;
    int rc = io->net ? gr_stress_contacts(sc, io->snap, io->net, t, nx, ny, g, io->sbuf, err)
                     : gr_sim_stress(st, io->sbuf ? nx : 1, io->sbuf ? ny : 1, g, io->sbuf, err);
    if (rc)
        return rc;
    gr_field_desc d = {"stress_global", "m tau-2", 1, 1, 4, 0, 0, sc->width, sc->height};
    if (gr_h5md_write_field(io->h, &d, step, t, g, err))
        return err->code;
    if (!io->sbuf)
        return GR_OK;
    d = (gr_field_desc){"stress", "m tau-2", nx, ny, 4, 0, 0, sc->width / nx, sc->height / ny};
    return gr_h5md_write_field(io->h, &d, step, t, io->sbuf, err);
}

static int write_fields(run_io *io, const gr_obs *o, gr_err *err)
{
    gr_field *f = io->field;
    if (!f || f->wsum <= 0)
        return GR_OK;
    size_t nc = gr_field_ncells(f);
    gr_field_desc d = {"packing_fraction", "1", f->nx, f->ny, 1, f->x0, f->y0, f->cx, f->cy};
    gr_field_packing(f, io->buf);
    if (gr_h5md_write_field(io->h, &d, o->steps, o->t, io->buf, err))
        return err->code;
    double *vx = io->buf, *vy = io->buf + nc, *v = io->buf + 2 * nc;
    gr_field_velocity(f, vx, vy);
    for (size_t c = 0; c < nc; c++)
        v[2 * c] = vx[c], v[2 * c + 1] = vy[c];
    d.name = "velocity", d.unit = "d tau-1", d.ncomp = 2;
    if (gr_h5md_write_field(io->h, &d, o->steps, o->t, v, err))
        return err->code;
    gr_field_temperature(f, io->buf);
    d.name = "temperature", d.unit = "m d+2 tau-2", d.ncomp = 1;
    if (gr_h5md_write_field(io->h, &d, o->steps, o->t, io->buf, err))
        return err->code;
    gr_field_clear(f);
    return GR_OK;
}

/* Each validity limit the method reports broken is told once, when it is
 * first seen; under [run] strict = yes the first one stops the run, and
 * the state that broke it is not kept as a good one. */
static int check_limits(run_io *io, const gr_scene *sc, gr_sim *st, const gr_run_opts *o, gr_err *err)
{
    gr_diag dg[GR_OBS_MAX];
    size_t n = gr_sim_diagnostics(st, dg, GR_OBS_MAX);
    for (size_t i = 0; i < n; i++) {
        if (io->warned & (1ull << dg[i].index))
            continue;
        io->warned |= 1ull << dg[i].index;
        char where[1200], msg[1800];
        gr_scene_where_key(sc, dg[i].key, where, sizeof where);
        snprintf(msg, sizeof msg, "%s: validity limit %s broken at t = %g: %s (%s changes it)",
                 gr_sim_type(st)->name, dg[i].name, gr_sim_time(st), dg[i].detail, where);
        if (sc->run.strict) {
            io->strict_stop = 1;
            char sw[1200];
            gr_scene_where(sc, "run", "strict", sw, sizeof sw);
            return gr_fail(err, GR_ERUN, "%s; stopped (%s = yes)", msg, sw);
        }
        if (o->warn)
            o->warn(o->warn_ctx, msg);
    }
    return GR_OK;
}

/* The limits broken over the whole run, one line each. */
static void sum_limits(gr_sim *st, const gr_run_opts *o)
{
    gr_diag dg[GR_OBS_MAX];
    size_t n = o->warn ? gr_sim_diagnostics(st, dg, GR_OBS_MAX) : 0;
    uint64_t steps = 0;
    const char *unit = "steps";
    if (n && !gr_sim_counter(st, "steps", &steps) && gr_sim_counter(st, "events", &steps))
        unit = "events";
    for (size_t i = 0; i < n; i++) {
        char msg[600];
        snprintf(msg, sizeof msg, "%s: validity limit %s counted %llu in %llu %s of the run (%s; key %s)",
                 gr_sim_type(st)->name, dg[i].name, (unsigned long long)dg[i].count, (unsigned long long)steps,
                 unit, dg[i].doc, dg[i].key);
        o->warn(o->warn_ctx, msg);
    }
}

/* Computed, not counted: an interval far below the time step would
 * otherwise count up for ever, or sample the same time twice. */
uint64_t gr_run_next_index(double t, double t0, double every, double eps)
{
    double q = floor((t - t0 + eps) / every);
    uint64_t k = q > 0 ? (uint64_t)q : 0;
    while (t >= t0 + (double)k * every - eps)
        k++;
    return k;
}

int gr_run_check(const gr_scene *sc, gr_err *err)
{
    const gr_runctl *r = &sc->run;
    const char *keys[3] = {"observe_every", "output_every", "checkpoint_every"};
    const double every[3] = {r->observe_every, r->output_every, r->checkpoint_every};
    for (int j = 0; j < 3; j++) {
        if (r->until / every[j] > GR_RUN_MAX_SAMPLES) {
            char where[1200];
            gr_scene_where(sc, "run", keys[j], where, sizeof where);
            return gr_fail(err, GR_EINPUT, "%s: %g asks for %.3g samples over until = %g; at most %.0e",
                           where, every[j], r->until / every[j], r->until, GR_RUN_MAX_SAMPLES);
        }
    }
    return GR_OK;
}

/* Observables every observe_every, frames and fields every output_every,
 * checkpoints every checkpoint_every; times are k * interval from the start
 * so that they do not drift and a restart lands on the same ones. */
static int loop(gr_scene *sc, gr_sim *st, run_io *io, const gr_run_opts *o, uint64_t k[3],
                double t0, gr_err *err)
{
    int frames = gr_sim_type(st)->snapshot != NULL;
    const gr_runctl *rc = &sc->run;
    gr_progress *pg = o->progress ? gr_progress_create(stderr, gr_sim_time(st), rc->until, 1.0) : NULL;
    gr_progress_thermo(pg, rc->thermo_every);
    const double eps = 1e-9 * (rc->until > 1 ? rc->until : 1);
    int status = GR_OK;
    exp_watch_init(&io->watch, st, rc);
    for (;;) {
        double t = gr_sim_time(st);
        gr_obs obs;
        gr_obs_clear(&obs);
        int observed = 0;
        if (t >= t0 + (double)k[0] * rc->observe_every - eps) {
            if ((status = room_check(&io->out_room, 0, err)) || (status = gr_sim_observe(st, &obs, err)) ||
                (status = gr_h5md_write_obs(io->h, &obs, err)))
                break;
            /* Each sample averages its window since the previous one. */
            gr_sim_reset_window(st);
            observed = 1;
            if (io->field && (status = gr_sim_fields(st, io->field, 1.0, err)))
                break;
            k[0] = gr_run_next_index(t, t0, rc->observe_every, eps);
            gr_progress_obs(pg, &obs);
        }
        if (t >= t0 + (double)k[1] * rc->output_every - eps || t >= rc->until - eps) {
            if ((status = room_check(&io->out_room, 0, err)) || (!observed && (status = gr_sim_observe(st, &obs, err))) ||
                (frames && (status = gr_sim_snapshot(st, io->snap, err))) ||
                (frames && (status = gr_h5md_write_frame(io->h, obs.steps, t, io->snap, err))))
                break;
            io->last_frame = t;
            if ((io->net && ((status = gr_sim_contacts(st, io->net, err)) ||
                             (sc->run.contacts &&
                              (status = gr_h5md_write_contacts(io->h, obs.steps, t, io->net, err))))) ||
                (sc->run.stress && (status = write_stress(io, sc, st, obs.steps, t, err))))
                break;
            if ((status = write_fields(io, &obs, err)))
                break;
            k[1] = gr_run_next_index(t, t0, rc->output_every, eps);
        }
        if (t >= t0 + (double)k[2] * rc->checkpoint_every - eps) {
            k[2] = gr_run_next_index(t, t0, rc->checkpoint_every, eps);
            if (o->ckpt && ((status = room_check(&io->ckpt_room, io->ckpt_room.last, err)) ||
                            (status = gr_run_save(o->ckpt, st, k, err))))
                break;
        }
        /* the first samples of every kind made their datasets: from now on
         * the file only grows, in the mode a kill cannot break */
        if ((status = gr_h5md_publish(io->h, err)))
            break;
        if (t >= rc->until - eps)
            break;
        /* a stop signal is read here, the samples of t written (or between
         * two chunks of an advance, when it came during one): the state
         * saved then restarts onto the same sample times */
        if ((io->stopped = exp_stop_signal())) {
            status = GR_ERUN;
            break;
        }
        double target = rc->until;
        for (int j = 0; j < 3; j++) {
            double every = j == 0 ? rc->observe_every : j == 1 ? rc->output_every : rc->checkpoint_every;
            double next = t0 + (double)k[j] * every;
            target = next < target ? next : target;
        }
        if ((status = exp_watch_advance(&io->watch, st, sc, target, pg, err)) ||
            (status = check_limits(io, sc, st, o, err)))
            break;
    }
    gr_progress_free(pg);
    return status;
}

/* After a restart whose intervals changed, the next sample of each kind
 * is the first of the new interval after the checkpoint; a branch samples
 * the checkpoint's state itself first, as a fresh run samples its start. */
void gr_run_resume_counters(const gr_scene *sc, const gr_runctl *was, double t, double t0, int branch,
                            uint64_t k[3])
{
    const gr_runctl *r = &sc->run;
    const double now[3] = {r->observe_every, r->output_every, r->checkpoint_every};
    const double old[3] = {was->observe_every, was->output_every, was->checkpoint_every};
    double eps = 1e-9 * (r->until > 1 ? r->until : 1);
    for (int j = 0; j < 3; j++) {
        if (branch && j < 2)
            k[j] = gr_run_next_index(t - 2 * eps, t0, now[j], eps);
        else if (now[j] != old[j])
            k[j] = gr_run_next_index(t, t0, now[j], eps);
    }
}

/* `[run] contacts = yes` asks the method for its contact network with each
 * frame, and so does `[run] stress = yes` of a method that has one (the
 * stress then also needs the grains' positions: snapshots); a method
 * without contacts gives its window-averaged stress instead. Refused up
 * front, naming the line, if the method has neither. */
static int want_contacts(const gr_scene *sc, const gr_method_type *m, run_io *io, gr_err *err)
{
    char where[1200], who[1300];
    gr_scene_where(sc, "run", sc->run.contacts ? "contacts" : "stress", where, sizeof where);
    snprintf(who, sizeof who, "%s = yes", where);
    if (sc->run.contacts && gr_sim_require(m, GR_OP_CONTACTS, who, err))
        return err->code;
    if (sc->run.stress && !m->contacts && !m->stress) {
        gr_scene_where(sc, "run", "stress", where, sizeof where);
        return gr_fail(err, GR_EINPUT, "%s = yes needs contact networks or a window-averaged stress, which "
                                       "method '%s' does not give", where, m->name);
    }
    if (m->contacts && sc->run.stress && gr_sim_require(m, GR_OP_SNAPSHOT, who, err))
        return err->code;
    if ((sc->run.contacts || (sc->run.stress && m->contacts)) && !(io->net = gr_contacts_create(0, err)))
        return err->code;
    if (sc->run.stress && sc->run.field_nx > 0 &&
        !(io->sbuf = malloc((size_t)sc->run.field_nx * (size_t)sc->run.field_ny * 4 * sizeof *io->sbuf)))
        return gr_fail(err, GR_ERUN, "out of memory");
    return GR_OK;
}

/* The samples of a continued result that the restart keeps: those up to
 * the checkpoint's time, taken before it was saved; a checkpoint saved
 * before its time's samples (the initial state's) keeps only the earlier
 * ones, or its time's samples would be written twice. */
static double kept_until(const gr_scene *sc, gr_sim *st, const uint64_t k[3], double t0)
{
    const gr_runctl *r = &sc->run;
    double t = gr_sim_time(st), eps = 1e-9 * (r->until > 1 ? r->until : 1);
    int pending = t0 + (double)k[0] * r->observe_every <= t + eps ||
                  t0 + (double)k[1] * r->output_every <= t + eps;
    return pending ? t - 2 * eps : t;
}

/* A stop signal ended the loop between samples: the state is a good one,
 * saved as the checkpoint, and the message says what the files hold. */
static void said_stop(const run_io *io, const gr_run_opts *o, gr_sim *st, const uint64_t k[3], gr_err *err)
{
    gr_err e2 = {0};
    int saved = o->ckpt && gr_run_save(o->ckpt, st, k, &e2) == GR_OK;
    char frames[128] = "";
    if (io->last_frame >= 0)
        snprintf(frames, sizeof frames, " up to t = %g", io->last_frame);
    gr_fail(err, GR_ERUN, "stopped by %s at t = %g: %s holds %zu frames%s; %s%s%s", exp_stop_name(io->stopped),
            gr_sim_time(st), o->out, gr_h5md_frames(io->h), frames,
            saved ? "the checkpoint " : o->ckpt ? "the checkpoint could not be saved: " : "no checkpoint",
            saved ? o->ckpt : o->ckpt ? e2.msg : "",
            saved ? " holds the state at that time (the same command with --restart CHECKPOINT continues the run)"
                  : "");
}

/* A method without snapshots (a lattice): the picture of the final state is
 * its packing field on cells of about one grain diameter. */
static int plot_density(const char *png, gr_sim *st, gr_err *err)
{
    const gr_scene *sc = gr_sim_scene(st);
    int nx = (int)ceil(sc->width), ny = (int)ceil(sc->height);
    nx = nx > 1200 ? 1200 : nx < 1 ? 1 : nx, ny = ny > 1200 ? 1200 : ny < 1 ? 1 : ny;
    gr_field *f = gr_field_create(nx, ny, 0, 0, sc->width / nx, sc->height / ny, err);
    double *phi = f ? malloc(gr_field_ncells(f) * sizeof *phi) : NULL;
    int rc = !f || !phi ? (err->code ? err->code : gr_fail(err, GR_ERUN, "out of memory"))
                        : gr_sim_fields(st, f, 1.0, err);
    if (!rc) {
        gr_field_packing(f, phi);
        /* lo = hi: the percentile scale */
        gr_plot_grid g = {nx, ny, 0, 0, f->cx, f->cy, phi, "packing fraction (lattice: occupied channels / 7)", 0, 0};
        rc = gr_plot_field(png, &g, sc->width, sc->height, gr_sim_time(st), sc->name, err);
    }
    free(phi);
    gr_field_free(f);
    return rc;
}

int gr_run_scene(gr_scene *sc, const gr_method_type *m, const gr_run_opts *o, gr_err *err)
{
    run_io io = {.out_room = {o->out, 0, 0}, .ckpt_room = {o->ckpt, 0, 0}, .last_frame = -1};
    gr_sim *st = NULL;
    int rc = GR_OK;
    gr_particles *init = gr_particles_create(0, err);
    io.snap = gr_particles_create(0, err);
    if (!init || !io.snap) {
        rc = GR_ERUN;
        goto done;
    }
    char pushed[512];
    if ((rc = gr_run_check(sc, err)) || (rc = gr_init_particles_noted(sc, init, pushed, sizeof pushed, err)) ||
        (rc = gr_sim_create(m, sc, init, &st, err)))
        goto done;
    gr_sim_note(st, pushed);
    if ((sc->run.contacts || sc->run.stress) && (rc = want_contacts(sc, m, &io, err)))
        goto done;
    uint64_t k[3] = {0, 0, 1};
    int at_end = 0;
    double t0 = gr_sim_time(st);
    if (o->restart) {
        gr_runctl was;
        if ((rc = gr_run_load(o->restart, st, k, o, &was, err)))
            goto done;
        gr_run_resume_counters(sc, &was, gr_sim_time(st), t0, o->branch, k);
        /* Past the end: refused. At the end (killed while closing): the
         * result is reopened and closed, nothing run or written twice. */
        double eps = 1e-9 * (sc->run.until > 1 ? sc->run.until : 1);
        if (gr_sim_time(st) > sc->run.until + (o->branch ? -eps : eps)) {
            rc = gr_fail(err, GR_EINPUT, "--restart: %s holds t = %g, at or past the end time until = %g; nothing to run",
                         o->restart, gr_sim_time(st), sc->run.until);
            goto done;
        }
        at_end = gr_sim_time(st) >= sc->run.until - eps;
    }
    if (sc->run.field_nx > 0) {
        io.field = gr_field_create(sc->run.field_nx, sc->run.field_ny, 0, 0,
                                   sc->width / sc->run.field_nx, sc->height / sc->run.field_ny, err);
        io.buf = malloc(4 * (size_t)sc->run.field_nx * (size_t)sc->run.field_ny * sizeof *io.buf);
        if (!io.field || !io.buf) {
            rc = err->code ? err->code : gr_fail(err, GR_ERUN, "out of memory");
            goto done;
        }
    }
    /* A state that cannot be checkpointed is refused before the result
     * file exists (the first save would fail mid-run); this is also the
     * checkpoint of the initial state. */
    if (o->ckpt && (rc = gr_run_save(o->ckpt, st, k, err)))
        goto done;
    gr_h5md_opts ho = {.method = m->name, .seed = sc->seed, .force = o->force, .version = GRANO_VERSION,
                       .obs = gr_method_observables(m), .obs_skip = gr_sim_obs_skip(st),
                       .derived = gr_sim_notes(st)};
    if (o->note && gr_sim_notes(st)[0])
        o->note(o->warn_ctx, gr_sim_notes(st));
    /* A restart continues its result file: the frames before the
     * checkpoint stay, those after it are written again. */
    struct stat ost;
    int cont = o->restart && !o->branch && stat(o->out, &ost) == 0;
    ho.any_text = cont;
    if (!(io.h = cont ? gr_h5md_reopen(o->out, sc, &ho, kept_until(sc, st, k, t0), err)
                      : gr_h5md_create(o->out, sc, &ho, err))) {
        rc = err->code;
        goto done;
    }
    exp_stop_install();
    rc = at_end ? GR_OK : loop(sc, st, &io, o, k, t0, err);
    if (!io.strict_stop)
        sum_limits(st, o);
    if (io.stopped) {
        said_stop(&io, o, st, k, err);
    } else if (rc == GR_ERUN && o->ckpt && !io.strict_stop) {
        /* The backend stopped at its last good step: keep that state. */
        gr_err e2 = {0};
        if (gr_run_save(o->ckpt, st, k, &e2) == GR_OK)
            gr_err_prefix(err, "(last good state saved in %s) ", o->ckpt);
    } else if (rc == GR_OK && o->ckpt) {
        rc = gr_run_save(o->ckpt, st, k, err);
    }
    if (rc == GR_OK && o->snapshot && !m->snapshot)
        rc = plot_density(o->snapshot, st, err);
    else if (rc == GR_OK && o->snapshot) {
        if (!(rc = gr_sim_snapshot(st, io.snap, err)))
            rc = gr_plot_snapshot(o->snapshot, io.snap, sc->width, sc->height, gr_sim_time(st), sc->name, err);
    }
    {
        gr_err e2 = {0};
        int crc = gr_h5md_close(io.h, rc ? &e2 : err);
        io.h = NULL;
        if (!rc)
            rc = crc;
    }
done:
    gr_h5md_free(io.h);
    free(io.buf);
    free(io.sbuf);
    gr_field_free(io.field);
    gr_contacts_free(io.net);
    gr_sim_free(st);
    gr_particles_free(init);
    gr_particles_free(io.snap);
    return rc;
}
