/* Scene files: INI through libinih, with the line of every key kept so
 * that every later message can name file, line and key. */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <ini.h>

#include "scene.h"
#include "scene_impl.h"

/* inih hands the handler no line number in Debian's build: count the lines
 * in the reader it calls once per line. */
struct parse_ctx;
typedef struct {
    const char *p;
    int line;     /* line of the text last returned */
    int at_bol;   /* next read starts a new line */
    struct parse_ctx *ctx;
} reader_state;

static int on_entry(void *user, const char *section, const char *key, const char *value);
static void note_section(reader_state *r, const char *str);

static char *read_line(char *str, int num, void *stream)
{
    reader_state *r = stream;
    if (!*r->p || num < 2)
        return NULL;
    if (r->at_bol)
        r->line++;
    int k = 0;
    while (k < num - 1 && r->p[0]) {
        char c = *r->p++;
        str[k++] = c;
        if (c == '\n')
            break;
    }
    str[k] = '\0';
    int starts_line = r->at_bol;
    r->at_bol = (k > 0 && str[k - 1] == '\n');
    if (starts_line)
        note_section(r, str);
    return str;
}

typedef struct parse_ctx {
    gr_scene *sc;
    reader_state *rd;
    gr_err *err;
    size_t cap;
} parse_ctx;

static int on_entry(void *user, const char *section, const char *key, const char *value)
{
    parse_ctx *c = user;
    gr_scene *sc = c->sc;
    if (c->err->code)
        return 0;
    int line = c->rd->line;
    if (strlen(section) >= sizeof sc->entries[0].section ||
        strlen(key) >= sizeof sc->entries[0].key ||
        strlen(value) >= sizeof sc->entries[0].value) {
        gr_fail(c->err, GR_EINPUT, "%s:%d: [%s] %s: name or value too long",
                sc->path, line, section, key);
        return 0;
    }
    for (size_t i = 0; i < sc->nentries && key[0]; i++) {
        const gr_scene_entry *e = &sc->entries[i];
        if (!strcmp(e->section, section) && !strcmp(e->key, key)) {
            gr_fail(c->err, GR_EINPUT, "%s:%d: key '%s' in [%s] is set twice (first at line %d)",
                    sc->path, line, key, section, e->line);
            return 0;
        }
    }
    if (sc->nentries == c->cap) {
        size_t cap = c->cap ? 2 * c->cap : 64;
        gr_scene_entry *q = realloc(sc->entries, cap * sizeof *q);
        if (!q) {
            gr_fail(c->err, GR_ERUN, "out of memory reading %s", sc->path);
            return 0;
        }
        sc->entries = q;
        c->cap = cap;
    }
    gr_scene_entry *e = &sc->entries[sc->nentries++];
    snprintf(e->section, sizeof e->section, "%s", section);
    snprintf(e->key, sizeof e->key, "%s", key);
    snprintf(e->value, sizeof e->value, "%s", value);
    e->line = line;
    e->used = 0;
    return 1;
}

/* inih calls no handler for a section without keys: record every header
 * as an entry with an empty key, so an unknown empty section is caught. */
static void note_section(reader_state *r, const char *str)
{
    while (*str == ' ' || *str == '\t')
        str++;
    const char *end = strchr(str, ']');
    if (*str != '[' || !end)
        return;
    char name[128];
    size_t n = (size_t)(end - str - 1);
    if (n >= sizeof name)
        n = sizeof name - 1;
    memcpy(name, str + 1, n);
    name[n] = '\0';
    on_entry(r->ctx, name, "", "");
}

int gr_scene_read_entries(gr_scene *sc, const char *text, gr_err *err)
{
    parse_ctx c = {sc, NULL, err, 0};
    reader_state rd = {text, 0, 1, &c};
    c.rd = &rd;
    int rc = ini_parse_stream(read_line, &rd, on_entry, &c);
    if (err->code)
        return err->code;
    if (rc > 0)
        return gr_fail(err, GR_EINPUT, "%s:%d: not a valid line (expected [section], key = value or a ; comment)",
                       sc->path, rc);
    if (rc < 0)
        return gr_fail(err, GR_ERUN, "%s: the INI parser failed (%d)", sc->path, rc);
    return GR_OK;
}

const gr_scene_entry *gr_scene_find(const gr_scene *sc, const char *section, const char *key)
{
    for (size_t i = 0; i < sc->nentries; i++)
        if (!strcmp(sc->entries[i].section, section) && !strcmp(sc->entries[i].key, key))
            return &sc->entries[i];
    return NULL;
}

void gr_scene_where(const gr_scene *sc, const char *section, const char *key, char *buf, size_t n)
{
    const gr_scene_entry *e = gr_scene_find(sc, section, key);
    if (e)
        snprintf(buf, n, "%s:%d: [%s] key '%s'", sc->path, e->line, section, key);
    else
        snprintf(buf, n, "%s: [%s] key '%s' (default)", sc->path, section, key);
}

/* Levenshtein distance, for "did you mean" suggestions. */
static size_t edit_distance(const char *a, const char *b)
{
    size_t la = strlen(a), lb = strlen(b);
    if (la > 63 || lb > 63)
        return la > lb ? la : lb;
    size_t row[64];
    for (size_t j = 0; j <= lb; j++)
        row[j] = j;
    for (size_t i = 1; i <= la; i++) {
        size_t diag = row[0];
        row[0] = i;
        for (size_t j = 1; j <= lb; j++) {
            size_t up = row[j];
            size_t cost = tolower((unsigned char)a[i - 1]) != tolower((unsigned char)b[j - 1]);
            size_t best = diag + cost;
            if (row[j] + 1 < best)
                best = row[j] + 1;
            if (row[j - 1] + 1 < best)
                best = row[j - 1] + 1;
            row[j] = best;
            diag = up;
        }
    }
    return row[lb];
}

const char *gr_nearest(const char *word, const char *const *candidates)
{
    const char *best = NULL;
    size_t bd = (size_t)-1;
    for (size_t i = 0; candidates && candidates[i]; i++) {
        size_t d = edit_distance(word, candidates[i]);
        if (d < bd) {
            bd = d;
            best = candidates[i];
        }
    }
    /* A suggestion further than half the word away misleads more than it helps. */
    if (best && bd > (strlen(word) + 1) / 2 + 1)
        return NULL;
    return best;
}

static int list_contains(const char *const *list, const char *s)
{
    for (size_t i = 0; list && list[i]; i++)
        if (!strcmp(list[i], s))
            return 1;
    return 0;
}

int gr_scene_check_keys(const gr_scene *sc, const char *section,
                        const char *const *valid, gr_err *err)
{
    for (size_t i = 0; i < sc->nentries; i++) {
        const gr_scene_entry *e = &sc->entries[i];
        if (strcmp(e->section, section) || !e->key[0] || list_contains(valid, e->key))
            continue;
        const char *near = gr_nearest(e->key, valid);
        if (near)
            return gr_fail(err, GR_EINPUT, "%s:%d: unknown key '%s' in [%s]; did you mean '%s'?",
                           sc->path, e->line, e->key, section, near);
        return gr_fail(err, GR_EINPUT, "%s:%d: unknown key '%s' in [%s]",
                       sc->path, e->line, e->key, section);
    }
    return GR_OK;
}

int gr_scene_parse_double(const gr_scene *sc, const gr_scene_entry *e, double *out, gr_err *err)
{
    char *end;
    errno = 0;
    double v = strtod(e->value, &end);
    while (isspace((unsigned char)*end))
        end++;
    if (end == e->value || *end)
        return gr_fail(err, GR_EINPUT, "%s:%d: [%s] key '%s': '%s' is not a number",
                       sc->path, e->line, e->section, e->key, e->value);
    if (!isfinite(v) || errno == ERANGE)
        return gr_fail(err, GR_EINPUT, "%s:%d: [%s] key '%s': '%s' is not a finite number",
                       sc->path, e->line, e->section, e->key, e->value);
    *out = v;
    return GR_OK;
}

int gr_scene_get_double(const gr_scene *sc, const char *section, const char *key,
                        double def, double *out, gr_err *err)
{
    const gr_scene_entry *e = gr_scene_find(sc, section, key);
    if (!e) {
        *out = def;
        return GR_OK;
    }
    return gr_scene_parse_double(sc, e, out, err);
}

int gr_scene_get_long(const gr_scene *sc, const char *section, const char *key,
                      long def, long *out, gr_err *err)
{
    const gr_scene_entry *e = gr_scene_find(sc, section, key);
    if (!e) {
        *out = def;
        return GR_OK;
    }
    char *end;
    errno = 0;
    long v = strtol(e->value, &end, 10);
    while (isspace((unsigned char)*end))
        end++;
    if (end == e->value || *end || errno == ERANGE)
        return gr_fail(err, GR_EINPUT, "%s:%d: [%s] key '%s': '%s' is not an integer",
                       sc->path, e->line, section, key, e->value);
    *out = v;
    return GR_OK;
}

int gr_scene_get_choice(const gr_scene *sc, const char *section, const char *key,
                        const char *const *choices, int def, int *out, gr_err *err)
{
    const gr_scene_entry *e = gr_scene_find(sc, section, key);
    if (!e) {
        *out = def;
        return GR_OK;
    }
    for (int i = 0; choices[i]; i++) {
        if (!strcmp(choices[i], e->value)) {
            *out = i;
            return GR_OK;
        }
    }
    char list[512] = "";
    for (int i = 0; choices[i]; i++) {
        strncat(list, i ? ", " : "", sizeof list - strlen(list) - 1);
        strncat(list, choices[i], sizeof list - strlen(list) - 1);
    }
    const char *near = gr_nearest(e->value, choices);
    if (near)
        return gr_fail(err, GR_EINPUT, "%s:%d: [%s] key '%s': '%s' is not one of %s; did you mean '%s'?",
                       sc->path, e->line, section, key, e->value, list, near);
    return gr_fail(err, GR_EINPUT, "%s:%d: [%s] key '%s': '%s' is not one of %s",
                   sc->path, e->line, section, key, e->value, list);
}

/* A fixed number of whitespace-separated finite numbers. */
int gr_scene_get_vec(const gr_scene *sc, const char *section, const char *key,
                     int n, double *out, int *found, gr_err *err)
{
    const gr_scene_entry *e = gr_scene_find(sc, section, key);
    *found = e != NULL;
    if (!e)
        return GR_OK;
    const char *s = e->value;
    for (int i = 0; i < n; i++) {
        char *end;
        double v = strtod(s, &end);
        if (end == s)
            return gr_fail(err, GR_EINPUT, "%s:%d: [%s] key '%s': expected %d numbers, got '%s'",
                           sc->path, e->line, section, key, n, e->value);
        if (!isfinite(v))
            return gr_fail(err, GR_EINPUT, "%s:%d: [%s] key '%s': '%s' holds a non-finite number",
                           sc->path, e->line, section, key, e->value);
        out[i] = v;
        s = end;
    }
    while (isspace((unsigned char)*s))
        s++;
    if (*s)
        return gr_fail(err, GR_EINPUT, "%s:%d: [%s] key '%s': expected %d numbers, got '%s'",
                       sc->path, e->line, section, key, n, e->value);
    return GR_OK;
}
