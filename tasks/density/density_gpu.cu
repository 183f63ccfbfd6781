/* Density loop on the GPU, gather form: one thread per particle i of a leaf
 * (one block per leaf) summing density_iact (density_iact.h, the function
 * the CPU loops call) over every j of the leaves in its neighbour list with
 * r < H_i (the loop: tasks/iact_loop_gpu.h).  Sums are accumulated in registers and stored once
 * with hydro_density_reset/hydro_density_add (hydro_parts.h). */
#include "src/gpu/gpu_kernels.h"
#include "tasks/hydro_parts.h"
#include "tasks/hydro/kernel.h"

/** See density_gpu_launch. */
#define IACT_GPU_NAME density_gpu_kernel
#define IACT_GPU_PARAMS , int only_unconverged
#define IACT_GPU_SKIP(p, i) \
  (PART_IS_INACTIVE(&(p), i) || (only_unconverged && ((p).flags[i] & PART_H_CONVERGED)))
#define IACT_GPU_BEGIN(p, i)                                                            \
  const double hi = (p).h[i], hi_inv = 1.0 / hi, Hi = kernel_gamma * hi, Hi2 = Hi * Hi; \
  const double *__restrict__ m = (p).m;                                                 \
  struct density_acc a = {0, 0, 0, 0, 0, {0, 0, 0}}
#define IACT_GPU_PAIR(p, i, j, r2, dx, self)                            \
  if ((r2) < Hi2 && !(self)) {                                          \
    const double dv[3] = {vi[0] - vx[j], vi[1] - vy[j], vi[2] - vz[j]}; \
    density_iact(r2, dx, hi_inv, m[j], dv, &a);                         \
  }
#define IACT_GPU_REDUCE(mask, o)           \
  gpu_lanes_add(&a.rho, 1, mask, o);       \
  gpu_lanes_add(&a.rho_dh, 1, mask, o);    \
  gpu_lanes_add(&a.wcount, 1, mask, o);    \
  gpu_lanes_add(&a.wcount_dh, 1, mask, o); \
  gpu_lanes_add(&a.div_v, 1, mask, o);     \
  gpu_lanes_add(a.curl_v, 3, mask, o)
#define IACT_GPU_END(p, i)      \
  hydro_density_reset(&(p), i); \
  hydro_density_add(&(p), i, &a)
#include "tasks/iact_loop_gpu.h"

void density_gpu_launch(cudaStream_t s, struct parts p, struct gpu_leaves_dev lv,
                        int only_unconverged) {
  if (lv.n == 0) return;
  density_gpu_kernel<<<lv.n, lv.block, 0, s>>>(p, lv, only_unconverged);
  gpu_check_launch(density_gpu_kernel);
}

/** The density family's step of the FORCE phase (tasks/task_families.h):
 *  the sums of every particle (the ghost's step repeats them for the
 *  particles still iterating h). */
int density_gpu_phase(struct gpu_phase *ph) {
  density_gpu_launch(ph->s, ph->dev, ph->lv, 0);
  return 0;
}
