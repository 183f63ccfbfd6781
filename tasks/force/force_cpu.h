/* Force loops on the CPU (see force_cpu.c). */
#ifndef BOLIDE_FORCE_CPU_H
#define BOLIDE_FORCE_CPU_H

#include "src/cell.h"
#include "tasks/hydro/hydro_props.h"
#include "src/part.h"

/** Hydrodynamic forces between every pair of particles of c. */
void force_self_cpu(struct parts *p, const struct cell *c, const struct hydro_props *hp);
/** Forces between the particles of ci and of cj (at x_j + shift), both updated. */
void force_pair_cpu(struct parts *p, const struct cell *ci, const struct cell *cj,
                    const double shift[3], const struct hydro_props *hp);

#endif
