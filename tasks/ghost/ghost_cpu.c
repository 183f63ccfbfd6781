/* The ghost task: smoothing-length iteration and equation of state for the
 * particles of one top-level cell (theory/architecture.md, "The task graph":
 * ghost completes the density sums, iterates the smoothing length towards
 * the target neighbour number, running density again for the particles that
 * need it, and evaluates the equation of state). */
#include "tasks/ghost/ghost_cpu.h"

#include <math.h>

#include "tasks/density/density_cpu.h"
#include "src/error.h"
#include "tasks/ghost/ghost_part.h"
#include "tasks/hydro/kernel.h"
#include "tasks/kick/kick.h"

int ghost_cell_cpu(struct parts *p, struct cell *c, const struct ghost_ngbs *ngbs,
                   const struct hydro_props *hp, const struct material_table *mats, double H_limit,
                   const struct ghost_wake *wake, long long *resummed) {
  const size_t beg = c->offset, end = c->offset + c->count;
  const double h_cap = H_limit / kernel_gamma;
  int capped = 0;
  size_t left = 0;
  *resummed = 0;
  for (size_t i = beg; i < end; i++) {
    if (PART_IS_INACTIVE(p, i)) { /* (time bins: it keeps its h and sums) */
      p->flags[i] |= PART_H_CONVERGED;
      if (wake && p->wake[i] > 0) {
        /* woken by the density phase: active from here on (kick.h) */
        kick_wake_part(p, i, wake->ti, wake->time_base, hp->solids);
        c->active++;
      }
      continue;
    }
    ghost_part_start(p, i);
    ghost_part_add_self(p, i);
    /* (a mirror ghost keeps its source's h, tasks/drift/drift_mirror.c; a
     * foreign copy its owner's, src/mpi/halo.c) */
    if (ghost_part_keeps_h(p, i)) continue;
    capped |= ghost_part_step(p, i, hp, h_cap);
    left += !(p->flags[i] & PART_H_CONVERGED);
  }
  for (int iter = 1; left > 0; iter++) {
    *resummed += (long long)left;
    if (iter > hp->max_iterations) {
      for (size_t i = beg; i < end; i++)
        if (!(p->flags[i] & PART_H_CONVERGED))
          error_exit(
              "smoothing length of particle %zu (id %lld) at (%g, %g, %g) did not converge in %d "
              "iterations (h = %g, bracket [%g, %g]); raise SPH:max_ghost_iterations or check "
              "the initial conditions",
              i, (long long)p->id[i], p->x[i], p->y[i], p->z[i], hp->max_iterations, p->h[i],
              p->h_lo[i], p->h_hi[i]);
    }
    /* redo the sums of the particles still iterating, with their new h */
    for (size_t i = beg; i < end; i++)
      if (!(p->flags[i] & PART_H_CONVERGED)) hydro_density_reset(p, i);
    cell_update_h_max(p, c);
    for (int k = 0; k < ngbs->n; k++)
      density_gather_unconverged_cpu(p, c, ngbs->cells[k], ngbs->shift[k]);
    left = 0;
    for (size_t i = beg; i < end; i++) {
      if (p->flags[i] & PART_H_CONVERGED) continue;
      ghost_part_add_self(p, i);
      capped |= ghost_part_step(p, i, hp, h_cap);
      left += !(p->flags[i] & PART_H_CONVERGED);
    }
  }
  cell_update_h_max(p, c);
  for (size_t i = beg; i < end; i++)
    if (!PART_IS_INACTIVE(p, i) && !(p->flags[i] & PART_WOKEN)) ghost_part_finish(p, i, hp, mats);
  return capped;
}
