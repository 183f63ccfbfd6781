/* The GPU twin of tasks/iact_loop.h: the neighbour loop of the hydro
 * kernels, written once for the density, gradient and force families.
 *
 * One block per leaf; i visits every particle j of the leaves in its
 * neighbour list (struct gpu_leaves_dev), each at its periodic image, in
 * the gather form (i's sums only, kept in registers).  A leaf of cnt
 * particles takes g lanes per particle, g the largest power of two with
 * g cnt <= the block's threads (1 for a leaf as large as the block): lane
 * s of i's group takes the particles s, s + g, ... of each neighbour leaf,
 * and the group's g partial sums are then added by a butterfly of
 * shuffles (IACT_GPU_REDUCE), in a fixed order, so the result is
 * reproducible.  Without it a leaf of the mean size, 10 to 20 particles at
 * the gravity tree's leaves, left half of each warp idle.  A family names
 * its kernel and its interaction, then includes this header in its .cu
 * file:
 *
 *   #define IACT_GPU_NAME density_gpu_kernel
 *   #define IACT_GPU_PARAMS , int only_unconverged     (extra kernel parameters)
 *   #define IACT_GPU_SKIP(p, i) (only_unconverged && ((p).flags[i] & PART_H_CONVERGED))
 *   #define IACT_GPU_BEGIN(p, i) ...                   (declares i's accumulator)
 *   #define IACT_GPU_PAIR(p, i, j, r2, dx, self) ...  (one j; self: j is i itself)
 *   #define IACT_GPU_REDUCE(mask, o) ...              (adds lane ^ o's accumulator
 *                                                       to this lane's, __shfl_xor_sync)
 *   #define IACT_GPU_END(p, i) ...                     (stores the accumulator)
 *   #include "tasks/iact_loop_gpu.h"
 *
 * which defines
 *
 *   __global__ void IACT_GPU_NAME(struct parts p, struct gpu_leaves_dev lv IACT_GPU_PARAMS);
 *
 * In the macros: p the particles (by value, device arrays), i and j
 * indices, r2 = |dx|^2 and dx (const double[3]) = (x_i - x_j) - shift, the
 * CPU loops' expression so that distances agree bit for bit; xi[3] and
 * vi[3] hold i's position and predicted velocity, x, y, z, vx, vy, vz the
 * arrays (restrict pointers); self is 1 when j is i in the unshifted leaf.
 * IACT_GPU_SKIP is optional (default: no particle skipped).  The macros are
 * undefined at the end, so the header can be included again. */
#include "src/gpu/gpu_kernels.h"
#include "src/gpu/gpu_lists.h"

#ifndef IACT_GPU_NAME
#error "define IACT_GPU_NAME before including iact_loop_gpu.h"
#endif
#ifndef IACT_GPU_PARAMS
#define IACT_GPU_PARAMS
#endif
#ifndef IACT_GPU_SKIP
#define IACT_GPU_SKIP(p, i) 0
#endif

__global__ void IACT_GPU_NAME(struct parts p, struct gpu_leaves_dev lv IACT_GPU_PARAMS) {
  const int L = blockIdx.x;
  const size_t beg = lv.offset[L];
  const int cnt = lv.count[L];
  const int k0 = lv.ngb_start[L], k1 = lv.ngb_start[L + 1];
  const double *__restrict__ x = p.x, *__restrict__ y = p.y, *__restrict__ z = p.z;
  const double *__restrict__ vx = p.vpx, *__restrict__ vy = p.vpy, *__restrict__ vz = p.vpz;
  /* g lanes per particle, lane sub of the group (gpu_lanes_of) */
  const int B = (int)blockDim.x;
  const struct gpu_lanes ln = gpu_lanes_of(cnt);
  const int g = ln.g, sub = ln.sub;
  const unsigned mask = ln.mask;
  (void)mask;
  for (int t = (int)threadIdx.x / g; t < cnt; t += B / g) {
    const size_t i = beg + (size_t)t;
    if (IACT_GPU_SKIP(p, i)) continue; /* (the whole group: the same i) */
    const double xi[3] = {x[i], y[i], z[i]}, vi[3] = {vx[i], vy[i], vz[i]};
    IACT_GPU_BEGIN(p, i);
    for (int k = k0; k < k1; k++) {
      const int J = lv.ngb_leaf[k];
      double s[3];
      gpu_shift_of(lv.ngb_code[k], lv.dim, s);
      const int unshifted = (s[0] == 0.0 && s[1] == 0.0 && s[2] == 0.0);
      (void)unshifted; /* (a family may test r2 > 0 instead of self) */
      const size_t jb = lv.offset[J], je = jb + (size_t)lv.count[J];
      for (size_t j = jb + (size_t)sub; j < je; j += (size_t)g) {
        const double dx[3] = {(xi[0] - x[j]) - s[0], (xi[1] - y[j]) - s[1], (xi[2] - z[j]) - s[2]};
        const double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
        IACT_GPU_PAIR(p, i, j, r2, dx, (unshifted && j == i));
      }
    }
    for (int o = g / 2; o > 0; o /= 2) {
      IACT_GPU_REDUCE(mask, o);
    }
    if (sub == 0) {
      IACT_GPU_END(p, i);
    }
  }
}

#undef IACT_GPU_NAME
#undef IACT_GPU_PARAMS
#undef IACT_GPU_SKIP
#undef IACT_GPU_BEGIN
#undef IACT_GPU_PAIR
#undef IACT_GPU_REDUCE
#undef IACT_GPU_END
