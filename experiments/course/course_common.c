/* What the course exercises share: building an instance from scene text,
 * counting pair collisions through the method's named counter, the result
 * file. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

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
    /* the algorithm is edmd's own key; dsmc runs the Enskog mode, since the
     * exercises' disks are hard disks at a finite packing fraction (the
     * references use Enskog's chi), with cells of 10 d, on which its rate
     * is within 1 % (docs/methods/dsmc.md); other methods on their defaults */
    if (!strcmp(o->m->name, "edmd"))
        snprintf(full, sizeof full, "%s[edmd]\nalgorithm = %s\n", text, o->naive ? "naive" : "tree");
    else if (!strcmp(o->m->name, "dsmc"))
        snprintf(full, sizeof full, "%s[dsmc]\nenskog = yes\ncell = 10\n", text);
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
    if (gr_sim_counter(s, "pair_collisions", pairs))
        return GR_OK;
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

gr_h5md *course_h5(const course_opts *o, const char *name, const gr_scene *sc, gr_err *err)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/%s.part", o->out, name);
    gr_h5md_opts ho = {.method = o->m->name, .seed = o->seed, .force = 1, .no_xdmf = 1};
    return gr_h5md_create(path, sc, &ho, err);
}

int course_h5_close(gr_h5md *h, const course_opts *o, const char *name, int rc, gr_err *err)
{
    char path[1200], part[1300];
    snprintf(path, sizeof path, "%s/%s", o->out, name);
    snprintf(part, sizeof part, "%s.part", path);
    if (!h)
        return rc ? rc : GR_ERUN;
    gr_err e2 = {0};
    int crc = gr_h5md_close(h, rc ? &e2 : err);
    if (rc || crc) {
        unlink(part);
        return rc ? rc : crc;
    }
    if (rename(part, path)) {
        unlink(part);
        return gr_fail(err, GR_ERUN, "cannot rename %s to %s: %s", part, path, strerror(errno));
    }
    return GR_OK;
}

const char *course_how(const course_opts *o)
{
    if (strcmp(o->m->name, "edmd"))
        return o->m->name;
    return o->naive ? "algorithm naive (v1.0)" : "algorithm tree";
}

double course_spacing(long n, double L) { return 0.99 * L / ceil(sqrt((double)n)); }

int course_box(const course_opts *o, long n, double eta0, double *L, gr_err *err)
{
    const char *flag = (o->given & COURSE_BOX) ? "--box" : (o->given & COURSE_ETA) ? "--eta" : "--n";
    double eta = (o->given & COURSE_ETA) ? o->eta : eta0;
    double l = (o->given & COURSE_BOX) ? o->box : sqrt((double)n * M_PI / 4 / eta);
    double spacing = course_spacing(n, l);
    if (!(spacing > 1.0))
        return gr_fail(err, GR_EINPUT,
                       "%s: %ld disks do not fit on the starting square lattice of a %.4g d box (spacing %.3g d, "
                       "below the diameter 1 d)",
                       flag, n, l, spacing);
    *L = l;
    return GR_OK;
}
