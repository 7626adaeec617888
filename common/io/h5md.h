/* Result files: HDF5 in the H5MD 1.1 layout (dimension 2), written as the
 * run goes and flushed after every write, so a killed run leaves a readable
 * file; an XDMF sidecar lets ParaView open the trajectory. The layout is
 * documented in docs/output-format.md. Every function returns a status
 * (GR_OK, GR_ERUN, GR_EINPUT) and fills err; nothing here prints. */
#ifndef GR_H5MD_H
#define GR_H5MD_H

#include <stddef.h>
#include <stdint.h>

#include "err.h"
#include "contacts.h"
#include "observe.h"
#include "particles.h"

struct gr_scene;

/* ---- writer ---------------------------------------------------------- */

typedef struct gr_h5md gr_h5md;

/* What goes into h5md/ and parameters/ besides the scene. A zeroed struct
 * is valid: no method, seed 0, no overwrite, sidecar written. */
typedef struct gr_h5md_opts {
    const char *method;   /* backend name (parameters/method) */
    uint64_t seed;        /* parameters/seed */
    int force;            /* replace an existing file */
    const char *version;  /* grano version for h5md/creator; NULL: built-in */
    const char *author;   /* h5md/author; NULL: $GRANO_AUTHOR, $USER, "unknown" */
    int no_xdmf;          /* 1: no <path>.xdmf sidecar */
    int any_text;         /* gr_h5md_reopen: the scene text may differ (a restart
                           * whose [run] or [measure] changed); the file keeps its own */
    const gr_obs_def *obs; /* the observables written (NULL-name ended); NULL: the particle set */
    uint64_t obs_skip;     /* bit k: obs[k] is not written (the scene has no such quantity) */
    const char *derived;   /* parameters/derived: what the method derived from the scene
                            * (written when not NULL or empty) */
} gr_h5md_opts;

/* Call first thing in main: the HDF5 library then runs no exit handler.
 * After a failed write (a full disk) a file cannot be closed, and the
 * handler's second attempt at exit crashed the program. */
void gr_h5_no_exit_handler(void);

/* Create path. Refuses an existing path unless o->force (GR_EINPUT naming
 * the file and --force). The file is built as <path>.part and appears at
 * path when published (gr_h5md_publish) or closed, so a failed creation
 * leaves nothing that looks like a result. sc may not be NULL. */
gr_h5md *gr_h5md_create(const char *path, const struct gr_scene *sc,
                        const gr_h5md_opts *o, gr_err *err);

/* Rename the file to its path in HDF5's single-writer/multiple-reader
 * mode: from then on a kill leaves it readable with every sample flushed
 * before the kill, and readers may open it while it grows (in SWMR read
 * mode, as gr_h5md_open does). Call once the first samples of every kind
 * exist (a later write that adds objects works on a copy renamed over the
 * file). A no-op when published already. */
int gr_h5md_publish(gr_h5md *h, gr_err *err);

/* Continue the result file of a run restarted from a checkpoint taken at
 * time t_keep, published (gr_h5md_publish): opens a copy for writing, checks that it holds a run of the
 * same scene text, method and seed (GR_EINPUT otherwise, nothing changed),
 * and drops every frame, observable sample and field sample later than
 * t_keep, which the resumed run writes again; results/ are kept. */
gr_h5md *gr_h5md_reopen(const char *path, const struct gr_scene *sc,
                        const gr_h5md_opts *o, double t_keep, gr_err *err);

/* Append a trajectory frame: every grain of p in the order given (the order
 * and count must stay the same for the whole file). A non-finite position,
 * velocity or spin is refused (GR_ERUN naming the grain), nothing written.
 * Radius, mass, inertia, species and id are stored once, and become
 * time-dependent series the first time one of them changes. */
int gr_h5md_write_frame(gr_h5md *h, uint64_t step, double time,
                        const gr_particles *p, gr_err *err);

/* Append one sample of every observable (step = o->steps, time = o->t). */
int gr_h5md_write_obs(gr_h5md *h, const gr_obs *o, gr_err *err);

/* The contact network of a frame (contacts/, docs/output-format.md): rows
 * (i, j, fn, ft) after those of the earlier frames, then the frame's count,
 * step and time, so a run killed half-way leaves only complete frames. */
int gr_h5md_write_contacts(gr_h5md *h, uint64_t step, double time, const gr_contacts *c,
                           gr_err *err);

/* A field on a regular grid: fields/<name>, values[(iy * nx + ix) * ncomp + c]
 * for the cell whose lower-left corner is (x0 + ix dx, y0 + iy dy). */
typedef struct {
    const char *name;
    const char *unit;     /* H5MD unit string, e.g. "1", "d tau-1" */
    int nx, ny;
    int ncomp;            /* 1: scalar field, 2: vector field, 4: 2x2 tensor (xx xy yx yy) */
    double x0, y0;        /* origin: lower-left corner of the grid */
    double dx, dy;        /* cell size */
} gr_field_desc;

/* Append one sample of a field; the first call fixes its grid, later calls
 * must match it. */
int gr_h5md_write_field(gr_h5md *h, const gr_field_desc *f, uint64_t step,
                        double time, const double *values, gr_err *err);

/* A result table or array of an experiment: results/<name> (name may hold
 * '/' for subgroups), float64 [rows] when cols == 0, else [rows][cols].
 * Writing an existing name replaces it. */
typedef struct {
    const char *name;
    size_t rows, cols;
    const char *const *columns; /* cols names, or NULL */
    const char *const *units;   /* cols unit strings (or one when cols == 0), or NULL */
    const char *description;    /* one line, or NULL */
} gr_result_desc;

int gr_h5md_write_result(gr_h5md *h, const gr_result_desc *d, const double *v,
                         gr_err *err);

/* Flush to disk (every write above already does). */
int gr_h5md_flush(gr_h5md *h, gr_err *err);
/* Flush, finish the sidecar and close; h is freed whatever the status. */
int gr_h5md_close(gr_h5md *h, gr_err *err);
/* Close without reporting (error paths); accepts NULL. */
void gr_h5md_free(gr_h5md *h);

/* Frames written so far. */
size_t gr_h5md_frames(const gr_h5md *h);

/* Read every object of an HDF5 file back (each dataset to its end): GR_OK
 * with the datasets and bytes read, or GR_ERUN naming the first damaged
 * object (a checksum that fails, a header that does not read). */
int gr_h5_verify(const char *path, size_t *ndsets, unsigned long long *bytes, gr_err *err);

/* ---- reader ---------------------------------------------------------- */

typedef struct gr_h5md_reader gr_h5md_reader;

typedef struct {
    char *path;
    char *creator, *creator_version, *author; /* h5md/ */
    int h5md_version[2];
    char *scene_text, *scene_name, *scene_path;  /* parameters/ */
    char *method, *grano_version;
    char *derived;        /* parameters/derived, "" when absent */
    uint64_t seed;
    size_t nparticles;    /* grains per frame (0 without frames) */
    size_t nframes;       /* complete frames */
    double box[2];        /* edges */
    int periodic[2];      /* boundary per axis */
    size_t nobs;          /* complete observable samples */
    int has_checkpoint;   /* a /checkpoint group is present */
    int writing;          /* opened in SWMR read mode: a run is writing it, or its
                           * writer stopped without closing it (a kill) */
} gr_h5md_info;

/* Open a grano result or checkpoint file read-only. A missing file, a file
 * that is not HDF5, or an HDF5 file that grano did not write fail with
 * GR_EINPUT and a message naming the file. */
gr_h5md_reader *gr_h5md_open(const char *path, gr_err *err);
void gr_h5md_reader_free(gr_h5md_reader *r);
const gr_h5md_info *gr_h5md_info_of(const gr_h5md_reader *r);

/* Times and steps of the nframes frames (either may be NULL). */
int gr_h5md_read_times(gr_h5md_reader *r, double *time, uint64_t *step, gr_err *err);
/* Frame i into p (resized; every field set; inertia from the file when
 * stored, else that of a disk). step and time may be NULL. */
int gr_h5md_read_frame(gr_h5md_reader *r, size_t frame, gr_particles *p,
                       uint64_t *step, double *time, gr_err *err);
/* The nobs observable samples into obs[]; a quantity absent from the file
 * is NaN (counts: 0). */
int gr_h5md_read_obs(gr_h5md_reader *r, gr_obs *obs, gr_err *err);

/* Frames that hold a contact network (0 when the run wrote none), and the
 * network of one of them (c resized; step and time may be NULL). */
int gr_h5md_contact_frames(gr_h5md_reader *r, size_t *frames, gr_err *err);
int gr_h5md_read_contacts(gr_h5md_reader *r, size_t k, gr_contacts *c, uint64_t *step,
                          double *time, gr_err *err);

/* (Re)write the XDMF sidecar <path>.xdmf of an opened file from what it
 * holds, e.g. after a killed run (the writer updates it in steps). */
int gr_h5md_write_xdmf(gr_h5md_reader *r, gr_err *err);

/* Members of a group ("observables", "fields", "results", "checkpoint",
 * "results/sub"...), sorted; an absent group gives n = 0. Free with
 * gr_h5md_names_free. */
int gr_h5md_list(gr_h5md_reader *r, const char *group, char ***names, size_t *n,
                 gr_err *err);
void gr_h5md_names_free(char **names, size_t n);

/* The last sample of observables/<name> as doubles (*ncomp of them, 1 or
 * 2) and, for a validity limit's counter, the key that changes it (else
 * ""). */
int gr_h5md_obs_last(gr_h5md_reader *r, const char *name, double v[2], int *ncomp, char *key, size_t keyn,
                     gr_err *err);

/* A time series element (e.g. "observables/ekin_trans", "fields/density"):
 * its complete samples and first and last time (NaN when empty). */
int gr_h5md_series_info(gr_h5md_reader *r, const char *path, size_t *samples,
                        double *t0, double *t1, gr_err *err);

/* The times of the first n samples of a series: a field ("fields/NAME"),
 * the contact networks ("contacts"), an observable; n from
 * gr_h5md_series_info, gr_h5md_field_info or gr_h5md_contact_frames. */
int gr_h5md_series_times(gr_h5md_reader *r, const char *path, size_t n, double *time, gr_err *err);

/* Field grid (name and unit of f are left untouched) and sample count. */
int gr_h5md_field_info(gr_h5md_reader *r, const char *name, gr_field_desc *f,
                       size_t *samples, gr_err *err);
/* Sample i of a field into values (nx * ny * ncomp doubles). */
int gr_h5md_read_field(gr_h5md_reader *r, const char *name, size_t sample,
                       double *values, uint64_t *step, double *time, gr_err *err);

/* Shape of results/<name> (cols 0 for a 1-D array) and its data (malloc'd,
 * caller frees; v may be NULL to get the shape only). */
int gr_h5md_read_result(gr_h5md_reader *r, const char *name, size_t *rows,
                        size_t *cols, double **v, gr_err *err);
/* Its description and column names (", " between), "" when absent. */
int gr_h5md_result_text(gr_h5md_reader *r, const char *name, char *desc, size_t n, char *cols,
                        size_t m, gr_err *err);

#endif
