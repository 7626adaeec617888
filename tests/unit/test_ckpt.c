/* Checkpoint store: every array type round-trips bit for bit, length and
 * type mismatches fail, a checkpoint replaces the previous one only when
 * complete, and a checkpoint is also an H5MD file with its frame. */
#include "test.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "ckpt.h"
#include "h5md.h"
#include "scene.h"

static char scene_text[] = "# checkpointed scene\n[domain]\nwidth = 20\nheight = 10\n";

static gr_scene make_scene(void)
{
    gr_scene sc;
    memset(&sc, 0, sizeof sc);
    sc.text = scene_text;
    snprintf(sc.path, sizeof sc.path, "scenes/ckpt.ini");
    snprintf(sc.name, sizeof sc.name, "ckptbox");
    sc.width = 20.0;
    sc.height = 10.0;
    return sc;
}

static gr_particles *make_particles(size_t n, uint64_t seed)
{
    gr_err e = {0};
    gr_particles *p = gr_particles_create(n, &e);
    assert_non_null(p);
    for (size_t i = 0; i < n; i++) {
        double u = (double)((seed * 2654435761u + i * 40503u) % 1000003u) / 1000003.0;
        gr_particles_push(p, 20 * u, 10 * (1 - u), 0.5 + 0.1 * u, 1 + u, i % 4 ? 0 : GR_PF_FIXED,
                          (int32_t)(i % 2), &e);
        p->vx[i] = u - 0.5;
        p->vy[i] = 1.0 / 3.0 + u;
        p->omega[i] = -u * 7.0;
        p->id[i] = 500 + (int64_t)i;
    }
    return p;
}

static int file_exists(const char *p)
{
    struct stat st;
    return stat(p, &st) == 0;
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

static void checkpoint_arrays_round_trip(void **state)
{
    (void)state;
    const char *path = "state.ckpt";
    unlink(path);
    gr_err e = {0};
    double f64[5] = {1.0 / 3.0, -0.0, NAN, INFINITY, 0x1.fffffffffffffp+1023};
    int64_t i64[3] = {INT64_MIN, -1, INT64_MAX};
    uint64_t u64[2] = {0, UINT64_MAX};
    uint32_t u32[4] = {0, 1, 0xdeadbeefu, UINT32_MAX};
    unsigned char bytes[6] = {0, 255, 'g', 'r', 0, 7};
    gr_ckpt *c = gr_ckpt_create(path, &e);
    assert_non_null(c);
    assert_false(file_exists(path)); /* published only on close */
    assert_int_equal(gr_ckpt_put_f64(c, "dem/pos", f64, 5, &e), GR_OK);
    assert_int_equal(gr_ckpt_put_i64(c, "i64", i64, 3, &e), GR_OK);
    assert_int_equal(gr_ckpt_put_u64(c, "rng/state", u64, 2, &e), GR_OK);
    assert_int_equal(gr_ckpt_put_u32(c, "u32", u32, 4, &e), GR_OK);
    assert_int_equal(gr_ckpt_put_bytes(c, "bytes", bytes, 6, &e), GR_OK);
    assert_int_equal(gr_ckpt_put_f64(c, "empty", NULL, 0, &e), GR_OK);
    gr_scene sc = make_scene();
    gr_particles *p = make_particles(12, 9);
    gr_h5md_opts o = {.method = "edmd", .seed = 5};
    assert_int_equal(gr_ckpt_put_h5md(c, &sc, &o, 77, 3.5, p, &e), GR_OK);
    assert_int_equal(gr_ckpt_close(c, &e), GR_OK);
    assert_true(file_exists(path));
    assert_false(file_exists("state.ckpt.tmp"));

    c = gr_ckpt_open(path, &e);
    assert_non_null(c);
    double g64[5];
    int64_t gi64[3];
    uint64_t gu64[2];
    uint32_t gu32[4];
    unsigned char gb[6];
    size_t n;
    assert_int_equal(gr_ckpt_get_f64(c, "dem/pos", g64, 5, &e), GR_OK);
    assert_memory_equal(g64, f64, sizeof f64);
    assert_int_equal(gr_ckpt_get_i64(c, "i64", gi64, 3, &e), GR_OK);
    assert_memory_equal(gi64, i64, sizeof i64);
    assert_int_equal(gr_ckpt_get_u64(c, "rng/state", gu64, 2, &e), GR_OK);
    assert_memory_equal(gu64, u64, sizeof u64);
    assert_int_equal(gr_ckpt_get_u32(c, "u32", gu32, 4, &e), GR_OK);
    assert_memory_equal(gu32, u32, sizeof u32);
    assert_int_equal(gr_ckpt_get_bytes(c, "bytes", gb, 6, &e), GR_OK);
    assert_memory_equal(gb, bytes, sizeof bytes);
    assert_int_equal(gr_ckpt_len(c, "u32", &n, &e), GR_OK);
    assert_int_equal(n, 4);
    assert_int_equal(gr_ckpt_len(c, "empty", &n, &e), GR_OK);
    assert_int_equal(n, 0);
    assert_int_equal(gr_ckpt_get_f64(c, "empty", NULL, 0, &e), GR_OK);
    /* Wrong length, wrong type, absent name. */
    assert_int_equal(gr_ckpt_get_f64(c, "dem/pos", g64, 4, &e), GR_ERUN);
    assert_non_null(strstr(e.msg, "holds 5 elements, 4 expected"));
    assert_int_equal(gr_ckpt_get_u64(c, "i64", gu64, 3, &e), GR_ERUN);
    assert_non_null(strstr(e.msg, "holds i64, not u64"));
    assert_int_equal(gr_ckpt_get_u32(c, "bytes", gu32, 6, &e), GR_ERUN);
    assert_int_equal(gr_ckpt_get_f64(c, "nope", g64, 1, &e), GR_ERUN);
    assert_non_null(strstr(e.msg, "no array 'nope'"));
    assert_int_equal(gr_ckpt_put_f64(c, "x", f64, 1, &e), GR_ERUN); /* read-only */
    assert_int_equal(gr_ckpt_close(c, &e), GR_OK);

    /* The checkpoint is an H5MD file with the scene and its one frame. */
    gr_h5md_reader *r = gr_h5md_open(path, &e);
    assert_non_null(r);
    const gr_h5md_info *in = gr_h5md_info_of(r);
    assert_int_equal(in->has_checkpoint, 1);
    assert_int_equal(in->nframes, 1);
    assert_string_equal(in->scene_text, scene_text);
    assert_string_equal(in->method, "edmd");
    gr_particles *got = gr_particles_create(1, &e);
    uint64_t st;
    double t;
    assert_int_equal(gr_h5md_read_frame(r, 0, got, &st, &t, &e), GR_OK);
    assert_true(st == 77 && t == 3.5);
    assert_same_particles(got, p);
    gr_particles_free(got);
    gr_h5md_reader_free(r);
    gr_particles_free(p);
    unlink(path);
}

static void checkpoint_replaced_only_when_complete(void **state)
{
    (void)state;
    const char *path = "atomic.ckpt";
    unlink(path);
    gr_err e = {0};
    uint64_t one = 1, two = 2, got = 0;
    gr_ckpt *c = gr_ckpt_create(path, &e);
    assert_int_equal(gr_ckpt_put_u64(c, "v", &one, 1, &e), GR_OK);
    assert_int_equal(gr_ckpt_close(c, &e), GR_OK);

    /* Abandoned: the old one stays, no temporary is left. */
    c = gr_ckpt_create(path, &e);
    assert_int_equal(gr_ckpt_put_u64(c, "v", &two, 1, &e), GR_OK);
    gr_ckpt *old = gr_ckpt_open(path, &e); /* readable while the next is written */
    assert_non_null(old);
    assert_int_equal(gr_ckpt_get_u64(old, "v", &got, 1, &e), GR_OK);
    assert_true(got == 1);
    gr_ckpt_close(old, &e);
    gr_ckpt_discard(c);
    assert_false(file_exists("atomic.ckpt.tmp"));

    /* A store failed: close refuses to publish. */
    c = gr_ckpt_create(path, &e);
    assert_int_equal(gr_ckpt_put_u64(c, "v", &two, 1, &e), GR_OK);
    assert_int_equal(gr_ckpt_put_u64(c, "v", &two, 1, &e), GR_ERUN); /* twice */
    assert_int_equal(gr_ckpt_close(c, &e), GR_ERUN);
    assert_non_null(strstr(e.msg, "previous checkpoint"));
    assert_false(file_exists("atomic.ckpt.tmp"));

    c = gr_ckpt_open(path, &e);
    assert_int_equal(gr_ckpt_get_u64(c, "v", &got, 1, &e), GR_OK);
    assert_true(got == 1);
    gr_ckpt_close(c, &e);

    /* A complete one replaces it. */
    c = gr_ckpt_create(path, &e);
    assert_int_equal(gr_ckpt_put_u64(c, "v", &two, 1, &e), GR_OK);
    assert_int_equal(gr_ckpt_close(c, &e), GR_OK);
    c = gr_ckpt_open(path, &e);
    assert_int_equal(gr_ckpt_get_u64(c, "v", &got, 1, &e), GR_OK);
    assert_true(got == 2);
    gr_ckpt_close(c, &e);
    unlink(path);
    assert_null(gr_ckpt_open(path, &e));
    assert_int_equal(e.code, GR_EINPUT);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(checkpoint_arrays_round_trip),
        cmocka_unit_test(checkpoint_replaced_only_when_complete),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
