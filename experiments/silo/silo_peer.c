/* grano silo-flow --peer lammps: the same settled silo run by grano's dem
 * and by LAMMPS (Debian's lmp) with the same contact law, one orifice; the
 * two flow rates with their error bars, and the CPU time of each code. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

#include "files.h"
#include "table.h"
#include "progress.h"
#include "silo_flow.h"

/* The LAMMPS data file of the branched silo: mobile grains type 1, wall
 * grains type 2; the gate grains are left out (the orifice is open from
 * the first step, as grano's gates open at t = 0). */
static int write_data(const char *path, const gr_particles *p, double ylo, gr_err *err)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return gr_fail(err, GR_ERUN, "%s: cannot write", path);
    double xlo = INFINITY, xhi = -INFINITY, yhi = -INFINITY;
    size_t n = 0;
    for (size_t i = 0; i < p->n; i++) {
        if (p->flags[i] & (GR_PF_GATE | GR_PF_GONE))
            continue;
        xlo = fmin(xlo, p->x[i]), xhi = fmax(xhi, p->x[i]), yhi = fmax(yhi, p->y[i]);
        n++;
    }
    fprintf(f, "grano silo-flow --peer lammps: the settled silo\n\n%zu atoms\n2 atom types\n\n"
               "%.17g %.17g xlo xhi\n%.17g %.17g ylo yhi\n-0.5 0.5 zlo zhi\n\nAtoms # sphere\n\n",
            n, xlo - 1, xhi + 1, ylo, yhi + 20);
    size_t k = 0;
    for (size_t i = 0; i < p->n; i++) {
        if (p->flags[i] & (GR_PF_GATE | GR_PF_GONE))
            continue;
        /* lmp 29Sep2021 makes the mass 4/3 pi r^3 rho even in 2d (checked:
         * d = 1, rho = 4/pi gave m = 2/3) */
        double r = p->radius[i], rho = p->mass[i] / (4.0 / 3.0 * M_PI * r * r * r);
        fprintf(f, "%zu %d %.17g %.17g %.17g %.17g 0\n", ++k, p->flags[i] & GR_PF_FIXED ? 2 : 1, 2 * r, rho,
                p->x[i], p->y[i]);
    }
    fprintf(f, "\nVelocities\n\n");
    k = 0;
    for (size_t i = 0; i < p->n; i++)
        if (!(p->flags[i] & (GR_PF_GATE | GR_PF_GONE)))
            fprintf(f, "%zu %.17g %.17g 0 0 0 %.17g\n", ++k, p->vx[i], p->vy[i], p->omega[i]);
    return fclose(f) ? gr_fail(err, GR_ERUN, "%s: write failed", path) : GR_OK;
}

/* The input script: grano's silo law (docs/methods/dem.md) in pair_style
 * granular: Hertz F = k_N R_eff^1/2 xi^3/2 (k_N = kn / sqrt(R_eff) gives
 * grano's kn xi^3/2, R_eff = d/4 for equal grains), damping velocity
 * (eta_n = gamma_n), tangential linear_nohistory with eta_t = 3 eta_n =
 * gamma_t and mu (grano's regularised Coulomb law), no attraction
 * (limit_damping); disks (fix nve/sphere disc); wall grains type 2 never
 * integrated; grains below exit_below deleted every 20 steps and counted. */
static int write_input(const char *path, const sf_ctx *c, double yexit, gr_err *err)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return gr_fail(err, GR_ERUN, "%s: cannot write", path);
    double reff = 0.25;
    fprintf(f,
            "# grano silo-flow --peer lammps\nunits lj\ndimension 2\natom_style sphere\nboundary f f p\n"
            "comm_modify vel yes\nread_data silo.data\ngroup mobile type 1\ngroup wall type 2\n"
            "neighbor 0.3 bin\nneigh_modify delay 0 every 1 check yes exclude type 2 2\n"
            "pair_style granular\n"
            "pair_coeff * * hertz %.17g 100 tangential linear_nohistory 3 0.5 damping velocity limit_damping\n"
            "fix grav mobile gravity 1.0 vector 0 -1 0\nfix int mobile nve/sphere disc\nfix flat all enforce2d\n"
            "region below block INF INF INF %.17g INF INF\nfix out mobile evaporate 20 1000000 below 4321\n"
            "timestep %.17g\nthermo 100000\nthermo_modify lost ignore\nvariable n equal f_out\nvariable s equal step\n"
            "run %ld\nfix blocks all print %ld \"${s} ${n}\" file counts.dat screen no\nrun %ld\n",
            1e5 / sqrt(reff), yexit, c->base.dt, c->discard, c->block, c->block * (long)c->nblocks);
    return fclose(f) ? gr_fail(err, GR_ERUN, "%s: write failed", path) : GR_OK;
}

/* Mean and standard error of the block rates (grains per tau). */
static void rate(const double *count, int nb, double tblock, double *w, double *e)
{
    double s = 0, s2 = 0;
    for (int b = 0; b < nb; b++)
        s += count[b] / tblock, s2 += count[b] * count[b] / (tblock * tblock);
    *w = s / nb;
    *e = nb > 1 ? sqrt(fmax(0, s2 / nb - *w * *w) / (nb - 1)) : NAN;
}

/* grano's run from the branched silo, without reinsertion (as LAMMPS):
 * the grains that leave in each block. */
static int run_grano(const sf_ctx *c, const silo_cfg *cfg, const silo_settled *set, double *count, gr_err *err)
{
    gr_scene *sc = NULL;
    gr_sim *st = NULL;
    int rc = silo_open(cfg, set, &sc, &st, err);
    gr_obs ob;
    gr_obs_clear(&ob);
    if (!rc)
        rc = silo_advance(cfg, st, (uint64_t)c->discard, err);
    if (!rc)
        rc = gr_sim_observe(st, &ob, err);
    uint64_t last = ob.outflow;
    for (int b = 0; b < c->nblocks && !rc; b++) {
        if ((rc = silo_advance(cfg, st, (uint64_t)c->block, err)) || (rc = gr_sim_observe(st, &ob, err)))
            break;
        count[b] = (double)(ob.outflow - last);
        last = ob.outflow;
    }
    gr_sim_free(st);
    gr_scene_free(sc);
    return rc;
}

/* LAMMPS's counts file: "step cumulative" per block. */
static int read_counts(const char *path, const sf_ctx *c, double *count, gr_err *err)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return gr_fail(err, GR_ERUN, "%s: LAMMPS wrote no counts (see log.lammps beside it)", path);
    char line[256];
    double last = 0;
    int b = 0;
    while (b < c->nblocks && fgets(line, sizeof line, f)) {
        long step;
        double n;
        if (line[0] == '#' || sscanf(line, "%ld %lf", &step, &n) != 2)
            continue;
        if (step == c->discard) { /* fix print also prints at the run's first step */
            last = n;
            continue;
        }
        count[b++] = n - last, last = n;
    }
    fclose(f);
    return b == c->nblocks ? GR_OK : gr_fail(err, GR_ERUN, "%s: %d of %d blocks", path, b, c->nblocks);
}

static double cpu_children(void)
{
    struct rusage ru;
    getrusage(RUSAGE_CHILDREN, &ru);
    return (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec + (double)ru.ru_stime.tv_sec +
           1e-6 * (double)ru.ru_stime.tv_usec;
}

int sf_peer_lammps(const sf_ctx *c, char *summary, size_t n, gr_err *err)
{
    if (system("command -v lmp >/dev/null 2>&1") != 0)
        return gr_fail(err, GR_EINPUT,
                       "--peer lammps: LAMMPS's 'lmp' is not on the PATH; install it with 'apt-get install lammps' "
                       "(Debian) or './grano.sh deps --optional'");
    if (strcmp(c->base.method->name, "dem"))
        return gr_fail(err, GR_EINPUT, "--peer lammps: compares dem's contact law; --method %s has another",
                       c->base.method->name);
    char dir[1100], path[1200], cmd[1400];
    snprintf(dir, sizeof dir, "%s/peer", c->dir);
    if (exp_mkdirs(dir, err))
        return err->code;
    silo_cfg fc = c->base, cfg = c->base;
    fc.orifice = SILO_FILL_D, fc.seed = cfg.seed = c->seed;
    cfg.orifice = c->orifice[0], cfg.reinsert = 0;
    silo_settled fill, set;
    double fill_cost[5];
    int rc = silo_fill_path(&c->fills, 0, path, sizeof path) ? silo_fill_load(&c->fills, 0, &fill, fill_cost, err)
                                                   : silo_fill(&fc, &fill, NULL, err);
    if (!rc)
        rc = silo_rebase(&cfg, &fill, &set, NULL, err), silo_settled_free(&fill);
    if (rc)
        return rc;
    double yexit = cfg.base - 1.5;
    snprintf(path, sizeof path, "%s/silo.data", dir);
    rc = write_data(path, set.p, yexit - 2, err);
    snprintf(path, sizeof path, "%s/in.silo", dir);
    if (!rc)
        rc = write_input(path, c, yexit, err);
    double *cg = calloc((size_t)c->nblocks, sizeof *cg), *cl = calloc((size_t)c->nblocks, sizeof *cl);
    if (!cg || !cl)
        rc = rc ? rc : gr_fail(err, GR_ERUN, "out of memory");
    double t0 = (double)clock() / CLOCKS_PER_SEC, w0 = gr_wall_seconds();
    if (!rc)
        rc = run_grano(c, &cfg, &set, cg, err);
    double tg = (double)clock() / CLOCKS_PER_SEC - t0, wg = gr_wall_seconds() - w0;
    double l0 = cpu_children(), w1 = gr_wall_seconds();
    snprintf(cmd, sizeof cmd, "cd '%s' && rm -f counts.dat && OMP_NUM_THREADS=1 lmp -in in.silo -log log.lammps -screen none",
             dir);
    if (!rc && system(cmd) != 0)
        rc = gr_fail(err, GR_ERUN, "--peer lammps: lmp failed (%s/log.lammps)", dir);
    double tl = cpu_children() - l0, wl = gr_wall_seconds() - w1;
    snprintf(path, sizeof path, "%s/counts.dat", dir);
    if (!rc)
        rc = read_counts(path, c, cl, err);
    if (!rc) {
        double tb = (double)c->block * c->base.dt, wgr, eg, wlm, el;
        rate(cg, c->nblocks, tb, &wgr, &eg);
        rate(cl, c->nblocks, tb, &wlm, &el);
        double z = (wgr - wlm) / sqrt(eg * eg + el * el);
        snprintf(path, sizeof path, "%s/peer.dat", c->dir);
        FILE *f = exp_dat_open(path, err);
        if (f) {
            fprintf(f, "# code W W_err cpu_s wall_s (D = %g d, %ld grains, %d blocks of %ld steps after %ld)\n"
                       "grano %.6g %.6g %.4g %.4g\nlammps %.6g %.6g %.4g %.4g\n",
                    cfg.orifice, cfg.n, c->nblocks, c->block, c->discard, wgr, eg, tg, wg, wlm, el, tl, wl);
            rc = exp_dat_close(f, path, err);
        } else {
            rc = err->code;
        }
        snprintf(summary, n,
                 "  D = %g d, %d blocks of %ld steps: grano W = %.3f +- %.3f, LAMMPS W = %.3f +- %.3f grains/tau "
                 "(difference %.2f sigma)\n  CPU s: grano %.1f, LAMMPS %.1f (LAMMPS / grano = %.2f)\n",
                 cfg.orifice, c->nblocks, c->block, wgr, eg, wlm, el, z, tg, tl, tl / tg);
    }
    free(cg), free(cl);
    silo_settled_free(&set);
    return rc;
}
