/* The battery's runner: one cmocka case per check, built at run time from
 * the backends and scenes it is given (GSL's battery over every step type
 * is the model), so a backend is held to the contract the moment it is in
 * a list, and one failure hides no other. */
#include "test.h"

#include <stdlib.h>
#include <string.h>

#include "conformance.h"

/* The registered names, then the battery's backends that are not among
 * them: the scene sections read. */
static const char **sections_of(const conf_battery *b)
{
    size_t n = 0;
    while (b->methods[n])
        n++;
    const char **s = calloc(GR_MAX_METHODS + n + 1, sizeof *s);
    assert_non_null(s);
    gr_method_names(s, GR_MAX_METHODS + 1);
    size_t k = 0;
    while (s[k])
        k++;
    for (size_t i = 0; i < n; i++) {
        int known = 0;
        for (size_t j = 0; j < k; j++)
            known |= !strcmp(s[j], b->methods[i]->name);
        if (!known)
            s[k++] = b->methods[i]->name;
    }
    return s;
}

typedef struct {
    struct CMUnitTest *t;
    conf_case *c;
    size_t n, cap;
} case_list;

static void add(case_list *l, const conf_case *c, CMUnitTestFunction fn, const char *fmt, const char *a,
                const char *b)
{
    if (l->n == l->cap) {
        l->cap = l->cap ? 2 * l->cap : 64;
        /* the cases' states point into c: grown only before any is taken */
        l->t = realloc(l->t, l->cap * sizeof *l->t);
        l->c = realloc(l->c, l->cap * sizeof *l->c);
        if (!l->t || !l->c)
            abort();
    }
    l->c[l->n] = *c;
    size_t len = strlen(fmt) + strlen(a) + strlen(b) + 1;
    char *name = malloc(len);
    if (!name)
        abort();
    snprintf(name, len, fmt, a, b);
    l->t[l->n] = (struct CMUnitTest){name, fn, NULL, NULL, NULL};
    l->n++;
}

int conf_run(const conf_battery *b)
{
    static const struct {
        CMUnitTestFunction fn;
        const char *what;
    } per_backend[] = {
        {conf_param_tables, "a consistent table of functions and parameters"},
        {conf_param_checks_in_scenes, "every parameter checked in scene files"},
        {conf_param_checkpoint, "a checkpoint refused under another parameter value"},
        {conf_param_docs, "the docs page lists exactly the parameter table"},
        {conf_optional_ops, "the optional operations' defaults"},
        {conf_features_run, "every declared feature runs on a scene"},
        {conf_obs_table, "a consistent table of observables"},
    };
    const char **sections = sections_of(b);
    case_list l = {0};
    conf_case c = {b, sections, NULL, NULL};
    add(&l, &c, conf_features_covered, "%s%s", "every scene feature has a scene", "");
    for (size_t k = 0; b->methods[k]; k++) {
        c.m = b->methods[k];
        c.cs = NULL;
        for (size_t i = 0; i < sizeof per_backend / sizeof per_backend[0]; i++)
            add(&l, &c, per_backend[i].fn, "%s: %s", c.m->name, per_backend[i].what);
        for (size_t j = 0; j < b->nscenes; j++) {
            c.cs = &b->scenes[j];
            add(&l, &c, conf_scene_case, "%s on %s", c.m->name, c.cs->name);
            add(&l, &c, conf_obs_scene, "%s observables on %s", c.m->name, c.cs->name);
        }
    }
    for (size_t i = 0; i < l.n; i++)
        l.t[i].initial_state = &l.c[i];
    /* cmocka_run_group_tests_name takes the array's size by sizeof: the
     * function behind it takes a count */
    int failed = _cmocka_run_group_tests(b->group, l.t, l.n, NULL, NULL);
    for (size_t i = 0; i < l.n; i++)
        free((char *)l.t[i].name);
    free(l.t), free(l.c), free(sections);
    return failed;
}
