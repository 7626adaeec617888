/* The local problem of the current step as a dense u = W r + q (the form of
 * tests/oracle/fc2d.h), for the Siconos oracle test and grano bench cd only:
 * the sweeps never assemble W, so it is built here from the bodies.
 * Bottom layer: calls no other file of the backend. */
#include <stdlib.h>
#include <string.h>

#include "cd_int.h"

void gr_cd_local_free(gr_cd_local *lp)
{
    free(lp->k);
    free(lp->W);
    free(lp->q);
    free(lp->mu);
    free(lp->r);
    free(lp->u);
    *lp = (gr_cd_local){0};
}

/* Jean's rule as local_solve applies it, on the current velocities: a
 * contact whose predicted gap stays positive carries no impulse and is
 * outside the velocity-level Signorini problem. */
static int closed(const gr_cd *d, const gr_cd_contact *c)
{
    double un, ut, th = d->par.theta;
    gr_cd_rel(d, c, &un, &ut);
    return c->g + d->par.dt * ((1 - th) * c->un0 + th * (un - c->wn * c->rn)) <= 0;
}

/* Rows of contact c on body b (the grain i or j of c): normal and
 * tangential, over (v_x, v_y, omega) of b. */
static void rows(const gr_cd *d, const gr_cd_contact *c, size_t b, double hn[3], double ht[3])
{
    double s = b == (size_t)c->i ? 1.0 : -1.0;
    hn[0] = s * c->nx, hn[1] = s * c->ny, hn[2] = 0;
    ht[0] = -s * c->ny, ht[1] = s * c->nx, ht[2] = -d->p->radius[b];
}

/* W += the part of H M^-1 H^T that goes through body b, whose contacts
 * (local indices) are list[0..m). Walls and fixed grains add nothing. */
static void add_body(const gr_cd *d, const gr_cd_local *lp, size_t b, const int *list, int m)
{
    size_t n2 = 2 * (size_t)lp->nc;
    double w[3] = {d->im[b], d->im[b], d->iI[b]};
    for (int x = 0; x < m; x++) {
        double a[2][3], c[2][3];
        rows(d, &d->cur.c[lp->k[list[x]]], b, a[0], a[1]);
        for (int y = 0; y < m; y++) {
            rows(d, &d->cur.c[lp->k[list[y]]], b, c[0], c[1]);
            for (int p = 0; p < 2; p++)
                for (int s = 0; s < 2; s++) {
                    double v = 0;
                    for (int t = 0; t < 3; t++)
                        v += a[p][t] * w[t] * c[s][t];
                    lp->W[(2 * (size_t)list[x] + (size_t)p) * n2 + 2 * (size_t)list[y] + (size_t)s] += v;
                }
        }
    }
}

/* Contacts of each grain, by counting sort: first[b]..first[b+1] in idx. */
static void by_body(const gr_cd *d, gr_cd_local *lp, size_t *first, int *idx)
{
    memset(first, 0, (d->n + 2) * sizeof *first);
    for (int a = 0; a < lp->nc; a++) {
        const gr_cd_contact *c = &d->cur.c[lp->k[a]];
        first[(size_t)c->i + 2]++;
        if ((size_t)c->j < d->n)
            first[(size_t)c->j + 2]++;
    }
    for (size_t b = 0; b < d->n; b++)
        first[b + 2] += first[b + 1];
    for (int a = 0; a < lp->nc; a++) {
        const gr_cd_contact *c = &d->cur.c[lp->k[a]];
        idx[first[(size_t)c->i + 1]++] = a;
        if ((size_t)c->j < d->n)
            idx[first[(size_t)c->j + 1]++] = a;
    }
}

/* W, then q = u - W r with u the current local velocities. With
 * restitution e, u and q carry + e u-: the formal velocity times (1 + e),
 * on which Signorini and Coulomb read the same (positive scaling). */
static void fill(const gr_cd *d, gr_cd_local *lp, const size_t *first, const int *idx)
{
    size_t n2 = 2 * (size_t)lp->nc;
    for (size_t b = 0; b < d->n; b++)
        add_body(d, lp, b, idx + first[b], (int)(first[b + 1] - first[b]));
    for (int a = 0; a < lp->nc; a++) {
        const gr_cd_contact *c = &d->cur.c[lp->k[a]];
        double un, ut;
        gr_cd_rel(d, c, &un, &ut);
        lp->u[2 * a] = un + c->en * c->un0;
        lp->u[2 * a + 1] = ut + c->et * c->ut0;
        lp->r[2 * a] = c->rn, lp->r[2 * a + 1] = c->rt;
        lp->mu[a] = d->mu;
    }
    for (size_t row = 0; row < n2; row++) {
        double s = lp->u[row];
        for (size_t col = 0; col < n2; col++)
            s -= lp->W[row * n2 + col] * lp->r[col];
        lp->q[row] = s;
    }
}

int gr_cd_local_export(const gr_cd *d, int closed_only, gr_cd_local *lp, gr_err *err)
{
    *lp = (gr_cd_local){0};
    size_t nc = 0, *first = NULL;
    int *idx = NULL;
    lp->k = malloc((d->cur.n + 1) * sizeof *lp->k);
    for (size_t a = 0; lp->k && a < d->cur.n; a++)
        if (!closed_only || closed(d, &d->cur.c[a]))
            lp->k[nc++] = a;
    lp->nc = (int)nc;
    size_t n2 = 2 * nc + 1;
    lp->W = calloc(n2 * n2, sizeof *lp->W);
    lp->q = malloc(n2 * sizeof *lp->q), lp->r = malloc(n2 * sizeof *lp->r);
    lp->u = malloc(n2 * sizeof *lp->u), lp->mu = malloc(n2 * sizeof *lp->mu);
    first = malloc((d->n + 2) * sizeof *first);
    idx = malloc((2 * nc + 1) * sizeof *idx);
    if (!lp->k || !lp->W || !lp->q || !lp->r || !lp->u || !lp->mu || !first || !idx) {
        free(first);
        free(idx);
        gr_cd_local_free(lp);
        return gr_fail(err, GR_ERUN, "out of memory for the dense local problem of %zu contacts", nc);
    }
    by_body(d, lp, first, idx);
    fill(d, lp, first, idx);
    free(first);
    free(idx);
    return GR_OK;
}
