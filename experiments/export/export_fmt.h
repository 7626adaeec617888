/* The trajectory formats of grano export: one frame at a time to a stream.
 * A 2-D system is written as 3-D with z = 0 (and vz = 0), its box one
 * diameter thick along z, so that 3-D readers take it. */
#ifndef GR_XP_FMT_H
#define GR_XP_FMT_H

#include <stdint.h>
#include <stdio.h>

#include "err.h"
#include "particles.h"

typedef enum { XP_LAMMPS_DUMP, XP_EXTXYZ, XP_CSV, XP_LAMMPS_DATA } xp_format;

typedef struct {
    size_t index;       /* frame number in the result file */
    uint64_t step;
    double time;
    double box[2];      /* [0, box[0]] x [0, box[1]] */
    int periodic[2];
    const gr_particles *p;
} xp_frame;

/* "lammps-dump" ... ; -1 if none. */
int xp_format_of(const char *name);
/* The names, for messages: "lammps-dump, extxyz, csv, lammps-data". */
const char *xp_format_names(void);
/* Write frame fr; first is 1 for the first frame written (csv header). */
int xp_write_frame(FILE *f, xp_format fmt, const xp_frame *fr, int first, gr_err *err);

#endif
