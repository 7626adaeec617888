/* grano course: the three exercises of the lecture slides on event-driven
 * hard disks (docs/course.md), through the method interface: relaxation to
 * the Maxwell distribution, wall pressure against density and against V0,
 * homogeneous cooling. Each writes an HDF5 file, a plain table and PNG
 * figures; this file holds the command and what the exercises share. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <gsl/gsl_errno.h>

#include "cmd.h"
#include "course.h"
#include "init.h"

int course_sim(const char *text, const course_opts *o, const gr_particles *init, gr_scene **psc,
               gr_sim **ps, gr_err *err)
{
    const char *names[GR_MAX_METHODS + 1];
    gr_method_names(names, GR_MAX_METHODS + 1);
    char full[4096];
    /* the algorithm is edmd's own key; other methods run on their defaults */
    if (!strcmp(o->m->name, "edmd"))
        snprintf(full, sizeof full, "%s[edmd]\nalgorithm = %s\n", text, o->naive ? "naive" : "tree");
    else
        snprintf(full, sizeof full, "%s", text);
    gr_scene *sc = gr_scene_parse(full, "(grano course)", names, err);
    if (!sc)
        return err->code;
    gr_particles *p = init ? NULL : gr_particles_create(0, err);
    int rc = !init && (!p || gr_init_particles(sc, p, err));
    if (!rc)
        rc = gr_sim_create(o->m, sc, init ? init : p, ps, err);
    gr_particles_free(p);
    if (rc) {
        gr_scene_free(sc);
        return err->code ? err->code : GR_ERUN;
    }
    *psc = sc;
    return GR_OK;
}

int course_pairs(const gr_sim *s, const char *who, uint64_t *pairs, gr_err *err)
{
    gr_counter c[GR_MAX_COUNTERS];
    size_t n = gr_sim_counters(s, c, GR_MAX_COUNTERS);
    for (size_t k = 0; k < n; k++) {
        if (!strcmp(c[k].name, "pair_collisions")) {
            *pairs = c[k].value;
            return GR_OK;
        }
    }
    return gr_fail(err, GR_EINPUT,
                   "%s counts disk-disk collisions (the counter 'pair_collisions'), which method '%s' "
                   "does not give",
                   who, gr_sim_type(s)->name);
}

int course_advance_pairs(gr_sim *s, uint64_t target, gr_err *err)
{
    uint64_t pairs;
    /* an event-driven method takes events as its steps, so the limit never
     * overshoots the target */
    for (;;) {
        if (course_pairs(s, "grano course", &pairs, err))
            return err->code;
        if (pairs >= target)
            return GR_OK;
        if (gr_sim_advance(s, INFINITY, target - pairs, err))
            return err->code;
    }
}

/* Refuse, before any output, a method that does not count disk-disk
 * collisions: a one-disk box is enough to ask it. */
static int require_pairs(const course_opts *o, const char *ex, gr_err *err)
{
    gr_scene *sc;
    gr_sim *s;
    if (course_sim("[domain]\nwidth = 4\nheight = 4\n[material]\nrestitution = 1\n[species]\ncount = 1\n"
                   "[init]\nkind = lattice\nvelocity = speed\nv0 = 1\n",
                   o, NULL, &sc, &s, err))
        return err->code;
    char who[64];
    snprintf(who, sizeof who, "the exercise%s", strcmp(ex, "all") ? "" : "s");
    uint64_t pairs;
    int rc = course_pairs(s, who, &pairs, err);
    gr_sim_free(s);
    gr_scene_free(sc);
    return rc;
}

gr_h5md *course_h5(const course_opts *o, const char *name, const gr_scene *sc, gr_err *err)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/%s", o->out, name);
    gr_h5md_opts ho = {.method = o->m->name, .seed = o->seed, .force = 1, .no_xdmf = 1};
    return gr_h5md_create(path, sc, &ho, err);
}

const char *course_how(const course_opts *o)
{
    if (strcmp(o->m->name, "edmd"))
        return o->m->name;
    return o->naive ? "algorithm naive (v1.0)" : "algorithm tree";
}

double course_chi(double eta)
{
    double u = 1 - eta;
    return (1 - 7 * eta / 16) / (u * u) - eta * eta * eta / (128 * u * u * u * u);
}

static void usage(FILE *f)
{
    fprintf(f, "usage: grano course EXERCISE [--method M] [--quick] [--out DIR] [--naive|--tree]\n"
               "                    [--alpha A] [--seed S]\n\n"
               "The exercises of the lecture slides on event-driven hard disks (docs/course.md):\n"
               "  maxwell    speed histograms after N/2, N, 2N, 3N, 10N collisions against Maxwell's law\n"
               "  pressure   wall pressure against the density n = N/L^2 and against V0\n"
               "  cooling    homogeneous cooling of inelastic disks against Haff's law (--alpha, default 0.9)\n"
               "  all        the three in turn\n"
               "--method M: the method (default edmd); every exercise counts disk-disk collisions, so\n"
               "the method must give the counter 'pair_collisions'. --out DIR: where the .h5, .dat\n"
               "and .png files go (default course-out); --quick: small runs for tests; --naive: the\n"
               "slides' algorithm v1.0 (edmd's algorithm = naive, the default for maxwell) instead\n"
               "of the event tree; --tree forces the tree.\n");
}

/* Options into o; 0, or the exit code of a bad flag (reported here). */
static int parse(int argc, char **argv, course_opts *o)
{
    const char *method = "edmd";
    for (int a = 2; a < argc; a++) {
        if (!strcmp(argv[a], "--quick"))
            o->quick = 1;
        else if (!strcmp(argv[a], "--naive"))
            o->naive = 1;
        else if (!strcmp(argv[a], "--tree"))
            o->naive = 0;
        else if (a + 1 < argc && !strcmp(argv[a], "--out"))
            o->out = argv[++a];
        else if (a + 1 < argc && !strcmp(argv[a], "--method"))
            method = argv[++a];
        else if (a + 1 < argc && !strcmp(argv[a], "--alpha"))
            o->alpha = atof(argv[++a]);
        else if (a + 1 < argc && !strcmp(argv[a], "--seed"))
            o->seed = strtoul(argv[++a], NULL, 10);
        else {
            fprintf(stderr, "grano course: unknown or incomplete option '%s'\n", argv[a]);
            usage(stderr);
            return 2;
        }
    }
    gr_err err = {0};
    if (gr_method_lookup(method, "--method", &o->m, &err)) {
        fprintf(stderr, "grano course: %s\n", err.msg);
        return 2;
    }
    if (o->naive >= 0 && strcmp(o->m->name, "edmd")) {
        fprintf(stderr, "grano course: --%s selects edmd's algorithm, which method '%s' does not have\n",
                o->naive ? "naive" : "tree", o->m->name);
        return 2;
    }
    if (!(o->alpha > 0 && o->alpha < 1)) {
        fprintf(stderr, "grano course: --alpha must be in (0, 1), got %g\n", o->alpha);
        return 2;
    }
    return 0;
}

int cmd_course(int argc, char **argv)
{
    if (argc < 2 || !strcmp(argv[1], "--help") || !strcmp(argv[1], "-h")) {
        usage(argc < 2 ? stderr : stdout);
        return argc < 2 ? 2 : 0;
    }
    const char *ex = argv[1];
    course_opts o = {.out = "course-out", .quick = 0, .naive = -1, .alpha = 0.9, .seed = 1};
    int rc = parse(argc, argv, &o);
    if (rc)
        return rc;
    int all = !strcmp(ex, "all");
    if (!all && strcmp(ex, "maxwell") && strcmp(ex, "pressure") && strcmp(ex, "cooling")) {
        fprintf(stderr, "grano course: unknown exercise '%s'\n", ex);
        usage(stderr);
        return 2;
    }
    gsl_set_error_handler_off();
    gr_err err = {0};
    if ((rc = require_pairs(&o, ex, &err))) {
        fprintf(stderr, "grano course %s: %s\n", ex, err.msg);
        return rc;
    }
    if (mkdir(o.out, 0777) && errno != EEXIST) {
        fprintf(stderr, "grano course: cannot create %s: %s\n", o.out, strerror(errno));
        return 2;
    }
    int naive = o.naive;
    if (!rc && (all || !strcmp(ex, "maxwell"))) {
        /* the first exercise is the slides' v1.0 */
        o.naive = naive < 0 ? !strcmp(o.m->name, "edmd") : naive;
        rc = course_maxwell(&o, &err);
    }
    o.naive = naive < 0 ? 0 : naive;
    if (!rc && (all || !strcmp(ex, "pressure")))
        rc = course_pressure(&o, &err);
    if (!rc && (all || !strcmp(ex, "cooling")))
        rc = course_cooling(&o, &err);
    if (rc) {
        fprintf(stderr, "grano course %s: %s\n", ex, err.msg);
        return rc;
    }
    return 0;
}
