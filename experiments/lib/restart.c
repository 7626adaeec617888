#include "restart.h"

#include <stdio.h>
#include <string.h>

#include "method.h"

static int allowed(const char *section, const char *key)
{
    return !strcmp(section, "run") || !strcmp(section, "measure") ||
           (!strcmp(section, "scene") && !strcmp(key, "name"));
}

static void note(char *notes, size_t cap, const char *fmt, const char *sec, const char *key, const char *a,
                 const char *b)
{
    size_t used = strlen(notes);
    if (used < cap)
        snprintf(notes + used, cap - used, fmt, sec, key, a, b);
}

/* One difference: listed when allowed (or branching), else refused. */
static int one_diff(const gr_scene *now, const char *sec, const char *key, const char *was, const char *is,
                    const char *ckpt, int branch, char *notes, size_t cap, gr_err *err)
{
    if (allowed(sec, key) || branch) {
        note(notes, cap, "[%s] %s: '%s' -> '%s'; ", sec, key, was, is);
        return GR_OK;
    }
    char where[1200];
    gr_scene_where(now, sec, key, where, sizeof where);
    return gr_fail(err, GR_EINPUT,
                   "--restart: %s: '%s' here, '%s' in %s: a physical parameter differs from the checkpoint's "
                   "(only [run] and [measure] may); --branch starts a new output from the checkpoint's state",
                   where, is, was, ckpt);
}

int gr_restart_compare(const gr_scene *now, const char *old_text, const char *ckpt, int branch,
                       char *notes, size_t cap, gr_runctl *old_run, gr_err *err)
{
    const char *names[GR_MAX_METHODS + 1];
    gr_method_names(names, GR_MAX_METHODS + 1);
    gr_err pe = {0};
    gr_scene *old = gr_scene_parse(old_text, ckpt, names, &pe);
    if (!old)
        return gr_fail(err, GR_EINPUT, "--restart: the scene stored in %s no longer reads: %s", ckpt, pe.msg);
    *old_run = old->run;
    int rc = GR_OK;
    for (size_t i = 0; i < now->nentries && !rc; i++) {
        const gr_scene_entry *e = &now->entries[i];
        const gr_scene_entry *o = e->key[0] ? gr_scene_find(old, e->section, e->key) : NULL;
        if (e->key[0] && (!o || strcmp(o->value, e->value)))
            rc = one_diff(now, e->section, e->key, o ? o->value : "(absent)", e->value, ckpt, branch, notes, cap,
                          err);
    }
    for (size_t i = 0; i < old->nentries && !rc; i++) {
        const gr_scene_entry *o = &old->entries[i];
        if (o->key[0] && !gr_scene_find(now, o->section, o->key))
            rc = one_diff(now, o->section, o->key, o->value, "(absent)", ckpt, branch, notes, cap, err);
    }
    gr_scene_free(old);
    return rc;
}
