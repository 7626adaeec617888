/* [init] kind = file: grains from a packing made elsewhere. Three formats,
 * told apart by their content: a LAMMPS data file (a "N atoms" header line,
 * an Atoms section of style sphere or atomic, optional Velocities), the
 * first frame of an extended XYZ file (a count line, then a comment line
 * with Properties=...), else plain columns x y [vx vy [diameter]]. The z
 * components are dropped (a 2-D packing lies at z = 0); a diameter absent
 * from the file is the first species'; masses come from the scene's
 * density, not the file. */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "init.h"

typedef struct {
    const char *path;
    const gr_species *sp;
    gr_particles *p;
    gr_err *err;
} reader;

static int add(reader *r, double x, double y, double vx, double vy, double w, double d, int ln)
{
    if (!isfinite(x) || !isfinite(y) || !isfinite(vx) || !isfinite(vy) || !isfinite(w) || !(d > 0) || !isfinite(d))
        return gr_fail(r->err, GR_EINPUT, "%s:%d: a non-finite value or a diameter <= 0", r->path, ln);
    if (r->p->n >= (size_t)GR_SCENE_MAX_GRAINS)
        return gr_fail(r->err, GR_EINPUT, "%s:%d: more than %ld grains (docs/reliability.md)", r->path, ln,
                       GR_SCENE_MAX_GRAINS);
    long i = gr_particles_push(r->p, x, y, 0.5 * d, r->sp->density * M_PI * d * d / 4, 0, 0, r->err);
    if (i < 0)
        return r->err->code;
    r->p->vx[i] = vx;
    r->p->vy[i] = vy;
    r->p->omega[i] = w;
    return GR_OK;
}

/* Up to cap numbers of s; their count, -1 if something else follows. */
static int numbers(const char *s, double *v, int cap)
{
    int k = 0;
    char *end;
    for (;;) {
        while (isspace((unsigned char)*s))
            s++;
        if (!*s || *s == '#')
            return k;
        if (k == cap)
            return -1;
        v[k] = strtod(s, &end);
        if (end == s)
            return -1;
        s = end, k++;
    }
}

static int read_plain(reader *r, FILE *f)
{
    char line[1024];
    int ln = 0;
    while (fgets(line, sizeof line, f)) {
        ln++;
        if (!strchr(line, '\n') && !feof(f))
            return gr_fail(r->err, GR_EINPUT, "%s:%d: line longer than %zu characters", r->path, ln,
                           sizeof line - 2);
        double v[5] = {0, 0, 0, 0, r->sp->diameter};
        int k = numbers(line, v, 5);
        if (k == 0)
            continue;
        if (k != 2 && k != 4 && k != 5)
            return gr_fail(r->err, GR_EINPUT,
                           "%s:%d: expected 'x y', 'x y vx vy' or 'x y vx vy diameter' (finite, diameter > 0)",
                           r->path, ln);
        if (add(r, v[0], v[1], v[2], v[3], 0, v[4], ln))
            return r->err->code;
    }
    return GR_OK;
}

/* Column of each wanted extxyz property, from "Properties=name:T:n:...". */
typedef struct {
    int pos, vel, mom, mass, rad, diam, spin, ncol;
} xyz_cols;

static int xyz_properties(reader *r, const char *comment, xyz_cols *c)
{
    *c = (xyz_cols){-1, -1, -1, -1, -1, -1, -1, 0};
    const char *s = strstr(comment, "Properties=");
    if (!s)
        return gr_fail(r->err, GR_EINPUT, "%s:2: extended XYZ without Properties=", r->path);
    char buf[1024];
    snprintf(buf, sizeof buf, "%s", s + 11);
    buf[strcspn(buf, " \t\r\n\"")] = '\0';
    char *save = NULL;
    for (char *name = strtok_r(buf, ":", &save); name; name = strtok_r(NULL, ":", &save)) {
        char *type = strtok_r(NULL, ":", &save), *n = strtok_r(NULL, ":", &save);
        if (!type || !n || atoi(n) < 1)
            return gr_fail(r->err, GR_EINPUT, "%s:2: a malformed Properties= entry '%s'", r->path, name);
        int *slot = !strcmp(name, "pos") ? &c->pos
                  : !strcmp(name, "velo") || !strcmp(name, "vel") || !strcmp(name, "velocities") ? &c->vel
                  : !strcmp(name, "momenta") ? &c->mom
                  : !strcmp(name, "masses") || !strcmp(name, "mass") ? &c->mass
                  : !strcmp(name, "radius") || !strcmp(name, "radii") ? &c->rad
                  : !strcmp(name, "diameter") ? &c->diam
                  : !strcmp(name, "omega_z") ? &c->spin : NULL;
        if (slot)
            *slot = c->ncol;
        c->ncol += atoi(n);
    }
    if (c->pos < 0)
        return gr_fail(r->err, GR_EINPUT, "%s:2: no pos among the Properties", r->path);
    return GR_OK;
}

static int read_extxyz(reader *r, FILE *f, long n)
{
    char line[4096];
    xyz_cols c;
    if (!fgets(line, sizeof line, f) || xyz_properties(r, line, &c))
        return r->err->code ? r->err->code : gr_fail(r->err, GR_EINPUT, "%s: no comment line", r->path);
    for (long i = 0; i < n; i++) {
        int ln = (int)i + 3;
        if (!fgets(line, sizeof line, f))
            return gr_fail(r->err, GR_EINPUT, "%s:%d: %ld atoms announced, %ld found", r->path, ln, n, i);
        double v[64] = {0};
        int k = 0;
        char *save = NULL;
        for (char *t = strtok_r(line, " \t\r\n", &save); t && k < 64; t = strtok_r(NULL, " \t\r\n", &save))
            v[k++] = strtod(t, NULL);
        if (k < c.ncol)
            return gr_fail(r->err, GR_EINPUT, "%s:%d: %d columns, Properties= has %d", r->path, ln, k, c.ncol);
        double vx = 0, vy = 0, d = r->sp->diameter;
        if (c.vel >= 0)
            vx = v[c.vel], vy = v[c.vel + 1];
        else if (c.mom >= 0 && c.mass >= 0)
            vx = v[c.mom] / v[c.mass], vy = v[c.mom + 1] / v[c.mass];
        if (c.rad >= 0)
            d = 2 * v[c.rad];
        else if (c.diam >= 0)
            d = v[c.diam];
        if (add(r, v[c.pos], v[c.pos + 1], vx, vy, c.spin >= 0 ? v[c.spin] : 0, d, ln))
            return r->err->code;
    }
    return GR_OK;
}

/* A LAMMPS data file: Atoms (sphere: id type diameter density x y z;
 * atomic: id type x y z; image flags may follow) and Velocities
 * (id vx vy vz [wx wy wz]); grains in id order. */
typedef struct {
    int64_t *ids;
    double *at;  /* x y diameter, per Atoms row */
    double *vel; /* id vx vy wz, per Velocities row */
    long na, nv;
} lmp_rows;

static int lammps_row(reader *r, lmp_rows *t, const char *section, int *sphere, const double *v, int k,
                      long n, int ln)
{
    if (!strcmp(section, "Atoms")) {
        if (*sphere == -1)
            *sphere = k == 7 || k == 10;
        if (*sphere == -2 || (*sphere && k != 7 && k != 10) || (!*sphere && k != 5 && k != 8) || t->na == n)
            return gr_fail(r->err, GR_EINPUT, "%s:%d: expected atom style sphere (id type diameter density "
                           "x y z) or atomic (id type x y z), %ld atoms", r->path, ln, n);
        double *q = t->at + 3 * t->na;
        t->ids[t->na++] = (int64_t)v[0];
        q[0] = v[*sphere ? 4 : 2], q[1] = v[*sphere ? 5 : 3], q[2] = *sphere ? v[2] : r->sp->diameter;
    } else if (!strcmp(section, "Velocities")) {
        if ((k != 4 && k != 7) || t->nv == n)
            return gr_fail(r->err, GR_EINPUT, "%s:%d: expected 'id vx vy vz [wx wy wz]'", r->path, ln);
        double *q = t->vel + 4 * t->nv++;
        q[0] = v[0], q[1] = v[1], q[2] = v[2], q[3] = k == 7 ? v[6] : 0;
    }
    return GR_OK;
}

static int lammps_grains(reader *r, lmp_rows *t, long n)
{
    if (t->na != n)
        return gr_fail(r->err, GR_EINPUT, "%s: %ld atoms announced, %ld in the Atoms section", r->path, n, t->na);
    gr_id_index *ix = malloc((size_t)n * sizeof *ix);
    double *v = calloc((size_t)n * 3, sizeof *v);
    int rc = ix && v ? GR_OK : gr_fail(r->err, GR_ERUN, "out of memory");
    if (!rc) {
        gr_id_index_sort(t->ids, (size_t)n, ix);
        int64_t dup = gr_id_index_duplicate(ix, (size_t)n);
        if (dup >= 0)
            rc = gr_fail(r->err, GR_EINPUT, "%s: atom id %lld appears twice", r->path, (long long)dup);
    }
    for (long j = 0; !rc && j < t->nv; j++) {
        const double *q = t->vel + 4 * j;
        const gr_id_index *e = gr_id_index_find(ix, (size_t)n, (int64_t)q[0]);
        if (!e)
            rc = gr_fail(r->err, GR_EINPUT, "%s: Velocities names atom %lld, not in Atoms", r->path,
                         (long long)q[0]);
        else
            memcpy(v + 3 * e->i, q + 1, 3 * sizeof *v);
    }
    for (long k = 0; !rc && k < n; k++) {
        size_t i = ix[k].i;
        const double *q = t->at + 3 * i;
        rc = add(r, q[0], q[1], v[3 * i], v[3 * i + 1], v[3 * i + 2], q[2], 0);
    }
    free(ix);
    free(v);
    return rc;
}

static int read_lammps_data(reader *r, FILE *f, long n)
{
    char line[1024], section[64] = "";
    int ln = 0, sphere = -1;
    lmp_rows t = {malloc((size_t)n * sizeof *t.ids), malloc((size_t)n * 3 * sizeof *t.at),
                  malloc((size_t)n * 4 * sizeof *t.vel), 0, 0};
    int rc = t.ids && t.at && t.vel ? GR_OK : gr_fail(r->err, GR_ERUN, "out of memory");
    while (!rc && fgets(line, sizeof line, f)) {
        if (++ln == 1)
            continue; /* the title */
        double v[10];
        int k = numbers(line, v, 10);
        const char *s = line + strspn(line, " \t");
        if (k < 0 && isalpha((unsigned char)*s)) {
            snprintf(section, sizeof section, "%s", s);
            if (!strncmp(section, "Atoms", 5) && strchr(section, '#'))
                sphere = strstr(section, "sphere") ? 1 : strstr(section, "atomic") ? 0 : -2;
            section[strcspn(section, " \t\r\n#")] = '\0';
        } else if (k > 0) {
            rc = lammps_row(r, &t, section, &sphere, v, k, n, ln);
        }
    }
    if (!rc)
        rc = lammps_grains(r, &t, n);
    free(t.ids);
    free(t.at);
    free(t.vel);
    return rc;
}

/* The LAMMPS "N atoms" header line among the first lines, or -1. */
static long lammps_atoms(FILE *f)
{
    char line[1024], word[32];
    long n;
    for (int ln = 0; ln < 30 && fgets(line, sizeof line, f); ln++)
        if (sscanf(line, "%ld %31s", &n, word) == 2 && !strcmp(word, "atoms") && n > 0)
            return n;
    return -1;
}

int gr_init_read_file(const char *path, const gr_species *sp, gr_particles *p, gr_err *err)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return gr_fail(err, GR_EINPUT, "%s: cannot read: %s", path, strerror(errno));
    reader r = {path, sp, p, err};
    char first[256] = "", extra[8];
    long n = -1;
    int rc;
    if (fgets(first, sizeof first, f) && sscanf(first, "%ld %7s", &n, extra) == 1 && n > 0) {
        if (n > GR_SCENE_MAX_GRAINS)
            n = GR_SCENE_MAX_GRAINS + 1; /* refused by add() at the limit, not allocated */
        rc = read_extxyz(&r, f, n);
    } else if (rewind(f), (n = lammps_atoms(f)) > 0) {
        if (n > GR_SCENE_MAX_GRAINS) {
            fclose(f);
            return gr_fail(err, GR_EINPUT, "%s: %ld atoms, more than %ld (docs/reliability.md)", path, n,
                           GR_SCENE_MAX_GRAINS);
        }
        rewind(f);
        rc = read_lammps_data(&r, f, n);
    } else {
        rewind(f);
        rc = read_plain(&r, f);
    }
    fclose(f);
    if (!rc && p->n == 0)
        rc = gr_fail(err, GR_EINPUT, "%s: no grains in the file", path);
    return rc;
}
