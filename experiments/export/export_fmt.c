/* Writers of grano export. Columns, in every format: id, a type (species + 1;
 * fixed wall grains species + 1 + 100, grains gone from the domain + 200),
 * position, velocity, radius, mass, spin omega_z. */
#include "export_fmt.h"

#include <math.h>
#include <string.h>

static const char *const names[] = {"lammps-dump", "extxyz", "csv", "lammps-data", NULL};

int xp_format_of(const char *name)
{
    for (int k = 0; names[k]; k++)
        if (!strcmp(name, names[k]))
            return k;
    return -1;
}

const char *xp_format_names(void) { return "lammps-dump, extxyz, csv, lammps-data"; }

static int type_of(const gr_particles *p, size_t i)
{
    int t = p->species[i] + 1;
    if (p->flags[i] & GR_PF_GONE)
        return t + 200;
    return p->flags[i] & (GR_PF_FIXED | GR_PF_GATE) ? t + 100 : t;
}

/* Half a diameter of z either side of the plane: a box of nonzero volume. */
static double zhalf(const gr_particles *p)
{
    double r = 0.5;
    for (size_t i = 0; i < p->n; i++)
        r = p->radius[i] > r ? p->radius[i] : r;
    return r;
}

/* LAMMPS text dump (read by LAMMPS's read_dump and rerun, Pizza.py, OVITO,
 * VMD's lammpstrj plugin, ASE); ITEM order as LAMMPS writes it. */
static void lammps_dump(FILE *f, const xp_frame *fr)
{
    const gr_particles *p = fr->p;
    double z = zhalf(p);
    fprintf(f, "ITEM: TIMESTEP\n%llu\nITEM: NUMBER OF ATOMS\n%zu\n", (unsigned long long)fr->step, p->n);
    fprintf(f, "ITEM: BOX BOUNDS %s %s pp\n%.17g %.17g\n%.17g %.17g\n%.17g %.17g\n",
            fr->periodic[0] ? "pp" : "ff", fr->periodic[1] ? "pp" : "ff", 0.0, fr->box[0], 0.0, fr->box[1], -z, z);
    fprintf(f, "ITEM: ATOMS id type x y z vx vy vz radius mass omegaz\n");
    for (size_t i = 0; i < p->n; i++)
        fprintf(f, "%lld %d %.17g %.17g 0 %.17g %.17g 0 %.17g %.17g %.17g\n", (long long)p->id[i] + 1,
                type_of(p, i), p->x[i], p->y[i], p->vx[i], p->vy[i], p->radius[i], p->mass[i], p->omega[i]);
}

/* Extended XYZ (ASE, OVITO; VMD's xyz plugin takes the positions). ASE
 * needs an element symbol as species: every grain is "H", its kind is the
 * type column. Velocities twice: velo for OVITO, momenta and masses for
 * ASE (whose get_velocities divides them). */
static void extxyz(FILE *f, const xp_frame *fr)
{
    const gr_particles *p = fr->p;
    double z = 2 * zhalf(p);
    fprintf(f, "%zu\nLattice=\"%.17g 0 0 0 %.17g 0 0 0 %.17g\" "
               "Properties=species:S:1:pos:R:3:velo:R:3:momenta:R:3:radius:R:1:masses:R:1:omega_z:R:1:id:I:1:type:I:1 "
               "Time=%.17g Step=%llu pbc=\"%c %c F\"\n",
            p->n, fr->box[0], fr->box[1], z, fr->time, (unsigned long long)fr->step, fr->periodic[0] ? 'T' : 'F',
            fr->periodic[1] ? 'T' : 'F');
    for (size_t i = 0; i < p->n; i++)
        fprintf(f, "H %.17g %.17g 0 %.17g %.17g 0 %.17g %.17g 0 %.17g %.17g %.17g %lld %d\n", p->x[i], p->y[i],
                p->vx[i], p->vy[i], p->mass[i] * p->vx[i], p->mass[i] * p->vy[i], p->radius[i], p->mass[i], p->omega[i],
                (long long)p->id[i], type_of(p, i));
}

static void csv(FILE *f, const xp_frame *fr, int first)
{
    const gr_particles *p = fr->p;
    if (first)
        fprintf(f, "frame,step,time,id,type,x,y,vx,vy,omega,radius,mass\n");
    for (size_t i = 0; i < p->n; i++)
        fprintf(f, "%zu,%llu,%.17g,%lld,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", fr->index,
                (unsigned long long)fr->step, fr->time, (long long)p->id[i], type_of(p, i), p->x[i], p->y[i],
                p->vx[i], p->vy[i], p->omega[i], p->radius[i], p->mass[i]);
}

/* LAMMPS data file, atom style sphere (read_data; grano's [init] kind =
 * file reads it back). The density is per area, as LAMMPS takes it in 2-D. */
static void lammps_data(FILE *f, const xp_frame *fr)
{
    const gr_particles *p = fr->p;
    double z = zhalf(p);
    int ntypes = 1;
    for (size_t i = 0; i < p->n; i++)
        ntypes = type_of(p, i) > ntypes ? type_of(p, i) : ntypes;
    fprintf(f, "LAMMPS data file from grano export: frame %zu, step %llu, time %.17g (2-D: z = 0)\n\n"
               "%zu atoms\n%d atom types\n\n%.17g %.17g xlo xhi\n%.17g %.17g ylo yhi\n%.17g %.17g zlo zhi\n\n"
               "Atoms # sphere\n\n",
            fr->index, (unsigned long long)fr->step, fr->time, p->n, ntypes, 0.0, fr->box[0], 0.0, fr->box[1], -z, z);
    for (size_t i = 0; i < p->n; i++)
        fprintf(f, "%lld %d %.17g %.17g %.17g %.17g 0\n", (long long)p->id[i] + 1, type_of(p, i), 2 * p->radius[i],
                p->mass[i] / (M_PI * p->radius[i] * p->radius[i]), p->x[i], p->y[i]);
    fprintf(f, "\nVelocities\n\n");
    for (size_t i = 0; i < p->n; i++)
        fprintf(f, "%lld %.17g %.17g 0 0 0 %.17g\n", (long long)p->id[i] + 1, p->vx[i], p->vy[i], p->omega[i]);
}

int xp_write_frame(FILE *f, xp_format fmt, const xp_frame *fr, int first, gr_err *err)
{
    switch (fmt) {
    case XP_LAMMPS_DUMP: lammps_dump(f, fr); break;
    case XP_EXTXYZ: extxyz(f, fr); break;
    case XP_CSV: csv(f, fr, first); break;
    case XP_LAMMPS_DATA: lammps_data(f, fr); break;
    }
    return ferror(f) ? gr_fail(err, GR_ERUN, "write failed (disk full?)") : GR_OK;
}
