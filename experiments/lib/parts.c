/* Part files: the checkpoint records a unit of a sweep leaves behind
 * (scalars, arrays, particle pictures, its key and its cost). */
#include "parts.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

int exp_put_scalar(gr_ckpt *ck, const char *name, double v, gr_err *err)
{
    return gr_ckpt_put_f64(ck, name, &v, 1, err);
}

double exp_get_scalar(gr_ckpt *ck, const char *name)
{
    double v = NAN;
    gr_err e = {0};
    if (gr_ckpt_get_f64(ck, name, &v, 1, &e))
        return NAN;
    return v;
}

int exp_get_array(gr_ckpt *ck, const char *name, double **v, size_t *n, gr_err *err)
{
    if (gr_ckpt_len(ck, name, n, err))
        return err->code;
    *v = malloc((*n ? *n : 1) * sizeof **v);
    if (!*v)
        return gr_fail(err, GR_ERUN, "out of memory");
    if (gr_ckpt_get_f64(ck, name, *v, *n, err)) {
        free(*v);
        *v = NULL;
        return err->code;
    }
    return GR_OK;
}

/* x, y, vx, vy, radius and flags: enough for pictures and statistics. */
int exp_put_particles(gr_ckpt *ck, const char *name, const gr_particles *p, gr_err *err)
{
    size_t n = p->n;
    double *v = malloc((6 * n + 1) * sizeof *v);
    if (!v)
        return gr_fail(err, GR_ERUN, "out of memory");
    for (size_t i = 0; i < n; i++) {
        v[6 * i] = p->x[i], v[6 * i + 1] = p->y[i], v[6 * i + 2] = p->vx[i];
        v[6 * i + 3] = p->vy[i], v[6 * i + 4] = p->radius[i], v[6 * i + 5] = p->flags[i];
    }
    int rc = gr_ckpt_put_f64(ck, name, v, 6 * n, err);
    free(v);
    return rc;
}

int exp_get_particles(gr_ckpt *ck, const char *name, gr_particles *p, gr_err *err)
{
    double *v;
    size_t n;
    if (exp_get_array(ck, name, &v, &n, err))
        return err->code;
    n /= 6;
    p->n = 0;
    int rc = GR_OK;
    for (size_t i = 0; i < n && !rc; i++) {
        double r = v[6 * i + 4];
        long k = gr_particles_push(p, v[6 * i], v[6 * i + 1], r, 4 * r * r, (uint32_t)v[6 * i + 5], 0, err);
        if (k < 0) {
            rc = err->code;
            break;
        }
        p->vx[k] = v[6 * i + 2], p->vy[k] = v[6 * i + 3];
    }
    free(v);
    return rc;
}

uint64_t exp_binary_hash(void)
{
    FILE *f = fopen("/proc/self/exe", "rb");
    if (!f)
        return 0;
    /* FNV-1a over 64-bit words: a megabyte in about a millisecond */
    uint64_t h = 0xcbf29ce484222325ull, w[512];
    size_t n;
    while ((n = fread(w, 1, sizeof w, f)) > 0) {
        if (n % 8)
            memset((char *)w + n, 0, 8 - n % 8);
        for (size_t k = 0; k < (n + 7) / 8; k++)
            h = (h ^ w[k]) * 0x100000001b3ull;
    }
    fclose(f);
    return h;
}

void exp_key_seal(char *key, size_t n, uint64_t bin)
{
    size_t len = strlen(key);
    if (len < n)
        snprintf(key + len, n - len, " bin=%016llx", (unsigned long long)bin);
}

int exp_part_key_is(const char *path, const char *key)
{
    if (access(path, F_OK) != 0)
        return 0;
    gr_err e = {0};
    gr_ckpt *ck = gr_ckpt_open(path, &e);
    if (!ck)
        return 0;
    size_t n;
    int ok = 0;
    if (!gr_ckpt_len(ck, "key", &n, &e) && n == strlen(key)) {
        char *s = calloc(n + 1, 1);
        ok = s && !gr_ckpt_get_bytes(ck, "key", s, n, &e) && !strcmp(s, key);
        free(s);
    }
    gr_ckpt_close(ck, &e);
    return ok;
}

int exp_part_key_matches(const char *path, const char *key)
{
    size_t n = strlen(key) + 32;
    char *sealed = malloc(n);
    if (!sealed)
        return 0;
    snprintf(sealed, n, "%s", key);
    exp_key_seal(sealed, n, exp_binary_hash());
    int ok = exp_part_key_is(path, sealed);
    free(sealed);
    return ok;
}

void exp_get_cost(gr_ckpt *ck, double cost[5])
{
    gr_err e = {0};
    if (gr_ckpt_get_f64(ck, "cost", cost, 5, &e))
        for (int k = 0; k < 5; k++)
            cost[k] = NAN;
}
