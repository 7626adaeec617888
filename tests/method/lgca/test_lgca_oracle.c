/* The lattice oracle (tests/oracle/lattice.h), written from the rules as
 * docs/methods/lgca.md states them, against the backend's own table: the
 * Boltzmann map of the granular table (every (state, chirality,
 * dissipation bit) input weighted by the product measure, the table's
 * output counted) gives the same movers and rest particles, to 1e-12, at
 * every step from several starts; and the hydrostatic column is a
 * profile of the stated mean that solves its midpoint relation, flat
 * without gravity. */
#include "lgca_test.h"

#include "lattice.h"

static void table_map(const uint8_t *tab, double p, double *f, double *r)
{
    double mov = 0, rest = 0;
    for (unsigned s = 0; s < 128; s++) {
        int nm = __builtin_popcount(s & 63u), nr = (int)(s >> LGCA_REST & 1u);
        double w = pow(*f, nm) * pow(1 - *f, 6 - nm) * (nr ? *r : 1 - *r);
        for (unsigned x = 0; x < 4; x++) {
            unsigned o = tab[s | (x & 1u) << 7 | (x >> 1) << 8];
            double wx = w * 0.5 * (x >> 1 ? p : 1 - p);
            mov += wx * __builtin_popcount(o & 63u), rest += wx * (double)(o >> LGCA_REST & 1u);
        }
    }
    *f = mov / 6, *r = rest;
}

static void cooling_is_the_tables(void **unused)
{
    (void)unused;
    uint8_t tab[LGCA_TABLE_SIZE];
    lgca_table_build(LGCA_RULES_GRANULAR, tab);
    const double start[][3] = {{0.2, 0, 0.05}, {0.5, 0.3, 0.5}, {0.05, 0.9, 1}, {0.8, 0, 0.2}};
    for (size_t k = 0; k < sizeof start / sizeof start[0]; k++) {
        double f = start[k][0], r = start[k][1], p = start[k][2];
        for (long n = 1; n <= 400; n++) {
            table_map(tab, p, &f, &r);
            double fo, ro;
            assert_int_equal(gr_lattice_cooling(start[k][0], start[k][1], p, n, &fo, &ro), 0);
            assert_true(fabs(fo - f) < 1e-12 && fabs(ro - r) < 1e-12);
        }
        printf("# f0 %.2f r0 %.2f p %.2f: after 400 steps f %.6f r %.6f (table and oracle)\n", start[k][0],
               start[k][1], p, f, r);
    }
    double f, r;
    assert_int_equal(gr_lattice_cooling(0.3, 0.2, 0, 100, &f, &r), 0);
    assert_true(f == 0.3 && r == 0.2); /* no dissipation, no change */
    assert_int_equal(gr_lattice_cooling(1.5, 0, 0.1, 1, &f, &r), -1);
}

static void column_solves_its_relation(void **unused)
{
    (void)unused;
    double d[118];
    assert_int_equal(gr_lattice_column(0.3, 0, 28, d), 0);
    for (int i = 0; i < 28; i++)
        assert_true(fabs(d[i] - 0.3) < 1e-12);
    assert_int_equal(gr_lattice_column(0.3, 0.01, 118, d), 0);
    double mean = 0;
    for (int i = 0; i < 118; i++)
        mean += d[i] / 118;
    assert_true(fabs(mean - 0.3) < 1e-12);
    for (int i = 0; i + 1 < 118; i++) {
        double q0 = 1 - pow(1 - d[i] * (1 - d[i]), 3), q1 = 1 - pow(1 - d[i + 1] * (1 - d[i + 1]), 3);
        assert_true(d[i + 1] < d[i] && fabs(3 * (d[i] - d[i + 1]) - 0.01 * (q0 + q1) / 2) < 1e-13);
    }
    assert_int_equal(gr_lattice_column(1.2, 0.01, 10, d), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(cooling_is_the_tables),
                                       cmocka_unit_test(column_solves_its_relation)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
