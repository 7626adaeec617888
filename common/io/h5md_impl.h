/* Internals shared by the H5MD writer, reader, XDMF sidecar and checkpoint
 * store. Not part of the public interface: only common/ includes it. */
#ifndef GR_H5MD_IMPL_H
#define GR_H5MD_IMPL_H

#include <hdf5.h>

#include "h5md.h"

#ifndef GRANO_VERSION
#define GRANO_VERSION "unknown"
#endif

/* HDF5 calls run inside a guard: the library's own report to stderr is
 * replaced by a recorder that keeps the innermost description of the first
 * failure (e.g. "unable to lock file, errno = 11 ..."); if the guarded
 * statement failed, that description is appended to err's message. (Any
 * successful HDF5 call clears the library's error stack, so the cause must
 * be caught when it happens, not when the failure is reported.) */
typedef struct {
    H5E_auto2_t fn;
    void *data;
    char text[400];
    int set;
} gr_h5_guard;
void gr_h5_guard_begin(gr_h5_guard *g);
void gr_h5_guard_end(gr_h5_guard *g, gr_err *err); /* err NULL: append nothing */
#define GR_H5_GUARD(err, failed, stmt)                                         \
    do {                                                                       \
        gr_h5_guard g5_;                                                       \
        gr_h5_guard_begin(&g5_);                                               \
        stmt;                                                                  \
        gr_h5_guard_end(&g5_, (failed) ? (err) : NULL);                        \
    } while (0)
#define GR_H5_QUIET(stmt) GR_H5_GUARD(NULL, 0, stmt)

/* Fill err (the guard adds the HDF5 cause). Returns code. */
int gr_h5_fail(gr_err *err, int code, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* File access list: strong close (the file is really closed by H5Fclose, so
 * a rename after it is safe) and the 1.10 format, which the
 * single-writer/multiple-reader mode needs (HDF5 1.10 or later reads it). */
hid_t gr_h5_fapl(void);
/* The data of a chunk of several rows: a page less its checksum. */
#define GR_H5_PAGE_DATA 4092

/* The single-writer/multiple-reader mode (h5swmr.c). Open for writing,
 * clearing the mark a killed writer leaves; open for reading, in SWMR read
 * mode when a writer has the file (or was killed holding it). */
/* File creation list of a result: no modification times, and the file's
 * space in pages of 4 KiB, an object smaller than a page within one page:
 * a kill cannot tear a write within a page (Linux stops a write between
 * pages), and a torn chunk or header would fail its checksum. */
hid_t gr_h5_paged_fcpl(void);
hid_t gr_h5_open_rw(const char *path);
hid_t gr_h5_open_ro(const char *path);
int gr_h5_copy_file(const char *from, const char *to);
/* Flush, enter the mode (a file of an older format goes on without it),
 * then rename part to path if part is given: -1 when HDF5 failed, 1 when
 * the rename did (errno says why). */
int gr_h5_swmr_start(hid_t file, const char *part, const char *path);
/* Leave the mode to change the file's objects: close *file (flushed) and
 * the n objects, copy path to part, open part for writing and reopen every
 * object by its name in *objs. */
int gr_h5_swmr_copy(hid_t *file, hid_t *const *objs, size_t n, const char *path, const char *part);
/* A creation property list of class cls (H5P_FILE_CREATE for a file's
 * root group, H5P_GROUP_CREATE, H5P_DATASET_CREATE) that records no
 * modification time: the same run writes the same bytes. */
hid_t gr_h5_untimed(hid_t cls);
void gr_h5_close(hid_t id); /* any id kind, ignores <= 0 */

/* Attributes. */
int gr_h5_attr_str(hid_t obj, const char *name, const char *value, int vlen);
int gr_h5_attr_strs(hid_t obj, const char *name, const char *const *v, size_t n, int vlen);
int gr_h5_attr_int(hid_t obj, const char *name, const int *v, size_t n); /* n 0: scalar */
int gr_h5_attr_f64(hid_t obj, const char *name, const double *v, size_t n);
int gr_h5_unit(hid_t obj, const char *unit);
/* String attribute (fixed or variable length) as a malloc'd string; NULL if
 * absent or unreadable. */
char *gr_h5_read_attr_str(hid_t obj, const char *name);
int gr_h5_read_attr_int(hid_t obj, const char *name, int *v, size_t n);
int gr_h5_read_attr_f64(hid_t obj, const char *name, double *v, size_t n);

/* Scalar datasets. */
int gr_h5_dset_str(hid_t loc, const char *name, const char *text);
int gr_h5_dset_u64(hid_t loc, const char *name, uint64_t v);
char *gr_h5_read_dset_str(hid_t loc, const char *name);
int gr_h5_read_dset_u64(hid_t loc, const char *name, uint64_t *v);

/* Element types. */
typedef enum { GR_T_F64 = 0, GR_T_I64, GR_T_I32, GR_T_U32, GR_T_U64, GR_T_U8 } gr_h5_type;
hid_t gr_h5_ftype(gr_h5_type t); /* little-endian file type */
hid_t gr_h5_mtype(gr_h5_type t); /* native memory type */
size_t gr_h5_tsize(gr_h5_type t);

/* Extendible datasets: shape [rows][item...], rows growing one at a time. */
hid_t gr_h5_ext_create(hid_t loc, const char *name, gr_h5_type t, int item_rank,
                       const hsize_t *item_dims);
int gr_h5_ext_append(hid_t dset, gr_h5_type t, const void *row);
/* HDF5's Fletcher-32 checksum of len bytes, as its filter computes it. */
uint32_t gr_h5_fletcher32(const void *data, size_t len);
hsize_t gr_h5_rows(hid_t dset); /* first dimension; 0 on error */
int gr_h5_read_rows(hid_t dset, gr_h5_type t, hsize_t first, hsize_t count, void *buf);
/* Fixed dataset of rank 1 or 2 (dims[1] 0 for rank 1), with a checksum as
 * the extendible ones have (gr_h5_checked_dcpl). */
hid_t gr_h5_fixed_create(hid_t loc, const char *name, gr_h5_type t, const hsize_t dims[2],
                         const void *data);

/* A dataset creation list that checksums every chunk (HDF5's Fletcher-32
 * filter: a read of a damaged chunk fails, naming the dataset), the data
 * in chunks of about 1 MiB along the first dimension; H5P_DEFAULT for an
 * empty dataset, which has nothing to damage. Close it with gr_h5_close. */
hid_t gr_h5_checked_dcpl(int rank, const hsize_t *dims, size_t elsize);

int gr_h5_exists(hid_t loc, const char *path); /* link exists (all components) */
int gr_h5_is_group(hid_t loc, const char *path);
hid_t gr_h5_mkgroup(hid_t loc, const char *path); /* with intermediate groups */
/* Complete samples of a time-dependent element group: the fewest rows of
 * its step, time and value (a writer killed mid-sample leaves them uneven). */
hsize_t gr_h5_series_rows(hid_t loc, const char *group);
int gr_h5_read_path(hid_t loc, const char *path, gr_h5_type t, hsize_t first, hsize_t count,
                    void *buf);
/* A name usable under results/ or fields/: relative, no "..", no XML specials. */
int gr_h5_valid_name(const char *s);

/* The file behind a writer or reader, and the writer's path for messages. */
hid_t gr_h5md_file_of(const gr_h5md *h);
const char *gr_h5md_path_of(const gr_h5md *h);
hid_t gr_h5md_reader_file(const gr_h5md_reader *r);

/* Drop the contact networks of frames later than t_keep (a restart writes
 * them again); 0 when there are none. */
int gr_h5md_contacts_keep(hid_t file, double t_keep);

/* ---- writer state (h5md.c; reopened by h5md_append.c) ---- */

enum { E_POS, E_VEL, E_OMEGA, E_FLAGS, E_RADIUS, E_MASS, E_INERTIA, E_SPECIES, E_ID, NPE };
typedef struct {
    const char *name;
    const char *unit;
    gr_h5_type type;
    int ncomp;        /* 1 or 2 (x, y) */
    int once;         /* stored once, as a dataset, until it changes */
} gr_elem_def;

typedef struct {
    hid_t group;   /* time-dependent: the element group */
    hid_t value;   /* time-dependent: its value; once: the dataset itself */
    int series;
    void *prev;    /* once: the stored values, to notice a change */
} gr_elem;

struct gr_h5md {
    hid_t file;
    int owned;            /* created by gr_h5md_create: closed on free */
    int broken;           /* a write failed half-way: refuse further frames */
    char *path, *xdmf, *h5name;
    char *part;           /* path.part: the file while unpublished */
    int published;        /* at path, in SWMR write mode */
    int republish;        /* unpublished to add objects: publish after the write */
    hid_t traj, box;
    size_t n, frames;
    size_t xdmf_frames;   /* frames in the sidecar on disk */
    hid_t step, time, edges;
    gr_elem pe[NPE];
    double width, height;
    void *buf;
    double *times;
    size_t times_cap;
    double last_time;
    hid_t obs_step, obs_time;
    gr_elem oe[GR_OBS_MAX];
    const gr_obs_def *odefs; /* the declared observables (gr_h5md_opts.obs) */
    size_t noe;
    uint64_t oskip;          /* declared but not written (gr_h5md_opts.obs_skip) */
    size_t o0;               /* the first written: owner of step and time */
    size_t nobs;
    double last_obs_time;
};

extern const gr_elem_def gr_h5md_pdefs[NPE];
/* Take the observables o declares (the particle set if none). */
int gr_h5md_set_obs(gr_h5md *h, const gr_h5md_opts *o);
gr_h5md *gr_h5md_alloc(void);
herr_t gr_h5md_release(gr_h5md *h); /* close handles (and the owned file), free */
int gr_h5md_write_sidecar(gr_h5md *h, gr_err *err);
/* Before a write that adds or removes objects: a published file goes on in
 * a copy (gr_h5_swmr_copy); after it, gr_h5md_edited publishes it again. */
int gr_h5md_edit(gr_h5md *h);
int gr_h5md_edited(gr_h5md *h, gr_err *err);
char *gr_h5_catstr(const char *a, const char *b); /* malloc'd a b */

/* Attach the H5MD layout to an open file that the caller keeps owning (the
 * checkpoint store): no rename, no sidecar, the file stays open on free. */
gr_h5md *gr_h5md_attach(hid_t file, const struct gr_scene *sc, const gr_h5md_opts *o,
                        gr_err *err);

/* XDMF sidecar: rewrite xdmf_path (via a temporary and rename) for the
 * trajectory in h5_name (a path relative to the sidecar), and for every
 * field found in file (skipped if file < 0). */
typedef struct {
    const char *name;      /* element under particles/trajectory */
    int series;            /* time-dependent (group with value) or a dataset */
    int ncomp;             /* 1 or 2 */
    gr_h5_type type;
} gr_xdmf_attr;

int gr_xdmf_write(const char *xdmf_path, const char *h5_name, hid_t file, size_t n,
                  size_t frames, const double *times, const gr_xdmf_attr *attrs,
                  size_t nattrs, gr_err *err);

#endif
