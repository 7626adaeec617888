/* The lattice gas's own mean-field (Boltzmann) answers, for comparisons
 * that hold the automaton to its model rather than to the grains': the
 * nodes' channels independent, each filled with its mean occupation
 * (docs/methods/lgca.md, "The lattice model's own references"). */
#ifndef GR_LGCA_THEORY_H
#define GR_LGCA_THEORY_H

/* FHP-III at rest under the gravity rule (probability g per node and
 * step), between a floor and a ceiling with `rows` fluid rows: the mean
 * occupation per channel of each row, d[0] (the row on the floor) ..
 * d[rows - 1], whose mean is dbar (a fraction of the 7 channels). The
 * rules keep no energy, so every channel of a row at rest holds the same
 * d; the momentum flux through a row, 3 d m c^2 / (a h), falls from one
 * row to the next by the force of gravity on them, m c / dt per node and
 * event, with the mean of the two rows' event rates g Q(d),
 *   3 (d_i - d_{i+1}) = g (Q(d_i) + Q(d_{i+1})) / 2,
 *   Q(d) = 1 - (1 - d (1 - d))^3,
 * Q the chance that one of the rule's three moves finds its channel full
 * and its target empty. Returns 0, or -1 when no profile has that mean
 * (dbar outside (0, 1), g outside [0, 1]). */
int lgca_theory_column(double dbar, double g, int rows, double *d);

/* The granular rules' homogeneous cooling from moving occupation f0 per
 * channel and rest occupation r0, with dissipation p and no gravity: the
 * Boltzmann map of the collision table (both chiralities equally likely,
 * the dissipation bit with probability p) applied `steps` times; *f and
 * *r the occupations after them. The moving population falls by
 * f / f0. Returns 0, or -1 on arguments outside [0, 1]. */
int lgca_theory_cooling(double f0, double r0, double p, long steps, double *f, double *r);

#endif
