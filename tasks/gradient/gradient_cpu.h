/* Gradient loops and the extra ghost on the CPU (see gradient_cpu.c). */
#ifndef BOLIDE_GRADIENT_CPU_H
#define BOLIDE_GRADIENT_CPU_H

#include "src/cell.h"
#include "tasks/hydro/hydro_props.h"
#include "src/part.h"

struct material_table;

/** Gradient sums between every pair of particles of c (symmetric form). */
void gradient_self_cpu(struct parts *p, const struct cell *c);
/** Gradient sums between the particles of ci and cj (at x_j + shift), both
 *  sides updated. */
void gradient_pair_cpu(struct parts *p, const struct cell *ci, const struct cell *cj,
                       const double shift[3]);
/** Gather form: the particles of ci from those of cj (ci itself when cj ==
 *  ci and the shift is zero); the GPU's form and the tests' reference. */
void gradient_gather_cpu(struct parts *p, const struct cell *ci, const struct cell *cj,
                         const double shift[3]);
/** The extra ghost of one cell: corrected velocity gradient, yield (radial
 *  return, plastic strain), dS/dt and artificial stress of each particle. */
void extra_ghost_cell_cpu(struct parts *p, const struct cell *c, const struct hydro_props *hp,
                          const struct material_table *mats);
/** The same for one particle (tests). */
void extra_ghost_part_cpu(struct parts *p, size_t i, const struct hydro_props *hp,
                          const struct material_table *mats);

#endif
