/* Force loop on the GPU, gather form: the threads of particle i of a leaf
 * (one block per leaf) summing force_iact (force_iact.h, the function the
 * CPU loops call) over every j of its neighbour list with
 * 0 < r < max(H_i, H_j), the pairs the symmetric CPU loop visits.
 * force_iact combines i and j commutatively, so the result equals the CPU's
 * up to the order of the sums (force_iact.h, tests/gpu/test_gpu.c).  The loop:
 * tasks/iact_loop_gpu.h. */
#include "src/gpu/gpu_kernels.h"
#include "tasks/hydro_parts.h"
#include "tasks/hydro/kernel.h"

/** See force_gpu_launch.  r2 > 0: coincident particles (and i itself)
 *  exert no pairwise force.  The macros read the settings as hp, a copy
 *  of the kernel's argument hp_run (IACT_GPU_BEGIN below). */
#define FORCE_GPU_BEGIN(p, i)                           \
  const double *__restrict__ h = (p).h;                 \
  const double Hi = kernel_gamma * h[i], Hi2 = Hi * Hi; \
  struct force_in in_i, in_j;                           \
  hydro_force_load(&(p), i, &in_i, hp.solids);          \
  struct force_acc a = {{0, 0, 0}, 0, 0, 0}
#define FORCE_GPU_PAIR(p, i, j, r2, dx, self)                             \
  {                                                                       \
    const double Hj = kernel_gamma * h[j];                                \
    if (((r2) < Hi2 || (r2) < Hj * Hj) && (r2) > 0.0) {                   \
      hydro_force_load(&(p), j, &in_j, hp.solids);                        \
      const double dv[3] = {vi[0] - vx[j], vi[1] - vy[j], vi[2] - vz[j]}; \
      force_iact(r2, dx, dv, &in_i, &in_j, &hp, &a);                      \
      if (hp.bin_limit) hydro_limiter_pair(&(p), i, j, hp.bin_limit, 1);  \
    }                                                                     \
  }
#define FORCE_GPU_REDUCE(mask, o)        \
  gpu_lanes_add(a.a, 3, mask, o);        \
  gpu_lanes_add(&a.du_dt, 1, mask, o);   \
  gpu_lanes_add(&a.drho_dt, 1, mask, o); \
  gpu_lanes_max(&a.v_sig, mask, o);      \
  gpu_lanes_add(a.xsph, 3, mask, o)

/* runs with strength (hp_run.solids) */
#define IACT_GPU_NAME force_gpu_kernel
#define IACT_GPU_SKIP(p, i) PART_IS_INACTIVE(&(p), i)
#define IACT_GPU_PARAMS , struct hydro_props hp_run
#define IACT_GPU_BEGIN(p, i)            \
  const struct hydro_props hp = hp_run; \
  FORCE_GPU_BEGIN(p, i)
#define IACT_GPU_PAIR FORCE_GPU_PAIR
#define IACT_GPU_REDUCE FORCE_GPU_REDUCE
#define IACT_GPU_END(p, i) hydro_force_add(&(p), i, &a)
#include "tasks/iact_loop_gpu.h"

/* runs without (the same loop with solids a constant 0: the compiler
 * drops the stress terms and their registers, 200 of them per thread with
 * both, and more warps fit on a multiprocessor) */
#define IACT_GPU_NAME force_fluid_gpu_kernel
#define IACT_GPU_SKIP(p, i) PART_IS_INACTIVE(&(p), i)
#define IACT_GPU_PARAMS , struct hydro_props hp_run
#define IACT_GPU_BEGIN(p, i)      \
  struct hydro_props hp = hp_run; \
  hp.solids = 0;                  \
  FORCE_GPU_BEGIN(p, i)
#define IACT_GPU_PAIR FORCE_GPU_PAIR
#define IACT_GPU_REDUCE FORCE_GPU_REDUCE
#define IACT_GPU_END(p, i) hydro_force_add(&(p), i, &a)
#include "tasks/iact_loop_gpu.h"

void force_gpu_launch(cudaStream_t s, struct parts p, struct gpu_leaves_dev lv,
                      struct hydro_props hp) {
  if (lv.n == 0) return;
  if (hp.solids) {
    force_gpu_kernel<<<lv.n, lv.block, 0, s>>>(p, lv, hp);
    gpu_check_launch(force_gpu_kernel);
  } else {
    force_fluid_gpu_kernel<<<lv.n, lv.block, 0, s>>>(p, lv, hp);
    gpu_check_launch(force_fluid_gpu_kernel);
  }
}

/** The force family's step of the FORCE phase (tasks/task_families.h). */
int force_gpu_phase(struct gpu_phase *ph) {
  force_gpu_launch(ph->s, ph->dev, ph->lv, ph->hp);
  return 0;
}
