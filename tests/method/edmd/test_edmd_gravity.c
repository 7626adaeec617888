/* Gravity (parabolic flights), vibrating floors and their high-frequency
 * limits, rough disks, and the guards against inelastic collapse. */
#include "test.h"

#include <stdlib.h>

#include "edmd_int.h"
#include "edmd_test.h"

static gr_edmd *make(const gr_scene *sc, const gr_particles *p, const gr_edmd_params *prm)
{
    gr_err e = {0};
    gr_edmd *s = NULL;
    int rc = gr_edmd_create(sc, p, prm, NULL, &s, &e);
    if (rc)
        fprintf(stderr, "create: %s\n", e.msg);
    assert_int_equal(rc, GR_OK);
    return s;
}

static gr_edmd *make_default(const gr_scene *sc, const gr_particles *p)
{
    gr_edmd_params prm;
    gr_edmd_params_default(&prm);
    return make(sc, p, &prm);
}

/* One disk bouncing on the floor: apex and period exact after many bounces. */
static void single_bounce(void **st)
{
    (void)st;
    gr_scene sc = edmd_box(10, 50, 0, 1.0);
    sc.gravity = 1.0;
    gr_particles *p = edmd_lattice(1, 0, 10, 10, 1, 0.0, 0, 1);
    p->vx[0] = 0.0;
    p->vy[0] = 0.0;
    double h = p->y[0] - 0.5; /* drop height */
    gr_edmd *s = make_default(&sc, p);
    gr_err e = {0};
    assert_int_equal(gr_edmd_advance(s, INFINITY, 1000, &e), GR_OK);
    double T = 2.0 * sqrt(2.0 * h); /* period of a bounce, g = 1 */
    double t_expect = 0.5 * T + 999 * T;
    printf("# 1000 bounces: t = %.15g, expected %.15g\n", gr_edmd_time(s), t_expect);
    assert_true(fabs(gr_edmd_time(s) - t_expect) < 1e-10 * t_expect);
    assert_int_equal(gr_edmd_advance(s, gr_edmd_time(s) + 0.5 * T, 0, &e), GR_OK);
    assert_int_equal(gr_edmd_snapshot(s, p, &e), GR_OK);
    assert_true(fabs(p->y[0] - 0.5 - h) < 1e-9 * h);
    gr_edmd_free(s);
    gr_particles_free(p);
}

typedef struct {
    long n, cap;
    long *i, *j;
    double *t;
} sequence;

static void record(void *user, int kind, long i, long j, double t)
{
    (void)kind;
    sequence *q = user;
    if (q->n == q->cap)
        return;
    q->i[q->n] = i;
    q->j[q->n] = j;
    q->t[q->n] = t;
    q->n++;
}

/* An elastic gas under gravity: energy (kinetic + m g y) conserved, no
 * overlaps, and the same events as the naive algorithm. */
static void gravity_gas(void **st)
{
    (void)st;
    gr_scene sc = edmd_box(20, 40, 0, 1.0);
    sc.gravity = 1.0;
    sequence q[2];
    double e0 = 0, e1[2] = {0, 0}, ov = 0;
    for (int a = 0; a < 2; a++) {
        gr_particles *p = edmd_lattice(100, 0, 0, 20, 20, 3.0, 0, 5);
        e0 = edmd_energy(p, 1.0);
        gr_edmd_params prm;
        gr_edmd_params_default(&prm);
        prm.algorithm = a == 0 ? GR_EDMD_TREE : GR_EDMD_NAIVE;
        gr_edmd *s = make(&sc, p, &prm);
        q[a] = (sequence){0, 10000, malloc(10000 * sizeof(long)), malloc(10000 * sizeof(long)),
                          malloc(10000 * sizeof(double))};
        gr_edmd_set_event_hook(s, record, &q[a]);
        gr_err e = {0};
        assert_int_equal(gr_edmd_advance(s, INFINITY, 10000, &e), GR_OK);
        assert_int_equal(gr_edmd_snapshot(s, p, &e), GR_OK);
        e1[a] = edmd_energy(p, 1.0);
        if (a == 0) {
            gr_edmd_set_event_hook(s, NULL, NULL);
            assert_int_equal(gr_edmd_advance(s, INFINITY, 300000, &e), GR_OK);
            assert_int_equal(gr_edmd_snapshot(s, p, &e), GR_OK);
            ov = edmd_max_overlap(p, 0, 0);
            double e2 = edmd_energy(p, 1.0);
            printf("# gravity gas: 3.1e5 collisions, |dE|/E = %.3e, overlap %.3e\n", fabs(e2 - e0) / e0, ov);
            assert_true(fabs(e2 - e0) < 1e-10 * e0);
            for (size_t i = 0; i < p->n; i++)
                assert_true(p->y[i] >= 0.5 - 1e-9 && p->y[i] <= 40 - 0.5 + 1e-9);
        }
        gr_edmd_free(s);
        gr_particles_free(p);
    }
    long diff = -1;
    for (long k = 0; k < 10000 && diff < 0; k++)
        if (q[0].i[k] != q[1].i[k] || q[0].j[k] != q[1].j[k] || q[0].t[k] != q[1].t[k])
            diff = k;
    printf("# gravity: tree and naive first differ at event %ld (-1: never in 1e4)\n", diff);
    assert_int_equal(diff, -1);
    assert_true(ov < 1e-9);
    assert_true(fabs(e1[0] - e0) < 1e-11 * e0);
    for (int a = 0; a < 2; a++)
        free(q[a].i), free(q[a].j), free(q[a].t);
}

/* Vibrated bed: inelastic disks (alpha 0.9, elastic floor and walls) on a
 * vibrating floor. Exactly, E(t1) - E(t0) = injected - dissipated; in the
 * steady state the floor's input balances the collisional losses (1 %). */
static void vibrated_balance(gr_floor_motion motion, double A, double omega, long n, const char *name)
{
    gr_scene sc = edmd_box(20, 200, 0, 0.9);
    sc.gravity = 1.0;
    sc.mat.wall_restitution = 1.0;
    sc.floor.motion = motion;
    sc.floor.amplitude = A;
    sc.floor.omega = omega;
    gr_particles *p = edmd_lattice(n, 0, 2 * A + 0.1, 20, 10, 1.0, 0, 7);
    gr_edmd_params prm;
    gr_edmd_params_default(&prm);
    prm.collapse = GR_EDMD_COLLAPSE_TC;
    prm.tc = 1e-5;
    gr_edmd *s = make(&sc, p, &prm);
    gr_err e = {0};
    assert_int_equal(gr_edmd_advance(s, 200.0, 0, &e), GR_OK); /* transient */
    assert_int_equal(gr_edmd_snapshot(s, p, &e), GR_OK);
    double E0 = edmd_energy(p, 1.0), i0, d0, i1, d1;
    gr_edmd_energy_budget(s, &i0, &d0);
    gr_edmd_reset_averages(s);
    assert_int_equal(gr_edmd_advance(s, 3200.0, 0, &e), GR_OK);
    assert_int_equal(gr_edmd_snapshot(s, p, &e), GR_OK);
    double E1 = edmd_energy(p, 1.0);
    gr_edmd_energy_budget(s, &i1, &d1);
    gr_edmd_averages av;
    gr_edmd_get_averages(s, &av);
    double inj = i1 - i0, dis = d1 - d0;
    gr_edmd_counters c;
    gr_edmd_get_counters(s, &c);
    printf("# %s: injected %.6g, dissipated %.6g (rel. diff %.2e), E1-E0 = %.4g, identity error %.2e, "
           "%llu collisions, %llu floor, <K> = %.4g, <U> = %.4g, floor pressure %.4g (N g / W = %.4g)\n",
           name, inj, dis, fabs(inj - dis) / inj, E1 - E0, fabs((E1 - E0) - (inj - dis)) / inj,
           (unsigned long long)c.pair, (unsigned long long)c.floor, av.ekin, av.epot, av.pressure[GR_BOTTOM],
           n * 1.0 / 20);
    assert_true(fabs((E1 - E0) - (inj - dis)) < 1e-9 * inj);
    assert_true(fabs(inj - dis) < 0.01 * inj);
    assert_true(fabs(av.e_injected - inj) < 1e-9 * inj);
    /* the floor carries the weight of the bed on average */
    assert_true(fabs(av.pressure[GR_BOTTOM] - n / 20.0) < 0.02 * n / 20.0);
    gr_edmd_free(s);
    gr_particles_free(p);
}

static void vibrated_sine(void **st)
{
    (void)st;
    vibrated_balance(GR_FLOOR_SINE, 0.05, 40.0, 60, "sine floor A=0.05 omega=40");
}
static void vibrated_sawtooth(void **st)
{
    (void)st;
    vibrated_balance(GR_FLOOR_SAWTOOTH, 0.05, 60.0, 60, "sawtooth floor A=0.05 omega=60");
}
static void vibrated_sine_hf(void **st)
{
    (void)st;
    vibrated_balance(GR_FLOOR_SINE_HF, 1.0, 2.0, 60, "sine-hf floor V0=2");
}
static void vibrated_sawtooth_hf(void **st)
{
    (void)st;
    vibrated_balance(GR_FLOOR_SAWTOOTH_HF, 1.0, 1.5, 60, "sawtooth-hf floor V0=1.5");
}

/* The sinusoidal floor rule: a disk at rest on the floor's lowest point
 * with A omega^2 > g is thrown at the floor's velocity when met. */
static void sine_floor_kick(void **st)
{
    (void)st;
    gr_scene sc = edmd_box(4, 100, 0, 1.0);
    sc.gravity = 1.0;
    sc.mat.wall_restitution = 0.0; /* sticks to the floor: leaves with its velocity */
    sc.floor.motion = GR_FLOOR_SINE;
    sc.floor.amplitude = 1.0;
    sc.floor.omega = 2.0;
    gr_particles *p = edmd_lattice(1, 0, 0, 4, 4, 0.0, 0, 1);
    p->y[0] = 1.5 + 1e-12; /* just above the floor at its top (y_f(0) = A = 1) */
    gr_edmd *s = make_default(&sc, p);
    gr_err e = {0};
    /* the floor falls away faster than g: the disk free-falls and meets the
     * rising floor; check the collision point lies on the floor */
    assert_int_equal(gr_edmd_advance(s, INFINITY, 1, &e), GR_OK);
    double t = gr_edmd_time(s);
    assert_int_equal(gr_edmd_snapshot(s, p, &e), GR_OK);
    double yf = cos(2.0 * t);
    printf("# sine floor: first contact at t = %.12g, y - r = %.12g, floor %.12g, vy %.6g, floor v %.6g\n", t,
           p->y[0] - 0.5, yf, p->vy[0], -2.0 * sin(2.0 * t));
    assert_true(fabs(p->y[0] - 0.5 - yf) < 1e-9);
    assert_true(fabs(p->vy[0] - (-2.0 * sin(2.0 * t))) < 1e-9);
    /* first root: no earlier contact on a fine scan */
    for (double u = 0; u < t; u += 1e-4) {
        double y = 1.0 + 1e-12 - 0.5 * u * u;
        assert_true(y >= cos(2.0 * u) - 1e-12);
    }
    gr_edmd_free(s);
    gr_particles_free(p);
}

/* Two rough disks, one collision with an offset: the impulses obey the
 * sticking rule below the Coulomb bound and |Jt| = mu Jn above it. */
static void rough_single_collision(void **st)
{
    (void)st;
    double mus[2] = {10.0, 0.02};
    for (int k = 0; k < 2; k++) {
        gr_scene sc = edmd_box(20, 20, 0, 0.8);
        sc.mat.tangential_restitution = 0.5;
        sc.mat.mu = mus[k];
        gr_err e = {0};
        gr_particles *p = gr_particles_create(2, &e);
        gr_particles_push(p, 8.0, 10.0, 0.5, 1.0, 0, 0, &e);
        gr_particles_push(p, 12.0, 10.3, 0.5, 1.0, 0, 0, &e);
        p->vx[0] = 1.0;
        p->vx[1] = -1.0;
        p->omega[0] = 0.7;
        p->omega[1] = -0.2;
        gr_particles *q = gr_particles_create(2, &e);
        gr_particles_copy(q, p, &e);
        gr_edmd *s = make_default(&sc, p);
        assert_int_equal(gr_edmd_advance(s, INFINITY, 1, &e), GR_OK);
        assert_int_equal(gr_edmd_snapshot(s, q, &e), GR_OK);
        double nx = q->x[1] - q->x[0], ny = q->y[1] - q->y[0], d = hypot(nx, ny);
        nx /= d, ny /= d;
        double tx = -ny, ty = nx;
        /* impulse on disk 1 */
        double Jx = q->vx[1] - p->vx[1], Jy = q->vy[1] - p->vy[1];
        double Jn = Jx * nx + Jy * ny, Jt = Jx * tx + Jy * ty;
        double gn0 = (p->vx[1] - p->vx[0]) * nx + (p->vy[1] - p->vy[0]) * ny;
        double gn1 = (q->vx[1] - q->vx[0]) * nx + (q->vy[1] - q->vy[0]) * ny;
        double gt0 = (p->vx[1] - p->vx[0]) * tx + (p->vy[1] - p->vy[0]) * ty - 0.5 * (p->omega[0] + p->omega[1]);
        double gt1 = (q->vx[1] - q->vx[0]) * tx + (q->vy[1] - q->vy[0]) * ty - 0.5 * (q->omega[0] + q->omega[1]);
        /* momentum and angular momentum about the contact point */
        assert_true(fabs(q->vx[0] + q->vx[1] - p->vx[0] - p->vx[1]) < 1e-14);
        double dw1 = q->omega[1] - p->omega[1];
        assert_true(fabs(dw1 - (-0.5 * Jt / p->inertia[1])) < 1e-13);
        assert_true(fabs(gn1 + 0.8 * gn0) < 1e-13);
        printf("# mu = %g: Jn = %.6g, Jt = %.6g, |Jt|/Jn = %.6g, gt %.6g -> %.6g\n", mus[k], Jn, Jt, fabs(Jt) / Jn,
               gt0, gt1);
        assert_true(fabs(Jt) <= mus[k] * Jn * (1 + 1e-12));
        if (k == 0)
            assert_true(fabs(gt1 + 0.5 * gt0) < 1e-13); /* sticking: gt' = -beta gt */
        else
            assert_true(fabs(fabs(Jt) - mus[k] * Jn) < 1e-13); /* sliding at the bound */
        gr_edmd_free(s);
        gr_particles_free(p);
        gr_particles_free(q);
    }
}

/* Many rough disks: beta = -1 leaves every spin untouched (rotation
 * decouples), beta = 1 with no Coulomb bound conserves the total energy. */
static void rough_limits(void **st)
{
    (void)st;
    double betas[2] = {-1.0, 1.0};
    for (int k = 0; k < 2; k++) {
        long n = 300;
        double L = sqrt(n * M_PI / 4 / 0.3);
        gr_scene sc = edmd_box(L, L, 1, 1.0);
        sc.mat.tangential_restitution = betas[k];
        sc.mat.mu = INFINITY;
        gr_particles *p = edmd_lattice(n, 0, 0, L, L, 1.0, 1, 21);
        for (long i = 0; i < n; i++)
            p->omega[i] = 2.0 * sin(1.0 + i);
        gr_particles *q = gr_particles_create(n, NULL);
        gr_err e = {0};
        gr_particles_copy(q, p, &e);
        gr_edmd *s = make_default(&sc, p);
        double e0 = edmd_energy(p, 0);
        assert_int_equal(gr_edmd_advance(s, INFINITY, 200000, &e), GR_OK);
        assert_int_equal(gr_edmd_snapshot(s, q, &e), GR_OK);
        double dw = 0, erot = 0;
        for (long i = 0; i < n; i++) {
            dw = fmax(dw, fabs(q->omega[i] - p->omega[i]));
            erot += 0.5 * q->inertia[i] * q->omega[i] * q->omega[i];
        }
        double de = fabs(edmd_energy(q, 0) - e0) / e0;
        printf("# beta = %g: max |d omega| = %.3e, |dE|/E = %.3e, rotational share %.4f\n", betas[k], dw, de,
               erot / edmd_energy(q, 0));
        if (k == 0)
            assert_true(dw == 0.0);
        else
            assert_true(dw > 0.1);
        assert_true(de < 1e-10);
        gr_edmd_free(s);
        gr_particles_free(p);
        gr_particles_free(q);
    }
}

/* A dense, very inelastic pile under gravity on a fixed floor: without a
 * guard the run stops with a collapse diagnostic; with the TC model or the
 * threshold it settles and its event rate stays bounded and does not grow
 * (the resting grains keep rattling elastically at a small scale). */
static void collapse_guards(void **st)
{
    (void)st;
    gr_edmd_collapse modes[3] = {GR_EDMD_COLLAPSE_NONE, GR_EDMD_COLLAPSE_TC, GR_EDMD_COLLAPSE_THRESHOLD};
    for (int k = 0; k < 3; k++) {
        gr_scene sc = edmd_box(10.37, 30, 0, 0.5); /* not a whole number of diameters: no jammed row */
        sc.gravity = 1.0;
        long n = 100;
        gr_particles *p = edmd_lattice(n, 0.2, 0.2, 9.6, 14, 1.0, 0, 3);
        gr_edmd_params prm;
        gr_edmd_params_default(&prm);
        prm.collapse = modes[k];
        prm.tc = 1e-3;
        prm.v_threshold = 1e-2;
        gr_edmd *s = make(&sc, p, &prm);
        gr_err e = {0};
        uint64_t cnt[3];
        int rc = 0;
        for (int q = 0; q < 3 && !rc; q++) {
            rc = gr_edmd_advance(s, 10.0 + 2.0 * q, 0, &e);
            gr_edmd_counters c;
            gr_edmd_get_counters(s, &c);
            cnt[q] = c.pair + c.wall;
        }
        assert_int_equal(gr_edmd_snapshot(s, p, &e), GR_OK);
        double ek = edmd_energy(p, 0), ov = edmd_max_overlap(p, 0, 0);
        gr_edmd_counters c;
        gr_edmd_get_counters(s, &c);
        printf("# collapse guard %d: rc %d (%s) t = %.6g, %llu collisions (%llu made elastic), K = %.3e, "
               "overlap %.2e\n",
               k, rc, rc ? e.msg : "ok", gr_edmd_time(s), (unsigned long long)(c.pair + c.wall),
               (unsigned long long)c.elastic_guard, ek, ov);
        if (k == 0) {
            assert_int_equal(rc, GR_ERUN);
            assert_non_null(strstr(e.msg, "collapse"));
        } else {
            assert_int_equal(rc, GR_OK);
            double r1 = (cnt[1] - cnt[0]) / 2.0, r2 = (cnt[2] - cnt[1]) / 2.0;
            printf("#   collision rate %.4g then %.4g per unit time\n", r1, r2);
            assert_true(gr_edmd_time(s) == 14.0);
            assert_true(r2 < 4.0 * r1); /* no divergence: slow growth as the pile compacts */
            assert_true(r2 < 1e4 * n);
            assert_true(ek < 0.01 * n); /* settled */
            assert_true(ov < 1e-6);
        }
        gr_edmd_free(s);
        gr_particles_free(p);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(single_bounce),
        cmocka_unit_test(gravity_gas),
        cmocka_unit_test(sine_floor_kick),
        cmocka_unit_test(vibrated_sine),
        cmocka_unit_test(vibrated_sawtooth),
        cmocka_unit_test(vibrated_sine_hf),
        cmocka_unit_test(vibrated_sawtooth_hf),
        cmocka_unit_test(rough_single_collision),
        cmocka_unit_test(rough_limits),
        cmocka_unit_test(collapse_guards),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
