/* --set section.key=value: settings applied as lines of the scene file, so
 * that they go through the same parser and checks as the file's own lines.
 * The file's line of an overridden key is commented out (line numbers stay)
 * and each setting is appended as "[section]\nkey = value"; the appended
 * lines start at set_line0, two per setting, and messages naming them are
 * rewritten to name the flag instead. */
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene.h"
#include "scene_impl.h"

typedef struct {
    char section[64], key[64], value[256];
} setting;

static int split_setting(const char *s, setting *o, gr_err *err)
{
    const char *eq = strchr(s, '=');
    const char *dot = NULL;
    for (const char *q = s; eq && q < eq; q++)
        if (*q == '.')
            dot = q;
    if (!eq || !dot || dot == s || dot + 1 == eq || strchr(s, '\n'))
        return gr_fail(err, GR_EINPUT, "--set '%s': expected SECTION.KEY=VALUE (e.g. --set material.mu=0.3)", s);
    for (const char *q = s; q < eq; q++)
        if (!isalnum((unsigned char)*q) && !strchr("._-", *q))
            return gr_fail(err, GR_EINPUT, "--set '%s': '%c' in a section or key name", s, *q);
    size_t ls = (size_t)(dot - s), lk = (size_t)(eq - dot - 1);
    if (ls >= sizeof o->section || lk >= sizeof o->key || strlen(eq + 1) >= sizeof o->value)
        return gr_fail(err, GR_EINPUT, "--set '%s': name or value too long", s);
    snprintf(o->section, sizeof o->section, "%.*s", (int)ls, s);
    snprintf(o->key, sizeof o->key, "%.*s", (int)lk, dot + 1);
    snprintf(o->value, sizeof o->value, "%s", eq + 1);
    return GR_OK;
}

/* Comment out line `line` (1-based) of text, which has room for 2 more bytes. */
static void comment_line(char *text, int line)
{
    char *p = text;
    for (int l = 1; l < line && p; l++)
        if ((p = strchr(p, '\n')))
            p++;
    if (p && *p) {
        memmove(p + 2, p, strlen(p) + 1);
        memcpy(p, "; ", 2);
    }
}

/* What gr_scene_read_entries allocated in a scene on the stack. */
static void free_entries(gr_scene *tmp)
{
    free(tmp->entries);
    free(tmp->parsed);
    free(tmp->index);
}

/* The file's text with the settings applied; *line0 the first added line. */
static char *apply(const char *path, const char *text, const setting *st, size_t n, int *line0, gr_err *err)
{
    gr_scene tmp = {0};
    snprintf(tmp.path, sizeof tmp.path, "%s", path);
    size_t len = strlen(text), cap = len + 2 + n * (sizeof *st + 10);
    char *out = malloc(cap);
    if (!out) {
        gr_fail(err, GR_ERUN, "out of memory");
        return NULL;
    }
    memcpy(out, text, len + 1);
    if (gr_scene_read_entries(&tmp, text, err)) {
        free_entries(&tmp);
        free(out);
        return NULL;
    }
    for (size_t i = 0; i < n; i++) {
        const gr_scene_entry *e = gr_scene_find(&tmp, st[i].section, st[i].key);
        if (e)
            comment_line(out, e->line);
    }
    free_entries(&tmp);
    len = strlen(out);
    if (len && out[len - 1] != '\n')
        out[len++] = '\n', out[len] = '\0';
    int lines = 0;
    for (const char *q = out; *q; q++)
        lines += *q == '\n';
    *line0 = lines + 1;
    for (size_t i = 0; i < n; i++)
        len += (size_t)snprintf(out + len, cap - len, "[%s]\n%s = %s\n", st[i].section, st[i].key, st[i].value);
    return out;
}

/* "path:N: [sec] key 'k'" with N a setting's line -> "--set sec.k". */
static void rename_lines(const char *path, int line0, const setting *st, size_t n, gr_err *err)
{
    size_t lp = strlen(path);
    char *m = err->msg, *at = m;
    while (line0 > 0 && (at = strstr(at, path))) {
        char *end;
        long line = strtol(at + lp + (at[lp] == ':'), &end, 10);
        size_t i = (size_t)(line - line0) / 2;
        if (at[lp] != ':' || *end != ':' || line < line0 || i >= n) {
            at += lp;
            continue;
        }
        char tail[1024], redundant[160];
        end++;
        snprintf(redundant, sizeof redundant, " [%s] key '%s'", st[i].section, st[i].key);
        if (!strncmp(end, redundant, strlen(redundant)) && end[strlen(redundant)] == ':')
            end += strlen(redundant) + 1;
        snprintf(tail, sizeof tail, "%s", end);
        size_t off = (size_t)(at - m);
        int k = snprintf(at, sizeof err->msg - off, "--set %s.%s:%s", st[i].section, st[i].key, tail);
        at += k > 0 && (size_t)k < sizeof err->msg - off ? (size_t)k - strlen(tail) : strlen(at);
    }
}

char *gr_scene_text_set(const char *text, const char *section, const char *key, const char *value,
                        gr_err *err)
{
    setting st;
    if (strlen(section) >= sizeof st.section || strlen(key) >= sizeof st.key || strlen(value) >= sizeof st.value) {
        gr_fail(err, GR_EINPUT, "%s.%s: name or value too long", section, key);
        return NULL;
    }
    snprintf(st.section, sizeof st.section, "%s", section);
    snprintf(st.key, sizeof st.key, "%s", key);
    snprintf(st.value, sizeof st.value, "%s", value);
    int line0;
    return apply("scene text", text, &st, 1, &line0, err);
}

static int split_all(const char *const *sets, size_t n, setting *st, gr_err *err)
{
    for (size_t i = 0; i < n; i++) {
        if (split_setting(sets[i], &st[i], err))
            return err->code;
        for (size_t j = 0; j < i; j++)
            if (!strcmp(st[i].section, st[j].section) && !strcmp(st[i].key, st[j].key))
                return gr_fail(err, GR_EINPUT, "--set %s.%s: given twice", st[i].section, st[i].key);
    }
    return GR_OK;
}

gr_scene *gr_scene_load_set(const char *path, const char *const *extra, const char *const *sets, size_t n,
                            gr_err *err)
{
    setting *st = calloc(n ? n : 1, sizeof *st);
    char *text = NULL, *run = NULL;
    gr_scene *sc = NULL;
    int line0 = 0;
    if (!st)
        gr_fail(err, GR_ERUN, "out of memory");
    else if (!split_all(sets, n, st, err) && (text = gr_scene_read_text(path, err)) &&
             (run = n ? apply(path, text, st, n, &line0, err) : text)) {
        sc = gr_scene_parse(run, path, extra, err);
        if (sc)
            sc->set_line0 = line0;
        else
            rename_lines(path, line0, st, n, err);
    }
    if (run != text)
        free(run);
    free(text);
    free(st);
    return sc;
}

void gr_scene_name_sets(const gr_scene *sc, const char *const *sets, size_t n, gr_err *err)
{
    setting *st = calloc(n ? n : 1, sizeof *st);
    gr_err ignore = {0};
    if (st && !split_all(sets, n, st, &ignore))
        rename_lines(sc->path, sc->set_line0, st, n, err);
    free(st);
}
