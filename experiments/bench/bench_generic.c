/* grano bench METHOD for a method without a bench of its own (and
 * grano bench --generic METHOD for any): a box of N grains with Gaussian
 * velocities at packing fraction 0.1, run through gr_sim alone for a
 * simulated time, timed on the wall and CPU clocks. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_generic.h"
#include "clock.h"
#include "init.h"
#include "opts.h"

typedef struct {
    long n;
    double until;
    int quick;
} bg_opts;

static void usage(FILE *f)
{
    fprintf(f,
            "usage: grano bench --generic METHOD [--n N] [--until T] [--quick]\n"
            "       (grano bench METHOD for a method without a bench of its own)\n\n"
            "The generic bench, through the method interface alone: N grains (default 1000; --quick 200)\n"
            "of diameter 1 in a closed box at packing fraction 0.1, Gaussian velocities (v0 = 1), no\n"
            "gravity, the method's default parameters, run for T (default 10 tau; --quick 1). Prints:\n"
            "  RESULT method=M bench=generic n=N steps=S sim_time=T wall_s=W cpu_s=C steps_per_s=X\n"
            "         grain_steps_per_s=Y\n"
            "(steps: the method's own, time steps or events).\n");
}

static int bg_option(void *ctx, int id, const char *arg, gr_err *err)
{
    bg_opts *o = ctx;
    switch (id) {
    case 'n': return exp_opt_long("--n", arg, 1, 10000000, &o->n, err);
    case 'u': return exp_opt_double("--until", arg, 1e-9, 1e9, &o->until, err);
    case 'Q': o->quick = 1; return 0;
    default: return gr_fail(err, GR_EINPUT, "unknown option");
    }
}

static gr_scene *bg_scene(const gr_method_type *m, long n, gr_err *err)
{
    double side = sqrt((double)n * M_PI / 4 / 0.1);
    char text[1024];
    snprintf(text, sizeof text,
             "[scene]\nname = bench-generic\nseed = 1\n[domain]\nwidth = %.17g\nheight = %.17g\n"
             "[material]\nkn = 1e4\n[species]\ncount = %ld\n[init]\nkind = random\nvelocity = gaussian\nv0 = 1\n",
             side, side, n);
    const char *sections[] = {m->name, NULL};
    return gr_scene_parse(text, "bench-generic", sections, err);
}

static int bg_run(const gr_method_type *m, long n, double until, gr_err *err)
{
    gr_scene *sc = bg_scene(m, n, err);
    gr_particles *p = sc ? gr_particles_create(0, err) : NULL;
    gr_sim *s = NULL;
    if (p && !gr_init_particles(sc, p, err))
        gr_sim_create(m, sc, p, &s, err);
    gr_particles_free(p);
    gr_obs o;
    double w0 = exp_wall_seconds(), c0 = exp_cpu_seconds();
    int rc = s ? gr_sim_advance(s, until, 0, err) : err->code;
    /* the clocks stop before the observation, which is not the method's work */
    double wall = exp_wall_seconds() - w0, cpu = exp_cpu_seconds() - c0;
    if (s && !rc && !gr_sim_observe(s, &o, err)) {
        printf("RESULT method=%s bench=generic n=%ld steps=%llu sim_time=%.6g wall_s=%.4g cpu_s=%.4g "
               "steps_per_s=%.4g grain_steps_per_s=%.4g\n",
               m->name, n, (unsigned long long)o.steps, gr_sim_time(s), wall, cpu, (double)o.steps / wall,
               (double)o.steps * (double)n / wall);
    }
    gr_sim_free(s);
    gr_scene_free(sc);
    return err->code;
}

int bench_generic(const gr_method_type *m, int argc, char **argv)
{
    static const struct option opts[] = {{"n", required_argument, NULL, 'n'},
                                         {"until", required_argument, NULL, 'u'},
                                         {"quick", no_argument, NULL, 'Q'},
                                         {NULL, 0, NULL, 0}};
    bg_opts o = {0};
    char cmd[96];
    snprintf(cmd, sizeof cmd, "bench %s", m->name);
    int first, rc = exp_getopt_main(cmd, argc, argv, opts, bg_option, &o, usage, 0, &first);
    if (rc >= 0)
        return rc;
    long n = o.n ? o.n : o.quick ? 200 : 1000;
    double until = o.until > 0 ? o.until : o.quick ? 1 : 10;
    gr_err err = {0};
    if (bg_run(m, n, until, &err)) {
        fprintf(stderr, "grano %s: %s\n", cmd, err.msg);
        return err.code;
    }
    return 0;
}
