/* Figures through gnuplot (pngcairo): data go inline as datablocks into a
 * script saved beside the figure (fig.png's is fig.gp, so `gnuplot fig.gp`
 * remakes it, restyled as one likes). GRANO_FIGURES=svg,pdf in the
 * environment also writes fig.svg / fig.pdf. Without gnuplot the script is
 * still saved and the error says how to install it. */
#ifndef GR_PLOT_H
#define GR_PLOT_H

#include <stdio.h>

#include "err.h"
#include "particles.h"

/* Start a gnuplot process writing a PNG of w x h pixels to png; write the
 * script into the returned stream, then call gr_plot_close. */
FILE *gr_plot_open(const char *png, int w, int h, gr_err *err);
int gr_plot_close(FILE *gp, const char *png, gr_err *err);
/* Whether gnuplot is on PATH: a study whose data are written but whose
 * figures cannot be drawn says so and still succeeds. */
int gr_plot_have_gnuplot(void);
/* s as a gnuplot single-quoted string ('' for each quote) into buf; text
 * from users (scene names, paths) goes through it. */
void gr_plot_quote(const char *s, char *buf, size_t n);

/* Grains as disks coloured by speed (fixed grains grey), the box outlined. */
int gr_plot_snapshot(const char *png, const gr_particles *p, double width, double height,
                     double t, const char *title, gr_err *err);

/* A scalar field on a grid of nx x ny cells of cx x cy from (x0, y0),
 * row-major (index iy nx + ix), as a colour map; NaN cells stay blank. */
typedef struct {
    int nx, ny;
    double x0, y0, cx, cy;
    const double *v;
    const char *label; /* colour bar */
} gr_plot_grid;
int gr_plot_field(const char *png, const gr_plot_grid *g, double width, double height, double t,
                  const char *title, gr_err *err);

#endif
