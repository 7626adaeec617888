/* Figures through gnuplot: data go inline as datablocks into a script
 * saved beside the figure (fig.png's is fig.gp, so `gnuplot fig.gp`
 * remakes it, restyled as one likes). The figure's format follows its
 * name: .svg and .pdf give those (vector), anything else a PNG (pngcairo).
 * GRANO_FIGURES=svg,pdf in the environment also writes fig.svg / fig.pdf.
 * Without gnuplot the script is still saved and the error says how to
 * install it. A figure appears under its name only once drawn whole.
 * plot.c runs gnuplot; plot_draw.c writes what grains and fields look like. */
#ifndef GR_PLOT_H
#define GR_PLOT_H

#include <stddef.h>
#include <stdio.h>

#include "err.h"
#include "particles.h"

/* Start the script of a figure of w x h pixels (PDF: at 96 per inch) at
 * path; write the drawing into the returned stream, then gr_plot_close. */
FILE *gr_plot_open(const char *path, int w, int h, gr_err *err);
int gr_plot_close(FILE *gp, const char *path, gr_err *err);
/* Whether gnuplot is on PATH: a study whose data are written but whose
 * figures cannot be drawn says so and still succeeds. */
int gr_plot_have_gnuplot(void);
/* Whether program prog (e.g. "ffmpeg") is on PATH. */
int gr_plot_on_path(const char *prog);
/* s as a gnuplot single-quoted string ('' for each quote) into buf; text
 * from users (scene names, paths) goes through it. */
void gr_plot_quote(const char *s, char *buf, size_t n);
/* A log axis ("x" or "y") fitted to data in [lo, hi] (both > 0): a margin
 * of a tenth of the data's span in decades each side (gnuplot's own
 * autoscale widens a log axis to whole decades, so that data within one
 * decade sit in a corner), with labelled tics (gnuplot labels only the
 * powers of ten). Data within a thousandth of a decade get 0.05 decades each
 * side. Nothing when lo or hi is not finite and positive. */
void gr_plot_log_axis(FILE *gp, const char *axis, double lo, double hi);
/* "png", "svg" or "pdf": the format a figure's name asks for. */
const char *gr_plot_format_of(const char *path);

/* ---- plot_draw.c: grains and fields ------------------------------------ */

/* The pct[0]-th and pct[1]-th percentiles (0..100) of the finite values of
 * v[0..n), as numpy.percentile's default (linear between order statistics),
 * into range; v is reordered. A range of zero width is widened by 0.5 (by
 * a millionth of the value when that is larger) each way, none (no finite
 * value) is [0, 1]. Returns how many values were finite. */
size_t gr_plot_percentiles(double *v, size_t n, const double pct[2], double range[2]);
/* "label; scale: 2nd to 98th percentile" into buf (what the colour bar says). */
void gr_plot_scale_label(const char *label, const double pct[2], char *buf, size_t n);

/* Lines of a contact network drawn over the grains: widths by force, in
 * classes 1 .. GR_PLOT_LINE_CLASSES. */
#define GR_PLOT_LINE_CLASSES 5
typedef struct {
    double x, y, dx, dy; /* from (x, y) to (x + dx, y + dy) */
    int cls;
} gr_plot_line;

/* A frame of grains as disks: the mobile ones coloured by value[i] (index
 * as in p), fixed grains grey, grains gone left out; the box outlined. */
typedef struct {
    const gr_particles *p;
    const double *value;
    double lo, hi;       /* colour range */
    const char *label;   /* colour bar */
    const gr_plot_line *lines; /* NULL: none */
    size_t nlines;
    double width, height, t;
    const char *title;   /* ", t = ... tau" follows it */
} gr_plot_disks;
/* Pixels: the box's aspect ratio, about 800 on its long side, and room for
 * the colour bar. */
void gr_plot_disks_size(double width, double height, int *w, int *h);
/* The commands that draw one frame, once a terminal and output are set
 * (a movie writes one after another into one script). */
void gr_plot_disks_body(FILE *f, const gr_plot_disks *d);
int gr_plot_disks_draw(const char *path, const gr_plot_disks *d, gr_err *err);

/* Grains coloured by speed on the scale of its 2nd to 98th percentile
 * (the colour bar says so), as `grano run --snapshot` draws a final state. */
int gr_plot_snapshot(const char *png, const gr_particles *p, double width, double height,
                     double t, const char *title, gr_err *err);

/* A scalar field on a grid of nx x ny cells of cx x cy from (x0, y0),
 * row-major (index iy nx + ix), as a colour map; NaN cells stay blank. */
typedef struct {
    int nx, ny;
    double x0, y0, cx, cy;
    const double *v;
    const char *label; /* colour bar */
    double lo, hi;     /* colour range; lo >= hi: the 2nd to 98th percentile
                        * of the cells, said on the colour bar */
} gr_plot_grid;
void gr_plot_field_size(double width, double height, int *w, int *h);
void gr_plot_field_body(FILE *f, const gr_plot_grid *g, double width, double height, double t,
                        const char *title);
int gr_plot_field(const char *png, const gr_plot_grid *g, double width, double height, double t,
                  const char *title, gr_err *err);

#endif
