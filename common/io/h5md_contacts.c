/* The contact network of each frame in a result file (a grano extension
 * beside H5MD's groups, docs/output-format.md):
 *   contacts/step, contacts/time, contacts/count   one row per frame
 *   contacts/i, contacts/j                         one row per contact
 *   contacts/force                                 [rows][2]: fn, ft
 * Frame k's contacts are the rows from the sum of count[0..k) on. A frame's
 * rows are written before its count, step and time, so a run killed in the
 * middle leaves rows that no count claims: readers take the counts. */
#include "h5md_impl.h"

#include <stdlib.h>
#include <string.h>

#include "contacts.h"

/* Append rows to an extendible dataset of item size `per` doubles or ints. */
static int append_rows(hid_t d, gr_h5_type t, hsize_t rows, hsize_t per, const void *data)
{
    if (!rows)
        return 0;
    hsize_t dims[2], start[2] = {0, 0}, count[2] = {rows, per};
    hid_t fs = H5Dget_space(d);
    int rank = fs >= 0 ? H5Sget_simple_extent_ndims(fs) : -1;
    if (rank >= 1 && rank <= 2)
        H5Sget_simple_extent_dims(fs, dims, NULL);
    gr_h5_close(fs);
    if (rank < 1 || rank > 2)
        return -1;
    start[0] = dims[0];
    dims[0] += rows;
    if (H5Dset_extent(d, dims) < 0)
        return -1;
    fs = H5Dget_space(d);
    hid_t ms = H5Screate_simple(rank, count, NULL);
    int rc = fs >= 0 && ms >= 0 &&
                     H5Sselect_hyperslab(fs, H5S_SELECT_SET, start, NULL, count, NULL) >= 0 &&
                     H5Dwrite(d, gr_h5_mtype(t), ms, fs, H5P_DEFAULT, data) >= 0
                 ? 0
                 : -1;
    gr_h5_close(ms);
    gr_h5_close(fs);
    return rc;
}

static hid_t open_or_create(hid_t g, const char *name, gr_h5_type t, int item_rank,
                            const hsize_t *item, const char *unit)
{
    if (gr_h5_exists(g, name))
        return H5Dopen2(g, name, H5P_DEFAULT);
    hid_t d = gr_h5_ext_create(g, name, t, item_rank, item);
    if (d >= 0 && unit && gr_h5_unit(d, unit) < 0) {
        gr_h5_close(d);
        return -1;
    }
    return d;
}

static int contacts_group(hid_t file, hid_t *g)
{
    if (gr_h5_exists(file, "contacts")) {
        *g = H5Gopen2(file, "contacts", H5P_DEFAULT);
        return *g < 0 ? -1 : 0;
    }
    *g = gr_h5_mkgroup(file, "contacts");
    if (*g < 0)
        return -1;
    return gr_h5_attr_str(*g, "description",
                          "contact network per frame: rows sum(count[0..k)) onwards are frame k's; "
                          "j = -1 - w for wall w; force = (fn, ft) on grain i",
                          0);
}

static int write_impl(gr_h5md *h, uint64_t step, double time, const gr_contacts *c, gr_err *err)
{
    hid_t g = -1, d[6] = {-1, -1, -1, -1, -1, -1};
    hsize_t two = 2;
    uint64_t n = c->n;
    /* time is made last: with it, the group is whole */
    int rc = !gr_h5_exists(h->file, "contacts/time") && gr_h5md_edit(h);
    rc = rc || contacts_group(h->file, &g);
    if (!rc) {
        d[0] = open_or_create(g, "i", GR_T_I64, 0, NULL, NULL);
        d[1] = open_or_create(g, "j", GR_T_I64, 0, NULL, NULL);
        d[2] = open_or_create(g, "force", GR_T_F64, 1, &two, "m d tau-2");
        d[3] = open_or_create(g, "count", GR_T_U64, 0, NULL, NULL);
        d[4] = open_or_create(g, "step", GR_T_U64, 0, NULL, NULL);
        d[5] = open_or_create(g, "time", GR_T_F64, 0, NULL, "tau");
        for (int k = 0; k < 6 && !rc; k++)
            rc = d[k] < 0 ? -1 : 0;
    }
    double *f = rc ? NULL : malloc((c->n ? 2 * c->n : 1) * sizeof *f);
    if (!rc && f) {
        for (size_t k = 0; k < c->n; k++)
            f[2 * k] = c->fn[k], f[2 * k + 1] = c->ft[k];
        rc = rc || append_rows(d[0], GR_T_I64, c->n, 1, c->i) || append_rows(d[1], GR_T_I64, c->n, 1, c->j) ||
             append_rows(d[2], GR_T_F64, c->n, 2, f) || gr_h5_ext_append(d[3], GR_T_U64, &n) ||
             gr_h5_ext_append(d[4], GR_T_U64, &step) || gr_h5_ext_append(d[5], GR_T_F64, &time);
    }
    free(f);
    for (int k = 0; k < 6; k++)
        gr_h5_close(d[k]);
    gr_h5_close(g);
    if (rc || (!rc && H5Fflush(h->file, H5F_SCOPE_GLOBAL) < 0))
        return gr_h5_fail(err, GR_ERUN, "%s: cannot write the contact network at t = %g",
                          gr_h5md_path_of(h), time);
    return gr_h5md_edited(h, err);
}

int gr_h5md_write_contacts(gr_h5md *h, uint64_t step, double time, const gr_contacts *c,
                           gr_err *err)
{
    int rc;
    GR_H5_GUARD(err, rc, rc = write_impl(h, step, time, c, err));
    return rc;
}

/* Complete frames of the network: the fewest rows of count, step, time. */
static hsize_t frames_of(hid_t f)
{
    static const char *const parts[] = {"contacts/count", "contacts/step", "contacts/time"};
    hsize_t r = (hsize_t)-1;
    for (int k = 0; k < 3; k++) {
        hid_t d = gr_h5_exists(f, parts[k]) ? H5Dopen2(f, parts[k], H5P_DEFAULT) : -1;
        hsize_t n = d >= 0 ? gr_h5_rows(d) : 0;
        gr_h5_close(d);
        r = n < r ? n : r;
    }
    return r;
}

/* Rows of the frames before frame k. */
static int rows_before(hid_t f, hsize_t k, uint64_t *rows)
{
    uint64_t *cnt = malloc((k ? k : 1) * sizeof *cnt);
    if (!cnt || (k && gr_h5_read_path(f, "contacts/count", GR_T_U64, 0, k, cnt))) {
        free(cnt);
        return -1;
    }
    *rows = 0;
    for (hsize_t q = 0; q < k; q++)
        *rows += cnt[q];
    free(cnt);
    return 0;
}

int gr_h5md_contact_frames(gr_h5md_reader *r, size_t *frames, gr_err *err)
{
    hid_t f = gr_h5md_reader_file(r);
    (void)err; /* absent or unreadable counts both mean no network */
    GR_H5_QUIET(*frames = gr_h5_exists(f, "contacts/count") ? frames_of(f) : 0);
    return GR_OK;
}

static int read_impl(hid_t f, size_t k, gr_contacts *c, uint64_t *step, double *time, gr_err *err)
{
    hsize_t frames = gr_h5_exists(f, "contacts/count") ? frames_of(f) : 0;
    uint64_t first = 0, n = 0;
    if (k >= frames || rows_before(f, k, &first) ||
        gr_h5_read_path(f, "contacts/count", GR_T_U64, k, 1, &n))
        return gr_h5_fail(err, GR_EINPUT, "no contact network for frame %zu (%llu frames hold one)", k,
                          (unsigned long long)frames);
    if (gr_contacts_reserve(c, n ? n : 1, err))
        return err->code;
    double *fr = malloc((n ? 2 * n : 1) * sizeof *fr);
    int bad = !fr || gr_h5_read_path(f, "contacts/i", GR_T_I64, first, n, c->i) ||
              gr_h5_read_path(f, "contacts/j", GR_T_I64, first, n, c->j) ||
              gr_h5_read_path(f, "contacts/force", GR_T_F64, first, n, fr) ||
              (step && gr_h5_read_path(f, "contacts/step", GR_T_U64, k, 1, step)) ||
              (time && gr_h5_read_path(f, "contacts/time", GR_T_F64, k, 1, time));
    for (uint64_t q = 0; !bad && q < n; q++)
        c->fn[q] = fr[2 * q], c->ft[q] = fr[2 * q + 1];
    free(fr);
    c->n = bad ? 0 : n;
    return bad ? gr_h5_fail(err, GR_ERUN, "cannot read the contact network of frame %zu", k) : GR_OK;
}

int gr_h5md_read_contacts(gr_h5md_reader *r, size_t k, gr_contacts *c, uint64_t *step,
                          double *time, gr_err *err)
{
    int rc;
    GR_H5_GUARD(err, rc, rc = read_impl(gr_h5md_reader_file(r), k, c, step, time, err));
    return rc;
}

/* A restart drops the frames later than t_keep: their networks go too. */
int gr_h5md_contacts_keep(hid_t file, double t_keep)
{
    if (!gr_h5_exists(file, "contacts/count"))
        return 0;
    hsize_t nf = frames_of(file), keep = 0;
    double *t = malloc((nf ? nf : 1) * sizeof *t);
    if (!t || (nf && gr_h5_read_path(file, "contacts/time", GR_T_F64, 0, nf, t))) {
        free(t);
        return -1;
    }
    while (keep < nf && t[keep] <= t_keep)
        keep++;
    free(t);
    /* rows past the kept frames' counts go too: later frames, or one cut short */
    uint64_t rows;
    if (rows_before(file, keep, &rows))
        return -1;
    static const char *const per_frame[] = {"count", "step", "time"};
    static const char *const per_row[] = {"i", "j", "force"};
    int rc = 0;
    for (int k = 0; k < 6 && !rc; k++) {
        char p[64];
        snprintf(p, sizeof p, "contacts/%s", k < 3 ? per_frame[k] : per_row[k - 3]);
        hid_t d = H5Dopen2(file, p, H5P_DEFAULT);
        hsize_t dims[2];
        hid_t s = d >= 0 ? H5Dget_space(d) : -1;
        int rank = s >= 0 ? H5Sget_simple_extent_ndims(s) : -1;
        if (rank >= 1 && rank <= 2)
            H5Sget_simple_extent_dims(s, dims, NULL);
        dims[0] = k < 3 ? keep : rows;
        rc = rank < 1 || rank > 2 || H5Dset_extent(d, dims) < 0 ? -1 : 0;
        gr_h5_close(s);
        gr_h5_close(d);
    }
    return rc;
}
