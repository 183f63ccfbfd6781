/* Density loops on the CPU: the loop skeleton (tasks/iact_loop.h) around
 * the pair interaction of density_iact.h, symmetric form for the self and
 * pair tasks, gather form for the h iteration of the ghost. */
#include "density_cpu.h"

#include "hydro_parts.h"

/** Symmetric form: i gets j's contribution if r < H_i, j gets i's if r < H_j. */
static inline void density_sym(struct parts *p, size_t i, size_t j, double r2, const double dx[3],
                               double hi, double hj) {
  const double Hi = kernel_gamma * hi, Hj = kernel_gamma * hj;
  if (r2 < Hi * Hi) hydro_density_gather(p, i, j, r2, dx, 1.0 / hi);
  if (r2 < Hj * Hj) {
    const double mdx[3] = {-dx[0], -dx[1], -dx[2]};
    hydro_density_gather(p, j, i, r2, mdx, 1.0 / hj);
  }
}

#define IACT_LOOP_NAME density
#define IACT_LOOP_SYM(p, i, j, r2, dx, hi, hj) density_sym(p, i, j, r2, dx, hi, hj)
#define IACT_LOOP_NONSYM(p, i, j, r2, dx, hi, hj) hydro_density_gather(p, i, j, r2, dx, 1.0 / (hi))
#define IACT_LOOP_ACTIVE(p, i) (!((p)->flags[i] & PART_H_CONVERGED))
#include "iact_loop.h"

void density_self_cpu(struct parts *p, const struct cell *c) {
  loop_density_self(p, c);
}

void density_pair_cpu(struct parts *p, const struct cell *ci, const struct cell *cj,
                      const double shift[3]) {
  loop_density_pair(p, ci, cj, shift);
}

void density_gather_unconverged_cpu(struct parts *p, const struct cell *ci, const struct cell *cj,
                                    const double shift[3]) {
  if (ci == cj && shift[0] == 0.0 && shift[1] == 0.0 && shift[2] == 0.0)
    loop_density_self_gather(p, ci);
  else
    loop_density_pair_gather(p, ci, cj, shift);
}
