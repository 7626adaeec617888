/* The battery's checks of a backend's parameter table (consistent,
 * enforced on scene files: range, type, unknown key with a suggestion;
 * compared by checkpoints; documented in its <name>.md page) and of the
 * defaults of its optional operations. */
#include "test.h"

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "conformance.h"
#include "init.h"
#include "method.h"

/* The battery's first scene is the plain box every backend runs. */
static int try_create(const conf_case *c, const gr_method_type *m, const char *extra, gr_sim **out, gr_err *e)
{
    *e = (gr_err){0};
    const char *box = c->b->scenes[0].text;
    size_t n = strlen(box) + strlen(extra) + 1;
    char *text = malloc(n);
    snprintf(text, n, "%s%s", box, extra);
    gr_scene *sc = gr_scene_parse(text, "conformance.ini", c->sections, e);
    free(text);
    if (!sc)
        print_error("%s: %s\n", extra, e->msg);
    assert_non_null(sc);
    gr_particles *p = gr_particles_create(0, e);
    assert_int_equal(gr_init_particles(sc, p, e), GR_OK);
    *out = NULL;
    int rc = gr_sim_create(m, sc, p, out, e);
    gr_particles_free(p);
    if (!*out)
        gr_scene_free(sc);
    return rc;
}

static void drop(gr_sim *s)
{
    if (!s)
        return;
    gr_scene *sc = (gr_scene *)gr_sim_scene(s);
    gr_sim_free(s);
    gr_scene_free(sc);
}

static int line_count(const char *t)
{
    int n = 0;
    for (; *t; t++)
        n += *t == '\n';
    return n;
}

/* [m] key = value is refused, naming file:line and the key. */
static void refused(const conf_case *c, const char *key, const char *value, const char *expect)
{
    const gr_method_type *m = c->m;
    char extra[256], where[64];
    snprintf(extra, sizeof extra, "[%s]\n%s = %s\n", m->name, key, value);
    snprintf(where, sizeof where, "conformance.ini:%d:", line_count(c->b->scenes[0].text) + 2);
    gr_err e = {0};
    gr_sim *s;
    int rc = try_create(c, m, extra, &s, &e);
    if (rc != GR_EINPUT)
        print_error("%s: %s = %s was not refused (%d: %s)\n", m->name, key, value, rc, e.msg);
    assert_int_equal(rc, GR_EINPUT);
    assert_null(s);
    if (!strstr(e.msg, where) || !strstr(e.msg, key) || (expect && !strstr(e.msg, expect)))
        print_error("%s: message for %s = %s: %s\n", m->name, key, value, e.msg);
    assert_non_null(strstr(e.msg, where));
    assert_non_null(strstr(e.msg, key));
    if (expect)
        assert_non_null(strstr(e.msg, expect));
}

void conf_param_tables(void **state)
{
    const conf_case *c = *state;
    const gr_method_type *m = c->m;
    gr_err e = {0};
    if (gr_params_check_table(m->name, m->params, &e))
        print_error("%s\n", e.msg);
    assert_int_equal(e.code, GR_OK);
    assert_non_null(m->summary);
    assert_true(m->create && m->time && m->save && m->load && m->free);
    /* advance and observe are had by the backend or through their defaults */
    assert_true(m->advance || (m->step && m->dt));
    assert_true(m->observe || m->snapshot);
    if (m->repr == GR_REPR_PARTICLES)
        assert_non_null(m->snapshot);
    else
        assert_non_null(m->fields);
    for (size_t j = 0; c->b->methods[j]; j++)
        if (c->b->methods[j] != m)
            assert_string_not_equal(m->name, c->b->methods[j]->name);
}

void conf_param_checks_in_scenes(void **state)
{
    const conf_case *c = *state;
    const gr_method_type *m = c->m;
    for (const gr_param *p = m->params; p->name; p++) {
        char v[64], typo[80];
        if (p->type == GR_PARAM_CHOICE) {
            refused(c, p->name, "no-such-word", NULL);
        } else {
            if (isfinite(p->min)) {
                snprintf(v, sizeof v, "%.17g", p->min_open ? p->min : p->min - 1);
                refused(c, p->name, v, "outside its range");
            }
            if (isfinite(p->max)) {
                snprintf(v, sizeof v, "%.17g", p->max + 1);
                refused(c, p->name, v, "outside its range");
            }
            refused(c, p->name, "1x", NULL);
            if (p->type == GR_PARAM_INT)
                refused(c, p->name, "2.5", NULL);
        }
        snprintf(typo, sizeof typo, "%sx", p->name);
        char want[100];
        snprintf(want, sizeof want, "did you mean '%s'", p->name);
        refused(c, typo, "1", want);
    }
}

/* A value inside the range other than the default, or NULL. */
static const char *other_value(const gr_param *p, char *buf, size_t n)
{
    if (p->type == GR_PARAM_CHOICE)
        return p->choices[(int)p->def + 1] ? p->choices[(int)p->def + 1] : p->def > 0 ? p->choices[0] : NULL;
    double d = isnan(p->def) ? (isfinite(p->min) ? p->min + 1 : 1) : p->def;
    double v = isfinite(p->max) ? (p->min + p->max) / 2 : d * 2 + 1;
    if (p->type == GR_PARAM_INT)
        v = floor(v) == d ? floor(v) + 1 : floor(v);
    if (v == d || v > p->max)
        return NULL;
    snprintf(buf, n, "%.17g", v);
    return buf;
}

/* A checkpoint written under one value of a parameter is refused by an
 * instance whose scene gives another, naming the key. */
void conf_param_checkpoint(void **state)
{
    const conf_case *c = *state;
    const gr_method_type *m = c->m;
    char path[] = "/tmp/grano-conformance-params-XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    gr_err e = {0};
    gr_sim *a;
    assert_int_equal(try_create(c, m, "", &a, &e), GR_OK);
    unlink(path);
    gr_ckpt *ck = gr_ckpt_create(path, &e);
    assert_int_equal(gr_sim_save(a, ck, &e), GR_OK);
    assert_int_equal(gr_ckpt_close(ck, &e), GR_OK);
    drop(a);
    int tried = 0;
    for (const gr_param *p = m->params; p->name && !tried; p++) {
        char buf[64], extra[160];
        const char *v = other_value(p, buf, sizeof buf);
        gr_sim *b;
        if (!v)
            continue;
        snprintf(extra, sizeof extra, "[%s]\n%s = %s\n", m->name, p->name, v);
        if (try_create(c, m, extra, &b, &e))
            continue; /* refused on its own grounds (a dt above the limit) */
        tried = 1;
        ck = gr_ckpt_open(path, &e);
        assert_int_equal(gr_sim_load(b, ck, &e), GR_EINPUT);
        assert_non_null(strstr(e.msg, p->name));
        gr_ckpt_close(ck, &e);
        drop(b);
    }
    assert_true(tried || !m->params[0].name);
    unlink(path);
}

/* The battery's docs folder (docs/methods/ for the registered backends)
 * has <name>.md with a "## Parameters" table whose rows name the table's
 * parameters, every one and no other. */
void conf_param_docs(void **state)
{
    const conf_case *c = *state;
    const gr_method_type *m = c->m;
    char path[4200], line[2048];
    snprintf(path, sizeof path, "%s/%s.md", c->b->docs, m->name);
    FILE *f = fopen(path, "r");
    if (!f)
        print_error("%s: no docs page\n", path);
    assert_non_null(f);
    int in = 0, n = gr_params_count(m->params), seen[GR_MAX_PARAMS] = {0};
    while (fgets(line, sizeof line, f)) {
        if (!strncmp(line, "## ", 3))
            in = !strncmp(line, "## Parameters", 13);
        if (!in || strncmp(line, "| `", 3))
            continue;
        char *end = strchr(line + 1, '|');
        for (char *q = line; (q = strchr(q, '`')) && q < end;) {
            char *r = strchr(q + 1, '`');
            assert_non_null(r);
            *r = '\0';
            int i = gr_param_index(m->params, q + 1);
            if (i < 0)
                print_error("%s: documents '%s', which [%s] has not\n", path, q + 1, m->name);
            assert_true(i >= 0);
            seen[i] = 1;
            q = r + 1;
        }
    }
    fclose(f);
    for (int i = 0; i < n; i++) {
        if (!seen[i])
            print_error("%s: parameter '%s' is not in its Parameters table\n", path, m->params[i].name);
        assert_true(seen[i]);
    }
}

/* The defaults of the optional operations, on a copy of each table with
 * them taken out (but for what the defaults of advance and observe stand
 * on, where the backend uses those): one step is one step, a missing
 * snapshot or stress is refused by name, counters default to none. */
void conf_optional_ops(void **state)
{
    const conf_case *c = *state;
    const gr_method_type *m = c->m;
    gr_method_type bare = *m;
    /* what the defaults of advance and observe stand on stays */
    int keep_step = !m->advance, keep_snap = !m->observe;
    bare.reset_window = NULL, bare.fields = NULL, bare.stress = NULL;
    if (!keep_step)
        bare.step = NULL;
    if (!keep_snap)
        bare.snapshot = NULL, bare.counters = NULL;
    gr_err e = {0};
    gr_sim *s;
    assert_int_equal(try_create(c, &bare, "", &s, &e), GR_OK);
    gr_obs o0, o1;
    assert_int_equal(gr_sim_observe(s, &o0, &e), GR_OK);
    assert_int_equal(gr_sim_step(s, &e), GR_OK);
    assert_int_equal(gr_sim_observe(s, &o1, &e), GR_OK);
    assert_true(o1.steps == o0.steps + 1);
    assert_true(o1.t >= o0.t);
    gr_counter cn[4];
    gr_particles *p = gr_particles_create(0, &e);
    if (!keep_snap) {
        assert_int_equal(gr_sim_counters(s, cn, 4), 0);
        assert_int_equal(gr_sim_snapshot(s, p, &e), GR_EINPUT);
        assert_non_null(strstr(e.msg, "snapshots"));
        assert_non_null(strstr(e.msg, bare.name));
        assert_int_equal(gr_sim_require(&bare, GR_OP_FIELDS, "the test", &e), GR_EINPUT);
    }
    double g[4];
    assert_int_equal(gr_sim_stress(s, 1, 1, g, NULL, &e), GR_EINPUT);
    assert_non_null(strstr(e.msg, "window-averaged stress"));
    assert_non_null(strstr(e.msg, bare.name));
    unsigned own = GR_OP_FIELDS | GR_OP_STEP | (m->repr == GR_REPR_PARTICLES ? GR_OP_SNAPSHOT : 0);
    assert_int_equal(gr_sim_require(m, own, "the test", &e), GR_OK);
    gr_particles_free(p);
    drop(s);
}
