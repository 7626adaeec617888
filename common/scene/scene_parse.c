/* Scene files: INI lines read here (libinih split lines of 200 characters
 * and more, and took '= value' for a key named ''), with the line of every
 * key kept so that every later message can name file, line and key. */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene.h"
#include "scene_impl.h"

/* The index of entries by (section, key): a file of 20 000 walls must
 * load in well under a second, so lookups and the duplicate check do not
 * scan the list. Open addressing, at most half full. */
static size_t entry_hash(const char *section, const char *key)
{
    size_t h = 1469598103934665603u;
    for (const char *s = section; *s; s++)
        h = (h ^ (unsigned char)*s) * 1099511628211u;
    h = (h ^ 0xff) * 1099511628211u;
    for (const char *s = key; *s; s++)
        h = (h ^ (unsigned char)*s) * 1099511628211u;
    return h;
}

static const gr_scene_entry *index_find(const gr_scene *sc, const char *section, const char *key)
{
    if (!sc->index_cap)
        return NULL;
    for (size_t h = entry_hash(section, key) & (sc->index_cap - 1);; h = (h + 1) & (sc->index_cap - 1)) {
        size_t i = sc->index[h];
        if (i == 0)
            return NULL;
        const gr_scene_entry *e = &sc->entries[i - 1];
        if (!strcmp(e->section, section) && !strcmp(e->key, key))
            return e;
    }
}

static int index_rebuild(gr_scene *sc, size_t cap)
{
    size_t *ix = calloc(cap, sizeof *ix);
    if (!ix)
        return -1;
    free(sc->index);
    sc->index = ix;
    sc->index_cap = cap;
    for (size_t i = 0; i < sc->nentries; i++) {
        size_t h = entry_hash(sc->entries[i].section, sc->entries[i].key) & (cap - 1);
        while (ix[h])
            h = (h + 1) & (cap - 1);
        ix[h] = i + 1;
    }
    return 0;
}

typedef struct {
    gr_scene *sc;
    gr_err *err;
    size_t cap;
    int line;
} parse_ctx;

static int add_entry(parse_ctx *c, const char *section, const char *key, char *value)
{
    gr_scene *sc = c->sc;
    if (strlen(section) >= sizeof sc->entries[0].section || strlen(key) >= sizeof sc->entries[0].key)
        return gr_fail(c->err, GR_EINPUT, "%s:%d: [%.60s] %.60s: section or key name longer than %zu characters",
                       sc->path, c->line, section, key, sizeof sc->entries[0].key - 1);
    const gr_scene_entry *old = index_find(sc, section, key);
    if (old && key[0])
        return gr_fail(c->err, GR_EINPUT, "%s:%d: key '%s' in [%s] is set twice (first at line %d)",
                       sc->path, c->line, key, section, old->line);
    if (old) /* a section header seen before: its keys join the first one's */
        return GR_OK;
    if (sc->nentries == c->cap) {
        size_t cap = c->cap ? 2 * c->cap : 64;
        gr_scene_entry *q = realloc(sc->entries, cap * sizeof *q);
        if (!q)
            return gr_fail(c->err, GR_ERUN, "out of memory reading %s", sc->path);
        sc->entries = q;
        c->cap = cap;
    }
    gr_scene_entry *e = &sc->entries[sc->nentries++];
    snprintf(e->section, sizeof e->section, "%s", section);
    snprintf(e->key, sizeof e->key, "%s", key);
    e->value = value;
    e->line = c->line;
    e->used = 0;
    if (2 * sc->nentries > sc->index_cap) {
        if (index_rebuild(sc, sc->index_cap ? 2 * sc->index_cap : 256))
            return gr_fail(c->err, GR_ERUN, "out of memory reading %s", sc->path);
    } else {
        size_t h = entry_hash(section, key) & (sc->index_cap - 1);
        while (sc->index[h])
            h = (h + 1) & (sc->index_cap - 1);
        sc->index[h] = sc->nentries;
    }
    return GR_OK;
}

static char *trim(char *s)
{
    while (*s == ' ' || *s == '\t')
        s++;
    size_t n = strlen(s);
    while (n && isspace((unsigned char)s[n - 1]))
        s[--n] = '\0';
    return s;
}

/* One line of the file, already cut out of the buffer: '[section]',
 * 'key = value' (or 'key : value'), a comment (';' or '#' first, or after
 * a value following a blank) or nothing. Lines may be of any length. */
static int parse_line(parse_ctx *c, char *line, char *section)
{
    char *s = trim(line);
    if (!*s || *s == ';' || *s == '#')
        return GR_OK;
    if (*s == '[') {
        char *end = strchr(s, ']');
        if (!end)
            return gr_fail(c->err, GR_EINPUT, "%s:%d: a section header needs its closing ']'",
                           c->sc->path, c->line);
        *end = '\0';
        char *name = trim(s + 1);
        if (strlen(name) >= sizeof c->sc->entries[0].section)
            return gr_fail(c->err, GR_EINPUT, "%s:%d: section name longer than %zu characters",
                           c->sc->path, c->line, sizeof c->sc->entries[0].section - 1);
        strcpy(section, name);
        /* Every header is an entry with an empty key, so that an unknown
         * section without keys is caught too. */
        return add_entry(c, section, "", end);
    }
    size_t k = strcspn(s, "=:");
    if (!s[k])
        return gr_fail(c->err, GR_EINPUT,
                       "%s:%d: not a valid line (expected [section], key = value or a ; comment)",
                       c->sc->path, c->line);
    char *value = s + k + 1;
    s[k] = '\0';
    char *key = trim(s);
    if (!*key)
        return gr_fail(c->err, GR_EINPUT, "%s:%d: a value without a key (expected key = value)",
                       c->sc->path, c->line);
    for (char *q = value; *q; q++)
        if ((*q == ';' || *q == '#') && q > value && (q[-1] == ' ' || q[-1] == '\t')) {
            *q = '\0';
            break;
        }
    return add_entry(c, section, key, trim(value));
}

int gr_scene_read_entries(gr_scene *sc, const char *text, gr_err *err)
{
    parse_ctx c = {sc, err, 0, 0};
    free(sc->parsed);
    if (!(sc->parsed = strdup(text)))
        return gr_fail(err, GR_ERUN, "out of memory reading %s", sc->path);
    char section[sizeof sc->entries[0].section] = "";
    char *p = sc->parsed;
    /* A UTF-8 byte order mark, as some editors write. */
    if (!strncmp(p, "\xef\xbb\xbf", 3))
        p += 3;
    while (*p) {
        char *nl = strchr(p, '\n');
        if (nl)
            *nl = '\0';
        c.line++;
        if (parse_line(&c, p, section))
            return err->code;
        if (!nl)
            break;
        p = nl + 1;
    }
    return GR_OK;
}

const gr_scene_entry *gr_scene_find(const gr_scene *sc, const char *section, const char *key)
{
    return index_find(sc, section, key);
}

void gr_scene_where(const gr_scene *sc, const char *section, const char *key, char *buf, size_t n)
{
    const gr_scene_entry *e = gr_scene_find(sc, section, key);
    const gr_scene_entry *h = e ? NULL : gr_scene_find(sc, section, "");
    if (e)
        snprintf(buf, n, "%s:%d: [%s] key '%s'", sc->path, e->line, section, key);
    else if (h) /* absent key: the line of its section */
        snprintf(buf, n, "%s:%d: [%s] key '%s' (absent, default)", sc->path, h->line, section, key);
    else
        snprintf(buf, n, "%s: [%s] key '%s' (absent, default)", sc->path, section, key);
}

void gr_scene_where_key(const gr_scene *sc, const char *dotted, char *buf, size_t n)
{
    char sec[64];
    const char *dot = strchr(dotted, '.');
    size_t l = dot ? (size_t)(dot - dotted) : 0;
    snprintf(sec, sizeof sec, "%.*s", (int)(l < sizeof sec ? l : sizeof sec - 1), dotted);
    gr_scene_where(sc, sec, dot ? dot + 1 : dotted, buf, n);
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
        if (!isfinite(v) || fabs(v) > GR_SCENE_MAX_MAGNITUDE)
            return gr_fail(err, GR_EINPUT, "%s:%d: [%s] key '%s': '%s' holds a non-finite number or one beyond +-1e100",
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
