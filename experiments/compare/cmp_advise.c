/* grano advise and grano run --method auto: the cheapest method for a
 * scene at an accepted error, from a comparison's results (compare.h5).
 *
 * The scene is matched to the nearest case of grano compare by what makes
 * the cases differ (an orifice, a vibrated floor, gravity and friction, a
 * gas's density and restitution, two grains); among the methods whose
 * features cover the scene, the case's rows that reach the tolerance
 * (error plus two error bars within it, every run finished) are ranked by
 * wall time per run, and the cheapest is the advice, with the row it
 * relies on. The scene's size differs from the case's: the ranking, not
 * the case's seconds, is what carries over. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmp_advise.h"
#include "h5tab.h"

/* The nearest case and the rule that chose it. */
static const char *nearest_case(const gr_scene *sc, char *rule, size_t n)
{
    double d = gr_scene_max_diameter(sc), g = sc->gravity;
    double eta = (double)gr_scene_count(sc) * M_PI * d * d / 4 / (sc->width * sc->height);
    int friction = sc->mat.tangential != GR_TANG_NONE && sc->mat.mu > 0;
    double shake = sc->floor.motion == GR_FLOOR_FIXED ? 0 : sc->floor.amplitude * sc->floor.omega;
    if (gr_scene_count(sc) == 2) {
        snprintf(rule, n, "two grains");
        return "collision";
    }
    if (sc->silo.present || sc->silo.orifice > 0) {
        snprintf(rule, n, "an orifice of %g d", sc->silo.orifice);
        return "silo";
    }
    if (g > 0 && shake >= 0.3 * sqrt(g * d)) {
        snprintf(rule, n, "a floor shaken at A omega = %.3g sqrt(g d)", shake / sqrt(g * d));
        return "vibrated";
    }
    if (g > 0) {
        snprintf(rule, n, "grains at rest under gravity, %s", friction ? "with friction" : "frictionless");
        return friction ? "janssen" : "column";
    }
    if (isfinite(sc->mat.restitution) && sc->mat.restitution >= 1) {
        snprintf(rule, n, "an elastic gas without gravity (packing %.3g)", eta);
        return "eos";
    }
    snprintf(rule, n, "an inelastic gas without gravity at packing %.3g (%s 0.2)", eta, eta < 0.2 ? "below" : "above");
    return eta < 0.2 ? "cooling-dilute" : "cooling-dense";
}

/* The case's table as read back. */
typedef struct {
    char **method, **variant, **knob, **value, **role;
    double *err, *sem, *wall, *runs, *done;
    size_t n;
} rows_t;

static void rows_free(rows_t *r)
{
    exp_tab_strs_free(r->method, r->n), exp_tab_strs_free(r->variant, r->n), exp_tab_strs_free(r->knob, r->n);
    exp_tab_strs_free(r->value, r->n), exp_tab_strs_free(r->role, r->n);
    free(r->err), free(r->sem), free(r->wall), free(r->runs), free(r->done);
}

static int rows_read(const char *from, const char *c, rows_t *r, gr_err *err)
{
    char g[64];
    snprintf(g, sizeof g, "cases/%s", c);
    size_t n[10];
    int rc = exp_tab_read_str(from, g, "method", &r->method, &n[0], err) ||
             exp_tab_read_str(from, g, "variant", &r->variant, &n[1], err) ||
             exp_tab_read_str(from, g, "knob", &r->knob, &n[2], err) ||
             exp_tab_read_str(from, g, "knob_value", &r->value, &n[3], err) ||
             exp_tab_read_str(from, g, "role", &r->role, &n[4], err) ||
             exp_tab_read_f64(from, g, "rel_error", &r->err, &n[5], err) ||
             exp_tab_read_f64(from, g, "rel_error_sem", &r->sem, &n[6], err) ||
             exp_tab_read_f64(from, g, "wall_s", &r->wall, &n[7], err) ||
             exp_tab_read_f64(from, g, "runs", &r->runs, &n[8], err) ||
             exp_tab_read_f64(from, g, "finished", &r->done, &n[9], err);
    r->n = n[0];
    for (int k = 1; !rc && k < 10; k++)
        if (n[k] != n[0])
            rc = gr_fail(err, GR_EINPUT, "%s: the columns of %s differ in length", from, g);
    return rc;
}

/* Whether method name covers the scene; appends why not to `lack`. */
static int covers(const gr_method_type *m, const gr_scene *sc, char *lack, size_t n)
{
    gr_err e = {0};
    if (!gr_method_require_features(m, gr_scene_features(sc), sc->path, &e))
        return 1;
    size_t k = strlen(lack);
    snprintf(lack + k, n - k, "%s%s", k ? ", " : "", m->name);
    return 0;
}

static int is_covered(const char *name, const char *const *ok, int nok)
{
    for (int i = 0; i < nok; i++)
        if (!strcmp(ok[i], name))
            return 1;
    return 0;
}

/* The cheapest qualifying row of r (-1: none); *best_err the smallest
 * error of a covered method's row, for the refusal. */
static long cheapest(const rows_t *r, const char *const *ok, int nok, double tol, long *closest)
{
    long best = -1;
    *closest = -1;
    for (size_t i = 0; i < r->n; i++) {
        int usable = is_covered(r->method[i], ok, nok) && r->done[i] == r->runs[i] &&
                     (!strcmp(r->role[i], "sweep") || !strcmp(r->role[i], "reference"));
        if (!usable)
            continue;
        if (*closest < 0 || r->err[i] < r->err[*closest])
            *closest = (long)i;
        if (r->err[i] + 2 * r->sem[i] <= tol && (best < 0 || r->wall[i] < r->wall[best]))
            best = (long)i;
    }
    return best;
}

static void fill(cmp_advice *a, const rows_t *r, long i)
{
    snprintf(a->method, sizeof a->method, "%s", r->method[i]);
    snprintf(a->row, sizeof a->row, "%s", r->variant[i]);
    snprintf(a->knob, sizeof a->knob, "%s", r->knob[i]);
    snprintf(a->value, sizeof a->value, "%s", r->value[i]);
    a->error = r->err[i], a->error_sem = r->sem[i], a->wall = r->wall[i];
    size_t k = strlen(a->method);
    a->setting = !strncmp(a->knob, a->method, k) && a->knob[k] == '.' && !strchr(a->knob, '+');
}

int cmp_advise(const gr_scene *sc, const char *from, double tol, cmp_advice *a, gr_err *err)
{
    memset(a, 0, sizeof *a);
    const char *ok[GR_MAX_METHODS];
    char lack[2048] = "", rule[160];
    int nok = 0;
    for (const gr_method_type *const *m = gr_method_all(); *m && nok < GR_MAX_METHODS; m++)
        if (covers(*m, sc, lack, sizeof lack))
            ok[nok++] = (*m)->name;
    if (!nok)
        return gr_fail(err, GR_EINPUT, "%s: no method models the scene (grano run --method M names what M lacks)",
                       sc->path);
    const char *c = nearest_case(sc, rule, sizeof rule);
    snprintf(a->case_name, sizeof a->case_name, "%s", c);
    if (nok == 1) {
        snprintf(a->method, sizeof a->method, "%s", ok[0]);
        snprintf(a->why, sizeof a->why, "%s is the only method that models the scene (%s lack a feature it needs: "
                 "grano run names it); no compare row is needed to choose it, and none measures its error here", ok[0], lack);
        return GR_OK;
    }
    rows_t r = {0};
    if (rows_read(from, c, &r, err)) {
        char why[1024];
        snprintf(why, sizeof why, "%s", err->msg);
        rows_free(&r);
        return gr_fail(err, GR_EINPUT, "%s; advice needs a comparison's results: run 'grano compare --out DIR' "
                       "(or --quick) and give --from DIR/compare.h5", why);
    }
    if (!(tol > 0)) { /* the case's own: the error a user of it accepts */
        char g[64], t[32];
        snprintf(g, sizeof g, "cases/%s", c);
        tol = exp_tab_read_attr(from, g, "tolerance", t, sizeof t, err) ? 0 : atof(t);
        if (!(tol > 0)) {
            rows_free(&r);
            return gr_fail(err, GR_EINPUT, "%s: case %s states no tolerance: give --tolerance", from, c);
        }
    }
    long closest, best = cheapest(&r, ok, nok, tol, &closest);
    int rc = GR_OK;
    if (best < 0 && closest >= 0)
        rc = gr_fail(err, GR_EINPUT, "--tolerance %.3g %%: no method reaches it on case %s (the nearest to %s: %s); "
                     "the closest is %s %s%s%s at %.3g +- %.2g (%s)", 100 * tol, c, sc->path, rule, r.variant[closest],
                     r.knob[closest], r.knob[closest][0] ? " = " : "", r.value[closest], r.err[closest],
                     r.sem[closest], from);
    else if (best < 0)
        rc = gr_fail(err, GR_EINPUT, "%s: case %s (%s) has no finished row of a method that models the scene (%s)",
                     from, c, rule, sc->path);
    else {
        fill(a, &r, best);
        snprintf(a->why, sizeof a->why,
                 "case %s (the nearest to the scene: %s): compare row %s%s%s%s%s%s, error %.3g +- %.2g, %.3g s a "
                 "run (%s), the cheapest row within %.3g %% of a method that models the scene", c, rule, a->row,
                 a->knob[0] ? " " : "", a->knob, a->knob[0] ? " = " : "", a->value,
                 strcmp(r.role[best], "reference") ? "" : " (the case's reference: its error is zero by definition)",
                 a->error, a->error_sem, a->wall, from, 100 * tol);
    }
    rows_free(&r);
    return rc;
}
