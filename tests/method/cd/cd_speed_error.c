/* Speed against error on a settling pile (docs/methods/cd.md): 200 disks
 * (mu = 0.5, e = 0) fall from random spots in a box 16 d wide and settle to
 * t = 15; for each time step and tolerance, the wall time, the packing
 * fraction of the pile's bulk and the floor's share of the weight
 * (averaged over the last 0.5 tau; the walls' friction carries the rest),
 * and their errors against the reference (the smallest dt and tol). Not a
 * test: a program that prints the table.
 *   build/tests/method/cd/cd_speed_error [dt,... [tol,...]] */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cd/cd_int.h"
#include "fields.h"
#include "init.h"
#include "progress.h"
#include "method.h"

extern const gr_method_type gr_cd_method;

#define T_END 15.0
#define T_WIN 0.5

typedef struct {
    double wall, phi, base, sweeps;
    unsigned long long nonconv;
} pile_res;

/* Packing fraction of the grains' bulk: a band 1 d in from the walls, from
 * 1 d above the floor to 2 d below the highest grain (exact disk areas). */
static double packing(const gr_particles *p)
{
    double top = 0, a = 0;
    for (size_t i = 0; i < p->n; i++)
        top = fmax(top, p->y[i]);
    double x0 = 1, x1 = 15, y0 = 1, y1 = top - 2;
    for (size_t i = 0; i < p->n; i++)
        a += gr_disk_rect_area(p->x[i], p->y[i], p->radius[i], x0, x1, y0, y1);
    return a / ((x1 - x0) * (y1 - y0));
}

static int run(double dt, double tol, pile_res *r, gr_err *e)
{
    char text[1024];
    snprintf(text, sizeof text,
             "[scene]\nseed = 5\n[domain]\nwidth = 16\nheight = 40\ngravity = 1\n"
             "[material]\ntangential = coulomb\nmu = 0.5\n[species]\ncount = 200\n"
             "[init]\nkind = random\nregion = 0 0 16 24\n"
             "[cd]\ndt = %.17g\ntol = %.17g\nmax_iter = 5000\n", dt, tol);
    static const char *const ext[] = {"cd", NULL};
    gr_scene *sc = gr_scene_parse(text, "pile", ext, e);
    gr_particles *p = sc ? gr_particles_create(0, e) : NULL;
    gr_sim *s = NULL;
    int rc = !p || gr_init_particles(sc, p, e) || gr_sim_create(&gr_cd_method, sc, p, &s, e);
    double w0 = gr_wall_seconds();
    if (!rc)
        rc = gr_sim_advance(s, T_END - T_WIN, 0, e);
    double base = 0, w = 0;
    while (!rc && gr_sim_time(s) < T_END - 0.5 * dt) {
        rc = gr_sim_step(s, e);
        const gr_cd *d = gr_sim_state(s);
        for (size_t k = 0; k < d->prev.n && !rc; k++)
            if ((size_t)d->prev.c[k].j == d->n + 2) /* the floor */
                base += d->prev.c[k].rn;
        w += dt;
    }
    if (!rc) {
        const gr_cd *d = gr_sim_state(s);
        r->wall = gr_wall_seconds() - w0;
        r->phi = packing(d->p);
        r->base = base / w / 200.0;
        r->sweeps = (double)d->sweeps / (double)d->step;
        r->nonconv = (unsigned long long)d->nonconv;
    }
    gr_sim_free(s);
    gr_particles_free(p);
    gr_scene_free(sc);
    return rc;
}

static size_t parse(const char *s, double *v, size_t cap)
{
    size_t n = 0;
    char *end;
    while (*s && n < cap) {
        v[n++] = strtod(s, &end);
        s = *end == ',' ? end + 1 : end + strlen(end);
    }
    return n;
}

int main(int argc, char **argv)
{
    double dts[16] = {5e-4, 1e-3, 2e-3, 5e-3, 1e-2}, tols[16] = {1e-6, 1e-4, 1e-3, 1e-2};
    size_t ndt = argc > 1 ? parse(argv[1], dts, 16) : 5, ntol = argc > 2 ? parse(argv[2], tols, 16) : 4;
    gr_err e = {0};
    pile_res ref;
    /* the reference first: the smallest dt and tol */
    if (run(dts[0], tols[0], &ref, &e)) {
        fprintf(stderr, "cd_speed_error: %s\n", e.msg);
        return 1;
    }
    printf("# pile of 200, t = %g; reference dt %g tol %g: packing %.5f, floor share %.5f, %.1f s\n", T_END, dts[0],
           tols[0], ref.phi, ref.base, ref.wall);
    printf("# dt tol wall_s sweeps_per_step nonconverged packing err_packing floor_share err_floor_share\n");
    for (size_t a = 0; a < ndt; a++)
        for (size_t b = 0; b < ntol; b++) {
            pile_res r = ref;
            if ((a || b) && run(dts[a], tols[b], &r, &e)) {
                printf("%g %g failed: %s\n", dts[a], tols[b], e.msg);
                e = (gr_err){0};
                continue;
            }
            printf("%g %g %.2f %.1f %llu %.5f %.2e %.5f %.2e\n", dts[a], tols[b], r.wall, r.sweeps, r.nonconv, r.phi,
                   fabs(r.phi - ref.phi), r.base, fabs(r.base - ref.base));
            fflush(stdout);
        }
    return 0;
}
