/* Kick and drift of a cell on the CPU. */
#ifndef BOLIDE_DRIFT_CPU_H
#define BOLIDE_DRIFT_CPU_H

#include "src/cell.h"
#include "src/part.h"

/** First half kick by dt_kick, then drift by dt, of every particle of c;
 *  updates the cell's h_max and dx_max.  h_continuity: SPH:h_evolution:
 *  continuity (drift_part). */
void drift_cell_cpu(struct parts *p, struct cell *c, double dt_kick, double dt, double xsph,
                    double h_max, int h_continuity);

#endif
