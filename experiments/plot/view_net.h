/* The contact network of a frame as the pictures use it: contacts and
 * normal force per grain, and lines between the centres of touching
 * grains (contacts with walls draw none: the file names the wall, not
 * where it touches). */
#ifndef GR_VIEW_NET_H
#define GR_VIEW_NET_H

#include <stddef.h>

#include "err.h"
#include "h5md.h"
#include "plot.h"

typedef struct vw_net vw_net;

/* GR_EINPUT, naming who asked, when the file holds no network; lines: the
 * network is drawn, not only counted. */
vw_net *vw_net_open(gr_h5md_reader *r, const char *who, int lines, gr_err *err);
void vw_net_free(vw_net *n);
/* The network written with the frame p at time t (GR_EINPUT when that
 * frame has none); box and periodic: lines across a periodic side go to
 * the nearest image. */
int vw_net_load(vw_net *n, const gr_particles *p, double t, const double box[2], const int periodic[2],
                gr_err *err);
/* Contacts of grain i (walls included) and the sum of their |fn|. */
double vw_net_count(const vw_net *n, size_t i);
double vw_net_force(const vw_net *n, size_t i);
/* |fn| of each line drawn (none when lines are not drawn; n may be NULL). */
void vw_net_forces(const vw_net *n, const double **fn, size_t *m);
/* The lines, their widths on the scale fref (the widest class from fref on). */
void vw_net_lines(vw_net *n, double fref, const gr_plot_line **lines, size_t *m);

#endif
