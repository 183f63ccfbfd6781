/* Gradient loop and extra ghost on the GPU (solids).  The loop is the gather
 * form: one thread per particle i of a leaf (one block per leaf) summing
 * gradient_iact (gradient_iact.h, the function the CPU loops call) over
 * every j of its neighbour list with r < H_i, in registers, added once with
 * hydro_gradient_add (the ghost zeroed the sums; the loop:
 * tasks/iact_loop_gpu.h).  The extra ghost runs
 * extra_ghost_part (extra_ghost_part.h, the CPU task's function) on every
 * particle: corrected velocity gradient, plasticity, dS/dt, artificial
 * stress. */
#include "tasks/gradient/extra_ghost_part.h"
#include "src/gpu/gpu_kernels.h"
#include "tasks/hydro_parts.h"
#include "tasks/hydro/kernel.h"

/** See gradient_gpu_launch. */
#define IACT_GPU_NAME gradient_gpu_kernel
#define IACT_GPU_SKIP(p, i) PART_IS_INACTIVE(&(p), i)
#define IACT_GPU_BEGIN(p, i)                                                         \
  const double hi_inv = 1.0 / (p).h[i], Hi = kernel_gamma * (p).h[i], Hi2 = Hi * Hi; \
  const double *__restrict__ m = (p).m, *__restrict__ rho = (p).rho;                 \
  struct gradient_acc a = {{0, 0, 0, 0, 0, 0}, {0, 0, 0, 0, 0, 0, 0, 0, 0}, 0}
#define IACT_GPU_PAIR(p, i, j, r2, dx, self)                            \
  if ((r2) < Hi2 && !(self)) {                                          \
    const double dv[3] = {vi[0] - vx[j], vi[1] - vy[j], vi[2] - vz[j]}; \
    gradient_iact(r2, dx, hi_inv, m[j] / rho[j], dv, &a);               \
  }
#define IACT_GPU_REDUCE(mask, o)  \
  gpu_lanes_add(a.M, 6, mask, o); \
  gpu_lanes_add(a.G, 9, mask, o); \
  gpu_lanes_add(&a.Z, 1, mask, o)
#define IACT_GPU_END(p, i) hydro_gradient_add(&(p), i, &a)
#include "tasks/iact_loop_gpu.h"

/** See extra_ghost_gpu_launch. */
__global__ void extra_ghost_gpu_kernel(struct parts p, struct hydro_props hp,
                                       const struct material_table *mats) {
  const size_t i = (size_t)blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= p.count || PART_IS_INACTIVE(&p, i)) return;
  extra_ghost_part(&p, i, &hp, mats);
}

void gradient_gpu_launch(cudaStream_t s, struct parts p, struct gpu_leaves_dev lv) {
  if (lv.n == 0) return;
  gradient_gpu_kernel<<<lv.n, lv.block, 0, s>>>(p, lv);
  gpu_check_launch(gradient_gpu_kernel);
}

void extra_ghost_gpu_launch(cudaStream_t s, struct parts p, struct hydro_props hp,
                            const struct material_table *mats) {
  if (p.count == 0) return;
  const unsigned nb = (unsigned)((p.count + GPU_BLOCK - 1) / GPU_BLOCK);
  extra_ghost_gpu_kernel<<<nb, GPU_BLOCK, 0, s>>>(p, hp, mats);
  gpu_check_launch(extra_ghost_gpu_kernel);
}

/** The gradient family's step of the FORCE phase (tasks/task_families.h;
 *  solids only): ghost -> gradient -> extra ghost -> force (engine_graph.c). */
int gradient_gpu_phase(struct gpu_phase *ph) {
  gradient_gpu_launch(ph->s, ph->dev, ph->lv);
  extra_ghost_gpu_launch(ph->s, ph->dev, ph->hp, ph->mats);
  return 0;
}
