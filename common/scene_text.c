/* Scene text edited in memory: one key set to a new value, so that a
 * program can sweep a parameter of a scene file (a method's accuracy knob,
 * the seed) and still parse the result with gr_scene_parse, which keeps
 * every file:line:key message meaningful for the lines left unchanged. */
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene.h"

/* The section a "[name]" line opens into sec (empty when the line is no
 * section header). */
static void header_name(const char *line, size_t len, char *sec, size_t n)
{
    sec[0] = 0;
    while (len && isspace((unsigned char)*line))
        line++, len--;
    if (!len || *line != '[')
        return;
    const char *end = memchr(line, ']', len);
    if (!end)
        return;
    size_t k = (size_t)(end - line - 1);
    if (k >= n)
        k = n - 1;
    memcpy(sec, line + 1, k);
    sec[k] = 0;
}

/* Whether the line assigns key (blanks, key, blanks, '=' or ':'). */
static int assigns(const char *line, size_t len, const char *key)
{
    size_t k = strlen(key);
    while (len && isspace((unsigned char)*line))
        line++, len--;
    if (len <= k || strncmp(line, key, k))
        return 0;
    line += k, len -= k;
    while (len && (*line == ' ' || *line == '\t'))
        line++, len--;
    return len && (*line == '=' || *line == ':');
}

char *gr_scene_text_set(const char *text, const char *section, const char *key, const char *value,
                        gr_err *err)
{
    size_t tl = strlen(text), extra = strlen(section) + strlen(key) + strlen(value) + 16;
    char *out = malloc(tl + extra + 2);
    if (!out) {
        gr_fail(err, GR_ERUN, "out of memory");
        return NULL;
    }
    char cur[64] = "", sec[64];
    const char *p = text, *insert_after = NULL;
    int done = 0;
    size_t o = 0;
    while (*p) {
        const char *nl = strchr(p, '\n');
        size_t len = nl ? (size_t)(nl - p) : strlen(p);
        header_name(p, len, sec, sizeof sec);
        if (sec[0]) {
            if (!done && insert_after && !strcmp(cur, section)) {
                o += (size_t)sprintf(out + o, "%s = %s\n", key, value);
                done = 1;
            }
            snprintf(cur, sizeof cur, "%s", sec);
            if (!strcmp(cur, section))
                insert_after = p;
        }
        if (!done && !strcmp(cur, section) && !sec[0] && assigns(p, len, key)) {
            o += (size_t)sprintf(out + o, "%s = %s", key, value); /* replaces the line */
            done = 1;
        } else {
            memcpy(out + o, p, len);
            o += len;
        }
        if (nl)
            out[o++] = '\n';
        p = nl ? nl + 1 : p + len;
    }
    if (!done) {
        if (o && out[o - 1] != '\n')
            out[o++] = '\n';
        if (insert_after && !strcmp(cur, section))
            o += (size_t)sprintf(out + o, "%s = %s\n", key, value);
        else
            o += (size_t)sprintf(out + o, "[%s]\n%s = %s\n", section, key, value);
    }
    out[o] = 0;
    return out;
}
