/* The efficient scheme against exact properties: energy and momentum
 * conservation, contact distances, no overlaps, and the same collision
 * sequence as the slides' naive algorithm v1.0. */
#include "test.h"

#include <stdlib.h>

#include "edmd_int.h"
#include "edmd_test.h"

typedef struct {
    gr_edmd *s;
    double worst_contact; /* | |r_ij| - sigma | at collisions, in diameters */
} contact_check;

static void check_contact(void *user, int kind, long i, long j, double t)
{
    (void)t;
    contact_check *c = user;
    if (kind != 0)
        return;
    const edmd_p *a = &c->s->p[i], *b = &c->s->p[j];
    double dx = edmd_min_image(b->x - a->x, c->s->periodic_x ? c->s->W : 0);
    double dy = edmd_min_image(b->y - a->y, c->s->periodic_y ? c->s->H : 0);
    double e = fabs(sqrt(dx * dx + dy * dy) - (a->r + b->r));
    if (e > c->worst_contact)
        c->worst_contact = e;
}

/* arity 0: the calendar queue instead of the tree */
static gr_edmd *make_arity(const gr_scene *sc, const gr_particles *p, gr_edmd_algorithm alg, int arity)
{
    gr_err e = {0};
    gr_edmd_params prm;
    gr_edmd_params_default(&prm);
    prm.algorithm = alg;
    prm.tree_arity = arity ? arity : 2;
    prm.calendar = arity == 0;
    gr_edmd *s = NULL;
    int rc = gr_edmd_create(sc, p, &prm, NULL, &s, &e);
    if (rc)
        fprintf(stderr, "create: %s\n", e.msg);
    assert_int_equal(rc, GR_OK);
    return s;
}

static gr_edmd *make(const gr_scene *sc, const gr_particles *p, gr_edmd_algorithm alg)
{
    return make_arity(sc, p, alg, 2);
}

/* 500 elastic disks at packing fraction 0.3 in a walled box, 1e6 collisions. */
static void elastic_energy_contacts_overlaps(void **st)
{
    (void)st;
    long n = 500;
    double L = sqrt(n * M_PI / 4 / 0.3);
    gr_scene sc = edmd_box(L, L, 0, 1.0);
    gr_particles *p = edmd_lattice(n, 0, 0, L, L, 1.0, 0, 11);
    gr_edmd *s = make(&sc, p, GR_EDMD_TREE);
    contact_check cc = {s, 0};
    gr_edmd_set_event_hook(s, check_contact, &cc);
    double e0 = edmd_energy(p, 0);
    gr_err e = {0};
    double worst_ov = 0, worst_de = 0;
    for (int k = 0; k < 20; k++) {
        assert_int_equal(gr_edmd_advance(s, INFINITY, 50000, &e), GR_OK);
        assert_int_equal(gr_edmd_snapshot(s, p, &e), GR_OK);
        double ov = edmd_max_overlap(p, 0, 0), de = fabs(edmd_energy(p, 0) - e0) / e0;
        worst_ov = ov > worst_ov ? ov : worst_ov;
        worst_de = de > worst_de ? de : worst_de;
    }
    gr_edmd_counters c;
    gr_edmd_get_counters(s, &c);
    printf("# 1e6 collisions (%llu pair, %llu wall, %llu crossings, %llu stale) to t = %g: "
           "max |dE|/E = %.3e, max overlap = %.3e, max contact error = %.3e\n",
           (unsigned long long)c.pair, (unsigned long long)c.wall, (unsigned long long)c.crossing,
           (unsigned long long)c.stale, gr_edmd_time(s), worst_de, worst_ov, cc.worst_contact);
    assert_true(c.pair + c.wall == 1000000);
    assert_true(worst_de < 1e-10);
    assert_true(worst_ov < 1e-9);
    assert_true(cc.worst_contact < 1e-9);
    gr_edmd_free(s);
    gr_particles_free(p);
}

/* Periodic box at packing fraction 0.4: total momentum stays zero. */
static void periodic_momentum(void **st)
{
    (void)st;
    long n = 400;
    double L = sqrt(n * M_PI / 4 / 0.4);
    gr_scene sc = edmd_box(L, L, 1, 1.0);
    gr_particles *p = edmd_lattice(n, 0, 0, L, L, 1.0, 1, 12);
    gr_edmd *s = make(&sc, p, GR_EDMD_TREE);
    contact_check cc = {s, 0};
    gr_edmd_set_event_hook(s, check_contact, &cc);
    double e0 = edmd_energy(p, 0);
    gr_err e = {0};
    assert_int_equal(gr_edmd_advance(s, INFINITY, 300000, &e), GR_OK);
    assert_int_equal(gr_edmd_snapshot(s, p, &e), GR_OK);
    double px = 0, py = 0;
    for (size_t i = 0; i < p->n; i++) {
        px += p->vx[i];
        py += p->vy[i];
    }
    double de = fabs(edmd_energy(p, 0) - e0) / e0, ov = edmd_max_overlap(p, L, L);
    printf("# periodic, 3e5 collisions: |P| = %.3e (N V0 = %ld), |dE|/E = %.3e, overlap %.3e, contact %.3e\n",
           hypot(px, py), n, de, ov, cc.worst_contact);
    assert_true(hypot(px, py) < 1e-10 * n);
    assert_true(de < 1e-10);
    assert_true(ov < 1e-9);
    assert_true(cc.worst_contact < 1e-9);
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
    sequence *q = user;
    if (q->n == q->cap)
        return;
    q->i[q->n] = kind == 0 ? i : i;
    q->j[q->n] = j;
    q->t[q->n] = t;
    q->n++;
}

static sequence run_sequence(gr_edmd_algorithm alg, long events, double alpha, int arity)
{
    long n = 100;
    double L = 20.0;
    gr_scene sc = edmd_box(L, L, 0, alpha);
    gr_particles *p = edmd_lattice(n, 0, 0, L, L, 1.0, 0, 13);
    gr_edmd *s = make_arity(&sc, p, alg, arity);
    sequence q = {0, events, malloc(events * sizeof(long)), malloc(events * sizeof(long)),
                  malloc(events * sizeof(double))};
    gr_edmd_set_event_hook(s, record, &q);
    gr_err e = {0};
    assert_int_equal(gr_edmd_advance(s, INFINITY, (uint64_t)events, &e), GR_OK);
    gr_edmd_free(s);
    gr_particles_free(p);
    return q;
}

/* 100 disks, 1e4 collisions (walls included): the tree (binary, and with
 * every other level elided), the calendar queue and the naive algorithm
 * execute the same events at the same times. */
static void same_sequence_as_naive(void **st)
{
    (void)st;
    double alphas[5] = {1.0, 0.95, 1.0, 1.0, 0.95};
    int arity[5] = {2, 2, 4, 0, 0};
    for (int a = 0; a < 5; a++) {
        long N = 10000;
        sequence A = run_sequence(GR_EDMD_TREE, N, alphas[a], arity[a]),
                 B = run_sequence(GR_EDMD_NAIVE, N, alphas[a], 2);
        assert_int_equal(A.n, N);
        assert_int_equal(B.n, N);
        long first_diff = -1;
        double worst_dt = 0;
        for (long k = 0; k < N; k++) {
            if (A.i[k] != B.i[k] || A.j[k] != B.j[k]) {
                first_diff = k;
                break;
            }
            double dt = fabs(A.t[k] - B.t[k]);
            worst_dt = dt > worst_dt ? dt : worst_dt;
        }
        printf("# alpha = %g, tree arity %d (0: calendar): %ld events, first difference at %ld, max |dt| = %.3e\n", alphas[a],
               arity[a], N, first_diff, worst_dt);
        assert_int_equal(first_diff, -1);
        assert_true(worst_dt <= 1e-12 * A.t[N - 1]);
        free(A.i), free(A.j), free(A.t), free(B.i), free(B.j), free(B.t);
    }
}

/* Spatial re-sorting renumbers the grains and rebuilds every list: the
 * collisions (by id) and their times are unchanged, to the bit, in a walled
 * box. (On periodic sides a grain's reference position is shifted by the
 * period when it wraps; a pair predicted again after a wrap can differ in
 * the last bit, so there the runs agree only statistically.) */
static void resort_keeps_sequence(void **st)
{
    (void)st;
    long n = 400, N = 20000;
    double L = sqrt(n * M_PI / 4 / 0.4);
    gr_scene sc = edmd_box(L, L, 0, 1.0);
    sequence q[2];
    for (int k = 0; k < 2; k++) {
        gr_particles *p = edmd_lattice(n, 0, 0, L, L, 1.0, 1, 15);
        gr_edmd_params prm;
        gr_edmd_params_default(&prm);
        prm.sort_every = k ? 1.0 : 0.0;
        gr_err e = {0};
        gr_edmd *s = NULL;
        assert_int_equal(gr_edmd_create(&sc, p, &prm, NULL, &s, &e), GR_OK);
        q[k] = (sequence){0, N, malloc(N * sizeof(long)), malloc(N * sizeof(long)), malloc(N * sizeof(double))};
        gr_edmd_set_event_hook(s, record, &q[k]);
        assert_int_equal(gr_edmd_advance(s, INFINITY, (uint64_t)N, &e), GR_OK);
        gr_edmd_free(s);
        gr_particles_free(p);
    }
    long diff = -1;
    for (long k = 0; k < N && diff < 0; k++)
        if (q[0].i[k] != q[1].i[k] || q[0].j[k] != q[1].j[k] || q[0].t[k] != q[1].t[k])
            diff = k;
    printf("# re-sorting every collision per grain: first difference at %ld of %ld\n", diff, N);
    for (long k = diff - 2; diff >= 0 && k < diff + 3 && k < N; k++)
        printf("#   %ld: %ld %ld %.17g | %ld %ld %.17g\n", k, q[0].i[k], q[0].j[k], q[0].t[k], q[1].i[k], q[1].j[k],
               q[1].t[k]);
    assert_int_equal(diff, -1);
    for (int k = 0; k < 2; k++)
        free(q[k].i), free(q[k].j), free(q[k].t);
}

/* The calendar queue against the tree on larger systems, where buckets,
 * spill lines, the overflow and re-sorting all come into play: the same
 * events (grains and times to the bit). Cases: an elastic periodic gas
 * re-sorted every collision per grain; a cooling gas (alpha 0.8, so the
 * event rate falls a hundredfold and the buckets become sparse); grains
 * under gravity in a walled box (long free flights in the overflow); and
 * 33 000 grains in a walled box re-sorted every half collision per grain,
 * large enough for the look-ahead prefetching (checked by the sanitizer
 * build). */
static void calendar_same_as_tree(void **st)
{
    (void)st;
    struct {
        long n, events;
        double eta, alpha, g;
        int periodic;
        double sort_every;
    } cs[4] = {{3000, 60000, 0.5, 1.0, 0.0, 1, 1.0}, {2000, 60000, 0.2, 0.8, 0.0, 1, 0.0},
               {1000, 40000, 0.2, 0.97, 1.0, 0, 0.0}, {33000, 60000, 0.4, 1.0, 0.0, 0, 0.5}};
    for (int c = 0; c < 4; c++) {
        double L = sqrt(cs[c].n * M_PI / 4 / cs[c].eta);
        gr_scene sc = edmd_box(L, L, cs[c].periodic, cs[c].alpha);
        sc.gravity = cs[c].g;
        sequence q[2];
        for (int k = 0; k < 2; k++) {
            gr_particles *p = edmd_lattice(cs[c].n, 0, 0, L, L, 1.0, 1, 21 + c);
            gr_edmd_params prm;
            gr_edmd_params_default(&prm);
            prm.sort_every = cs[c].sort_every;
            prm.calendar = k;
            gr_err e = {0};
            gr_edmd *s = NULL;
            assert_int_equal(gr_edmd_create(&sc, p, &prm, NULL, &s, &e), GR_OK);
            long N = cs[c].events;
            q[k] = (sequence){0, N, malloc(N * sizeof(long)), malloc(N * sizeof(long)), malloc(N * sizeof(double))};
            gr_edmd_set_event_hook(s, record, &q[k]);
            assert_int_equal(gr_edmd_advance(s, INFINITY, (uint64_t)N, &e), GR_OK);
            gr_edmd_free(s);
            gr_particles_free(p);
        }
        assert_int_equal(q[0].n, cs[c].events);
        assert_int_equal(q[1].n, cs[c].events);
        long diff = -1;
        for (long k = 0; k < cs[c].events && diff < 0; k++)
            if (q[0].i[k] != q[1].i[k] || q[0].j[k] != q[1].j[k] || q[0].t[k] != q[1].t[k])
                diff = k;
        printf("# calendar vs tree, N = %ld, eta %g, alpha %g, g %g: %ld events to t = %.6g, first difference at "
               "%ld\n",
               cs[c].n, cs[c].eta, cs[c].alpha, cs[c].g, cs[c].events, q[0].t[cs[c].events - 1], diff);
        assert_int_equal(diff, -1);
        for (int k = 0; k < 2; k++)
            free(q[k].i), free(q[k].j), free(q[k].t);
    }
}

/* Inelastic disks: the kinetic energy lost equals the sum of the losses
 * at the collisions, (1 - alpha^2) m_12 v_n^2 / 2 each. */
static void inelastic_bookkeeping(void **st)
{
    (void)st;
    long n = 400;
    double L = sqrt(n * M_PI / 4 / 0.1);
    gr_scene sc = edmd_box(L, L, 1, 0.9);
    gr_particles *p = edmd_lattice(n, 0, 0, L, L, 1.0, 1, 14);
    gr_edmd *s = make(&sc, p, GR_EDMD_TREE);
    double e0 = edmd_energy(p, 0);
    gr_err e = {0};
    assert_int_equal(gr_edmd_advance(s, INFINITY, 20000, &e), GR_OK);
    assert_int_equal(gr_edmd_snapshot(s, p, &e), GR_OK);
    double inj, diss, e1 = edmd_energy(p, 0);
    gr_edmd_energy_budget(s, &inj, &diss);
    printf("# alpha 0.9: E %g -> %g, dissipated %g, mismatch %.3e\n", e0, e1, diss, fabs(e0 - diss - e1) / e0);
    assert_true(e1 < 0.5 * e0);
    assert_true(fabs(e0 - diss - e1) < 1e-10 * e0);
    gr_edmd_free(s);
    gr_particles_free(p);
}

/* A binary mixture (diameters 1 and 1.4, masses 1 and 3) and a
 * polydisperse gas: conservation, no overlap, and the naive algorithm's
 * sequence of events. */
static void mixtures(void **st)
{
    (void)st;
    for (int k = 0; k < 2; k++) {
        long n = 120;
        double L = 24;
        gr_scene sc = edmd_box(L, L, 0, 1.0);
        gr_particles *p = edmd_lattice(n, 0, 0, L, L, 1.0, 0, 16 + k);
        for (long i = 0; i < n; i++) {
            double d = k == 0 ? (i % 3 == 0 ? 1.4 : 1.0) : 0.8 + 0.6 * fmod(0.618 * i, 1.0);
            p->radius[i] = 0.5 * d;
            p->mass[i] = k == 0 ? (i % 3 == 0 ? 3.0 : 1.0) : d * d;
            p->inertia[i] = 0.5 * p->mass[i] * p->radius[i] * p->radius[i];
            p->species[i] = k == 0 ? (i % 3 == 0) : 0;
        }
        double e0 = edmd_energy(p, 0);
        sequence q[2];
        for (int a = 0; a < 2; a++) {
            gr_edmd *s = make(&sc, p, a ? GR_EDMD_NAIVE : GR_EDMD_TREE);
            q[a] = (sequence){0, 5000, malloc(5000 * sizeof(long)), malloc(5000 * sizeof(long)),
                              malloc(5000 * sizeof(double))};
            gr_edmd_set_event_hook(s, record, &q[a]);
            gr_err e = {0};
            assert_int_equal(gr_edmd_advance(s, INFINITY, 5000, &e), GR_OK);
            if (a == 0) {
                gr_edmd_set_event_hook(s, NULL, NULL);
                assert_int_equal(gr_edmd_advance(s, INFINITY, 200000, &e), GR_OK);
                gr_particles *r = gr_particles_create(0, &e);
                assert_int_equal(gr_edmd_snapshot(s, r, &e), GR_OK);
                double de = fabs(edmd_energy(r, 0) - e0) / e0, ov = edmd_max_overlap(r, 0, 0);
                printf("# %s: 2e5 collisions, |dE|/E = %.2e, overlap %.2e\n", k ? "polydisperse" : "binary mixture",
                       de, ov);
                assert_true(de < 1e-10);
                assert_true(ov < 1e-9);
                gr_particles_free(r);
            }
            gr_edmd_free(s);
        }
        long diff = -1;
        for (long c = 0; c < 5000 && diff < 0; c++)
            if (q[0].i[c] != q[1].i[c] || q[0].j[c] != q[1].j[c] || q[0].t[c] != q[1].t[c])
                diff = c;
        assert_int_equal(diff, -1);
        for (int a = 0; a < 2; a++)
            free(q[a].i), free(q[a].j), free(q[a].t);
        gr_particles_free(p);
    }
}

static void refuses_bad_starts(void **st)
{
    (void)st;
    gr_scene sc = edmd_box(10, 10, 0, 1.0);
    gr_particles *p = edmd_lattice(4, 0, 0, 10, 10, 1.0, 0, 1);
    p->x[1] = p->x[0] + 0.5;
    p->y[1] = p->y[0];
    gr_edmd_params prm;
    gr_edmd_params_default(&prm);
    gr_edmd *s = NULL;
    gr_err e = {0};
    assert_int_equal(gr_edmd_create(&sc, p, &prm, NULL, &s, &e), GR_EINPUT);
    assert_non_null(strstr(e.msg, "overlap"));
    gr_particles_free(p);
    p = edmd_lattice(4, 0, 0, 10, 10, 1.0, 0, 1);
    prm.cell = 0.5;
    assert_int_equal(gr_edmd_create(&sc, p, &prm, NULL, &s, &e), GR_EINPUT);
    assert_non_null(strstr(e.msg, "cell"));
    gr_scene pc = edmd_box(3.5, 10, 1, 1.0);
    prm.cell = 0;
    gr_particles_free(p);
    p = edmd_lattice(4, 0, 0, 3.5, 10, 1.0, 0, 1);
    assert_int_equal(gr_edmd_create(&pc, p, &prm, NULL, &s, &e), GR_EINPUT);
    assert_non_null(strstr(e.msg, "periodic"));
    gr_particles_free(p);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(elastic_energy_contacts_overlaps),
        cmocka_unit_test(periodic_momentum),
        cmocka_unit_test(same_sequence_as_naive),
        cmocka_unit_test(resort_keeps_sequence),
        cmocka_unit_test(calendar_same_as_tree),
        cmocka_unit_test(inelastic_bookkeeping),
        cmocka_unit_test(mixtures),
        cmocka_unit_test(refuses_bad_starts),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
