#include "params.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int gr_params_count(const gr_param *table)
{
    int n = 0;
    while (table && table[n].name)
        n++;
    return n;
}

int gr_param_index(const gr_param *table, const char *name)
{
    for (int k = 0; table && table[k].name; k++)
        if (!strcmp(table[k].name, name))
            return k;
    return -1;
}

static void defaults(const gr_param *table, gr_param_values *pv)
{
    memset(pv, 0, sizeof *pv);
    pv->table = table;
    pv->n = gr_params_count(table);
    for (int k = 0; k < pv->n && k < GR_MAX_PARAMS; k++)
        pv->v[k] = table[k].def;
}

double gr_param_get(const gr_param_values *pv, const char *name)
{
    int k = gr_param_index(pv->table, name);
    if (k < 0)
        abort();
    return pv->v[k];
}

void gr_param_format(const gr_param *p, double v, char *buf, size_t n)
{
    if (p->type == GR_PARAM_CHOICE) {
        int k = (int)v, m = 0;
        while (p->choices && p->choices[m])
            m++;
        snprintf(buf, n, "%s", k >= 0 && k < m ? p->choices[k] : "?");
    } else if (isnan(v)) {
        snprintf(buf, n, "auto");
    } else if (p->type == GR_PARAM_INT) {
        snprintf(buf, n, "%.0f", v);
    } else {
        /* the shortest text that reads back as the same double */
        for (int prec = 6; prec <= 17; prec++) {
            snprintf(buf, n, "%.*g", prec, v);
            if (strtod(buf, NULL) == v)
                break;
        }
    }
}

/* "(0, inf)", "[1, 256]": the range as the messages and tables show it. */
static void format_range(const gr_param *p, char *buf, size_t n)
{
    char lo[40], hi[40];
    if (isinf(p->min))
        snprintf(lo, sizeof lo, "-inf");
    else
        snprintf(lo, sizeof lo, "%g", p->min);
    if (isinf(p->max))
        snprintf(hi, sizeof hi, "inf");
    else
        snprintf(hi, sizeof hi, "%g", p->max);
    snprintf(buf, n, "%s%s, %s%s", p->min_open || isinf(p->min) ? "(" : "[", lo, hi, isinf(p->max) ? ")" : "]");
}

static int read_one(const gr_scene *sc, const char *section, const gr_param *p, double *v,
                    gr_err *err)
{
    if (p->type == GR_PARAM_CHOICE) {
        int k;
        if (gr_scene_get_choice(sc, section, p->name, p->choices, (int)p->def, &k, err))
            return err->code;
        *v = k;
        return GR_OK;
    }
    if (p->type == GR_PARAM_INT) {
        long l;
        if (gr_scene_get_long(sc, section, p->name, 0, &l, err))
            return err->code;
        *v = (double)l;
    } else if (gr_scene_get_double(sc, section, p->name, 0.0, v, err)) {
        return err->code;
    }
    int low = p->min_open ? !(*v > p->min) : !(*v >= p->min);
    if (low || !(*v <= p->max)) {
        char where[1200], range[100];
        gr_scene_where(sc, section, p->name, where, sizeof where);
        format_range(p, range, sizeof range);
        return gr_fail(err, GR_EINPUT, "%s: %g is outside its range %s (%s)", where, *v, range,
                       p->doc);
    }
    return GR_OK;
}

int gr_params_read(const gr_scene *sc, const char *section, const gr_param *table,
                   gr_param_values *pv, gr_err *err)
{
    defaults(table, pv);
    const char *names[GR_MAX_PARAMS + 1];
    for (int k = 0; k < pv->n; k++)
        names[k] = table[k].name;
    names[pv->n] = NULL;
    if (gr_scene_check_keys(sc, section, names, err))
        return err->code;
    for (int k = 0; k < pv->n; k++) {
        if (!gr_scene_find(sc, section, table[k].name))
            continue;
        if (read_one(sc, section, &table[k], &pv->v[k], err))
            return err->code;
    }
    return GR_OK;
}

int gr_params_check_table(const char *section, const gr_param *t, gr_err *err)
{
    int n = gr_params_count(t);
    if (n > GR_MAX_PARAMS)
        return gr_fail(err, GR_EINPUT, "[%s]: %d parameters, more than %d", section, n, GR_MAX_PARAMS);
    for (int k = 0; k < n; k++) {
        const gr_param *p = &t[k];
        if (!p->doc || !p->doc[0] || !p->unit)
            return gr_fail(err, GR_EINPUT, "[%s] %s: no doc or unit", section, p->name);
        if (gr_param_index(t, p->name) != k)
            return gr_fail(err, GR_EINPUT, "[%s] %s: named twice", section, p->name);
        if (p->type == GR_PARAM_CHOICE) {
            int m = 0;
            while (p->choices && p->choices[m])
                m++;
            if (m == 0 || !(p->def >= 0 && p->def < m))
                return gr_fail(err, GR_EINPUT, "[%s] %s: default is not one of its choices", section, p->name);
            continue;
        }
        if (!(p->min <= p->max))
            return gr_fail(err, GR_EINPUT, "[%s] %s: empty range", section, p->name);
        int low = p->min_open ? !(p->def > p->min) : !(p->def >= p->min);
        if (!isnan(p->def) && (low || !(p->def <= p->max)))
            return gr_fail(err, GR_EINPUT, "[%s] %s: default %g outside its range", section, p->name, p->def);
        if (p->type == GR_PARAM_INT && !isnan(p->def) && p->def != floor(p->def))
            return gr_fail(err, GR_EINPUT, "[%s] %s: integer with default %g", section, p->name, p->def);
    }
    return GR_OK;
}

void gr_params_print(FILE *f, const gr_param *t)
{
    static const char *const types[] = {"real", "int", "choice"};
    for (int k = 0; t && t[k].name; k++) {
        const gr_param *p = &t[k];
        char def[64], range[200] = "";
        gr_param_format(p, p->def, def, sizeof def);
        if (p->type == GR_PARAM_CHOICE) {
            size_t o = 0;
            for (int m = 0; p->choices[m] && o + 2 < sizeof range; m++)
                o += (size_t)snprintf(range + o, sizeof range - o, "%s%s", m ? "|" : "", p->choices[m]);
        } else {
            format_range(p, range, sizeof range);
        }
        fprintf(f, "    %-14s %-6s %-10s %-22s %-6s %s\n", p->name, types[p->type], def, range,
                p->unit, p->doc);
    }
}
