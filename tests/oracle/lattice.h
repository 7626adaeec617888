/* Oracles for the lattice gas's own mean-field (Boltzmann) answers,
 * written apart from methods/lgca from the rules as docs/methods/lgca.md
 * states them: the nodes' channels independent, each filled with its mean
 * occupation. grano compare holds the automaton to them (its own rows,
 * docs/comparison.md). Channel k < 6 moves along (sin 60k, cos 60k);
 * channel 6 is the rest particle. */
#ifndef GR_LATTICE_ORACLE_H
#define GR_LATTICE_ORACLE_H

/* FHP-III at rest under the gravity rule (probability g per node and
 * step), between a floor and a ceiling with `rows` fluid rows: the mean
 * occupation per channel of each row, d[0] (the row on the floor) ..
 * d[rows - 1], whose mean is dbar. The rules keep no energy, so every
 * channel of a row at rest holds the same d; the momentum flux through a
 * row, 3 d m c^2 / (a h), falls from one row to the next by the force of
 * gravity on them, m c / dt per node and event, at the mean of the two
 * rows' event rates g Q(d):
 *   3 (d_i - d_{i+1}) = g (Q(d_i) + Q(d_{i+1})) / 2,
 *   Q(d) = 1 - (1 - d (1 - d))^3,
 * Q the chance that one of the rule's three moves (rest to down, up-right
 * to down-right, up-left to down-left) finds its channel full and its
 * target empty. Returns 0, or -1 when no profile has that mean (dbar
 * outside (0, 1), g outside [0, 1]). */
int gr_lattice_column(double dbar, double g, int rows, double *d);

/* The granular rules' homogeneous cooling from moving occupation f0 per
 * channel and rest occupation r0, dissipation p, no gravity, no rest
 * collisions (stop = 0): the Boltzmann map applied `steps` times; *f and
 * *r the occupations after them. Only dissipation changes the movers: at
 * a node without a rest particle whose movers have the mass and momentum
 * of one or two states with one mover fewer and a rest particle (three or
 * more, the symmetric triple, stay elastic), a collision makes the rest
 * particle with probability p; propagation keeps a homogeneous state.
 * The moving population falls by f / f0. Returns 0, or -1 on arguments
 * outside [0, 1]. */
int gr_lattice_cooling(double f0, double r0, double p, long steps, double *f, double *r);

#endif
