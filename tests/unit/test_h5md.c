/* H5MD writer and reader: exact round trips, refusals, and a writer killed
 * without closing. Other modes (docs/output-format.md):
 *   --sample FILE         write a small result file for check_h5md.py
 *   --bench N FRAMES      cost of writing and reading frames of N grains
 *   --kill TRIALS N       SIGKILL a writer at random moments, read what is left */
#include "test.h"

#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <signal.h>
#include <time.h>
#include <unistd.h>

#include "ckpt.h"
#include "h5md.h"
#include "scene.h"

static char scene_text[] = "# test scene\n[domain]\nwidth = 20\nheight = 10\n"
                           "# accents survive: caída, orificio\n";

static gr_scene make_scene(void)
{
    gr_scene sc;
    memset(&sc, 0, sizeof sc);
    sc.text = scene_text;
    snprintf(sc.path, sizeof sc.path, "scenes/test.ini");
    snprintf(sc.name, sizeof sc.name, "testbox");
    sc.width = 20.0;
    sc.height = 10.0;
    sc.side[GR_LEFT] = sc.side[GR_RIGHT] = GR_BC_PERIODIC;
    sc.side[GR_BOTTOM] = sc.side[GR_TOP] = GR_BC_WALL;
    return sc;
}

/* xorshift64*: deterministic values with every mantissa bit in use. */
static double next_u(uint64_t *s)
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return (double)((*s * 2685821657736338717ull) >> 11) * 0x1.0p-53;
}

static gr_particles *make_particles(size_t n, uint64_t seed)
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
static void move(gr_particles *p, int f)
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

static void assert_same_particles(const gr_particles *a, const gr_particles *b)
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

static gr_obs make_obs(int k)
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

static int file_exists(const char *p)
{
    struct stat st;
    return stat(p, &st) == 0;
}

static char *read_text(const char *p)
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

static void rm(const char *base)
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
static gr_h5md *write_sample(const char *path, gr_particles **want, int close_it)
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

static void frames_and_obs_round_trip(void **state)
{
    (void)state;
    const char *path = "rt.h5";
    rm(path);
    gr_particles *want[NFR];
    write_sample(path, want, 1);
    assert_true(file_exists(path));
    assert_false(file_exists("rt.h5.part"));
    assert_true(file_exists("rt.h5.xdmf"));

    gr_err e = {0};
    gr_h5md_reader *r = gr_h5md_open(path, &e);
    assert_non_null(r);
    const gr_h5md_info *in = gr_h5md_info_of(r);
    assert_string_equal(in->creator, "grano");
    assert_string_equal(in->creator_version, "0.1.0-test");
    assert_string_equal(in->author, "Test Author");
    assert_int_equal(in->h5md_version[0], 1);
    assert_int_equal(in->h5md_version[1], 1);
    assert_string_equal(in->scene_text, scene_text);
    assert_string_equal(in->scene_name, "testbox");
    assert_string_equal(in->scene_path, "scenes/test.ini");
    assert_string_equal(in->method, "dem");
    assert_true(in->seed == 12345678901234567ull);
    assert_int_equal(in->nframes, NFR);
    assert_int_equal(in->nparticles, NP);
    assert_int_equal(in->nobs, NOBS);
    assert_true(in->box[0] == 20.0 && in->box[1] == 10.0);
    assert_int_equal(in->periodic[0], 1);
    assert_int_equal(in->periodic[1], 0);
    assert_int_equal(in->has_checkpoint, 0);

    double t[NFR];
    uint64_t st[NFR];
    assert_int_equal(gr_h5md_read_times(r, t, st, &e), GR_OK);
    gr_particles *got = gr_particles_create(1, &e);
    for (int f = 0; f < NFR; f++) {
        assert_true(t[f] == 0.5 * f);
        assert_true(st[f] == 100u * (uint64_t)f);
        uint64_t s1;
        double t1;
        assert_int_equal(gr_h5md_read_frame(r, (size_t)f, got, &s1, &t1, &e), GR_OK);
        assert_true(s1 == st[f] && t1 == t[f]);
        assert_same_particles(got, want[f]);
        gr_particles_free(want[f]);
    }
    assert_int_equal(gr_h5md_read_frame(r, NFR, got, NULL, NULL, &e), GR_EINPUT);
    gr_particles_free(got);

    gr_obs obs[NOBS];
    assert_int_equal(gr_h5md_read_obs(r, obs, &e), GR_OK);
    for (int k = 0; k < NOBS; k++) {
        gr_obs w = make_obs(k);
        /* NaN and infinities included: compare the bits. */
        assert_memory_equal(&obs[k].t, &w.t, sizeof w.t);
        assert_true(obs[k].steps == w.steps && obs[k].n_mobile == w.n_mobile &&
                    obs[k].outflow == w.outflow);
        assert_memory_equal(&obs[k].ekin_trans, &w.ekin_trans, sizeof(double));
        assert_memory_equal(&obs[k].ekin_rot, &w.ekin_rot, sizeof(double));
        assert_memory_equal(&obs[k].epot_grav, &w.epot_grav, sizeof(double));
        assert_memory_equal(&obs[k].temperature, &w.temperature, sizeof(double));
        assert_memory_equal(&obs[k].px, &w.px, 2 * sizeof(double));
        assert_memory_equal(&obs[k].wall_pressure, &w.wall_pressure, sizeof(double));
        assert_memory_equal(&obs[k].max_overlap, &w.max_overlap, sizeof(double));
    }
    size_t ns;
    double t0, t1;
    assert_int_equal(gr_h5md_series_info(r, "observables/temperature", &ns, &t0, &t1, &e), GR_OK);
    assert_int_equal(ns, NOBS);
    assert_true(t0 == make_obs(0).t && t1 == make_obs(NOBS - 1).t);
    char **names;
    size_t nn;
    assert_int_equal(gr_h5md_list(r, "observables", &names, &nn, &e), GR_OK);
    assert_int_equal(nn, 9);
    assert_string_equal(names[0], "ekin_rot"); /* sorted */
    gr_h5md_names_free(names, nn);
    gr_h5md_reader_free(r);

    /* The sidecar names one grid per frame, read from this file. */
    char *x = read_text("rt.h5.xdmf");
    assert_non_null(x);
    assert_non_null(strstr(x, "frame 4"));
    assert_null(strstr(x, "frame 5"));
    assert_non_null(strstr(x, "rt.h5:/particles/trajectory/position/value"));
    assert_non_null(strstr(x, "GeometryType=\"XY\""));
    free(x);
    rm(path);
}

static void changing_radius_becomes_time_dependent(void **state)
{
    (void)state;
    const char *path = "promote.h5";
    rm(path);
    gr_err e = {0};
    gr_scene sc = make_scene();
    gr_h5md *h = gr_h5md_create(path, &sc, NULL, &e);
    assert_non_null(h);
    gr_particles *p = make_particles(10, 3);
    gr_particles *first = gr_particles_create(10, &e);
    gr_particles_copy(first, p, &e);
    assert_int_equal(gr_h5md_write_frame(h, 0, 0.0, p, &e), GR_OK);
    assert_int_equal(gr_h5md_write_frame(h, 1, 1.0, p, &e), GR_OK);
    p->radius[4] *= 1.5;
    p->inertia[4] = gr_disk_inertia(p->mass[4], p->radius[4]);
    assert_int_equal(gr_h5md_write_frame(h, 2, 2.0, p, &e), GR_OK);
    assert_int_equal(gr_h5md_write_frame(h, 3, 3.0, p, &e), GR_OK);
    /* Frames must keep their grain count and move forward in time. */
    gr_particles *small = make_particles(9, 3);
    assert_int_equal(gr_h5md_write_frame(h, 4, 4.0, small, &e), GR_ERUN);
    assert_non_null(strstr(e.msg, "9 grains"));
    assert_int_equal(gr_h5md_write_frame(h, 4, 2.5, p, &e), GR_ERUN);
    gr_particles_free(small);
    assert_int_equal(gr_h5md_close(h, &e), GR_OK);

    gr_h5md_reader *r = gr_h5md_open(path, &e);
    assert_non_null(r);
    assert_int_equal(gr_h5md_info_of(r)->nframes, 4);
    gr_particles *got = gr_particles_create(1, &e);
    for (size_t f = 0; f < 4; f++) {
        assert_int_equal(gr_h5md_read_frame(r, f, got, NULL, NULL, &e), GR_OK);
        assert_same_particles(got, f < 2 ? first : p);
    }
    gr_particles_free(got);
    gr_h5md_reader_free(r);
    char *x = read_text("promote.h5.xdmf");
    assert_non_null(strstr(x, "/particles/trajectory/radius/value"));
    assert_non_null(strstr(x, ":/particles/trajectory/species<"));
    free(x);
    gr_particles_free(first);
    gr_particles_free(p);
    rm(path);
}

static void nonfinite_frame_refused(void **state)
{
    (void)state;
    const char *path = "nan.h5";
    rm(path);
    gr_err e = {0};
    gr_scene sc = make_scene();
    gr_h5md *h = gr_h5md_create(path, &sc, NULL, &e);
    gr_particles *p = make_particles(8, 5);
    assert_int_equal(gr_h5md_write_frame(h, 0, 0.0, p, &e), GR_OK);
    p->vy[6] = NAN;
    assert_int_equal(gr_h5md_write_frame(h, 1, 1.0, p, &e), GR_ERUN);
    assert_non_null(strstr(e.msg, "id 1006"));
    assert_non_null(strstr(e.msg, "velocity"));
    assert_int_equal(gr_h5md_frames(h), 1);
    p->vy[6] = 0.0;
    assert_int_equal(gr_h5md_write_frame(h, 1, 1.0, p, &e), GR_OK);
    assert_int_equal(gr_h5md_close(h, &e), GR_OK);
    gr_particles_free(p);
    rm(path);
}

static void existing_output_refused_without_force(void **state)
{
    (void)state;
    const char *path = "exists.h5";
    rm(path);
    gr_err e = {0};
    gr_scene sc = make_scene();
    gr_h5md_opts o = {.method = "first"};
    gr_h5md *h = gr_h5md_create(path, &sc, &o, &e);
    assert_non_null(h);
    assert_int_equal(gr_h5md_close(h, &e), GR_OK);

    o.method = "second";
    assert_null(gr_h5md_create(path, &sc, &o, &e));
    assert_int_equal(e.code, GR_EINPUT);
    assert_non_null(strstr(e.msg, path));
    assert_non_null(strstr(e.msg, "--force"));
    gr_h5md_reader *r = gr_h5md_open(path, &e);
    assert_non_null(r);
    assert_string_equal(gr_h5md_info_of(r)->method, "first");
    gr_h5md_reader_free(r);

    o.force = 1;
    h = gr_h5md_create(path, &sc, &o, &e);
    assert_non_null(h);
    assert_int_equal(gr_h5md_close(h, &e), GR_OK);
    r = gr_h5md_open(path, &e);
    assert_string_equal(gr_h5md_info_of(r)->method, "second");
    gr_h5md_reader_free(r);
    rm(path);

    /* An unwritable place fails as bad input and leaves nothing behind. */
    assert_null(gr_h5md_create("no-such-dir/out.h5", &sc, &o, &e));
    assert_int_equal(e.code, GR_EINPUT);
    assert_non_null(strstr(e.msg, "no-such-dir/out.h5"));
    assert_non_null(strstr(e.msg, "No such file or directory")); /* HDF5's cause kept */
    assert_false(file_exists("no-such-dir/out.h5.part"));
    mkdir("adir.h5", 0700);
    assert_null(gr_h5md_create("adir.h5", &sc, &o, &e));
    assert_int_equal(e.code, GR_EINPUT);
    rmdir("adir.h5");
}

/* A run killed after a flush: the child writes and _exit()s without closing
 * anything; every flushed frame must read back exactly. */
static void killed_writer_leaves_readable_file(void **state)
{
    (void)state;
    const char *path = "killed.h5";
    rm(path);
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        write_sample(path, NULL, 0);
        _exit(0);
    }
    int status = 0;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_true(WIFEXITED(status) && WEXITSTATUS(status) == 0);

    gr_particles *want[NFR];
    write_sample("killed-ref.h5", want, 1);
    gr_err e = {0};
    gr_h5md_reader *r = gr_h5md_open(path, &e);
    if (!r)
        fail_msg("%s", e.msg);
    assert_int_equal(gr_h5md_info_of(r)->nframes, NFR);
    assert_int_equal(gr_h5md_info_of(r)->nobs, NOBS);
    gr_particles *got = gr_particles_create(1, &e);
    for (int f = 0; f < NFR; f++) {
        assert_int_equal(gr_h5md_read_frame(r, (size_t)f, got, NULL, NULL, &e), GR_OK);
        assert_same_particles(got, want[f]);
        gr_particles_free(want[f]);
    }
    gr_particles_free(got);
    gr_h5md_reader_free(r);
    rm(path);
    rm("killed-ref.h5");
}

static void fields_and_results(void **state)
{
    (void)state;
    const char *path = "fields.h5";
    rm(path);
    gr_err e = {0};
    gr_scene sc = make_scene();
    gr_h5md *h = gr_h5md_create(path, &sc, NULL, &e);
    gr_field_desc f = {"velocity", "d tau-1", 4, 3, 2, 0.0, -1.0, 5.0, 2.5};
    double v[3][24];
    for (int s = 0; s < 3; s++) {
        for (int i = 0; i < 24; i++)
            v[s][i] = s * 100 + i + 0.125;
        assert_int_equal(gr_h5md_write_field(h, &f, 10u * (uint64_t)s, 0.1 * s, v[s], &e), GR_OK);
    }
    gr_field_desc g = f;
    g.nx = 5;
    assert_int_equal(gr_h5md_write_field(h, &g, 40, 0.4, v[0], &e), GR_ERUN);
    double tab[4][3] = {{1, 2, 3}, {4, 5, 6}, {7, 8, 9}, {10, 11, NAN}};
    const char *cols[] = {"D", "Q", "Q_err"};
    const char *units[] = {"d", "tau-1", "tau-1"};
    gr_result_desc rd = {"beverloo/flow", 4, 3, cols, units, "flow rate against orifice"};
    assert_int_equal(gr_h5md_write_result(h, &rd, &tab[0][0], &e), GR_OK);
    tab[0][0] = -1; /* rewriting replaces */
    assert_int_equal(gr_h5md_write_result(h, &rd, &tab[0][0], &e), GR_OK);
    gr_result_desc bad = {"../x", 1, 0, NULL, NULL, NULL};
    assert_int_equal(gr_h5md_write_result(h, &bad, &tab[0][0], &e), GR_ERUN);
    assert_int_equal(gr_h5md_close(h, &e), GR_OK);

    gr_h5md_reader *r = gr_h5md_open(path, &e);
    assert_non_null(r);
    gr_field_desc got = {0};
    size_t ns;
    assert_int_equal(gr_h5md_field_info(r, "velocity", &got, &ns, &e), GR_OK);
    assert_int_equal(ns, 3);
    assert_true(got.nx == 4 && got.ny == 3 && got.ncomp == 2 && got.x0 == 0.0 && got.y0 == -1.0 &&
                got.dx == 5.0 && got.dy == 2.5);
    double back[24], t;
    uint64_t st;
    assert_int_equal(gr_h5md_read_field(r, "velocity", 2, back, &st, &t, &e), GR_OK);
    assert_memory_equal(back, v[2], sizeof back);
    assert_true(st == 20 && t == 0.2);
    size_t rows, ncol;
    double *data;
    assert_int_equal(gr_h5md_read_result(r, "beverloo/flow", &rows, &ncol, &data, &e), GR_OK);
    assert_true(rows == 4 && ncol == 3);
    assert_memory_equal(data, &tab[0][0], sizeof tab);
    free(data);
    assert_int_equal(gr_h5md_read_result(r, "nothing", &rows, &ncol, NULL, &e), GR_EINPUT);
    gr_h5md_reader_free(r);
    rm(path);
}

static void not_a_grano_file(void **state)
{
    (void)state;
    gr_err e = {0};
    assert_null(gr_h5md_open("does-not-exist.h5", &e));
    assert_int_equal(e.code, GR_EINPUT);
    assert_non_null(strstr(e.msg, "does-not-exist.h5: no such file"));
    FILE *f = fopen("text.h5", "w");
    fputs("not hdf5\n", f);
    fclose(f);
    assert_null(gr_h5md_open("text.h5", &e));
    assert_int_equal(e.code, GR_EINPUT);
    assert_non_null(strstr(e.msg, "not an HDF5 file"));
    unlink("text.h5");
    hid_t fid = H5Fcreate("other.h5", H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    H5Gclose(H5Gcreate2(fid, "data", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
    H5Fclose(fid);
    assert_null(gr_h5md_open("other.h5", &e));
    assert_int_equal(e.code, GR_EINPUT);
    assert_non_null(strstr(e.msg, "not a grano result file"));
    assert_null(gr_ckpt_open("other.h5", &e));
    assert_int_equal(e.code, GR_EINPUT);
    unlink("other.h5");
}


static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* --bench N FRAMES: write then read FRAMES frames of N grains (and one
 * observable sample per frame); prints the cost per frame and the size. */
static int bench(size_t n, int frames)
{
    gr_err e = {0};
    gr_scene sc = make_scene();
    gr_h5md_opts o = {.force = 1};
    gr_particles *p = make_particles(n, 1);
    gr_obs ob = make_obs(0);
    double t0 = now();
    gr_h5md *h = gr_h5md_create("bench.h5", &sc, &o, &e);
    for (int f = 0; h && f < frames; f++) {
        move(p, f % 3);
        ob.t = 0.1 * f;
        if (gr_h5md_write_frame(h, (uint64_t)f, 0.1 * f, p, &e) || gr_h5md_write_obs(h, &ob, &e))
            break;
    }
    if (!h || e.code || gr_h5md_close(h, &e)) {
        fprintf(stderr, "%s\n", e.msg);
        return 1;
    }
    double t1 = now();
    gr_h5md_reader *r = gr_h5md_open("bench.h5", &e);
    for (int f = 0; r && f < frames; f++)
        gr_h5md_read_frame(r, (size_t)f, p, NULL, NULL, &e);
    gr_h5md_reader_free(r);
    double t2 = now();
    struct stat st, sx;
    stat("bench.h5", &st);
    stat("bench.h5.xdmf", &sx);
    /* Per grain and frame: position, velocity 32 B, omega 8, flags 4. */
    double raw = (double)n * frames * 44.0 + (double)n * 36.0;
    printf("N %zu, %d frames: write %.3f ms/frame (%.0f MB/s), read %.3f ms/frame, "
           "file %.1f MB (%.1f %% over the raw data), sidecar %.0f kB\n",
           n, frames, 1e3 * (t1 - t0) / frames, raw / (t1 - t0) / 1e6, 1e3 * (t2 - t1) / frames,
           (double)st.st_size / 1e6, 100.0 * ((double)st.st_size / raw - 1.0), (double)sx.st_size / 1e3);
    gr_particles_free(p);
    rm("bench.h5");
    return 0;
}

/* --kill TRIALS N: a child writes frames of N grains, observables and a
 * field without end; it is SIGKILLed after a random 20-420 ms; every file
 * left must open and read back every frame it reports. */
static int kill_stress(int trials, size_t n)
{
    int bad = 0;
    uint64_t s = 12345;
    for (int t = 0; t < trials; t++) {
        rm("killed-stress.h5");
        pid_t pid = fork();
        if (pid < 0)
            return 1;
        if (pid == 0) {
            gr_err e = {0};
            gr_scene sc = make_scene();
            gr_h5md *h = gr_h5md_create("killed-stress.h5", &sc, NULL, &e);
            gr_particles *p = make_particles(n, 2);
            gr_field_desc fd = {"rho", "1", 8, 4, 1, 0, 0, 2.5, 2.5};
            double v[32] = {0};
            for (int f = 0; h; f++) {
                move(p, f);
                if (f % 50 == 49)
                    p->radius[0] *= 1.01; /* a promotion now and then */
                gr_obs ob = make_obs(f);
                if (gr_h5md_write_frame(h, (uint64_t)f, 0.1 * f, p, &e) ||
                    gr_h5md_write_obs(h, &ob, &e) ||
                    gr_h5md_write_field(h, &fd, (uint64_t)f, 0.1 * f, v, &e))
                    _exit(3);
            }
            _exit(4);
        }
        struct timespec ts = {0, 20000000L + (long)(next_u(&s) * 400e6)};
        nanosleep(&ts, NULL);
        kill(pid, SIGKILL);
        int status;
        waitpid(pid, &status, 0);
        gr_err e = {0};
        gr_h5md_reader *r = gr_h5md_open("killed-stress.h5", &e);
        int ok = r != NULL;
        size_t frames = 0;
        if (r) {
            frames = gr_h5md_info_of(r)->nframes;
            gr_particles *p = gr_particles_create(1, &e);
            for (size_t f = 0; ok && f < frames; f++)
                ok = gr_h5md_read_frame(r, f, p, NULL, NULL, &e) == GR_OK;
            gr_particles_free(p);
            gr_h5md_reader_free(r);
        }
        printf("trial %d: %zu frames readable%s%s\n", t, frames, ok ? "" : ", FAILED: ", ok ? "" : e.msg);
        bad += !ok;
    }
    rm("killed-stress.h5");
    printf("%d of %d killed files unreadable\n", bad, trials);
    return bad != 0;
}

int main(int argc, char **argv)
{
    if (argc == 4 && !strcmp(argv[1], "--bench"))
        return bench((size_t)atol(argv[2]), atoi(argv[3]));
    if (argc == 4 && !strcmp(argv[1], "--kill"))
        return kill_stress(atoi(argv[2]), (size_t)atol(argv[3]));
    if (argc == 3 && !strcmp(argv[1], "--sample")) {
        /* A small file for check_h5md.py: frames, observables, a field and a
         * result table. */
        rm(argv[2]);
        gr_h5md *h = write_sample(argv[2], NULL, 0);
        gr_err e = {0};
        gr_field_desc f = {"packing_fraction", "1", 4, 2, 1, 0.0, 0.0, 5.0, 5.0};
        double v[8] = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8};
        const char *cols[] = {"D", "Q"};
        const char *units[] = {"d", "tau-1"};
        gr_result_desc rd = {"flow", 4, 2, cols, units, "test table"};
        if (gr_h5md_write_field(h, &f, 0, 0.0, v, &e) || gr_h5md_write_field(h, &f, 10, 1.0, v, &e) ||
            gr_h5md_write_result(h, &rd, v, &e) || gr_h5md_close(h, &e)) {
            fprintf(stderr, "%s\n", e.msg);
            return 1;
        }
        return 0;
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(frames_and_obs_round_trip),
        cmocka_unit_test(changing_radius_becomes_time_dependent),
        cmocka_unit_test(nonfinite_frame_refused),
        cmocka_unit_test(existing_output_refused_without_force),
        cmocka_unit_test(killed_writer_leaves_readable_file),
        cmocka_unit_test(fields_and_results),
        cmocka_unit_test(not_a_grano_file),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
