/* Density loops on the CPU: the loop skeleton (tasks/iact_loop.h) around
 * the pair interaction of density_iact.h, symmetric form for the self and
 * pair tasks, gather form for the h iteration of the ghost.  Particle i's
 * sums are kept in a local accumulator over its inner loop. */
#include "tasks/density/density_cpu.h"

#include "tasks/density/density_wake.h"
#include "tasks/hydro_parts.h"

/* TimeIntegration:limiter_wake: density: what the symmetric loops of this
 * thread's task need to decide the wakes (NULL: none; density_task.c) */
static _Thread_local const struct density_wake *density_wk;

/** What the symmetric loops cache of a neighbour j: its velocity, mass,
 *  inverse smoothing length, whether it is inactive, and its sums (the only
 *  part written back). */
struct density_jcache {
  struct density_acc sum;
  double v[3], m, h_inv;
  int inactive;
};

BOLIDE_ALWAYS_INLINE void density_jcache_load(const struct parts *p, size_t j,
                                              struct density_jcache *c) {
  hydro_density_sums_load(p, j, &c->sum);
  c->v[0] = p->vpx[j];
  c->v[1] = p->vpy[j];
  c->v[2] = p->vpz[j];
  c->m = p->m[j];
  c->h_inv = 1.0 / p->h[j];
  c->inactive = PART_IS_INACTIVE(p, j);
}

/** Symmetric form: i (local accumulator acc_i, inverse smoothing length
 *  hi_inv, velocity vi, mass mi) gets j's contribution if r < H_i; j gets
 *  i's, in the sums of its cache entry cj, if r < H_j.  A particle marked
 *  PART_INACTIVE (time bins) takes no sums (IACT_LOOP_ACC_END drops i's). */
BOLIDE_ALWAYS_INLINE void density_sym(double r2, const double dx[3], double hi, double hi_inv,
                                      double hj, double mi, const double vi[3],
                                      struct density_acc *acc_i, struct density_jcache *cj) {
  const double Hi = kernel_gamma * hi, Hj = kernel_gamma * hj;
  const double dv[3] = {vi[0] - cj->v[0], vi[1] - cj->v[1], vi[2] - cj->v[2]};
  if (r2 < Hi * Hi) density_iact(r2, dx, hi_inv, cj->m, dv, acc_i);
  if (r2 < Hj * Hj && !cj->inactive) {
    struct density_acc a = {0, 0, 0, 0, 0, {0, 0, 0}};
    const double mdx[3] = {-dx[0], -dx[1], -dx[2]};
    const double mdv[3] = {-dv[0], -dv[1], -dv[2]};
    density_iact(r2, mdx, cj->h_inv, mi, mdv, &a);
    density_acc_merge(&cj->sum, &a);
  }
}

/** The wakes of the pair (i, j) (density_wake.h): the active one's
 *  support decides, within H_i for i active and j asleep, within H_j for
 *  the other way round; vi and cj->v the predicted velocities. */
BOLIDE_ALWAYS_INLINE void density_sym_wake(struct parts *p, size_t i, size_t j, double r2,
                                           const double dx[3], double hi, double hj,
                                           const double vi[3], const struct density_jcache *cj,
                                           const struct density_wake *wk) {
  const int inactive_i = PART_IS_INACTIVE(p, i) != 0;
  if (inactive_i == cj->inactive) return;
  const double dv[3] = {vi[0] - cj->v[0], vi[1] - cj->v[1], vi[2] - cj->v[2]};
  if (!inactive_i) {
    const double Hi = kernel_gamma * hi;
    if (r2 < Hi * Hi) density_wake_pair(p, i, j, r2, dx, dv, wk);
  } else {
    const double Hj = kernel_gamma * hj;
    const double mdx[3] = {-dx[0], -dx[1], -dx[2]}, mdv[3] = {-dv[0], -dv[1], -dv[2]};
    if (r2 < Hj * Hj) density_wake_pair(p, j, i, r2, mdx, mdv, wk);
  }
}

/** Gather form into the local accumulator of i. */
BOLIDE_ALWAYS_INLINE void density_gather(const struct parts *p, size_t j, double r2,
                                         const double dx[3], double hi_inv, const double vi[3],
                                         struct density_acc *acc_i) {
  const double dv[3] = {vi[0] - p->vpx[j], vi[1] - p->vpy[j], vi[2] - p->vpz[j]};
  density_iact(r2, dx, hi_inv, p->m[j], dv, acc_i);
}

#define IACT_LOOP_NAME density
#define IACT_LOOP_ACC_BEGIN(p, i)                               \
  struct density_acc acc_i = {0, 0, 0, 0, 0, {0, 0, 0}};        \
  const double vi[3] = {(p)->vpx[i], (p)->vpy[i], (p)->vpz[i]}; \
  const double hi_inv = 1.0 / (p)->h[i], mi = (p)->m[i];        \
  const struct density_wake *const wk_i = density_wk;           \
  (void)mi;                                                     \
  (void)wk_i
#define IACT_LOOP_ACC_END(p, i) \
  if (!PART_IS_INACTIVE(p, i)) hydro_density_add(p, i, &acc_i)
#define IACT_LOOP_JACC_T struct density_jcache
#define IACT_LOOP_JACC_LOAD(p, j, a) density_jcache_load(p, j, a)
#define IACT_LOOP_JACC_STORE(p, j, a) hydro_density_sums_store(p, j, &(a)->sum)
#define IACT_LOOP_ACC_END_J(p, i, ai) \
  if (!PART_IS_INACTIVE(p, i)) density_acc_merge(&(ai)->sum, &acc_i)
#define IACT_LOOP_SYM(p, i, j, r2, dx, hi, hj) /* only the cached form is used */
#define IACT_LOOP_SYM_J(p, i, j, r2, dx, hi, hj, aj)       \
  density_sym(r2, dx, hi, hi_inv, hj, mi, vi, &acc_i, aj); \
  if (wk_i) density_sym_wake(p, i, j, r2, dx, hi, hj, vi, aj, wk_i)
#define IACT_LOOP_NONSYM(p, i, j, r2, dx, hi, hj) density_gather(p, j, r2, dx, hi_inv, vi, &acc_i)
#define IACT_LOOP_ACTIVE(p, i) (!((p)->flags[i] & PART_H_CONVERGED))
#include "tasks/iact_loop.h"

void density_self_cpu(struct parts *p, const struct cell *c, const struct density_wake *wake) {
  density_wk = wake;
  loop_density_self(p, c);
  density_wk = NULL;
}

void density_pair_cpu(struct parts *p, const struct cell *ci, const struct cell *cj,
                      const double shift[3], const struct density_wake *wake) {
  density_wk = wake;
  loop_density_pair(p, ci, cj, shift);
  density_wk = NULL;
}

void density_gather_unconverged_cpu(struct parts *p, const struct cell *ci, const struct cell *cj,
                                    const double shift[3]) {
  if (ci == cj && shift[0] == 0.0 && shift[1] == 0.0 && shift[2] == 0.0)
    loop_density_self_gather(p, ci);
  else
    loop_density_pair_gather(p, ci, cj, shift);
}
