/* The measurements of grano compare's cases, each through the method
 * interface only (advance, observe, snapshot, counters, windows), and their
 * references. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cmp.h"
#include "init.h"
#include "refs.h"
#include "stats.h"

#define NBLOCKS 10

static int steps_done(gr_sim *s, double *steps, gr_err *err)
{
    gr_obs o;
    if (gr_sim_observe(s, &o, err))
        return err->code;
    *steps = (double)o.steps;
    return GR_OK;
}

/* ---------------------------------------------------------------- collision */

/* Centre distance and normal relative velocity (negative: approaching). */
static void pair_state(const gr_particles *p, double *dist, double *un)
{
    double dx = p->x[1] - p->x[0], dy = p->y[1] - p->y[0];
    *dist = hypot(dx, dy);
    *un = ((p->vx[1] - p->vx[0]) * dx + (p->vy[1] - p->vy[0]) * dy) / *dist;
}

/* Step by step (one step or event at a time, never past until): the
 * restitution from the normal relative velocities before and after, the
 * contact time from the crossings of distance 1, interpolated linearly
 * between steps (0 when the disks never overlap: hard disks). */
int cmp_measure_collision(const cmp_case *c, gr_sim *s, const gr_scene *sc, cmp_meas *out, gr_err *err)
{
    (void)c;
    gr_particles *p = gr_particles_create(2, err);
    if (!p)
        return err->code;
    double d0, u0, d, u, t_in = NAN, t_out = NAN;
    int rc = gr_sim_snapshot(s, p, err);
    if (!rc && p->n != 2)
        rc = gr_fail(err, GR_EINPUT, "%s: the collision case needs exactly two disks", sc->path);
    if (!rc)
        pair_state(p, &d0, &u0);
    double dprev = d0, tprev = gr_sim_time(s), ubefore = u0;
    while (!rc && gr_sim_time(s) < sc->run.until) {
        if ((rc = gr_sim_advance(s, sc->run.until, 1, err)) || (rc = gr_sim_snapshot(s, p, err)))
            break;
        double t = gr_sim_time(s);
        pair_state(p, &d, &u);
        if (d < 1 && dprev >= 1 && isnan(t_in)) {
            t_in = tprev + (t - tprev) * (dprev - 1) / (dprev - d);
            ubefore = u0;
        }
        if (d >= 1 && dprev < 1 && isnan(t_out))
            t_out = tprev + (t - tprev) * (1 - dprev) / (d - dprev);
        if (isnan(t_in))
            u0 = u; /* the approach speed just before contact */
        dprev = d, tprev = t;
    }
    if (!rc) {
        pair_state(p, &d, &u);
        out->value = -u / ubefore;
        out->sem = NAN;
        out->aux = isnan(t_in) ? 0 : t_out - t_in;
        rc = steps_done(s, &out->steps, err);
    }
    gr_particles_free(p);
    return rc;
}

/* The scene's two disks moved apart by a seed-dependent fraction of 0.004
 * (twice the coarsest dt times the approach speed): the realisations of
 * the case meet at different phases of a time step, whose scatter is the
 * error bar of a stepping method (one collision alone can be off by a few
 * 1e-3 at coarse steps). */
int cmp_prepare_collision(const gr_scene *sc, gr_particles *p, gr_err *err)
{
    if (gr_init_particles(sc, p, err))
        return err->code;
    double phase = fmod((double)(sc->seed - 1) * 0.6180339887498949, 1.0) * 0.004;
    if (p->n == 2 && p->x[0] < p->x[1])
        p->x[0] -= phase / 2, p->x[1] += phase / 2;
    return GR_OK;
}

/* The linear law's restitution and contact time for two equal grains. */
double cmp_ref_collision(const gr_scene *sc, double *aux_ref)
{
    double m = sc->species[0].density * M_PI * sc->species[0].diameter * sc->species[0].diameter / 4;
    return exp_lsd_restitution(sc->mat.kn, sc->mat.gamma_n, m / 2, aux_ref);
}

/* ------------------------------------------------------------------ cooling */

static double area(const gr_scene *sc)
{
    return sc->width * sc->height;
}

/* The grains the scene stands for: dsmc's particles may each stand for
 * [species] weight of them. */
static double represented(const gr_scene *sc)
{
    double n = 0;
    for (int k = 0; k < sc->nspecies; k++)
        n += (double)sc->species[k].count * sc->species[k].weight;
    return n;
}

static double packing(const gr_scene *sc, double a)
{
    double d = sc->species[0].diameter;
    return represented(sc) * M_PI * d * d / 4 / a;
}

/* The scene's grains after an elastic edmd run of three collisions per disk,
 * which gives them the equilibrium pair correlation of the hard-disk fluid
 * (a random placement has not got it) before the quench. */
int cmp_prepare_cooling(const gr_scene *sc, gr_particles *p, gr_err *err)
{
    const gr_method_type *edmd = gr_method_find("edmd");
    if (gr_init_particles(sc, p, err))
        return err->code;
    if (!edmd || represented(sc) != (double)gr_scene_count(sc))
        return GR_OK; /* weighted particles (dsmc) have no pair correlation to give */
    const char *names[GR_MAX_METHODS + 1];
    gr_method_names(names, GR_MAX_METHODS + 1);
    char *text = gr_scene_text_set(sc->text, "material", "restitution", "1", err);
    gr_scene *el = text ? gr_scene_parse(text, sc->path, names, err) : NULL;
    free(text);
    gr_sim *s = NULL;
    int rc = !el || gr_sim_create(edmd, el, p, &s, err);
    uint64_t pairs = 0, n = 3 * (uint64_t)gr_scene_count(sc) / 2; /* a pair collision is two disks' */
    while (!rc && gr_sim_counter(s, "pair_collisions", &pairs) && pairs < n)
        rc = gr_sim_advance(s, INFINITY, n - pairs, err);
    if (!rc)
        rc = gr_sim_snapshot(s, p, err);
    gr_sim_free(s);
    gr_scene_free(el);
    return rc ? (err->code ? err->code : GR_ERUN) : GR_OK;
}

static int temperature(gr_sim *s, gr_particles *p, double *T, gr_err *err)
{
    gr_obs o;
    if (gr_sim_snapshot(s, p, err))
        return err->code;
    gr_obs_from_particles(p, 0, &o);
    *T = o.temperature;
    return GR_OK;
}

/* T/T0 at Haff's time tau (Sonine-corrected, from the measured T0), and at
 * tau/2 (aux). */
int cmp_measure_cooling(const cmp_case *c, gr_sim *s, const gr_scene *sc, cmp_meas *out, gr_err *err)
{
    (void)c;
    gr_particles *p = gr_particles_create(0, err);
    if (!p)
        return err->code;
    double T0 = NAN, T1 = NAN, T2 = NAN, a = area(sc), n = represented(sc) / a;
    int rc = temperature(s, p, &T0, err);
    double tau = rc ? 0 : exp_haff_tau(sc->mat.restitution, n, packing(sc, a), T0, 1);
    if (!rc && tau > sc->run.until)
        rc = gr_fail(err, GR_EINPUT, "%s: [run] until = %g is shorter than Haff's time %g", sc->path,
                     sc->run.until, tau);
    rc = rc || cmp_advance(s, sc, out, tau / 2, err) || temperature(s, p, &T1, err) ||
         cmp_advance(s, sc, out, tau, err) || temperature(s, p, &T2, err) || steps_done(s, &out->steps, err);
    gr_particles_free(p);
    if (rc)
        return err->code ? err->code : GR_ERUN;
    out->value = T2 / T0;
    out->aux = T1 / T0;
    out->sem = NAN;
    return GR_OK;
}

double cmp_ref_cooling(const gr_scene *sc, double *aux_ref)
{
    (void)sc;
    *aux_ref = 1 / 2.25;
    return 0.25;
}

/* ---------------------------------------------------- equation of state */

/* The area the centres reach. */
static double free_area(const gr_scene *sc)
{
    double d = sc->species[0].diameter;
    return (sc->width - d) * (sc->height - d);
}

#define NSAMP 5 /* density samples per window */

/* Mobile grains with centres in the central half of the box, per area. */
static double bulk_density(const gr_particles *p, const gr_scene *sc)
{
    double x0 = sc->width / 4, x1 = 3 * sc->width / 4, y0 = sc->height / 4, y1 = 3 * sc->height / 4;
    long k = 0;
    for (size_t i = 0; i < p->n; i++)
        k += !(p->flags[i] & (GR_PF_FIXED | GR_PF_GONE)) && p->x[i] >= x0 && p->x[i] < x1 && p->y[i] >= y0 &&
             p->y[i] < y1;
    return (double)k / ((x1 - x0) * (y1 - y0));
}

/* The wall pressure equals the bulk pressure, but the walls layer the
 * grains near them, so the bulk density is not N / area: it is counted in
 * the central half of the box, and Z = P / (n T) is compared with
 * Luding's Z at that density, window by window after the first fifth of the
 * run. value: Z / Z_Luding(eta_bulk); aux: eta_bulk. */
int cmp_measure_eos(const cmp_case *c, gr_sim *s, const gr_scene *sc, cmp_meas *out, gr_err *err)
{
    (void)c;
    double R[NBLOCKS], eta = 0, t0 = sc->run.until / 5, d = sc->species[0].diameter;
    gr_particles *p = gr_particles_create(0, err);
    int rc = !p || cmp_advance(s, sc, out, t0, err);
    for (int b = 0; b < NBLOCKS && !rc; b++) {
        gr_obs o;
        double n = 0, T = 0;
        gr_sim_reset_window(s);
        for (int k = 1; k <= NSAMP && !rc; k++) {
            rc = cmp_advance(s, sc, out, t0 + (sc->run.until - t0) * (b * NSAMP + k) / (NBLOCKS * NSAMP), err) ||
                 gr_sim_snapshot(s, p, err);
            gr_obs_from_particles(p, 0, &o);
            n += bulk_density(p, sc) / NSAMP, T += o.temperature / NSAMP;
        }
        if (rc || (rc = gr_sim_observe(s, &o, err)))
            break;
        double eb = n * M_PI * d * d / 4;
        R[b] = o.wall_pressure / (n * T) / exp_z_luding(eb);
        eta += eb / NBLOCKS;
    }
    gr_particles_free(p);
    if (rc)
        return err->code ? err->code : GR_ERUN;
    gr_block_average(R, NBLOCKS, 1, NULL, &out->value, &out->sem);
    out->aux = eta;
    return steps_done(s, &out->steps, err);
}

double cmp_ref_eos(const gr_scene *sc, double *aux_ref)
{
    *aux_ref = packing(sc, free_area(sc));
    return 1;
}

/* --------------------------------------------------------- vibrated bed */

#define BED_SAMPLES 20 /* snapshots per window */

/* A grain below the lowest position of the floor went through it: the
 * run is wrong even if every number is finite. */
static int below_floor(const gr_particles *p, const gr_scene *sc, double t, gr_err *err)
{
    double low = -sc->floor.amplitude - gr_scene_max_diameter(sc);
    for (size_t i = 0; i < p->n; i++)
        if (!(p->flags[i] & (GR_PF_FIXED | GR_PF_GONE)) && p->y[i] < low)
            return gr_fail(err, GR_ERUN, "grain %lld is at y = %.4g at t = %.6g, below the floor: it went through",
                           (long long)p->id[i], p->y[i], t);
    return GR_OK;
}

/* One snapshot's share of a window's profiles: grains and kinetic energy
 * (1/2 m v^2) per bin of height 1 d. */
static void bin_grains(const gr_particles *p, double *cnt, double *ke)
{
    for (size_t i = 0; i < p->n; i++) {
        int b = (int)floor(p->y[i]);
        if (!(p->flags[i] & (GR_PF_FIXED | GR_PF_GONE)) && b >= 0 && b < CMP_NBINS)
            cnt[b] += 1, ke[b] += 0.5 * p->mass[i] * (p->vx[i] * p->vx[i] + p->vy[i] * p->vy[i]);
    }
}

/* Per bin, the number density and the temperature (kinetic energy per
 * grain: the bed has no mean flow) block-averaged over the windows with
 * their error bars; a bin no window reached has temperature NaN. */
static void bed_profiles(const double (*cnt)[CMP_NBINS], const double (*ke)[CMP_NBINS], double area, cmp_meas *out)
{
    for (int b = 0; b < CMP_NBINS; b++) {
        double nb[NBLOCKS], Tb[NBLOCKS];
        int k = 0;
        for (int w = 0; w < NBLOCKS; w++) {
            nb[w] = cnt[w][b] / area;
            if (cnt[w][b] > 0)
                Tb[k++] = ke[w][b] / cnt[w][b];
        }
        double *o = out->prof + 4 * b;
        gr_block_average(nb, NBLOCKS, 1, NULL, &o[0], &o[1]);
        o[2] = o[3] = NAN;
        if (k >= 2)
            gr_block_average(Tb, k, 1, NULL, &o[2], &o[3]);
    }
    out->nprof = 4 * CMP_NBINS;
}

/* After the first fifth of the run, in NBLOCKS windows of BED_SAMPLES
 * snapshots: the mean height of the grains (the first moment of the
 * density profile), their mean granular temperature (aux), and the
 * profiles of density and temperature. A grain found below the floor
 * fails the run. */
int cmp_measure_bed(const cmp_case *c, gr_sim *s, const gr_scene *sc, cmp_meas *out, gr_err *err)
{
    (void)c;
    double H[NBLOCKS], T[NBLOCKS], t0 = sc->run.until / 5, sem;
    double cnt[NBLOCKS][CMP_NBINS] = {{0}}, ke[NBLOCKS][CMP_NBINS] = {{0}};
    gr_particles *p = gr_particles_create(0, err);
    int rc = !p || cmp_advance(s, sc, out, t0, err);
    for (int b = 0; b < NBLOCKS && !rc; b++) {
        H[b] = T[b] = 0;
        for (int k = 1; k <= BED_SAMPLES && !rc; k++) {
            double t = t0 + (sc->run.until - t0) * (b * BED_SAMPLES + k) / (NBLOCKS * BED_SAMPLES);
            gr_obs o;
            if ((rc = cmp_advance(s, sc, out, t, err) || gr_sim_snapshot(s, p, err) || below_floor(p, sc, t, err)))
                break;
            gr_obs_from_particles(p, sc->gravity, &o);
            H[b] += o.epot_grav / (sc->gravity * (double)o.n_mobile) / BED_SAMPLES;
            T[b] += o.temperature / BED_SAMPLES;
            bin_grains(p, cnt[b], ke[b]);
        }
    }
    gr_particles_free(p);
    if (rc)
        return err->code ? err->code : GR_ERUN;
    gr_block_average(H, NBLOCKS, 1, NULL, &out->value, &out->sem);
    gr_block_average(T, NBLOCKS, 1, NULL, &out->aux, &sem);
    bed_profiles((const double (*)[CMP_NBINS])cnt, (const double (*)[CMP_NBINS])ke, sc->width * BED_SAMPLES, out);
    return steps_done(s, &out->steps, err);
}

/* ------------------------------------------------------------------ silo */

/* The outflow rate (grains per tau) in NBLOCKS windows from 5 tau after
 * the orifice opens to the end of the run; aux: the mean kinetic energy per
 * grain over the windows' ends. */
int cmp_measure_silo(const cmp_case *c, gr_sim *s, const gr_scene *sc, cmp_meas *out, gr_err *err)
{
    (void)c;
    double W[NBLOCKS], K[NBLOCKS], t0 = sc->silo.open_time + 5, sem;
    if (!(t0 < sc->run.until))
        return gr_fail(err, GR_EINPUT, "%s: the silo case needs [silo] open_time + 5 < [run] until", sc->path);
    gr_obs o;
    int rc = cmp_advance(s, sc, out, t0, err) || gr_sim_observe(s, &o, err);
    uint64_t last = o.outflow;
    for (int b = 0; b < NBLOCKS && !rc; b++) {
        double t1 = t0 + (sc->run.until - t0) * (b + 1) / NBLOCKS;
        if ((rc = cmp_advance(s, sc, out, t1, err) || gr_sim_observe(s, &o, err)))
            break;
        W[b] = (double)(o.outflow - last) / ((sc->run.until - t0) / NBLOCKS);
        K[b] = o.ekin_trans / (double)(o.n_mobile ? o.n_mobile : 1);
        last = o.outflow;
    }
    if (rc)
        return err->code ? err->code : GR_ERUN;
    gr_block_average(W, NBLOCKS, 1, NULL, &out->value, &out->sem);
    gr_block_average(K, NBLOCKS, 1, NULL, &out->aux, &sem);
    return steps_done(s, &out->steps, err);
}
