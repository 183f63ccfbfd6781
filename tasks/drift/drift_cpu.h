/* Kick and drift of a cell on the CPU. */
#ifndef BOLIDE_DRIFT_CPU_H
#define BOLIDE_DRIFT_CPU_H

#include "src/cell.h"
#include "src/part.h"
#include "src/timeline.h"

struct hydro_props;
struct material_table;
struct drift_stage;

/** First half kick by dt_kick, then drift by dt, of every particle of c;
 *  updates the cell's h_max and dx_max.  h_continuity: SPH:h_evolution:
 *  continuity (drift_part). */
void drift_cell_cpu(struct parts *p, struct cell *c, double dt_kick, double dt, double xsph,
                    double h_max, int h_continuity);

/** The same with individual time steps (TimeIntegration:global_step:
 *  false): every particle of c drifts from ti_old to ti_new on the time
 *  line tl (drift_part_bins; the sleeping ones' hydrodynamic state
 *  predicted with the SPH settings hp and the materials mats);
 *  c->active: the number of its particles that end their step at
 *  ti_new. */
void drift_cell_bins_cpu(struct parts *p, struct cell *c, const struct timeline *tl,
                         integertime_t ti_old, integertime_t ti_new, const struct hydro_props *hp,
                         const struct material_table *mats);

/** A stage of TimeIntegration:scheme rk2 or pc (drift_rk_stage, st) for
 *  every particle of c, the density accumulators zeroed and the cell's
 *  h_max and dx_max updated; returns the largest scaled error estimate
 *  of its particles (0 without st->err). */
double drift_cell_stage_cpu(struct parts *p, struct cell *c, const struct drift_stage *st,
                            const struct hydro_props *hp);

#endif
