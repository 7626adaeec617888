/* grano bench cd: the contact dynamics backend on a resting pile and a
 * flowing silo against N: steps per second with warm start, contact
 * updates (single-contact solves in the sweeps) per second on cold solves
 * of one step's local problem, the warm start's factor on sweeps, and, when
 * Siconos is built in (GR_BENCH_SICONOS, tests/oracle/fc2d.c compiled into
 * grano), the time of fc2d_nsgs_dense on the same exported problem over
 * cd's own cold solve, in alternating rounds. */
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cd/cd_int.h"
#include "clock.h"
#include "cmd.h"
#include "init.h"
#include "method.h"
#include "opts.h"
#ifdef GR_BENCH_SICONOS
#include "fc2d.h"
#endif

/* Dense W costs (2 nc)^2 doubles and fc2d_nsgs_dense O(nc^2) per sweep:
 * above this many contacts the Siconos comparison is left out. */
#define SICONOS_MAX_CONTACTS 2500

typedef struct {
    long ns[16];
    int nn, quick, rounds;
    long steps;
    double tol, settle;
    int given_n;
    int cases;        /* bit 0: pile, bit 1: silo */
    char extra[512];  /* KEY = VALUE lines added to [cd] by --set */
} bc_opts;

typedef struct {
    const char *name;
    long n;
    double updates_per_s, steps_per_s, iter_per_step, siconos_ratio;
    double cold_sweeps; /* one cold solve of a step, -1 if it hit the cap */
} bc_result;

static void usage(FILE *f)
{
    fprintf(f,
            "usage: grano bench cd [--n N1,N2,...] [--steps S] [--settle T] [--tol E] [--rounds R] [--quick]\n"
            "                      [--case pile|silo] [--set KEY=VALUE]...\n\n"
            "Polydisperse disks (d = 0.8..1.2, mu = 0.5, e = 0, dt = 2e-3, [cd] tol E, default 1e-4) in two\n"
            "cases: a resting pile in a box (lattice start, settled for T tau, default 20) and a silo with walls\n"
            "of fixed grains, an orifice of 6 d and reinsertion (flowing for T/2 tau before timing).\n"
            "Defaults: --n 500,2000,8000 --steps 200 --rounds 5; --quick: --n 100 --steps 20 --settle 2 --rounds 3.\n"
            "Per case: S timed steps with warm start (steps/s, sweeps per step), then one step's local\n"
            "problem solved cold by cd (contact updates per second, in the sweeps) and, when Siconos is\n"
            "built in and it has at most %d closed contacts, by fc2d_nsgs_dense to the same tolerance,\n"
            "R alternating rounds (siconos_ratio: median of time(Siconos) / time(cd)).\n"
            "Prints: RESULT method=cd case=C n=N contact_updates_per_s=X steps_per_s=Y iterations_per_step=I\n"
            "        [siconos_ratio=R], and for the pile WARM ... factor=F (cold over warm sweeps per step).\n"
            "--case runs one case only; --set KEY=VALUE sets a [cd] key (relax, order, ...) for every step.\n",
            SICONOS_MAX_CONTACTS);
}

static int parse_list(const char *s, long *out, int cap)
{
    int n = 0;
    char *end;
    while (*s && n < cap) {
        out[n] = strtol(s, &end, 10);
        if (end == s || out[n] < 10)
            return -1;
        n++;
        if (*end && *end != ',')
            return -1;
        s = *end ? end + 1 : end;
    }
    return n;
}

static int cd_option(void *ctx, int id, const char *arg, gr_err *err)
{
    bc_opts *o = ctx;
    long v;
    switch (id) {
    case 'Q': o->quick = 1; return 0;
    case 'c':
        if (strcmp(arg, "pile") && strcmp(arg, "silo"))
            return gr_fail(err, GR_EINPUT, "--case: '%s' is neither pile nor silo", arg);
        o->cases = strcmp(arg, "pile") ? 2 : 1;
        return 0;
    case 'k': {
        const char *eq = strchr(arg, '=');
        size_t used = strlen(o->extra);
        if (!eq || eq == arg)
            return gr_fail(err, GR_EINPUT, "--set: '%s' is not KEY=VALUE", arg);
        if (used + strlen(arg) + 4 >= sizeof o->extra)
            return gr_fail(err, GR_EINPUT, "--set: too many keys");
        snprintf(o->extra + used, sizeof o->extra - used, "%.*s = %s\n", (int)(eq - arg), arg, eq + 1);
        return 0;
    }
    case 'n':
        if ((o->nn = parse_list(arg, o->ns, 16)) < 1)
            return gr_fail(err, GR_EINPUT, "--n: '%s' is not a list of integers >= 10", arg);
        o->given_n = 1;
        return 0;
    case 's': return exp_opt_long("--steps", arg, 1, LONG_MAX, &o->steps, err);
    case 'S': return exp_opt_double("--settle", arg, 0, 1e12, &o->settle, err);
    case 't': return exp_opt_double("--tol", arg, 1e-300, 1, &o->tol, err);
    case 'r':
        if (exp_opt_long("--rounds", arg, 1, 1000, &v, err))
            return err->code;
        o->rounds = (int)v;
        return 0;
    default: return gr_fail(err, GR_EINPUT, "unknown option");
    }
}

/* Parse argv into *o; -1 to go on, else the exit code (0 after --help). */
static int parse_args(int argc, char **argv, bc_opts *o)
{
    static const struct option opts[] = {
        {"quick", no_argument, NULL, 'Q'}, {"n", required_argument, NULL, 'n'},
        {"steps", required_argument, NULL, 's'}, {"settle", required_argument, NULL, 'S'},
        {"tol", required_argument, NULL, 't'}, {"rounds", required_argument, NULL, 'r'},
        {"case", required_argument, NULL, 'c'}, {"set", required_argument, NULL, 'k'},
        {NULL, 0, NULL, 0}};
    *o = (bc_opts){{500, 2000, 8000}, 3, 0, 5, 200, 1e-4, 20.0, 0, 3, ""};
    int first = 0;
    int rc = exp_getopt_main("bench cd", argc, argv, opts, cd_option, o, usage, 0, &first);
    if (rc >= 0)
        return rc;
    int given_n = o->given_n;
    if (o->quick && !given_n)
        o->ns[0] = 100, o->nn = 1;
    if (o->quick)
        o->steps = 20, o->settle = 2, o->rounds = 3;
    if (o->nn < 1 || o->steps < 1 || !(o->settle >= 0) || !(o->tol > 0) || o->rounds < 1) {
        fprintf(stderr, "grano bench cd: bad --n, --steps, --settle, --tol or --rounds\n");
        return 2;
    }
    return -1;
}

/* The case's scene: polydisperse grains from a loose lattice (no overlap
 * whatever the diameters) with random velocities (so that columns do not
 * stay stacked), in a box (pile) or a silo of fixed-grain walls
 * emptying through an orifice into its reinsertion band (silo). */
static gr_scene *bench_cd_scene(const char *name, long n, double tol, const char *extra, gr_err *err)
{
    static const char *const ext[] = {"cd", NULL};
    char text[2560], geo[768];
    double site = 1.05 * 1.2 * 1.2; /* the reader's lattice pitch: spacing x d_max x (1 + poly) */
    int silo = !strcmp(name, "silo");
    double w = ceil((silo ? 1.0 : 1.5) * sqrt((double)n)) + 2;
    double rows = ceil((double)n / floor((w - 1) / site)) + 1, fill = rows * site + 1;
    if (silo)
        snprintf(geo, sizeof geo,
                 "[domain]\nwidth = %g\nheight = %g\nbottom = open\ngravity = 1\n"
                 "[silo]\nleft = 2\nwidth = %g\nheight = %g\nbase = 5\norifice = 6\nopen_time = 0\n"
                 "walls = grains\nreinsert = yes\n[init]\nkind = lattice\nspacing = 1.05\nregion = 2.5 6 %g %g\nvelocity = gaussian\nv0 = 1\n",
                 w + 4, fill + 12, w, fill + 5, w + 1.5, 6 + fill);
    else
        snprintf(geo, sizeof geo,
                 "[domain]\nwidth = %g\nheight = %g\ngravity = 1\n"
                 "[init]\nkind = lattice\nspacing = 1.05\nregion = 0 0 %g %g\nvelocity = gaussian\nv0 = 1\n",
                 w, fill + 4, w, fill);
    snprintf(text, sizeof text,
             "[scene]\nname = bench-cd-%s\nseed = 3\n%s"
             "[material]\ntangential = coulomb\nmu = 0.5\n"
             "[species]\ncount = %ld\npolydispersity = 0.2\n"
             "[cd]\ndt = 2e-3\ntol = %.17g\nmax_iter = 100000\n%s",
             name, geo, n, tol, extra);
    return gr_scene_parse(text, "bench-cd", ext, err);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Timed steps with warm start: steps/s and sweeps per step, with the
 * median and largest step on stderr (the mean can be a few hard steps). */
static int time_steps(gr_cd *d, long steps, bc_result *r, gr_err *err)
{
    uint64_t s0 = d->sweeps;
    double *per = malloc((size_t)steps * sizeof *per);
    if (!per)
        return gr_fail(err, GR_ERUN, "out of memory");
    double t0 = exp_wall_seconds();
    for (long k = 0; k < steps; k++) {
        uint64_t sk = d->sweeps;
        if (gr_cd_step(d, err)) {
            free(per);
            return err->code;
        }
        per[k] = (double)(d->sweeps - sk);
    }
    double t = exp_wall_seconds() - t0;
    r->steps_per_s = (double)steps / t;
    r->iter_per_step = (double)(d->sweeps - s0) / (double)steps;
    qsort(per, (size_t)steps, sizeof *per, cmp_double);
    fprintf(stderr,
            "cd %s n=%ld: %ld steps in %.3f s, %.2f sweeps per step (median %.0f, largest %.0f), %zu contacts, "
            "largest overlap %.2e d; %llu of the %llu steps since t = 0 left a contact open by the flip rule\n",
            r->name, r->n, steps, t, r->iter_per_step, per[steps / 2], per[steps - 1], d->prev.n, d->max_ovl,
            (unsigned long long)d->forced, (unsigned long long)d->step);
    free(per);
    return GR_OK;
}

/* The step's free velocities, kept so that every cold solve starts alike. */
typedef struct {
    double *vx, *vy, *w;
} free_vel;

/* One cold solve of the begun step: free velocities, zero impulses. */
static int cold_solve(gr_cd *d, const free_vel *fv, double *sec, long *sweeps, gr_err *err)
{
    memcpy(d->vx, fv->vx, d->n * sizeof *d->vx);
    memcpy(d->vy, fv->vy, d->n * sizeof *d->vy);
    memcpy(d->w, fv->w, d->n * sizeof *d->w);
    for (size_t k = 0; k < d->cur.n; k++)
        d->cur.c[k].rn = d->cur.c[k].rt = 0;
    gr_cd_solve_info si;
    double t0 = exp_wall_seconds();
    if (gr_cd_solve(d, &si, err))
        return err->code;
    *sec = exp_wall_seconds() - t0;
    *sweeps = si.converged ? si.sweeps : -si.sweeps;
    return GR_OK;
}

#ifdef GR_BENCH_SICONOS
/* cd's residual (fc2d.h's rule) on the exported problem, from its impulses. */
static double cd_residual(const gr_cd *d, gr_cd_local *lp, gr_err *err)
{
    gr_fc2d_res res;
    for (int a = 0; a < lp->nc; a++)
        lp->r[2 * a] = d->cur.c[lp->k[a]].rn, lp->r[2 * a + 1] = d->cur.c[lp->k[a]].rt;
    return gr_fc2d_residual(lp->nc, lp->W, lp->q, lp->mu, lp->r, NULL, &res, err) ? NAN : res.total;
}

/* The two criteria differ (fc2d.h, docs/methods/cd.md): at the same tol
 * Siconos may stop at a smaller residual. Tighten cd's tol by tens (from
 * tol itself) until its residual is at most Siconos's, and report that
 * time ratio too. Each of cd's answers is judged on the problem exported
 * from it: contacts at the edge of Jean's rule may close or open. */
static void matched_residual(gr_cd *d, const free_vel *fv, double target, double t_sic, const bc_result *r,
                             gr_err *err)
{
    double tol = d->par.tol, tc = 0, res = INFINITY;
    long sw = 0, cap = d->par.max_iter;
    d->par.max_iter = 1000000;
    for (int k = 0; k <= 6 && !(res <= target); k++) {
        gr_cd_local lp;
        d->par.tol = tol * pow(10, -k);
        if (cold_solve(d, fv, &tc, &sw, err) || gr_cd_local_export(d, 1, &lp, err))
            break;
        res = cd_residual(d, &lp, err);
        gr_cd_local_free(&lp);
    }
    fprintf(stderr, "cd %s n=%ld: cd at tol %.0e: %ld sweeps %.4g s, residual %.2e (Siconos's %.2e): ratio %.3g\n",
            r->name, r->n, d->par.tol, labs(sw), tc, res, target, t_sic / tc);
    d->par.tol = tol, d->par.max_iter = cap;
}

/* Rounds of cd's cold solve then fc2d_nsgs_dense on the problem exported
 * from cd's solution (its closed contacts, q from the free velocities), to
 * the same tolerance; the median of the time ratios, and both residuals
 * by the solver-independent rule of fc2d.h on stderr. */
static int siconos_rounds(gr_cd *d, const free_vel *fv, int rounds, bc_result *r, double *upd, double *sec,
                          gr_err *err)
{
    gr_cd_local lp;
    if (gr_cd_local_export(d, 1, &lp, err))
        return err->code;
    if (lp.nc > SICONOS_MAX_CONTACTS || lp.nc == 0) {
        fprintf(stderr, "cd %s n=%ld: %d closed contacts, no Siconos comparison (bound %d)\n", r->name, r->n,
                lp.nc, SICONOS_MAX_CONTACTS);
        gr_cd_local_free(&lp);
        return GR_OK;
    }
    size_t n2 = 2 * (size_t)lp.nc;
    double *rs = malloc(n2 * sizeof *rs), *us = malloc(n2 * sizeof *us), ratio[64], tc = 0;
    long sw = 0;
    gr_fc2d_stats st = {0};
    int rc = rs && us ? GR_OK : gr_fail(err, GR_ERUN, "out of memory");
    for (int k = 0; k < rounds && k < 64 && !rc; k++) {
        if (!(rc = cold_solve(d, fv, &tc, &sw, err)))
            rc = gr_fc2d_solve(lp.nc, lp.W, lp.q, lp.mu, d->par.tol, 10000000, rs, us, &st, err);
        *upd += (double)labs(sw) * (double)d->cur.n, *sec += tc;
        ratio[k] = st.seconds / tc;
    }
    if (!rc) {
        gr_fc2d_res rsic;
        double rcd = cd_residual(d, &lp, err);
        gr_fc2d_residual(lp.nc, lp.W, lp.q, lp.mu, rs, NULL, &rsic, err);
        int m = rounds < 64 ? rounds : 64;
        qsort(ratio, (size_t)m, sizeof *ratio, cmp_double);
        r->siconos_ratio = m % 2 ? ratio[m / 2] : 0.5 * (ratio[m / 2 - 1] + ratio[m / 2]);
        fprintf(stderr,
                "cd %s n=%ld: %d closed contacts of %zu; cd %ld sweeps %.4g s, residual %.2e; fc2d_nsgs_dense "
                "%d sweeps %.4g s, residual %.2e; ratio median of %d rounds %.3g (min %.3g, max %.3g)\n",
                r->name, r->n, lp.nc, d->cur.n, labs(sw), tc, rcd, st.iterations, st.seconds, rsic.total, m,
                r->siconos_ratio, ratio[0], ratio[m - 1]);
        matched_residual(d, fv, rsic.total, st.seconds, r, err);
    }
    free(rs);
    free(us);
    gr_cd_local_free(&lp);
    return rc;
}
#endif

/* One step begun and solved cold (contact updates per second over every
 * cold solve made), then the Siconos rounds when built in. */
static int cold_rates(gr_cd *d, int rounds, bc_result *r, gr_err *err)
{
    if (gr_cd_begin(d, err))
        return err->code;
    size_t n = d->n;
    free_vel fv = {malloc(n * sizeof(double)), malloc(n * sizeof(double)), malloc(n * sizeof(double))};
    int rc = fv.vx && fv.vy && fv.w ? GR_OK : gr_fail(err, GR_ERUN, "out of memory");
    double sec = 0, upd = 0;
    long sw = 0;
    if (!rc) {
        memcpy(fv.vx, d->vx, n * sizeof *fv.vx);
        memcpy(fv.vy, d->vy, n * sizeof *fv.vy);
        memcpy(fv.w, d->w, n * sizeof *fv.w);
        rc = cold_solve(d, &fv, &sec, &sw, err);
        upd = (double)labs(sw) * (double)d->cur.n;
        r->cold_sweeps = sw > 0 ? (double)sw : -1;
    }
    r->siconos_ratio = NAN;
#ifdef GR_BENCH_SICONOS
    if (!rc)
        rc = siconos_rounds(d, &fv, rounds, r, &upd, &sec, err);
#else
    (void)rounds;
#endif
    r->updates_per_s = upd / sec;
    free(fv.vx);
    free(fv.vy);
    free(fv.w);
    return rc;
}

/* Settle (loose tolerance, then 0.5 tau at the bench's), time the steps,
 * then the cold solves. */
static int run_case(const char *name, long n, const bc_opts *o, bc_result *r, gr_err *err)
{
    *r = (bc_result){.name = name, .n = n};
    gr_scene *sc = bench_cd_scene(name, n, o->tol, o->extra, err);
    gr_particles *p = sc ? gr_particles_create(0, err) : NULL;
    gr_sim *s = NULL;
    int rc = GR_OK;
    if (!p || gr_init_particles(sc, p, err) || gr_sim_create(gr_method_find("cd"), sc, p, &s, err)) {
        rc = err->code;
        goto done;
    }
    gr_cd *d = gr_sim_state(s);
    double t_settle = strcmp(name, "silo") ? o->settle : 0.5 * o->settle;
    d->par.tol = fmax(o->tol, 1e-3);
    if ((rc = gr_cd_advance(d, t_settle, 0, err)))
        goto done;
    d->par.tol = o->tol;
    if ((rc = gr_cd_advance(d, d->t + 0.5, 0, err)) || (rc = time_steps(d, o->steps, r, err)))
        goto done;
    d->par.max_iter = 20000;
    rc = cold_rates(d, o->rounds, r, err);
done:
    gr_sim_free(s);
    gr_particles_free(p);
    gr_scene_free(sc);
    return rc;
}

static void print_case(const bc_result *r)
{
    printf("RESULT method=cd case=%s n=%ld contact_updates_per_s=%.4g steps_per_s=%.4g iterations_per_step=%.3g",
           r->name, r->n, r->updates_per_s, r->steps_per_s, r->iter_per_step);
    if (isfinite(r->siconos_ratio))
        printf(" siconos_ratio=%.3g", r->siconos_ratio);
    printf("\n");
    if (!strcmp(r->name, "pile") && r->cold_sweeps > 0)
        printf("WARM method=cd case=pile n=%ld warm_iterations_per_step=%.3g cold_iterations_per_step=%.0f factor=%.3g\n",
               r->n, r->iter_per_step, r->cold_sweeps, r->cold_sweeps / r->iter_per_step);
    fflush(stdout);
}

int bench_cd(int argc, char **argv)
{
    bc_opts o;
    int rc = parse_args(argc, argv, &o);
    if (rc >= 0)
        return rc;
    static const char *const cases[] = {"pile", "silo"};
    gr_err err = {0};
    for (int c = 0; c < 2; c++) {
        for (int k = 0; k < o.nn && (o.cases >> c & 1); k++) {
            bc_result r;
            if (run_case(cases[c], o.ns[k], &o, &r, &err)) {
                fprintf(stderr, "grano bench cd: %s n = %ld: %s\n", cases[c], o.ns[k], err.msg);
                return err.code ? err.code : 1;
            }
            print_case(&r);
        }
    }
    return 0;
}
