/* grano silo-flow: the outflow against the orifice size (thesis chapter 4).
 * Each unit of work is one orifice size and one realisation: fill, settle,
 * open with reinsertion at the top, discard the transient, then count the
 * grains that leave in each block and sample the packing fraction of the
 * D x D square above the orifice. */
#include <errno.h>
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
#include "silo_flow.h"
#include "sweep.h"

void sf_label(size_t unit, void *ctx, char *buf, size_t n)
{
    const sf_ctx *c = ctx;
    size_t o = unit / (size_t)c->nreal, r = unit % (size_t)c->nreal;
    snprintf(buf, n, "D%g-r%02zu", c->orifice[o], r);
}

void sf_key(size_t unit, void *ctx, char *buf, size_t n)
{
    const sf_ctx *c = ctx;
    size_t o = unit / (size_t)c->nreal, r = unit % (size_t)c->nreal;
    const silo_cfg *b = &c->base;
    snprintf(buf, n,
             "silo-flow 2 band=top+1..5 n=%ld W=%.17g H=%.17g base=%.17g hopper=%d D=%.17g seed=%llu method=%s dt=%.17g ke=%.17g "
             "discard=%ld block=%ld nblocks=%d sample=%ld lift=%.17g",
             b->n, b->width, b->height, b->base, b->hopper, c->orifice[o],
             (unsigned long long)(c->seed + r), b->method->name, b->dt, b->ke_tol, c->discard, c->block, c->nblocks,
             c->sample_every, c->lift);
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
    silo_settled set;
    volatile double fillp = 0;
    double w0 = gr_wall_seconds(), c0 = (double)clock() / CLOCKS_PER_SEC;
    int rc = silo_fill(&cfg, &set, &fillp, err);
    double w1 = gr_wall_seconds(), c1 = (double)clock() / CLOCKS_PER_SEC;
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
    if (!rc && (rc = silo_advance(&cfg, st, (uint64_t)c->discard, err)) == GR_OK) {
        gr_obs ob;
        gr_obs_clear(&ob);
        rc = gr_sim_observe(st, &ob, err);
        uint64_t last = ob.outflow;
        for (int b = 0; b < c->nblocks && !rc; b++) {
            long done = 0;
            int ns = 0;
            while (done < c->block && !rc) {
                long k = c->sample_every < c->block - done ? c->sample_every : c->block - done;
                if ((rc = silo_advance(&cfg, st, (uint64_t)k, err)) || (rc = gr_sim_snapshot(st, snap, err)))
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
    }
    double cost[5] = {w1 - w0, c1 - c0, gr_wall_seconds() - w1, (double)clock() / CLOCKS_PER_SEC - c1,
                      (double)total};
    gr_ckpt *ck = rc ? NULL : gr_ckpt_create(part, err);
    if (!rc && !ck)
        rc = err->code;
    if (!rc) rc = gr_ckpt_put_bytes(ck, "key", key, strlen(key), err);
    if (!rc) rc = gr_ckpt_put_f64(ck, "counts", count, (size_t)c->nblocks, err);
    if (!rc) rc = gr_ckpt_put_f64(ck, "packing", phi, (size_t)c->nblocks, err);
    if (!rc) rc = gr_ckpt_put_f64(ck, "top", top, (size_t)c->nblocks, err);
    if (!rc) rc = exp_put_scalar(ck, "bulk_packing", bulk, err);
    if (!rc) rc = exp_put_scalar(ck, "t_settle", set.t_settle, err);
    if (!rc) rc = exp_put_scalar(ck, "top0", set.top, err);
    if (!rc) rc = exp_put_particles(ck, "final", snap, err);
    if (!rc) rc = gr_ckpt_put_f64(ck, "cost", cost, 5, err);
    if (ck) {
        if (rc)
            gr_ckpt_discard(ck);
        else
            rc = gr_ckpt_close(ck, err);
    }
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
        "DEM backend: for each orifice, fill, settle, open with the grains that leave\n"
        "reinserted at the top, discard the first steps, then count the grains that\n"
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
        "      --method M       the method (default dem); one without the silo's features\n"
        "                       (walls made of fixed grains, an orifice, ...) is refused\n"
        "  -Q, --quick          900 grains in a 24 d x 48 d silo filled without hopper,\n"
        "                       7 orifices, 16 blocks of 2000 steps: a smoke test\n"
        "  -f, --force          redo every part, even finished ones\n"
        "  -q, --quiet          no progress line\n"
        "  -h, --help           this help\n\n"
        "Each unit writes DIR/parts/flow-D<D>-r<r>.part when done; a run that is\n"
        "interrupted and started again with the same options redoes only the missing\n"
        "parts. Exit codes: 0 done, 1 a run failed, 2 bad input.\n");
}

static int bad(const char *opt, const char *val, const char *what)
{
    fprintf(stderr, "grano silo-flow: %s: '%s' is not %s\n", opt, val ? val : "", what);
    return 2;
}

static int parse_long(const char *s, long lo, long *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (*end || end == s || errno || v < lo)
        return -1;
    *out = v;
    return 0;
}

static int sf_report_any(const void *ctx, char *const *parts, char *summary, size_t nsum, gr_err *err)
{
    return sf_report(ctx, parts, summary, nsum, err);
}

/* Run (or reuse) every unit, then the report; the exit code. */
static int run_sweep(sf_ctx *c, int jobs, int force, int quiet)
{
    char pdir[1100];
    snprintf(pdir, sizeof pdir, "%s/parts", c->dir);
    gr_err e = {0};
    size_t nu = c->norif * (size_t)c->nreal, reused = 0;
    exp_sweep sw = {nu, jobs, pdir, "flow", !quiet, "orifices", force};
    char summary[4096] = "";
    double t_units = 0;
    int rc = exp_sweep_and_report(&sw, sf_unit, sf_label, sf_key, sf_report_any, c, summary,
                                   sizeof summary, &t_units, &reused, &e);
    if (rc)
        fprintf(stderr, "grano silo-flow: %s\n", e.msg);
    else if (!quiet)
        fprintf(stderr, "grano silo-flow: %zu units (%zu reused) in %.1f s wall with %d job%s; wrote %s/\n%s",
                nu, reused, t_units, jobs, jobs > 1 ? "s" : "", c->dir, summary);
    return rc;
}

/* a long option without a short one */
#define OPT_METHOD 0x100

int cmd_silo_flow(int argc, char **argv)
{
    static const struct option opts[] = {
        {"orifices", required_argument, NULL, 'D'}, {"realisations", required_argument, NULL, 'n'},
        {"seed", required_argument, NULL, 's'},     {"jobs", required_argument, NULL, 'j'},
        {"out", required_argument, NULL, 'o'},      {"blocks", required_argument, NULL, 'b'},
        {"block-steps", required_argument, NULL, 'B'}, {"discard", required_argument, NULL, 'X'},
        {"grains", required_argument, NULL, 'G'},   {"width", required_argument, NULL, 'W'},
        {"method", required_argument, NULL, OPT_METHOD}, {"quick", no_argument, NULL, 'Q'},
        {"force", no_argument, NULL, 'f'},
        {"quiet", no_argument, NULL, 'q'},          {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0}};
    const char *orif = NULL, *out = NULL, *method = "dem";
    long nreal = 1, jobs = 1, seed = 1, grains = -1, blocks = -1, bsteps = -1, discard = -1;
    double width = -1;
    int quick = 0, force = 0, quiet = 0, ch;
    opterr = 0;
    optind = 1;
    while ((ch = getopt_long(argc, argv, ":D:n:s:j:o:b:Qfqh", opts, NULL)) != -1) {
        char *end;
        switch (ch) {
        case 'D': orif = optarg; break;
        case 'n': if (parse_long(optarg, 1, &nreal)) return bad("--realisations", optarg, "a positive integer"); break;
        case 's': if (parse_long(optarg, 0, &seed)) return bad("--seed", optarg, "a non-negative integer"); break;
        case 'j': if (parse_long(optarg, 1, &jobs) || jobs > 256) return bad("--jobs", optarg, "an integer in 1..256"); break;
        case 'o': out = optarg; break;
        case 'b': if (parse_long(optarg, 4, &blocks)) return bad("--blocks", optarg, "an integer >= 4"); break;
        case 'B': if (parse_long(optarg, 10, &bsteps)) return bad("--block-steps", optarg, "an integer >= 10"); break;
        case 'X': if (parse_long(optarg, 0, &discard)) return bad("--discard", optarg, "a non-negative integer"); break;
        case 'G': if (parse_long(optarg, 10, &grains)) return bad("--grains", optarg, "an integer >= 10"); break;
        case 'W':
            width = strtod(optarg, &end);
            if (*end || !(width >= 8) || !isfinite(width)) return bad("--width", optarg, "a width >= 8");
            break;
        case OPT_METHOD: method = optarg; break;
        case 'Q': quick = 1; break;
        case 'f': force = 1; break;
        case 'q': quiet = 1; break;
        case 'h': usage(stdout); return 0;
        case ':': fprintf(stderr, "grano silo-flow: option '%s' needs a value\n", argv[optind - 1]); return 2;
        default:
            fprintf(stderr, "grano silo-flow: unknown option '%s' (see grano silo-flow --help)\n", argv[optind - 1]);
            return 2;
        }
    }
    if (optind != argc) {
        fprintf(stderr, "grano silo-flow: unexpected argument '%s'\n", argv[optind]);
        return 2;
    }
    sf_ctx c = {0};
    c.quick = quick;
    if (quick) {
        silo_cfg_quick(&c.base, 1);
        c.base.n = 900, c.base.width = 24;
    } else
        silo_cfg_thesis(&c.base, 1);
    if (grains > 0)
        c.base.n = grains;
    if (width > 0)
        c.base.width = width, c.base.height = 2 * width;
    const char *deflist = quick ? "3.56,4.2,6.24,8,10,12,14" : "3.56,4.5,5.3,6.24,7.2,8.2,9.2,10.5,12,13.5,15,16.04";
    if (exp_parse_list(orif ? orif : deflist, c.orifice, SF_MAX_ORIF, &c.norif))
        return bad("--orifices", orif, "a comma-separated list of positive widths");
    for (size_t i = 0; i < c.norif; i++)
        if (c.orifice[i] >= c.base.width - 2)
            return bad("--orifices", orif, "narrower than the silo");
    gr_err me = {0};
    /* the silo as the units will open it */
    silo_cfg probe = c.base;
    probe.orifice = c.orifice[0];
    probe.reinsert = 1;
    if (silo_choose_method(&probe, method, &me)) {
        fprintf(stderr, "grano silo-flow: %s\n", me.msg);
        return 2;
    }
    c.base.method = probe.method;
    c.nreal = (int)nreal;
    c.seed = (uint64_t)seed;
    c.discard = discard >= 0 ? discard : quick ? 8000 : 10000;
    c.block = bsteps > 0 ? bsteps : quick ? 2000 : 10000;
    c.nblocks = (int)(blocks > 0 ? blocks : quick ? 16 : 100);
    c.sample_every = c.block >= 500 ? c.block / 20 : c.block;
    c.lift = 6;
    c.split = 9;
    char dir[1024];
    snprintf(dir, sizeof dir, "%s", out ? out : quick ? "results/silo-flow-quick" : "results/silo-flow");
    c.dir = dir;
    return run_sweep(&c, (int)jobs, force, quiet);
}
