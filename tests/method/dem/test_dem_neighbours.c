/* Validation 5 of docs/methods/dem.md: Verlet lists, linked cells and brute force give
 * the same forces (to 1e-12 of the largest force) on random dense packings,
 * also after thousands of steps with list rebuilds, with and without the
 * tangential spring; and the spring's history survives the rebuilds (a run
 * rebuilding its list often follows a run without lists). */
#include "dem_test.h"

#include <string.h>

#include "dem/dem_eval.h"

static const char *packing(const char *tang, double skin, const char *nb, const char *sides)
{
    static char text[2048];
    snprintf(text, sizeof text,
             "[scene]\nseed = 9\n"
             "[domain]\nwidth = 20\nheight = 40\ngravity = 1\n%s"
             "[material]\nnormal = hertz\ntangential = %s\nkn = 1e5\ngamma_n = 100\n"
             "kt = 3e4\ngamma_t = 300\nmu = 0.5\n"
             "[species]\ncount = 330\npolydispersity = 0.2\n"
             "[init]\nkind = random\nregion = 0 8 20 40\nvelocity = gaussian\nv0 = 1\n"
             "[wall.ramp]\nfrom = 0 6\nto = 8 1\n"
             "[dem]\ndt = 1.25e-4\nskin = %g\nneighbour = %s\n",
             sides, tang, skin, nb);
    return text;
}

static double compare_modes(gr_dem *d)
{
    gr_err e = {0};
    size_t n = d->n;
    double *f[3][3];
    for (int m = 0; m < 3; m++) {
        for (int c = 0; c < 3; c++)
            f[m][c] = malloc(n * sizeof(double));
        if (gr_dem_forces(d, m, f[m][0], f[m][1], f[m][2], &e))
            print_error("%s\n", e.msg);
        assert_int_equal(e.code, GR_OK);
    }
    double fmaxv = 0, diff = 0;
    for (size_t i = 0; i < n; i++) {
        for (int c = 0; c < 3; c++) {
            fmaxv = fmax(fmaxv, fabs(f[GR_DEM_NB_BRUTE][c][i]));
            for (int m = 0; m < 2; m++)
                diff = fmax(diff, fabs(f[m][c][i] - f[GR_DEM_NB_BRUTE][c][i]));
        }
    }
    for (int m = 0; m < 3; m++)
        for (int c = 0; c < 3; c++)
            free(f[m][c]);
    assert_true(fmaxv > 0);
    return diff / fmaxv;
}

/* The packing after it fell and piled up for 4 tau (dense, many contacts
 * per grain), as particles in id order. */
static gr_particles *settled(const char *tang, const char *sides)
{
    gr_scene *sc = dt_scene(packing(tang, 0.1, "verlet", sides));
    gr_dem *d = dt_create(sc, NULL);
    dt_advance(d, 4.0);
    gr_err e = {0};
    gr_particles *p = gr_particles_create(0, &e);
    assert_int_equal(gr_dem_snapshot(d, p, &e), GR_OK);
    gr_dem_free(d);
    gr_scene_free(sc);
    return p;
}

static void modes_agree(const char *tang, const char *sides)
{
    gr_particles *p = settled(tang, sides);
    gr_scene *sc = dt_scene(packing(tang, 0.1, "verlet", sides));
    gr_dem *d = dt_create(sc, p);
    double worst = compare_modes(d);
    uint64_t b0 = d->builds;
    for (int k = 0; k < 5; k++) {
        dt_step(d, 1000);
        worst = fmax(worst, compare_modes(d));
    }
    printf("# %s, %s: %llu steps from a settled packing, %llu list builds, largest force difference %.2e of the largest force\n",
           tang, sides[0] ? "periodic x" : "walls", (unsigned long long)d->step,
           (unsigned long long)(d->builds - b0), worst);
    assert_true(worst < 1e-12);
    gr_dem_free(d);
    gr_scene_free(sc);
    gr_particles_free(p);
}

static void regularised_walls(void **state)
{
    (void)state;
    modes_agree("regularised", "");
}

static void spring_periodic(void **state)
{
    (void)state;
    modes_agree("spring", "left = periodic\nright = periodic\n");
}

/* Lockstep runs from a settled packing: a tiny skin (a rebuild every few
 * steps) against linked cells (no list); if a rebuild lost a spring, the
 * runs would part by far more than round-off. */
static void history_survives_rebuilds(void **state)
{
    (void)state;
    gr_particles *p = settled("spring", "");
    /* stir it: the grains slide past each other and springs stretch */
    for (size_t i = 0; i < p->n; i++)
        if (!(p->flags[i] & GR_PF_FIXED))
            p->vx[i] += 0.3 * sin(0.7 * (double)i);
    gr_scene *s1 = dt_scene(packing("spring", 0.02, "verlet", ""));
    gr_dem *a = dt_create(s1, p);
    gr_scene *s2 = dt_scene(packing("spring", 0.02, "cells", ""));
    gr_dem *b = dt_create(s2, p);
    uint64_t b0 = a->builds;
    dt_step(a, 3000);
    dt_step(b, 3000);
    double worst = 0, moved = 0;
    for (size_t t = 0; t < a->ntag; t++) {
        long i = gr_dem_index(a, (long)t), j = gr_dem_index(b, (long)t);
        assert_true(i >= 0 && j >= 0);
        worst = fmax(worst, hypot(a->f[F_X][a->cur][i] - b->f[F_X][b->cur][j],
                                  a->f[F_Y][a->cur][i] - b->f[F_Y][b->cur][j]));
        moved = fmax(moved, hypot(a->f[F_X][a->cur][i] - p->x[t], a->f[F_Y][a->cur][i] - p->y[t]));
    }
    printf("# spring friction, 3000 steps: %llu list builds, grains moved up to %.3f; largest position difference to linked cells %.2e\n",
           (unsigned long long)(a->builds - b0), moved, worst);
    assert_true(a->builds - b0 > 50);
    assert_true(worst < 1e-9);
    gr_dem_free(a);
    gr_dem_free(b);
    gr_scene_free(s1);
    gr_scene_free(s2);
    gr_particles_free(p);
}

/* A grain with more list pairs than a batch of the pair loop holds goes
 * one pair at a time (dem_batch.h): a disk of radius 50 ringed by 300 unit
 * grains, each pressed 0.01 d into it and moving, gives the same forces
 * with Verlet lists as by brute force, and its list is longer than a
 * batch (else the test would miss that path). */
static void list_longer_than_batch(void **state)
{
    (void)state;
    gr_scene *sc = dt_scene("[domain]\nwidth = 130\nheight = 130\n"
                            "[material]\nnormal = hertz\ntangential = regularised\nkn = 1e5\ngamma_n = 100\n"
                            "gamma_t = 300\nmu = 0.5\n[species]\ncount = 1\n"
                            "[dem]\ndt = 1e-4\nskin = 0.1\nneighbour = verlet\n");
    gr_err e = {0};
    gr_particles *p = gr_particles_create(301, &e);
    assert_non_null(p);
    /* the disk first in the lowest of the cells, so that every pair with it
     * is in its own half list */
    assert_true(gr_particles_push(p, 64, 64, 50, 1e4, 0, 0, &e) >= 0);
    for (int k = 0; k < 300; k++) {
        double a = 2 * M_PI * k / 300;
        long i = gr_particles_push(p, 64 + 50.49 * cos(a), 64 + 50.49 * sin(a), 0.5, 1.0, 0, 0, &e);
        assert_true(i >= 0);
        p->vx[i] = 0.3 * sin(3 * a);
        p->vy[i] = 0.3 * cos(5 * a);
        p->omega[i] = sin(7 * a);
    }
    for (size_t i = 0; i < p->n; i++)
        p->id[i] = (int64_t)i;
    gr_dem *d = dt_create(sc, p);
    /* the forces of evaluation 64: every 64th runs the batches (dem_force.c) */
    dt_step(d, 63);
    long longest = 0;
    for (size_t i = 0; i < d->n; i++)
        longest = fmax(longest, d->nb_start[i + 1] - d->nb_start[i]);
    double worst = compare_modes(d);
    printf("# ring of 300 on a disk: longest list %ld pairs (batch %d), largest force difference %.2e\n", longest,
           DEM_BATCH, worst);
    assert_true(longest > DEM_BATCH);
    assert_true(worst < 1e-12);
    gr_dem_free(d);
    gr_scene_free(sc);
    gr_particles_free(p);
}

/* The list rebuilt on the threads of a team (gr_dem_rebuild: the sort's
 * arrays shared out, each thread the list of a run of grains, then joined)
 * is the serial sort and list, entry for entry: grains, cells and list,
 * on walls (the forward scan of cells in order) and periodic in x with the
 * spring's history (the full scan), on 1, 2 and 3 threads. */
static void same_list(gr_dem *a, gr_dem *b)
{
    size_t n = a->n;
    assert_int_equal(n, b->n);
    for (int f = 0; f < F_NBASIC; f++)
        if (a->f[f][a->cur])
            assert_memory_equal(a->f[f][a->cur], b->f[f][b->cur], n * sizeof(double));
    assert_memory_equal(a->tag, b->tag, n * sizeof *a->tag);
    assert_memory_equal(a->rad, b->rad, n * sizeof *a->rad);
    assert_memory_equal(a->xref, b->xref, n * sizeof *a->xref);
    assert_memory_equal(a->cells.cell, b->cells.cell, n * sizeof *a->cells.cell);
    assert_memory_equal(a->cells.idx, b->cells.idx, n * sizeof *a->cells.idx);
    assert_memory_equal(a->nb_start, b->nb_start, (n + 1) * sizeof *a->nb_start);
    assert_memory_equal(a->sg_start, b->sg_start, (n + 1) * sizeof *a->sg_start);
    size_t np = (size_t)a->nb_start[n], ns = (size_t)a->sg_start[n];
    assert_memory_equal(a->nb_j, b->nb_j, np * sizeof *a->nb_j);
    assert_memory_equal(a->nb_i, b->nb_i, np * sizeof *a->nb_i);
    assert_memory_equal(a->sg_j, b->sg_j, ns * sizeof *a->sg_j);
    if (a->hist_on)
        assert_memory_equal(a->hist.partner, b->hist.partner, n * (size_t)a->hist.cap * sizeof *a->hist.partner);
}

static void rebuild_on_threads(const char *tang, const char *sides)
{
    gr_particles *p = settled(tang, sides);
    for (size_t i = 0; i < p->n; i++)
        if (!(p->flags[i] & GR_PF_FIXED))
            p->vx[i] += 0.5 * sin(0.7 * (double)i), p->vy[i] += 0.5 * cos(0.3 * (double)i);
    gr_scene *sc = dt_scene(packing(tang, 2.0, "verlet", sides));
    for (int T = 1; T <= 3; T++) {
        gr_dem *a = dt_create(sc, p), *b = dt_create(sc, p);
        /* a wide skin: no rebuild in these steps, grains out of cell order */
        dt_step(a, 4000);
        dt_step(b, 4000);
        gr_err e = {0};
        assert_int_equal(gr_dem_bin(a, a->f[F_X][a->cur], a->f[F_Y][a->cur], &e), GR_OK);
        size_t moved = 0;
        for (size_t i = 0; i < a->n; i++)
            moved += a->cells.idx[i] != (int32_t)i;
        assert_true(moved > a->n / 10);
        b->par.threads = T;
        assert_int_equal(gr_dem_sort(a, &e), GR_OK);
        assert_int_equal(gr_dem_build_list(a, a->f[F_X][a->cur], a->f[F_Y][a->cur], &e), GR_OK);
        assert_int_equal(gr_dem_rebuild(b, &e), GR_OK);
        same_list(a, b);
        printf("# %s, %s, %d threads: %zu grains (%zu out of cell order), %d list pairs: the same list\n", tang,
               sides[0] ? "periodic x" : "walls", T, a->n, moved, a->nb_start[a->n]);
        gr_dem_free(a);
        gr_dem_free(b);
    }
    gr_scene_free(sc);
    gr_particles_free(p);
}

static void rebuild_walls(void **state)
{
    (void)state;
    rebuild_on_threads("regularised", "");
}

static void rebuild_periodic(void **state)
{
    (void)state;
    rebuild_on_threads("spring", "left = periodic\nright = periodic\n");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(regularised_walls),
        cmocka_unit_test(spring_periodic),
        cmocka_unit_test(history_survives_rebuilds),
        cmocka_unit_test(list_longer_than_batch),
        cmocka_unit_test(rebuild_walls),
        cmocka_unit_test(rebuild_periodic),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
