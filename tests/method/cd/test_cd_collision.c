/* Validation 4: two-disk and disk-wall collisions without gravity, unit
 * mass and diameter. After the step whose contact carries an impulse:
 * the normal relative velocity is -e times the one before (e = 0, 0.5, 1,
 * relative 1e-12); with mu large the contact point's tangential velocity
 * vanishes (stick, |u_t| <= 1e-12), with mu small |r_t| = mu r_n (slide,
 * relative 1e-12); the kinetic energy never increases. */
#include "cd_test.h"

typedef struct {
    double un, ut, ek;
} kin;

/* Relative normal and tangential velocity of the contact point of grain 0
 * with grain 1 (or the floor) along the contact's normal (from 1 to 0),
 * and the kinetic energy. */
static kin measure(const gr_particles *q, int wall, double nx, double ny)
{
    kin k = {0, 0, 0};
    for (size_t i = 0; i < q->n; i++)
        k.ek += 0.5 * q->mass[i] * (q->vx[i] * q->vx[i] + q->vy[i] * q->vy[i]) +
                0.5 * q->inertia[i] * q->omega[i] * q->omega[i];
    double dvx = q->vx[0] - (wall ? 0 : q->vx[1]), dvy = q->vy[0] - (wall ? 0 : q->vy[1]);
    double spin = q->omega[0] * q->radius[0] + (wall ? 0 : q->omega[1] * q->radius[1]);
    k.un = dvx * nx + dvy * ny;
    k.ut = -dvx * ny + dvy * nx - spin;
    return k;
}

static void collide(int wall, double e, double mu, double vt)
{
    char text[512];
    snprintf(text, sizeof text,
             "[domain]\nwidth = 40\nheight = 40\ngravity = 0\n"
             "[material]\nrestitution = %g\ntangential = coulomb\nmu = %g\n[species]\ncount = 1\n"
             "[cd]\ndt = 1e-3\ntol = 1e-12\n", e, mu);
    gr_scene *sc = ct_scene(text);
    gr_err err = {0};
    gr_particles *p = gr_particles_create(2, &err);
    if (wall) {
        gr_particles_push(p, 20, 0.5 + 0.0123, 0.5, 1.0, 0, 0, &err);
        p->vx[0] = vt, p->vy[0] = -1;
    } else {
        gr_particles_push(p, 19.5 - 0.0123, 20, 0.5, 1.0, 0, 0, &err);
        gr_particles_push(p, 20.5, 20, 0.5, 1.0, 0, 0, &err);
        p->vx[0] = 1, p->vy[0] = vt;
        p->omega[1] = 0.3;
    }
    gr_sim *s = ct_sim(sc, p);
    gr_particles *q = gr_particles_create(2, &err);
    assert_int_equal(gr_sim_snapshot(s, q, &err), GR_OK);
    double ek0 = measure(q, wall, 0, 1).ek;
    const gr_cd_contact *c = NULL;
    for (int k = 0; k < 100 && !c; k++) {
        ct_steps(s, 1);
        c = ct_contact(ct_state(s), 0, wall ? 1 + 2 : 1); /* the floor is wall 2 */
        c = c && c->rn > 0 ? c : NULL;
        assert_int_equal(gr_sim_snapshot(s, q, &err), GR_OK);
        assert_true(measure(q, wall, 0, 1).ek <= ek0 * (1 + 1e-12));
    }
    assert_non_null(c);
    /* no impulse before this step: the velocities before it are the first */
    kin before = measure(p, wall, c->nx, c->ny), after = measure(q, wall, c->nx, c->ny);
    int stick = c->status == GR_CD_STICK;
    printf("# %s e %.1f mu %.2f: u_n %+.6f -> %+.12f, u_t %+.4f -> %+.3e, %s (|r_t|/mu r_n %.12f), "
           "energy %.6f -> %.6f\n",
           wall ? "disk-wall" : "disk-disk", e, mu, before.un, after.un, before.ut, after.ut,
           stick ? "stick" : "slide", fabs(c->rt) / (mu * c->rn), before.ek, after.ek);
    assert_close(after.un, -e * before.un, 1e-12);
    if (stick)
        assert_close(after.ut, 0.0, 1e-12);
    else
        assert_rel(fabs(c->rt), mu * c->rn, 1e-12);
    assert_int_equal(stick, mu > 0.5);
    ct_steps(s, 5); /* they part: no further impulse, energy kept */
    assert_int_equal(gr_sim_snapshot(s, q, &err), GR_OK);
    assert_true(measure(q, wall, 0, 1).ek <= after.ek * (1 + 1e-12));
    gr_particles_free(p), gr_particles_free(q);
    gr_sim_free(s);
    gr_scene_free(sc);
}

static void collisions(void **unused)
{
    (void)unused;
    static const double es[] = {0, 0.5, 1};
    for (int w = 0; w < 2; w++) {
        for (int k = 0; k < 3; k++) {
            collide(w, es[k], 2.0, 0.4);  /* stick: mu r_n exceeds what stopping u_t takes */
            collide(w, es[k], 0.05, 0.4); /* slide */
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(collisions)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
