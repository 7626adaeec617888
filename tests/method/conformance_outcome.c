/* What a run shows (the snapshot, a lattice's fields, the contact network,
 * the observables, the counters): taken, compared bit for bit between two
 * runs, and checked for what the contract promises of it. */
#include "test.h"

#include <stdlib.h>
#include <string.h>

#include "conformance.h"

conf_outcome conf_look(gr_sim *s)
{
    gr_err e = {0};
    conf_outcome r;
    memset(&r, 0, sizeof r);
    gr_obs_clear(&r.o);
    assert_int_equal(gr_sim_observe(s, &r.o, &e), GR_OK);
    r.nc = gr_sim_counters(s, r.c, GR_MAX_COUNTERS);
    if (gr_sim_type(s)->snapshot) {
        r.p = gr_particles_create(0, &e);
        assert_int_equal(gr_sim_snapshot(s, r.p, &e), GR_OK);
    }
    if (gr_sim_type(s)->repr == GR_REPR_LATTICE) {
        const gr_scene *sc = gr_sim_scene(s);
        r.f = gr_field_create(40, 40, 0, 0, sc->width / 40, sc->height / 40, &e);
        assert_non_null(r.f);
        assert_int_equal(gr_sim_fields(s, r.f, 1.0, &e), GR_OK);
    }
    if (gr_sim_type(s)->contacts) {
        r.net = gr_contacts_create(0, &e);
        assert_int_equal(gr_sim_contacts(s, r.net, &e), GR_OK);
    }
    return r;
}

void conf_same(const conf_outcome *a, const conf_outcome *b)
{
    assert_memory_equal(&a->o, &b->o, sizeof a->o);
    assert_int_equal(a->nc, b->nc);
    for (size_t k = 0; k < a->nc; k++)
        assert_true(a->c[k].value == b->c[k].value);
    if (a->net) {
        size_t m = a->net->n;
        assert_int_equal(m, b->net->n);
        assert_memory_equal(a->net->i, b->net->i, m * sizeof(int64_t));
        assert_memory_equal(a->net->j, b->net->j, m * sizeof(int64_t));
        assert_memory_equal(a->net->fn, b->net->fn, m * sizeof(double));
        assert_memory_equal(a->net->ft, b->net->ft, m * sizeof(double));
    }
    if (a->f) {
        size_t nc = gr_field_ncells(a->f);
        assert_memory_equal(a->f->num, b->f->num, nc * sizeof(double));
        assert_memory_equal(a->f->px, b->f->px, nc * sizeof(double));
        assert_memory_equal(a->f->py, b->f->py, nc * sizeof(double));
        assert_memory_equal(a->f->mv2, b->f->mv2, nc * sizeof(double));
    }
    if (!a->p)
        return;
    size_t n = a->p->n;
    assert_int_equal(n, b->p->n);
    assert_memory_equal(a->p->x, b->p->x, n * sizeof(double));
    assert_memory_equal(a->p->y, b->p->y, n * sizeof(double));
    assert_memory_equal(a->p->vx, b->p->vx, n * sizeof(double));
    assert_memory_equal(a->p->vy, b->p->vy, n * sizeof(double));
    assert_memory_equal(a->p->omega, b->p->omega, n * sizeof(double));
    assert_memory_equal(a->p->flags, b->p->flags, n * sizeof(uint32_t));
    assert_memory_equal(a->p->id, b->p->id, n * sizeof(int64_t));
}

void conf_outcome_free(conf_outcome *r)
{
    gr_particles_free(r->p);
    gr_field_free(r->f);
    gr_contacts_free(r->net);
}

void conf_check_outcome(const gr_method_type *m, const conf_scene *cs, const conf_outcome *r)
{
    assert_true(isfinite(r->o.ekin_trans) && isfinite(r->o.ekin_rot) && isfinite(r->o.temperature));
    assert_true(isfinite(r->o.px) && isfinite(r->o.py) && isfinite(r->o.epot_grav));
    assert_true(r->o.n_mobile <= (uint64_t)cs->grains);
    for (size_t k = 0; k < r->nc; k++) {
        assert_non_null(r->c[k].name);
        for (size_t j = 0; j < k; j++)
            assert_string_not_equal(r->c[k].name, r->c[j].name);
    }
    if (!r->p)
        return;
    /* a network names grains of the snapshot (or walls, j < 0), finite forces */
    for (size_t k = 0; r->net && k < r->net->n; k++) {
        int found_i = 0, found_j = r->net->j[k] < 0;
        for (size_t q = 0; q < r->p->n; q++) {
            found_i |= r->p->id[q] == r->net->i[k];
            found_j |= r->p->id[q] == r->net->j[k];
        }
        assert_true(found_i && found_j && r->net->i[k] != r->net->j[k]);
        assert_true(isfinite(r->net->fn[k]) && isfinite(r->net->ft[k]));
    }
    for (size_t i = 1; i < r->p->n; i++)
        assert_true(r->p->id[i] > r->p->id[i - 1]);
    for (size_t i = 0; i < r->p->n; i++)
        assert_true(isfinite(r->p->x[i]) && isfinite(r->p->y[i]) && isfinite(r->p->vx[i]) &&
                    isfinite(r->p->vy[i]) && isfinite(r->p->omega[i]));
    (void)m;
}

/* The packing field over the whole domain holds the area of every mobile
 * grain inside it, and every field value is finite where defined. */
void conf_check_fields(gr_sim *s, const gr_scene *sc)
{
    gr_err e = {0};
    gr_field *f = gr_field_create(7, 5, 0, 0, sc->width / 7, sc->height / 5, &e);
    assert_non_null(f);
    assert_int_equal(gr_sim_fields(s, f, 1.0, &e), GR_OK);
    size_t nc = gr_field_ncells(f);
    double *phi = malloc(nc * sizeof *phi), *T = malloc(nc * sizeof *T), area = 0;
    gr_field_packing(f, phi);
    gr_field_temperature(f, T);
    for (size_t c = 0; c < nc; c++) {
        assert_true(isfinite(phi[c]) && phi[c] >= 0 && phi[c] <= 1);
        assert_true(isnan(T[c]) || (isfinite(T[c]) && T[c] >= 0));
        area += phi[c] * f->cx * f->cy;
    }
    if (gr_sim_type(s)->repr == GR_REPR_LATTICE) {
        /* every particle counts once, in the cell of its node */
        double *num = malloc(nc * sizeof *num), total = 0;
        gr_field_number(f, num, NULL);
        for (size_t c = 0; c < nc; c++)
            total += num[c];
        gr_obs o;
        assert_int_equal(gr_sim_observe(s, &o, &e), GR_OK);
        assert_rel(total, (double)o.n_mobile, 1e-12);
        free(num), free(phi), free(T);
        gr_field_free(f);
        return;
    }
    gr_particles *p = gr_particles_create(0, &e);
    assert_int_equal(gr_sim_snapshot(s, p, &e), GR_OK);
    double want = 0;
    for (size_t i = 0; i < p->n; i++)
        if (!(p->flags[i] & (GR_PF_FIXED | GR_PF_GONE)))
            want += gr_disk_rect_area(p->x[i], p->y[i], p->radius[i], 0, sc->width, 0, sc->height);
    assert_rel(area, want, 1e-9);
    gr_particles_free(p);
    free(phi), free(T);
    gr_field_free(f);
}

