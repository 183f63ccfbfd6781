/* Force loop on the GPU, gather form: one thread per particle i of a leaf
 * (one block per leaf) summing force_iact (force_iact.h, the function the
 * CPU loops call) over every j of its neighbour list with
 * 0 < r < max(H_i, H_j), the pairs the symmetric CPU loop visits.
 * force_iact combines i and j commutatively, so the result equals the CPU's
 * up to the order of the sums (force_iact.h, tests/test_gpu.c). */
#include "src/gpu/gpu_kernels.h"
#include "tasks/hydro_parts.h"
#include "tasks/hydro/kernel.h"

/** See force_gpu_launch. */
__global__ void force_gpu_kernel(struct parts p, struct gpu_leaves_dev lv, struct hydro_props hp) {
  const int L = blockIdx.x;
  const size_t beg = lv.offset[L];
  const int cnt = lv.count[L];
  const int k0 = lv.ngb_start[L], k1 = lv.ngb_start[L + 1];
  const double *__restrict__ x = p.x, *__restrict__ y = p.y, *__restrict__ z = p.z;
  const double *__restrict__ vx = p.vpx, *__restrict__ vy = p.vpy, *__restrict__ vz = p.vpz;
  const double *__restrict__ h = p.h;
  for (int t = threadIdx.x; t < cnt; t += blockDim.x) {
    const size_t i = beg + (size_t)t;
    const double xi[3] = {x[i], y[i], z[i]}, vi[3] = {vx[i], vy[i], vz[i]};
    const double Hi = kernel_gamma * h[i], Hi2 = Hi * Hi;
    struct force_in in_i, in_j;
    hydro_force_load(&p, i, &in_i, hp.solids);
    struct force_acc a = {{0, 0, 0}, 0, 0, 0};
    for (int k = k0; k < k1; k++) {
      const int J = lv.ngb_leaf[k];
      const double s[3] = {lv.ngb_shift[3 * k], lv.ngb_shift[3 * k + 1], lv.ngb_shift[3 * k + 2]};
      const size_t jb = lv.offset[J], je = jb + (size_t)lv.count[J];
      for (size_t j = jb; j < je; j++) {
        const double dx[3] = {(xi[0] - x[j]) - s[0], (xi[1] - y[j]) - s[1], (xi[2] - z[j]) - s[2]};
        const double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
        const double Hj = kernel_gamma * h[j];
        /* r2 > 0: coincident particles (and i itself) exert no pairwise force */
        if ((r2 < Hi2 || r2 < Hj * Hj) && r2 > 0.0) {
          hydro_force_load(&p, j, &in_j, hp.solids);
          const double dv[3] = {vi[0] - vx[j], vi[1] - vy[j], vi[2] - vz[j]};
          force_iact(r2, dx, dv, &in_i, &in_j, &hp, &a);
        }
      }
    }
    hydro_force_add(&p, i, &a);
  }
}

void force_gpu_launch(cudaStream_t s, struct parts p, struct gpu_leaves_dev lv,
                      struct hydro_props hp) {
  if (lv.n == 0) return;
  force_gpu_kernel<<<lv.n, lv.block, 0, s>>>(p, lv, hp);
  gpu_check_launch(force_gpu_kernel);
}

/** The force family's step of the FORCE phase (tasks/task_families.h). */
int force_gpu_phase(struct gpu_phase *ph) {
  force_gpu_launch(ph->s, ph->dev, ph->lv, ph->hp);
  return 0;
}
