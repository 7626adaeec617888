/* Helpers shared by the contact dynamics validations: a scene from INI
 * text, an instance from given grains, and the backend's state. */
#ifndef GR_CD_TEST_H
#define GR_CD_TEST_H

#include "sim_test.h"

#include <stdlib.h>
#include <string.h>

#include "cd/cd_int.h"
#include "init.h"
#include "method.h"

extern const gr_method_type gr_cd_method;

static inline gr_scene *ct_scene(const char *text)
{
    static const char *const ext[] = {"cd", NULL};
    return st_scene(text, "cd-test.ini", ext);
}

/* An instance from the grains p (NULL: the scene's own). */
static inline gr_sim *ct_sim(const gr_scene *sc, const gr_particles *p) { return st_sim(&gr_cd_method, sc, p); }

static inline gr_cd *ct_state(gr_sim *s) { return gr_sim_state(s); }

static inline void ct_steps(gr_sim *s, long n)
{
    gr_err e = {0};
    for (long k = 0; k < n; k++) {
        if (gr_sim_step(s, &e)) {
            print_error("step: %s\n", e.msg);
            fail();
        }
    }
}

/* The last step's contact of (i, j), or NULL. */
static inline const gr_cd_contact *ct_contact(const gr_cd *d, int64_t i, int64_t j)
{
    for (size_t k = 0; k < d->prev.n; k++)
        if (d->prev.c[k].i == i && d->prev.c[k].j == j)
            return &d->prev.c[k];
    return NULL;
}

/* A resting column of N unit disks after one step: disk k carries itself
 * and the disks above, an impulse of (N - k) dt (m = g = 1), from the
 * floor (the contact with id `floor`) or from disk k - 1. Returns the
 * largest relative error; each asserted within 1e-6 when check. */
static inline double ct_column_error(const gr_cd *d, int N, int64_t floor, int check)
{
    double dt = d->par.dt, worst = 0;
    for (int k = 0; k < N; k++) {
        const gr_cd_contact *c = k ? ct_contact(d, k - 1, k) : ct_contact(d, 0, floor);
        assert_non_null(c);
        double want = (N - k) * dt, got = k ? -c->rn * c->ny : c->rn;
        worst = fmax(worst, fabs(got / want - 1));
        if (check)
            assert_rel(got, want, 1e-6);
    }
    return worst;
}

/* nx x ny unit disks on a hexagonal lattice resting on the floor, odd
 * rows shifted by half a diameter. */
static inline gr_particles *ct_hex_pile(int nx, int ny)
{
    gr_err e = {0};
    gr_particles *p = gr_particles_create((size_t)nx * (size_t)ny, &e);
    assert_non_null(p);
    double h = sqrt(3.0) / 2;
    for (int r = 0; r < ny; r++)
        for (int k = 0; k < nx; k++)
            gr_particles_push(p, k + 0.5 + 0.5 * (r % 2), 0.5 + r * h, 0.5, 1.0, 0, 0, &e);
    return p;
}

static inline uint64_t ct_counter(gr_sim *s, const char *name)
{
    uint64_t v = 0;
    if (!gr_sim_counter(s, name, &v))
        fail_msg("no counter %s", name);
    return v;
}

#endif
