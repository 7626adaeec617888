/* grano course: the three exercises of the lecture slides on event-driven
 * hard disks (docs/course.md), through the method interface: relaxation to
 * the Maxwell distribution, wall pressure against density and against V0,
 * homogeneous cooling. Each writes an HDF5 file, a plain table and PNG
 * figures; this file holds the command (course_common.c what they share). */
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
        o.pg = gr_progress_create(stderr, 0, 1, 1.0);
        rc = course_maxwell(&o, &err);
        gr_progress_free(o.pg);
    }
    o.naive = naive < 0 ? 0 : naive;
    if (!rc && (all || !strcmp(ex, "pressure"))) {
        o.pg = gr_progress_create(stderr, 0, 1, 1.0);
        rc = course_pressure(&o, &err);
        gr_progress_free(o.pg);
    }
    if (!rc && (all || !strcmp(ex, "cooling"))) {
        o.pg = gr_progress_create(stderr, 0, 1, 1.0);
        rc = course_cooling(&o, &err);
        gr_progress_free(o.pg);
    }
    if (rc) {
        fprintf(stderr, "grano course %s: %s\n", ex, err.msg);
        return rc;
    }
    return 0;
}
