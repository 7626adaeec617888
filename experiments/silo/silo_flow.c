/* grano silo-flow: the outflow against the orifice size (thesis chapter 4).
 * The fillings come first, one per realisation (silo_fill.c); each unit of
 * work is then one orifice size and one realisation: branch the settled
 * silo to the orifice (silo_rebase), open with reinsertion at the top, discard the transient, then count the
 * grains that leave in each block and sample the packing fraction of the
 * D x D square above the orifice. */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cmd.h"
#include "opts.h"
#include "parts.h"
#include "progress.h"
#include "silo_cli.h"
#include "silo_flow.h"
#include "sweep.h"

void sf_label(size_t unit, void *ctx, char *buf, size_t n)
{
    const sf_ctx *c = ctx;
    silo_unit_label(c->orifice, c->nreal, unit, buf, n);
}

void sf_key(size_t unit, void *ctx, char *buf, size_t n)
{
    const sf_ctx *c = ctx;
    size_t o = unit / (size_t)c->nreal, r = unit % (size_t)c->nreal;
    int k = snprintf(buf, n, "silo-flow 4 band=top+1..5 branchmax=%g D=%.17g discard=%ld block=%ld nblocks=%d sample=%ld lift=%.17g ",
                     SILO_BRANCH_MAX, c->orifice[o], c->discard, c->block, c->nblocks, c->sample_every, c->lift);
    if (k > 0 && (size_t)k < n)
        silo_fill_key(r, (void *)&c->fills, buf + k, n - (size_t)k);
}

/* The measured blocks after the discarded transient: the grains that
 * leave in each block (from the method's outflow counter), the packing of
 * the square sq = {x0, y0, x1, y1} sampled every sample_every steps, and
 * the surface at the block's end. The progress weighs the filling 0.3. */
static int measure_blocks(const sf_ctx *c, const silo_cfg *cfg, gr_sim *st, gr_particles *snap, const double *sq,
                          volatile double fillp, volatile double *progress, double *count, double *phi,
                          double *top, gr_err *err)
{
    long total = c->discard + c->block * (long)c->nblocks;
    gr_obs ob;
    gr_obs_clear(&ob);
    int rc = gr_sim_observe(st, &ob, err);
    uint64_t last = ob.outflow;
    for (int b = 0; b < c->nblocks && !rc; b++) {
        long done = 0;
        int ns = 0;
        while (done < c->block && !rc) {
            long k = c->sample_every < c->block - done ? c->sample_every : c->block - done;
            if ((rc = silo_advance(cfg, st, (uint64_t)k, err)) || (rc = gr_sim_snapshot(st, snap, err)))
                break;
            done += k;
            phi[b] += silo_packing(snap, sq[0], sq[1], sq[2], sq[3]);
            ns++;
            if (progress)
                *progress = 0.3 * fillp + 0.7 * (double)(c->discard + b * c->block + done) / (double)total;
        }
        if (rc || (rc = gr_sim_observe(st, &ob, err)))
            break;
        phi[b] /= ns > 0 ? ns : 1;
        count[b] = (double)(ob.outflow - last);
        last = ob.outflow;
        top[b] = silo_top(snap);
    }
    return rc;
}

/* The unit's part file: the key, the block series, the settled silo's
 * bulk packing and height, the branch (its settling time, the lift, the
 * shared filling's CPU seconds, the kinetic energy per grain at opening), the final grains and the cost (the
 * branch's settling in place of the filling). */
static int write_part(const sf_ctx *c, const char *part, const char *key, const double *count, const double *phi,
                      const double *top, double bulk, const silo_settled *set, const gr_particles *snap,
                      const double *cost, const double *branch, gr_err *err)
{
    int rc = GR_OK;
    gr_ckpt *ck = gr_ckpt_create(part, err);
    if (!ck)
        return err->code;
    if (!rc) rc = gr_ckpt_put_bytes(ck, "key", key, strlen(key), err);
    if (!rc) rc = gr_ckpt_put_f64(ck, "counts", count, (size_t)c->nblocks, err);
    if (!rc) rc = gr_ckpt_put_f64(ck, "packing", phi, (size_t)c->nblocks, err);
    if (!rc) rc = gr_ckpt_put_f64(ck, "top", top, (size_t)c->nblocks, err);
    if (!rc) rc = exp_put_scalar(ck, "bulk_packing", bulk, err);
    if (!rc) rc = exp_put_scalar(ck, "t_settle", set->t_settle, err);
    if (!rc) rc = exp_put_scalar(ck, "top0", set->top, err);
    if (!rc) rc = gr_ckpt_put_f64(ck, "branch", branch, 4, err);
    if (!rc) rc = exp_put_particles(ck, "final", snap, err);
    if (!rc) rc = gr_ckpt_put_f64(ck, "cost", cost, 5, err);
    if (rc) {
        gr_ckpt_discard(ck);
        return rc;
    }
    return gr_ckpt_close(ck, err);
}

int sf_unit(size_t unit, const char *part, const char *key, void *ctx, volatile double *progress,
            gr_err *err)
{
    const sf_ctx *c = ctx;
    size_t o = unit / (size_t)c->nreal, r = unit % (size_t)c->nreal;
    silo_cfg cfg = c->base;
    cfg.orifice = c->orifice[o];
    cfg.seed = c->seed + r;
    cfg.reinsert = 1;
    silo_settled fill, set;
    volatile double fillp = 0;
    double fill_cost[5];
    double w0 = gr_wall_seconds(), c0 = (double)clock() / CLOCKS_PER_SEC;
    int rc = silo_fill_load(&c->fills, r, &fill, fill_cost, err);
    if (!rc)
        rc = silo_rebase(&cfg, &fill, &set, &fillp, err);
    double w1 = gr_wall_seconds(), c1 = (double)clock() / CLOCKS_PER_SEC;
    /* the part's t_settle stays the filling's; the branch's own settling apart */
    double branch[4] = {rc ? 0 : set.t_settle, rc ? 0 : set.lift, fill_cost[1], rc ? 0 : set.ekin};
    if (!rc)
        set.t_settle = fill.t_settle;
    silo_settled_free(&fill);
    if (rc)
        return rc;
    gr_scene *sc = NULL;
    gr_sim *st = NULL;
    gr_particles *snap = gr_particles_create(0, err);
    double *count = calloc((size_t)c->nblocks, sizeof *count);
    double *phi = calloc((size_t)c->nblocks, sizeof *phi);
    double *top = calloc((size_t)c->nblocks, sizeof *top);
    if (!snap || !count || !phi || !top)
        rc = gr_fail(err, GR_ERUN, "out of memory");
    if (!rc)
        rc = silo_open(&cfg, &set, &sc, &st, err);
    double xc = rc ? 0 : sc->silo.orifice_center, D = cfg.orifice;
    double sq[4] = {xc - 0.5 * D, cfg.base + c->lift, xc + 0.5 * D, cfg.base + c->lift + D};
    /* bulk packing of the settled silo, away from walls, base and surface */
    double mg = cfg.width > 30 ? 5 : 2;
    double bulk = rc ? NAN
                     : silo_packing(set.p, (rc ? 0 : sc->silo.x0) + mg, cfg.base + 2 * mg + 6,
                                    (rc ? 0 : sc->silo.x0) + cfg.width - mg, set.top - 2 * mg);
    long total = c->discard + c->block * (long)c->nblocks;
    if (!rc && (rc = silo_advance(&cfg, st, (uint64_t)c->discard, err)) == GR_OK)
        rc = measure_blocks(c, &cfg, st, snap, sq, fillp, progress, count, phi, top, err);
    double cost[5] = {w1 - w0, c1 - c0, gr_wall_seconds() - w1, (double)clock() / CLOCKS_PER_SEC - c1,
                      (double)total};
    if (!rc)
        rc = write_part(c, part, key, count, phi, top, bulk, &set, snap, cost, branch, err);
    gr_sim_free(st);
    gr_scene_free(sc);
    gr_particles_free(snap);
    free(count), free(phi), free(top);
    silo_settled_free(&set);
    return rc;
}

/* ------------------------------------------------------------------ CLI */

static void usage(FILE *f)
{
    fprintf(f,
        "usage: grano silo-flow [options]\n\n"
        "The outflow of a silo against its orifice size (thesis chapter 4) on the soft\n"
        "DEM backend: fill and settle once per realisation, then for each orifice branch\n"
        "that settled silo to it, open with the grains that leave reinserted at the\n"
        "top, discard the first steps, then count the grains that\n"
        "leave in each block and the packing fraction of the D x D square 6 d above\n"
        "the base. Writes DIR/silo-flow.h5, .dat tables and the figures fig4_1 ... fig4_6.\n\n"
        "options:\n"
        "  -D, --orifices LIST  orifice widths in d, comma separated (default 12 sizes,\n"
        "                       3.56,4.5,5.3,6.24,7.2,8.2,9.2,10.5,12,13.5,15,16.04)\n"
        "  -n, --realisations N realisations per orifice (default 1)\n"
        "  -s, --seed S         seed of realisation 0 (S + r for realisation r; the same\n"
        "                       seeds for every orifice) (default 1)\n"
        "  -j, --jobs N         units (orifice, realisation) run at once (default 1)\n"
        "  -o, --out DIR        output directory (default results/silo-flow)\n"
        "  -b, --blocks N       measured blocks (default 100)\n"
        "      --block-steps N  steps per block (default 10000)\n"
        "      --discard N      steps discarded after opening (default 10000)\n"
        "      --grains N       mobile grains (default 5000)\n"
        "      --width W        container width in d (default 50; height 2 W)\n"
        "      --hopper-outlet F the filling hopper's outlet, a fraction of the width\n"
        "                       (default " SILO_STR(SILO_OUTLET) ")\n"
        "      --method M       the method (default dem); one without the silo's features\n"
        "                       (walls made of fixed grains, an orifice, ...) is refused.\n"
        "                       Steps stay dem's (1.25e-4 tau); cd runs its own dt\n"
        "                       (2.5e-3 tau, 20 steps) on rigid disks, mu 0.5, e = 0\n"
        "      --param K=V      a key of the method's section (repeatable), e.g. tol=1e-4\n"
        "      --material K=V   a key of [material] (repeatable), replacing the thesis's\n"
        "                       law (normal = hertz, tangential = regularised, kn = 1e5,\n"
        "                       gamma_n = 100, gamma_t = 300, mu = 0.5), e.g. mu=0.3\n"
        "      --peer lammps    instead of the sweep: the first orifice's silo, settled and\n"
        "                       branched as the sweep does, run without reinsertion by dem\n"
        "                       and by LAMMPS (lmp; apt-get install lammps) from the same\n"
        "                       state with the same contact law; both flow rates with\n"
        "                       their errors and CPU times in DIR/peer.dat\n"
        "  -Q, --quick          900 grains in a 24 d x 48 d silo filled without hopper,\n"
        "                       7 orifices, 16 blocks of 2000 steps: a smoke test\n"
        "  -f, --force          redo every part, even finished ones\n"
        "  -q, --quiet          no progress line\n"
        "  -h, --help           this help\n\n"
        "Under mpirun -n K (a build with MPI) the units are spread over the ranks and\n"
        "rank 0 writes the results, the same numbers as one process.\n\n"
        "Each filling writes DIR/parts/fill-r<r>.part, each unit\n"
        "DIR/parts/flow-D<D>-r<r>.part when done; a run that is\n"
        "interrupted and started again with the same options redoes only the missing\n"
        "parts. Exit codes: 0 done, 1 a run failed, 2 bad input.\n");
}

static int sf_report_any(const void *ctx, char *const *parts, char *summary, size_t nsum, gr_err *err)
{
    return sf_report(ctx, parts, summary, nsum, err);
}

/* silo-flow's own options; a number not given is -1 */
typedef struct {
    long blocks, bsteps, discard;
    int peer;
} sf_own;

static const struct option sf_own_opts[] = {
    {"blocks", required_argument, NULL, 'b'}, {"block-steps", required_argument, NULL, 'B'},
    {"discard", required_argument, NULL, 'X'}, {"peer", required_argument, NULL, 'P'}, {NULL, 0, NULL, 0}};

static int sf_own_option(int ch, const char *arg, void *own);

/* A filling per realisation; a unit: the branch, the discarded steps and
 * the blocks. */
static void sf_estimate(const void *ctx, double *pre, double *unit)
{
    const sf_ctx *c = ctx;
    *pre = silo_cpu_estimate(&c->base, SILO_FILL_STEPS);
    *unit = silo_cpu_estimate(&c->base, SILO_BRANCH_STEPS + (double)c->discard + (double)c->block * c->nblocks);
}

static const silo_cli sf_cli = {
    .name = "silo-flow", .usage = usage, .own = sf_own_opts, .own_short = "b:", .own_parse = sf_own_option,
    .orifices = "3.56,4.5,5.3,6.24,7.2,8.2,9.2,10.5,12,13.5,15,16.04",
    .quick_orifices = "3.56,4.2,6.24,8,10,12,14", .quick_n = 900, .quick_width = 24, .reinsert = 1,
    .prefix = "flow", .progress_what = "orifices", .units_what = "units",
    .unit = sf_unit, .label = sf_label, .key = sf_key, .report = sf_report_any,
    .pre_unit = silo_fill_unit, .pre_label = silo_fill_label, .pre_key = silo_fill_key, .pre_prefix = "fill",
    .pre_what = "fillings", .estimate = sf_estimate};

static int sf_own_option(int ch, const char *arg, void *own)
{
    sf_own *w = own;
    switch (ch) {
    case 'b': return silo_parse_long(arg, 4, &w->blocks) ? silo_bad(&sf_cli, "--blocks", arg, "an integer >= 4") : 0;
    case 'B':
        return silo_parse_long(arg, 10, &w->bsteps) ? silo_bad(&sf_cli, "--block-steps", arg, "an integer >= 10") : 0;
    case 'X':
        return silo_parse_long(arg, 0, &w->discard) ? silo_bad(&sf_cli, "--discard", arg, "a non-negative integer")
                                                    : 0;
    case 'P':
        if (strcmp(arg, "lammps"))
            return silo_bad(&sf_cli, "--peer", arg, "lammps");
        w->peer = 1;
        return 0;
    default: return 1;
    }
}

int cmd_silo_flow(int argc, char **argv)
{
    silo_opts o;
    sf_own w = {-1, -1, -1, 0};
    int rc = silo_cli_parse(&sf_cli, argc, argv, &o, &w);
    if (rc >= 0)
        return rc;
    sf_ctx c = {0};
    c.quick = o.quick;
    if ((rc = silo_cli_silo(&sf_cli, &o, &c.base, c.orifice, SF_MAX_ORIF, &c.norif)))
        return rc;
    int quick = o.quick;
    c.nreal = (int)(o.nreal > 0 ? o.nreal : 1);
    c.seed = (uint64_t)o.seed;
    c.discard = w.discard >= 0 ? w.discard : quick ? 8000 : 10000;
    c.block = w.bsteps > 0 ? w.bsteps : quick ? 2000 : 10000;
    c.nblocks = (int)(w.blocks > 0 ? w.blocks : quick ? 16 : 100);
    /* 20 samples a block unless the block is shorter than 0.0625 tau (500
     * steps of dem) */
    c.sample_every = c.block >= lround(0.0625 / c.base.dt) ? c.block / 20 : c.block;
    c.lift = 6;
    c.split = 9;
    char dir[1024];
    c.dir = silo_cli_dir(&sf_cli, &o, dir, sizeof dir);
    c.fills = (silo_fills){&c.base, c.seed, c.dir, SILO_FILL_D};
    if (w.peer) {
        char summary[1024] = "";
        gr_err e = {0};
        if (sf_peer_lammps(&c, summary, sizeof summary, &e)) {
            fprintf(stderr, "grano silo-flow: %s\n", e.msg);
            return e.code == GR_EINPUT ? 2 : 1;
        }
        fprintf(stderr, "grano silo-flow --peer lammps: wrote %s/peer.dat, %s/peer/\n%s", c.dir, c.dir, summary);
        return 0;
    }
    return silo_cli_sweep(&sf_cli, &o, &c, &c.fills, (size_t)c.nreal, c.norif * (size_t)c.nreal, c.dir);
}
