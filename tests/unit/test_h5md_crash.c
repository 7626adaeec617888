/* H5MD files across crashes and restarts: a writer that dies without
 * closing leaves every flushed frame readable, and a restarted run
 * continues its file. Other modes (docs/output-format.md):
 *   --bench N FRAMES      cost of writing and reading frames of N grains
 *   --kill TRIALS N       SIGKILL a writer at random moments, read what is left */
#include "test.h"

#include <signal.h>
#include <sys/wait.h>
#include <time.h>

#include "h5md_sample.h"

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

/* A run restarted from a checkpoint at t = 1 continues its file: the frames,
 * observables and field samples after t = 1 are dropped and written again,
 * and the file ends equal to one written without interruption. */
static void reopen_continues_the_file(void **state)
{
    (void)state;
    const char *path = "cont.h5";
    gr_particles *want[NFR];
    gr_h5md *h = write_sample(path, want, 0);
    gr_err e = {0};
    gr_field_desc fd = {"rho", "1", 2, 2, 1, 0.0, 0.0, 10.0, 5.0};
    double v[4] = {1, 2, 3, 4};
    assert_int_equal(gr_h5md_write_field(h, &fd, 1, 0.5, v, &e), GR_OK);
    assert_int_equal(gr_h5md_write_field(h, &fd, 3, 1.5, v, &e), GR_OK);
    assert_int_equal(gr_h5md_close(h, &e), GR_OK);
    gr_scene sc = make_scene();
    gr_h5md_opts o = {.method = "dem", .seed = 12345678901234567ull, .version = "0.1.0-test"};

    gr_h5md_opts other = o;
    other.method = "edmd";
    assert_null(gr_h5md_reopen(path, &sc, &other, 1.0, &e));
    assert_int_equal(e.code, GR_EINPUT);
    assert_non_null(strstr(e.msg, "method 'dem', not 'edmd'"));
    assert_null(gr_h5md_reopen("nothing.h5", &sc, &o, 1.0, &e));
    assert_int_equal(e.code, GR_EINPUT);

    h = gr_h5md_reopen(path, &sc, &o, 1.0, &e);
    if (!h)
        fail_msg("%s", e.msg);
    assert_int_equal(gr_h5md_frames(h), 3); /* t = 0, 0.5, 1 */
    gr_h5md_reader *r;
    for (int f = 3; f < NFR; f++)
        assert_int_equal(gr_h5md_write_frame(h, 100u * (uint64_t)f, 0.5 * f, want[f], &e), GR_OK);
    for (int k = 4; k < NOBS; k++) { /* samples at 1 + 1e-13 and later were dropped */
        gr_obs ob = make_obs(k);
        assert_int_equal(gr_h5md_write_obs(h, &ob, &e), GR_OK);
    }
    /* A radius change after the restart is still noticed. */
    gr_particles *p = gr_particles_create(NP, &e);
    gr_particles_copy(p, want[NFR - 1], &e);
    p->radius[0] = 0.77;
    assert_int_equal(gr_h5md_write_frame(h, 500, 2.5, p, &e), GR_OK);
    assert_int_equal(gr_h5md_close(h, &e), GR_OK);

    r = gr_h5md_open(path, &e);
    assert_non_null(r);
    assert_int_equal(gr_h5md_info_of(r)->nframes, NFR + 1);
    assert_int_equal(gr_h5md_info_of(r)->nobs, NOBS);
    gr_particles *got = gr_particles_create(1, &e);
    for (int f = 0; f <= NFR; f++) {
        assert_int_equal(gr_h5md_read_frame(r, (size_t)f, got, NULL, NULL, &e), GR_OK);
        assert_same_particles(got, f < NFR ? want[f] : p);
    }
    size_t ns;
    gr_field_desc got_fd;
    assert_int_equal(gr_h5md_field_info(r, "rho", &got_fd, &ns, &e), GR_OK);
    assert_int_equal(ns, 1); /* the sample at 1.5 was dropped */
    gr_obs obs[NOBS];
    assert_int_equal(gr_h5md_read_obs(r, obs, &e), GR_OK);
    for (int k = 0; k < NOBS; k++) {
        gr_obs w = make_obs(k);
        assert_memory_equal(&obs[k].t, &w.t, sizeof w.t);
        assert_memory_equal(&obs[k].temperature, &w.temperature, sizeof(double));
    }
    gr_h5md_reader_free(r);

    /* Before the first frame: the trajectory starts again. */
    h = gr_h5md_reopen(path, &sc, &o, -1.0, &e);
    assert_non_null(h);
    assert_int_equal(gr_h5md_frames(h), 0);
    assert_int_equal(gr_h5md_write_frame(h, 0, 0.0, want[1], &e), GR_OK);
    assert_int_equal(gr_h5md_close(h, &e), GR_OK);
    r = gr_h5md_open(path, &e);
    assert_int_equal(gr_h5md_info_of(r)->nframes, 1);
    assert_int_equal(gr_h5md_info_of(r)->nobs, 0);
    assert_int_equal(gr_h5md_read_frame(r, 0, got, NULL, NULL, &e), GR_OK);
    assert_same_particles(got, want[1]);
    gr_h5md_reader_free(r);

    for (int f = 0; f < NFR; f++)
        gr_particles_free(want[f]);
    gr_particles_free(p);
    gr_particles_free(got);
    rm(path);
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
 * field without end, published after the first, a promotion every 50
 * frames; it is SIGKILLed after a random 20-420 ms; every file left must
 * open and read back every frame it reports. */
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
                    gr_h5md_write_field(h, &fd, (uint64_t)f, 0.1 * f, v, &e) ||
                    (!f && gr_h5md_publish(h, &e)))
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
        struct stat st;
        if (stat("killed-stress.h5", &st) != 0) {
            /* killed before its first samples were published: a .part */
            printf("trial %d: killed before the first frame was published\n", t);
            rm("killed-stress.h5.part");
            continue;
        }
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
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(killed_writer_leaves_readable_file),
        cmocka_unit_test(reopen_continues_the_file),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
