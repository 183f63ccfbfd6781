/* Force loops on the CPU: the loop skeleton around force_iact.h.  The
 * symmetric form evaluates the terms a pair shares once (force_pair_eval:
 * the two kernels, the viscosity, the pressure term) and adds each side's
 * contribution (force_pair_side): the pair function combines i and j with
 * commutative operations only, so the two sides are what the gather
 * interaction gives for (i, j) and for (j, i), bit for bit, and the result
 * equals the gather form's (tests/unit/test_hydro_forms.c). */
#include "tasks/force/force_cpu.h"

#include "tasks/hydro_parts.h"

/** The hydro settings of the running loop (the skeleton's interaction macro
 *  has a fixed signature); thread-local so that tasks can run in parallel. */
static _Thread_local const struct hydro_props *force_hp;

/** What the symmetric loops cache of a neighbour j: its inputs and
 *  velocity as hydro_force_load reads them, whether it is inactive, and
 *  its sums (the only part written back). */
struct force_jcache {
  struct force_acc sum;
  struct force_in in;
  double v[3];
  int inactive;
};

BOLIDE_ALWAYS_INLINE void force_jcache_load(const struct parts *p, size_t j,
                                            struct force_jcache *c) {
  hydro_force_sums_load(p, j, &c->sum);
  hydro_force_load(p, j, &c->in, force_hp->solids);
  c->v[0] = p->vpx[j];
  c->v[1] = p->vpy[j];
  c->v[2] = p->vpz[j];
  c->inactive = PART_IS_INACTIVE(p, j);
}

/** Both sides of one interacting pair: i's (inputs in_i, velocity vi,
 *  active_i: not PART_INACTIVE) into its local accumulator acc_i, j's into
 *  the sums of its cache entry cj (a particle marked PART_INACTIVE, time
 *  bins, takes none). */
BOLIDE_ALWAYS_INLINE void force_sym(struct parts *p, size_t i, size_t j, double r2,
                                    const double dx[3], const struct force_in *in_i,
                                    const double vi[3], int active_i, struct force_acc *acc_i,
                                    struct force_jcache *cj) {
  if (r2 <= 0.0) return; /* coincident particles exert no pairwise force */
  const struct force_in *in_j = &cj->in;
  const double dv[3] = {vi[0] - cj->v[0], vi[1] - cj->v[1], vi[2] - cj->v[2]};
  struct force_pair pr;
  force_pair_eval(r2, dx, dv, in_i, in_j, force_hp, &pr);
  if (active_i) {
    force_pair_side(&pr, 0, dx, dv, in_i, in_j, force_hp, acc_i);
    if (force_hp->bin_limit) hydro_limiter_pair(p, i, j, force_hp->bin_limit, 0);
  }
  if (!cj->inactive) {
    const double mdx[3] = {-dx[0], -dx[1], -dx[2]};
    const double mdv[3] = {-dv[0], -dv[1], -dv[2]};
    struct force_acc aj;
    force_acc_zero(&aj);
    force_pair_side(&pr, 1, mdx, mdv, in_j, in_i, force_hp, &aj);
    force_acc_merge(&cj->sum, &aj);
    if (force_hp->bin_limit) hydro_limiter_pair(p, j, i, force_hp->bin_limit, 0);
  }
}

#define IACT_LOOP_NAME force
#define IACT_LOOP_ACC_BEGIN(p, i)                               \
  struct force_in in_i;                                         \
  hydro_force_load(p, i, &in_i, force_hp->solids);              \
  const double vi[3] = {(p)->vpx[i], (p)->vpy[i], (p)->vpz[i]}; \
  const int active_i = !PART_IS_INACTIVE(p, i);                 \
  struct force_acc acc_i;                                       \
  force_acc_zero(&acc_i)
#define IACT_LOOP_ACC_END(p, i) \
  if (active_i) hydro_force_add(p, i, &acc_i)
#define IACT_LOOP_JACC_T struct force_jcache
#define IACT_LOOP_JACC_LOAD(p, j, a) force_jcache_load(p, j, a)
#define IACT_LOOP_JACC_STORE(p, j, a) hydro_force_sums_store(p, j, &(a)->sum)
#define IACT_LOOP_ACC_END_J(p, i, ai) \
  if (active_i) force_acc_merge(&(ai)->sum, &acc_i)
#define IACT_LOOP_SYM(p, i, j, r2, dx, hi, hj) /* only the cached form is used */
#define IACT_LOOP_SYM_J(p, i, j, r2, dx, hi, hj, aj) \
  force_sym(p, i, j, r2, dx, &in_i, vi, active_i, &acc_i, aj)
#include "tasks/iact_loop.h"

void force_self_cpu(struct parts *p, const struct cell *c, const struct hydro_props *hp) {
  force_hp = hp;
  loop_force_self(p, c);
}

void force_pair_cpu(struct parts *p, const struct cell *ci, const struct cell *cj,
                    const double shift[3], const struct hydro_props *hp) {
  force_hp = hp;
  loop_force_pair(p, ci, cj, shift);
}
