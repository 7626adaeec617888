/* H5MD writer and reader: exact round trips, fields and results, refusals.
 * With `--sample FILE` it only writes a small result file for check_h5md.py.
 * Crashes and restarts are in test_h5md_crash.c. */
#include "test.h"

#include <hdf5.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "ckpt.h"
#include "h5md.h"
#include "scene.h"

#include "h5md_sample.h"

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

/* Frames of many grains are written as whole checksummed chunks (grano's
 * own Fletcher-32, not HDF5's filter): HDF5 reads them back only if every
 * checksum is its own. Values whose bytes are mostly 0xff push the sums to
 * their largest, where 32-bit arithmetic wraps. */
static void large_frames_checksummed(void **state)
{
    (void)state;
    const char *path = "large.h5";
    rm(path);
    gr_err e = {0};
    gr_scene sc = make_scene();
    gr_h5md *h = gr_h5md_create(path, &sc, NULL, &e);
    gr_particles *want[3];
    for (int f = 0; f < 3; f++) {
        want[f] = make_particles(3000 + 1000 * (size_t)f, (uint64_t)f + 7);
        for (size_t i = 0; f == 1 && i < want[f]->n; i++) {
            want[f]->vx[i] = -DBL_MAX;
            want[f]->vy[i] = i % 2 ? -DBL_MAX : DBL_MAX;
            want[f]->flags[i] = 0xffffffffu;
        }
        gr_h5md *g = f ? gr_h5md_create(path, &sc, &(gr_h5md_opts){.force = 1}, &e) : h;
        assert_non_null(g);
        assert_int_equal(gr_h5md_write_frame(g, (uint64_t)f, 0.0, want[f], &e), GR_OK);
        assert_int_equal(gr_h5md_write_frame(g, (uint64_t)f + 1, 1.0, want[f], &e), GR_OK);
        assert_int_equal(gr_h5md_close(g, &e), GR_OK);
        gr_h5md_reader *r = gr_h5md_open(path, &e);
        assert_non_null(r);
        gr_particles *got = gr_particles_create(1, &e);
        for (size_t k = 0; k < 2; k++) {
            if (gr_h5md_read_frame(r, k, got, NULL, NULL, &e))
                fail_msg("frame %zu of %zu grains: %s", k, want[f]->n, e.msg);
            assert_same_particles(got, want[f]);
        }
        gr_particles_free(got);
        gr_h5md_reader_free(r);
        gr_particles_free(want[f]);
    }
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
    double times[3];
    assert_int_equal(gr_h5md_series_times(r, "fields/velocity", 3, times, &e), GR_OK);
    assert_true(times[0] == 0.0 && times[1] == 0.1 && times[2] == 0.2);
    assert_int_equal(gr_h5md_series_times(r, "fields/nothing", 1, times, &e), GR_EINPUT);
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


int main(int argc, char **argv)
{
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
        cmocka_unit_test(large_frames_checksummed),
        cmocka_unit_test(existing_output_refused_without_force),
        cmocka_unit_test(fields_and_results),
        cmocka_unit_test(not_a_grano_file),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
