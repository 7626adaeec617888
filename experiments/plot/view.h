/* What `grano plot` and `grano movie` share: their options, and a view of
 * a result file (view.c) that loads one frame at a time as grains coloured
 * by a quantity (with the contact network over them) or as a field. */
#ifndef GR_VIEW_H
#define GR_VIEW_H

#include <getopt.h>
#include <stddef.h>
#include <stdio.h>

#include "err.h"
#include "plot.h"

/* ---- view_opts.c -------------------------------------------------------- */

typedef struct {
    const char *color;  /* --color NAME (NULL: speed) */
    const char *field;  /* --field NAME[.COMPONENT] */
    int contacts;       /* --contacts */
    int has_range, has_pct;
    double range[2], pct[2]; /* --range MIN,MAX; --percentiles LO,HI (default 2,98) */
    /* grano plot */
    int has_frame, has_time;
    long frame;
    double time;
    const char *format; /* --format png|svg|pdf */
    /* grano movie */
    long every, fps;
    double from, to;
} vw_opts;

/* The options of both commands (a struct option list, NULL-name ended,
 * movie's or plot's), and the handler for exp_getopt. */
const struct option *vw_options(int movie);
void vw_opts_init(vw_opts *o);
int vw_option(void *ctx, int id, const char *arg, gr_err *err);
/* Options given to the wrong command, or together where they exclude
 * each other: GR_EINPUT naming them. */
int vw_opts_check(const vw_opts *o, int movie, gr_err *err);
/* The options both commands take, for their usage text. */
void vw_usage_common(FILE *f);

/* ---- view.c ------------------------------------------------------------- */

typedef struct vw_view vw_view;

/* Open a result for drawing what o asks: GR_EINPUT naming the file when
 * it holds nothing to draw or not the quantity or field asked for. */
vw_view *vw_open(const char *path, const vw_opts *o, gr_err *err);
void vw_free(vw_view *v);

/* The frames (trajectory frames, or a field's samples) and their times. */
size_t vw_count(const vw_view *v);
const double *vw_times(const vw_view *v);
/* The frame nearest t (the earlier of two as near). */
size_t vw_nearest(const vw_view *v, double t);

/* Load frame k. */
int vw_load(vw_view *v, size_t k, gr_err *err);
/* The loaded frame's values on the colour scale (mobile grains, or
 * cells), and its contact forces |fn| (none without --contacts); the
 * pointers stay valid until the next load. */
void vw_values(const vw_view *v, const double **val, size_t *n);
void vw_forces(const vw_view *v, const double **fn, size_t *n);
/* The colour bar's label (what is drawn, its unit). */
const char *vw_label(const vw_view *v);

/* Figure size in pixels, and the commands drawing the loaded frame on the
 * colour scale lo..hi with the bar's label, the network's line widths on
 * the force scale fref (the force of the widest line). */
void vw_size(const vw_view *v, int *w, int *h);
void vw_body(vw_view *v, FILE *f, double lo, double hi, double fref, const char *label);

#endif
