/* Density loop on the GPU, gather form: one thread per particle i of a leaf
 * (one block per leaf) summing density_iact (density_iact.h, the function
 * the CPU loops call) over every j of the leaves in its neighbour list with
 * r < H_i.  Sums are accumulated in registers and stored once with
 * hydro_density_reset/hydro_density_add (hydro_parts.h). */
#include "src/gpu/gpu_kernels.h"
#include "tasks/hydro_parts.h"
#include "tasks/hydro/kernel.h"

/** See density_gpu_launch. */
__global__ void density_gpu_kernel(struct parts p, struct gpu_leaves_dev lv, int only_unconverged) {
  const int L = blockIdx.x;
  const size_t beg = lv.offset[L];
  const int cnt = lv.count[L];
  const int k0 = lv.ngb_start[L], k1 = lv.ngb_start[L + 1];
  const double *__restrict__ x = p.x, *__restrict__ y = p.y, *__restrict__ z = p.z;
  const double *__restrict__ m = p.m;
  const double *__restrict__ vx = p.vpx, *__restrict__ vy = p.vpy, *__restrict__ vz = p.vpz;
  for (int t = threadIdx.x; t < cnt; t += blockDim.x) {
    const size_t i = beg + (size_t)t;
    if (only_unconverged && (p.flags[i] & PART_H_CONVERGED)) continue;
    const double xi[3] = {x[i], y[i], z[i]}, vi[3] = {vx[i], vy[i], vz[i]};
    const double hi = p.h[i], hi_inv = 1.0 / hi, Hi = kernel_gamma * hi, Hi2 = Hi * Hi;
    struct density_acc a = {0, 0, 0, 0, 0, {0, 0, 0}};
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
          density_iact(r2, dx, hi_inv, m[j], dv, &a);
        }
      }
    }
    hydro_density_reset(&p, i);
    hydro_density_add(&p, i, &a);
  }
}

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
