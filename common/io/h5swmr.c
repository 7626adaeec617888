/* Result files a kill cannot break (docs/reliability.md): HDF5's
 * single-writer/multiple-reader mode orders every flush so that the file
 * on disk is always one a reader could have opened; a kill at any moment
 * leaves the frames flushed before it readable. The mode appends to
 * existing datasets only: whatever adds or removes an object does so on a
 * copy under a temporary name, renamed over the file once consistent. */
#include "h5md_impl.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

hid_t gr_h5_paged_fcpl(void)
{
    hid_t p = gr_h5_untimed(H5P_FILE_CREATE);
    if (p >= 0 && (H5Pset_file_space_strategy(p, H5F_FSPACE_STRATEGY_PAGE, 0, 1) < 0 ||
                   H5Pset_file_space_page_size(p, 4096) < 0)) {
        H5Pclose(p);
        return -1;
    }
    return p;
}

/* A writer killed after its superblock recorded the end of the space it
 * had allocated, and before the last page was written, leaves a file
 * shorter than that end: a reader takes it (HDF5's SWMR reader checks no
 * end), a writer refuses it as truncated. The missing bytes were never
 * part of a flushed sample: the file is extended to that end with zeros. */
static int extend_to_eoa(const char *path)
{
    hid_t f = -1;
    haddr_t eoa = 0;
    struct stat st;
    GR_H5_QUIET(f = H5Fopen(path, H5F_ACC_RDONLY | H5F_ACC_SWMR_READ, H5P_DEFAULT));
    int ok = f >= 0 && H5Fget_eoa(f, &eoa) >= 0;
    if (f >= 0)
        H5Fclose(f);
    if (!ok || stat(path, &st) != 0 || (haddr_t)st.st_size >= eoa)
        return 0;
    return truncate(path, (off_t)eoa);
}

hid_t gr_h5_open_rw(const char *path)
{
    if (extend_to_eoa(path))
        return -1;
    hid_t fapl = gr_h5_fapl();
    /* A killed writer leaves the superblock marked open for writing; the
     * file itself is consistent (that is the mode's promise), so the mark is
     * cleared as h5clear -s would. */
    hbool_t clear = 1;
    hid_t f = -1;
    if (fapl >= 0 && H5Pset(fapl, "clear_status_flags", &clear) >= 0)
        f = H5Fopen(path, H5F_ACC_RDWR, fapl);
    gr_h5_close(fapl);
    return f;
}

hid_t gr_h5_open_ro(const char *path)
{
    hid_t fapl = gr_h5_fapl();
    if (fapl < 0)
        return -1;
    hid_t f = -1;
    GR_H5_QUIET(f = H5Fopen(path, H5F_ACC_RDONLY, fapl));
    /* a file being written (or whose writer was killed) opens as its
     * readers are meant to: SWMR read */
    if (f < 0)
        f = H5Fopen(path, H5F_ACC_RDONLY | H5F_ACC_SWMR_READ, fapl);
    gr_h5_close(fapl);
    return f;
}

int gr_h5_copy_file(const char *from, const char *to)
{
    int in = open(from, O_RDONLY), out = in < 0 ? -1 : open(to, O_WRONLY | O_CREAT | O_TRUNC, 0666);
    static const size_t bufsize = 1 << 20;
    char *buf = out < 0 ? NULL : malloc(bufsize);
    int rc = buf ? 0 : -1;
    for (ssize_t got; !rc && (got = read(in, buf, bufsize)) != 0;) {
        if (got < 0) {
            rc = errno == EINTR ? 0 : -1;
            continue;
        }
        for (ssize_t off = 0, w; !rc && off < got; off += w > 0 ? w : 0)
            if ((w = write(out, buf + off, (size_t)(got - off))) < 0 && errno != EINTR)
                rc = -1;
    }
    free(buf);
    if (in >= 0)
        close(in);
    if (out >= 0 && close(out))
        rc = -1;
    if (rc && out >= 0)
        unlink(to);
    return rc;
}

int gr_h5_swmr_start(hid_t file, const char *part, const char *path)
{
    if (H5Fflush(file, H5F_SCOPE_GLOBAL) < 0)
        return -1;
    unsigned intent = 0;
    if (H5Fget_intent(file, &intent) < 0)
        return -1;
    /* a file of an older format (a result begun by an older build) goes
     * on without the mode */
    H5F_info2_t fi;
    if (!(intent & H5F_ACC_SWMR_WRITE)) {
        herr_t st;
        GR_H5_QUIET(st = H5Fstart_swmr_write(file));
        /* only the 1.10 format (superblock 3) can, and then must: tried
         * again unguarded, so that the caller's guard hears HDF5's reason */
        if (st < 0 && (H5Fget_info2(file, &fi) < 0 || fi.super.version >= 3) &&
            H5Fstart_swmr_write(file) < 0)
            return -1;
    }
    return part && rename(part, path) != 0 ? 1 : 0;
}

int gr_h5_swmr_copy(hid_t *file, hid_t *const *objs, size_t n, const char *path, const char *part)
{
    char **names = calloc(n ? n : 1, sizeof *names);
    int rc = names && H5Fflush(*file, H5F_SCOPE_GLOBAL) >= 0 ? 0 : -1;
    for (size_t k = 0; k < n && !rc; k++) {
        if (*objs[k] < 0)
            continue;
        ssize_t len = H5Iget_name(*objs[k], NULL, 0);
        if (len <= 0 || !(names[k] = malloc((size_t)len + 1)) ||
            H5Iget_name(*objs[k], names[k], (size_t)len + 1) != len)
            rc = -1;
    }
    if (!rc) {
        for (size_t k = 0; k < n; k++) {
            gr_h5_close(*objs[k]);
            *objs[k] = -1;
        }
        rc = H5Fclose(*file) < 0 ? -1 : 0;
        *file = -1;
        rc = rc || gr_h5_copy_file(path, part) ? -1 : 0;
        *file = rc ? -1 : gr_h5_open_rw(part);
        rc = *file < 0 ? -1 : 0;
        for (size_t k = 0; k < n && !rc; k++)
            if (names[k] && (*objs[k] = H5Oopen(*file, names[k], H5P_DEFAULT)) < 0)
                rc = -1;
    }
    for (size_t k = 0; k < n && names; k++)
        free(names[k]);
    free(names);
    return rc;
}
