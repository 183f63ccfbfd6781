/* Density loops on the CPU (see density_cpu.c). */
#ifndef BOLIDE_DENSITY_CPU_H
#define BOLIDE_DENSITY_CPU_H

#include "src/cell.h"
#include "src/part.h"

struct density_wake;

/** Density sums between every pair of particles of c (symmetric form).
 *  wake: with TimeIntegration:limiter_wake: density in a step of time
 *  bins, the limiter's wakes are decided here too (density_wake.h; NULL:
 *  none). */
void density_self_cpu(struct parts *p, const struct cell *c, const struct density_wake *wake);
/** Density sums between the particles of ci and those of cj (seen at
 *  x_j + shift), both sides updated; wake as density_self_cpu's. */
void density_pair_cpu(struct parts *p, const struct cell *ci, const struct cell *cj,
                      const double shift[3], const struct density_wake *wake);
/** Gather form for the particles of ci whose h has not converged
 *  (PART_H_CONVERGED clear), from the particles of cj (ci itself when cj ==
 *  ci and shift is zero). */
void density_gather_unconverged_cpu(struct parts *p, const struct cell *ci, const struct cell *cj,
                                    const double shift[3]);

#endif
