/* Contact networks in a result file (contacts/, docs/output-format.md):
 * each frame's rows read back exactly; a frame whose rows were written but
 * whose count was not (a run killed in between) is not a frame; a restart
 * from t = 1 drops the networks of later frames, rows included. */
#include "test.h"

#include <hdf5.h>

#include "h5md_sample.h"

/* Frame f: f + 2 contacts with recognisable values. */
static gr_contacts *make_net(int f)
{
    gr_err e = {0};
    gr_contacts *c = gr_contacts_create(0, &e);
    for (int k = 0; k < f + 2; k++)
        assert_int_equal(gr_contacts_push(c, 100 * f + k, k == 0 ? -3 : 100 * f + k + 1, 10.0 * f + k,
                                          -0.5 * k, &e),
                         GR_OK);
    return c;
}

static void assert_net(gr_h5md_reader *r, int f)
{
    gr_err e = {0};
    gr_contacts *got = gr_contacts_create(0, &e), *want = make_net(f);
    uint64_t step;
    double t;
    assert_int_equal(gr_h5md_read_contacts(r, (size_t)f, got, &step, &t, &e), GR_OK);
    assert_int_equal(got->n, want->n);
    assert_memory_equal(got->i, want->i, want->n * sizeof(int64_t));
    assert_memory_equal(got->j, want->j, want->n * sizeof(int64_t));
    assert_memory_equal(got->fn, want->fn, want->n * sizeof(double));
    assert_memory_equal(got->ft, want->ft, want->n * sizeof(double));
    assert_true(step == 100u * (uint64_t)f && t == 0.5 * f);
    gr_contacts_free(got);
    gr_contacts_free(want);
}

static size_t net_frames(const char *path)
{
    gr_err e = {0};
    gr_h5md_reader *r = gr_h5md_open(path, &e);
    assert_non_null(r);
    size_t n = 99;
    assert_int_equal(gr_h5md_contact_frames(r, &n, &e), GR_OK);
    gr_h5md_reader_free(r);
    return n;
}

static void networks_round_trip_and_restart(void **state)
{
    (void)state;
    const char *path = "contacts.h5";
    gr_h5md *h = write_sample(path, NULL, 0);
    gr_err e = {0};
    for (int f = 0; f < NFR; f++) {
        gr_contacts *c = make_net(f);
        assert_int_equal(gr_h5md_write_contacts(h, 100u * (uint64_t)f, 0.5 * f, c, &e), GR_OK);
        gr_contacts_free(c);
    }
    assert_int_equal(gr_h5md_close(h, &e), GR_OK);
    gr_h5md_reader *r = gr_h5md_open(path, &e);
    for (int f = 0; f < NFR; f++)
        assert_net(r, f);
    double times[NFR];
    assert_int_equal(gr_h5md_series_times(r, "contacts", NFR, times, &e), GR_OK);
    for (int f = 0; f < NFR; f++)
        assert_true(times[f] == 0.5 * f);
    assert_int_equal(gr_h5md_read_contacts(r, NFR, NULL, NULL, NULL, &e), GR_EINPUT);
    gr_h5md_reader_free(r);

    /* rows of a sixth frame without its count: a write cut short */
    hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    hid_t d = H5Dopen2(f, "contacts/i", H5P_DEFAULT);
    hsize_t dims[1] = {0};
    hid_t s = H5Dget_space(d);
    H5Sget_simple_extent_dims(s, dims, NULL);
    H5Sclose(s);
    dims[0] += 3;
    assert_true(H5Dset_extent(d, dims) >= 0);
    H5Dclose(d);
    H5Fclose(f);
    assert_int_equal(net_frames(path), NFR);

    gr_scene sc = make_scene();
    gr_h5md_opts o = {.method = "dem", .seed = 12345678901234567ull, .version = "0.1.0-test"};
    h = gr_h5md_reopen(path, &sc, &o, 1.0, &e);
    if (!h)
        fail_msg("%s", e.msg);
    assert_int_equal(gr_h5md_close(h, &e), GR_OK);
    assert_int_equal(net_frames(path), 3); /* t = 0, 0.5, 1 */
    r = gr_h5md_open(path, &e);
    for (int q = 0; q < 3; q++)
        assert_net(r, q);
    gr_h5md_reader_free(r);
    f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    d = H5Dopen2(f, "contacts/force", H5P_DEFAULT);
    hsize_t fd[2];
    s = H5Dget_space(d);
    H5Sget_simple_extent_dims(s, fd, NULL);
    H5Sclose(s);
    H5Dclose(d);
    H5Fclose(f);
    assert_int_equal(fd[0], 2 + 3 + 4); /* the kept frames' rows, and no more */
    rm(path);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(networks_round_trip_and_restart)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
