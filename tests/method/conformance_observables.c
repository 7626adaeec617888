/* The conformance battery's cases on declared observables (methods/method.h,
 * common/observe.h): a backend's observables hold to their contract, on
 * each scene of the battery it takes:
 *   the table: unique HDF5-safe names, units and meanings, at most
 *   GR_OBS_MAX, counts as integers, a validity limit's key naming a real
 *   key of the method's own section;
 *   every counter the method gives is declared, and the sample carries its
 *   value where the declaration says;
 *   after a window, every declared quantity the scene has is finite (no NaN
 *   stand-in) and observing twice gives the same bits. */
#include "test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "conformance.h"
#include "init.h"

static void check_table(const gr_method_type *m)
{
    const gr_obs_def *d = gr_method_observables(m);
    size_t n = gr_obs_count(d);
    if (n < 1 || n > GR_OBS_MAX)
        fail_msg("%s: %zu observables, 1 to %d allowed", m->name, n, GR_OBS_MAX);
    for (size_t k = 0; k < n; k++) {
        if (!d[k].name[0] || strchr(d[k].name, '/') || strchr(d[k].name, ' '))
            fail_msg("%s: observable %zu has the name '%s'", m->name, k, d[k].name);
        for (size_t j = 0; j < k; j++)
            if (!strcmp(d[j].name, d[k].name))
                fail_msg("%s: observable '%s' declared twice", m->name, d[k].name);
        if (!d[k].unit || !d[k].unit[0] || !d[k].doc || !d[k].doc[0] || (d[k].ncomp != 1 && d[k].ncomp != 2))
            fail_msg("%s: observable '%s' lacks a unit, a meaning or a shape", m->name, d[k].name);
        int uint_field = d[k].src == GR_OBS_FIELD &&
                         (d[k].off == offsetof(gr_obs, n_mobile) || d[k].off == offsetof(gr_obs, outflow));
        if (d[k].integer != (d[k].src == GR_OBS_COUNTER || uint_field))
            fail_msg("%s: observable '%s' is stored as the wrong type", m->name, d[k].name);
        if (!d[k].key)
            continue;
        const char *dot = strchr(d[k].key, '.');
        int found = d[k].src == GR_OBS_COUNTER && dot && (size_t)(dot - d[k].key) == strlen(m->name) &&
                    !strncmp(d[k].key, m->name, strlen(m->name)) && gr_param_index(m->params, dot + 1) >= 0;
        if (!found)
            fail_msg("%s: limit '%s' names the key '%s', not a counter's key of [%s]", m->name, d[k].name,
                     d[k].key, m->name);
    }
}

static void check_sample(const conf_case *cc, gr_scene *sc)
{
    const gr_method_type *m = cc->m;
    const conf_scene *cs = cc->cs;
    gr_sim *s = conf_create(m, sc);
    gr_err e = {0};
    assert_int_equal(gr_sim_advance(s, 0.2 * cs->t_end, 0, &e), GR_OK);
    gr_sim_reset_window(s);
    assert_int_equal(gr_sim_advance(s, 0.4 * cs->t_end, 0, &e), GR_OK);
    gr_obs a, b;
    gr_obs_clear(&a), gr_obs_clear(&b);
    assert_int_equal(gr_sim_observe(s, &a, &e), GR_OK);
    assert_int_equal(gr_sim_observe(s, &b, &e), GR_OK);
    if (memcmp(&a, &b, sizeof a))
        fail_msg("%s on %s: observing twice differs", m->name, cs->name);
    const gr_obs_def *d = gr_sim_observables(s);
    uint64_t skip = gr_sim_obs_skip(s);
    gr_counter c[GR_MAX_COUNTERS];
    size_t nc = gr_sim_counters(s, c, GR_MAX_COUNTERS);
    for (size_t j = 0; j < nc; j++) {
        size_t k = 0;
        while (d[k].name && strcmp(d[k].name, c[j].name))
            k++;
        if (!d[k].name)
            fail_msg("%s: counter '%s' is not declared as an observable", m->name, c[j].name);
        if (d[k].src == GR_OBS_COUNTER && a.count[k] != c[j].value)
            fail_msg("%s: observable '%s' is %llu, its counter %llu", m->name, c[j].name,
                     (unsigned long long)a.count[k], (unsigned long long)c[j].value);
    }
    for (size_t k = 0; d[k].name; k++) {
        if ((skip >> k & 1) || d[k].integer)
            continue;
        const double *v = gr_obs_value(&a, d, k);
        for (int q = 0; q < d[k].ncomp; q++)
            if (!isfinite(v[q]))
                fail_msg("%s on %s: observable '%s' is %g after a window", m->name, cs->name, d[k].name, v[q]);
    }
    gr_sim_free(s);
}

void conf_obs_table(void **state)
{
    const conf_case *c = *state;
    check_table(c->m);
}

void conf_obs_scene(void **state)
{
    const conf_case *c = *state;
    gr_scene *sc = conf_parse(c, c->cs->text);
    if (!(gr_scene_features(sc) & ~c->m->features) && conf_accepts(c->m, sc, c->cs->name))
        check_sample(c, sc);
    gr_scene_free(sc);
}
