/* Shared by the H5MD test programs: a scene, grains with every mantissa
 * bit in use, frames that move them, observables, and a sample file. */
#ifndef GR_TEST_H5MD_SAMPLE_H
#define GR_TEST_H5MD_SAMPLE_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "h5md.h"
#include "scene.h"

static const char scene_text[] = "# test scene\n[domain]\nwidth = 20\nheight = 10\n"
                           "# accents survive: caída, orificio\n";

static inline gr_scene make_scene(void)
{
    gr_scene sc;
    memset(&sc, 0, sizeof sc);
    sc.text = (char *)scene_text; /* never written through */
    snprintf(sc.path, sizeof sc.path, "scenes/test.ini");
    snprintf(sc.name, sizeof sc.name, "testbox");
    sc.width = 20.0;
    sc.height = 10.0;
    sc.side[GR_LEFT] = sc.side[GR_RIGHT] = GR_BC_PERIODIC;
    sc.side[GR_BOTTOM] = sc.side[GR_TOP] = GR_BC_WALL;
    return sc;
}

/* xorshift64*: deterministic values with every mantissa bit in use. */
static inline double next_u(uint64_t *s)
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return (double)((*s * 2685821657736338717ull) >> 11) * 0x1.0p-53;
}

static inline gr_particles *make_particles(size_t n, uint64_t seed)
{
    gr_err e = {0};
    gr_particles *p = gr_particles_create(n, &e);
    assert_non_null(p);
    uint64_t s = seed | 1;
    for (size_t i = 0; i < n; i++) {
        double r = 0.4 + 0.2 * next_u(&s);
        long k = gr_particles_push(p, 20 * next_u(&s), 10 * next_u(&s), r, 4 * r * r,
                                   i % 7 == 0 ? GR_PF_FIXED : 0, (int32_t)(i % 3), &e);
        assert_int_equal(k, (long)i);
        p->id[i] = 1000 + (int64_t)i;
    }
    return p;
}

/* Move the grains of frame f: every kinematic field changes. */
static inline void move(gr_particles *p, int f)
{
    uint64_t s = 77 + (uint64_t)f;
    for (size_t i = 0; i < p->n; i++) {
        if (p->flags[i] & GR_PF_FIXED)
            continue;
        p->vx[i] = next_u(&s) - 0.5;
        p->vy[i] = -next_u(&s) * 1e-3;
        p->omega[i] = (next_u(&s) - 0.5) * 1e5;
        p->x[i] += 0.01 * p->vx[i];
        p->y[i] += 0.01 * p->vy[i];
        if (f >= 3 && i % 5 == 1)
            p->flags[i] |= GR_PF_GONE;
    }
}

static inline void assert_same_particles(const gr_particles *a, const gr_particles *b)
{
    assert_int_equal(a->n, b->n);
    size_t n = a->n;
    assert_memory_equal(a->x, b->x, n * sizeof(double));
    assert_memory_equal(a->y, b->y, n * sizeof(double));
    assert_memory_equal(a->vx, b->vx, n * sizeof(double));
    assert_memory_equal(a->vy, b->vy, n * sizeof(double));
    assert_memory_equal(a->omega, b->omega, n * sizeof(double));
    assert_memory_equal(a->radius, b->radius, n * sizeof(double));
    assert_memory_equal(a->mass, b->mass, n * sizeof(double));
    assert_memory_equal(a->inertia, b->inertia, n * sizeof(double));
    assert_memory_equal(a->flags, b->flags, n * sizeof(uint32_t));
    assert_memory_equal(a->id, b->id, n * sizeof(int64_t));
    assert_memory_equal(a->species, b->species, n * sizeof(int32_t));
}

static inline gr_obs make_obs(int k)
{
    gr_obs o;
    memset(&o, 0, sizeof o);
    o.t = 0.25 * k + 1e-13;
    o.steps = 1000u * (uint64_t)k + 7;
    o.n_mobile = 40 - (uint64_t)k;
    o.ekin_trans = 1.0 / (k + 3.0);
    o.ekin_rot = 1e-300 * k;
    o.epot_grav = -12.5 + k / 3.0;
    o.temperature = sqrt(2.0 + k);
    o.px = -0.1 * k;
    o.py = 1e10 + k;
    o.outflow = (uint64_t)k * 3;
    o.wall_pressure = NAN;
    o.max_overlap = k % 2 ? 0.01 / k : INFINITY;
    return o;
}

static inline int file_exists(const char *p)
{
    struct stat st;
    return stat(p, &st) == 0;
}

static inline char *read_text(const char *p)
{
    FILE *f = fopen(p, "r");
    if (!f)
        return NULL;
    char *buf = calloc(1 << 20, 1);
    size_t n = fread(buf, 1, (1 << 20) - 1, f);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

static inline void rm(const char *base)
{
    char p[1100];
    const char *suffix[] = {"", ".xdmf", ".part", ".tmp", ".xdmf.tmp"};
    for (size_t i = 0; i < sizeof suffix / sizeof *suffix; i++) {
        snprintf(p, sizeof p, "%s%s", base, suffix[i]);
        unlink(p);
    }
}

#define NFR 5
#define NP 40
#define NOBS 7

/* Write NFR frames (and NOBS observables) of NP grains to path; the frames
 * written are kept in want[] when given. Returns the writer if left open. */
static inline gr_h5md *write_sample(const char *path, gr_particles **want, int close_it)
{
    rm(path); /* left over by an earlier failed run */
    gr_err e = {0};
    gr_scene sc = make_scene();
    gr_h5md_opts o = {.method = "dem", .seed = 12345678901234567ull, .version = "0.1.0-test",
                      .author = "Test Author"};
    gr_h5md *h = gr_h5md_create(path, &sc, &o, &e);
    assert_non_null(h);
    gr_particles *p = make_particles(NP, 42);
    for (int f = 0; f < NFR; f++) {
        move(p, f);
        assert_int_equal(gr_h5md_write_frame(h, 100u * (uint64_t)f, 0.5 * f, p, &e), GR_OK);
        /* published after the first frame, so that the observables are
         * added to a published file (on a copy renamed over it) */
        if (!f)
            assert_int_equal(gr_h5md_publish(h, &e), GR_OK);
        if (want) {
            want[f] = gr_particles_create(NP, &e);
            assert_int_equal(gr_particles_copy(want[f], p, &e), GR_OK);
        }
    }
    for (int k = 0; k < NOBS; k++) {
        gr_obs ob = make_obs(k);
        assert_int_equal(gr_h5md_write_obs(h, &ob, &e), GR_OK);
    }
    gr_particles_free(p);
    if (!close_it)
        return h;
    assert_int_equal(gr_h5md_close(h, &e), GR_OK);
    return NULL;
}

#endif
