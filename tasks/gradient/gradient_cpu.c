/* Gradient loops on the CPU: the loop skeleton (tasks/iact_loop.h) around
 * gradient_iact.h, and the extra ghost that finishes each solid particle
 * (extra_ghost_part.h, shared with the GPU).  theory/solids.md. */
#include "tasks/gradient/gradient_cpu.h"

#include "tasks/gradient/extra_ghost_part.h"
#include "tasks/hydro_parts.h"

/** Symmetric form: i gets j's contribution if r < H_i, j gets i's if r < H_j
 *  (a particle marked PART_INACTIVE, time bins, none). */
static inline void gradient_sym(struct parts *p, size_t i, size_t j, double r2, const double dx[3],
                                double hi, double hj) {
  const double Hi = kernel_gamma * hi, Hj = kernel_gamma * hj;
  if (r2 < Hi * Hi && !PART_IS_INACTIVE(p, i)) hydro_gradient_gather(p, i, j, r2, dx, 1.0 / hi);
  if (r2 < Hj * Hj && !PART_IS_INACTIVE(p, j)) {
    const double mdx[3] = {-dx[0], -dx[1], -dx[2]};
    hydro_gradient_gather(p, j, i, r2, mdx, 1.0 / hj);
  }
}

#define IACT_LOOP_NAME gradient
#define IACT_LOOP_SYM(p, i, j, r2, dx, hi, hj) gradient_sym(p, i, j, r2, dx, hi, hj)
#define IACT_LOOP_NONSYM(p, i, j, r2, dx, hi, hj) hydro_gradient_gather(p, i, j, r2, dx, 1.0 / (hi))
#include "tasks/iact_loop.h"

void gradient_self_cpu(struct parts *p, const struct cell *c) {
  loop_gradient_self(p, c);
}

void gradient_pair_cpu(struct parts *p, const struct cell *ci, const struct cell *cj,
                       const double shift[3]) {
  loop_gradient_pair(p, ci, cj, shift);
}

void gradient_gather_cpu(struct parts *p, const struct cell *ci, const struct cell *cj,
                         const double shift[3]) {
  if (ci == cj && shift[0] == 0.0 && shift[1] == 0.0 && shift[2] == 0.0)
    loop_gradient_self_gather(p, ci);
  else
    loop_gradient_pair_gather(p, ci, cj, shift);
}

void extra_ghost_part_cpu(struct parts *p, size_t i, const struct hydro_props *hp,
                          const struct material_table *mats) {
  extra_ghost_part(p, i, hp, mats);
}

void extra_ghost_cell_cpu(struct parts *p, const struct cell *c, const struct hydro_props *hp,
                          const struct material_table *mats) {
  const size_t end = c->offset + c->count;
  for (size_t i = c->offset; i < end; i++)
    if (!PART_IS_INACTIVE(p, i)) extra_ghost_part(p, i, hp, mats);
}
