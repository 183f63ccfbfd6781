/* Gradient loop and extra ghost on the GPU (solids).  The loop is the gather
 * form: one thread per particle i of a leaf (one block per leaf) summing
 * gradient_iact (gradient_iact.h, the function the CPU loops call) over
 * every j of its neighbour list with r < H_i, in registers, added once with
 * hydro_gradient_add (the ghost zeroed the sums).  The extra ghost runs
 * extra_ghost_part (extra_ghost_part.h, the CPU task's function) on every
 * particle: corrected velocity gradient, plasticity, dS/dt, artificial
 * stress. */
#include "tasks/gradient/extra_ghost_part.h"
#include "src/gpu/gpu_kernels.h"
#include "tasks/hydro_parts.h"
#include "tasks/hydro/kernel.h"

/** See gradient_gpu_launch. */
__global__ void gradient_gpu_kernel(struct parts p, struct gpu_leaves_dev lv) {
  const int L = blockIdx.x;
  const size_t beg = lv.offset[L];
  const int cnt = lv.count[L];
  const int k0 = lv.ngb_start[L], k1 = lv.ngb_start[L + 1];
  const double *__restrict__ x = p.x, *__restrict__ y = p.y, *__restrict__ z = p.z;
  const double *__restrict__ m = p.m, *__restrict__ rho = p.rho;
  const double *__restrict__ vx = p.vpx, *__restrict__ vy = p.vpy, *__restrict__ vz = p.vpz;
  for (int t = threadIdx.x; t < cnt; t += blockDim.x) {
    const size_t i = beg + (size_t)t;
    const double xi[3] = {x[i], y[i], z[i]}, vi[3] = {vx[i], vy[i], vz[i]};
    const double hi_inv = 1.0 / p.h[i], Hi = kernel_gamma * p.h[i], Hi2 = Hi * Hi;
    struct gradient_acc a = {{0, 0, 0, 0, 0, 0}, {0, 0, 0, 0, 0, 0, 0, 0, 0}, 0};
    for (int k = k0; k < k1; k++) {
      const int J = lv.ngb_leaf[k];
      const double s[3] = {lv.ngb_shift[3 * k], lv.ngb_shift[3 * k + 1], lv.ngb_shift[3 * k + 2]};
      const int unshifted = (s[0] == 0.0 && s[1] == 0.0 && s[2] == 0.0);
      const size_t jb = lv.offset[J], je = jb + (size_t)lv.count[J];
      for (size_t j = jb; j < je; j++) {
        /* the CPU loops' expression, so that distances agree bit for bit */
        const double dx[3] = {(xi[0] - x[j]) - s[0], (xi[1] - y[j]) - s[1], (xi[2] - z[j]) - s[2]};
        const double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
        if (r2 < Hi2 && !(unshifted && j == i)) {
          const double dv[3] = {vi[0] - vx[j], vi[1] - vy[j], vi[2] - vz[j]};
          gradient_iact(r2, dx, hi_inv, m[j] / rho[j], dv, &a);
        }
      }
    }
    hydro_gradient_add(&p, i, &a);
  }
}

/** See extra_ghost_gpu_launch. */
__global__ void extra_ghost_gpu_kernel(struct parts p, struct hydro_props hp,
                                       const struct material_table *mats) {
  const size_t i = (size_t)blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= p.count) return;
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
