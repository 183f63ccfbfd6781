/* First half kick and drift on the GPU, one thread per particle, with
 * kick_part and drift_part (drift.h), the functions the CPU drift task
 * calls.  The density sums need no zeroing here: the density kernel writes
 * them whole. */
#include "tasks/drift/drift.h"
#include "tasks/drift/drift_rk.h"
#include "src/gpu/gpu_kernels.h"

/** See drift_gpu_launch. */
__global__ void drift_gpu_kernel(struct parts p, double dt_kick, double dt, double xsph,
                                 double h_max, int h_continuity) {
  const size_t i = (size_t)blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= p.count) return;
  /* (several MPI ranks: a foreign copy takes its state from its owner's
   * refreshes, as in drift_cell_cpu) */
  if (p.flags[i] & PART_FOREIGN) return;
  kick_part(&p, i, dt_kick);
  /* XSPH sums of the last force kernel (force_iact.h) */
  drift_part(&p, i, dt, xsph, h_max, h_continuity);
}

void drift_gpu_launch(cudaStream_t s, struct parts p, double dt_kick, double dt, double xsph,
                      double h_max, int h_continuity) {
  if (p.count == 0) return;
  const unsigned nb = (unsigned)((p.count + GPU_BLOCK - 1) / GPU_BLOCK);
  drift_gpu_kernel<<<nb, GPU_BLOCK, 0, s>>>(p, dt_kick, dt, xsph, h_max, h_continuity);
  gpu_check_launch(drift_gpu_kernel);
}

/** See drift_bins_gpu_launch. */
__global__ void drift_bins_gpu_kernel(struct parts p, double time_base, integertime_t ti_old,
                                      integertime_t ti_new, struct hydro_props hp,
                                      const struct material_table *mats) {
  const size_t i = (size_t)blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= p.count) return;
  drift_part_bins(&p, i, time_base, ti_old, ti_new, &hp, mats);
}

void drift_bins_gpu_launch(cudaStream_t s, struct parts p, const struct gpu_bins *bins,
                           struct hydro_props hp, const struct material_table *mats) {
  if (p.count == 0) return;
  const unsigned nb = (unsigned)((p.count + GPU_BLOCK - 1) / GPU_BLOCK);
  drift_bins_gpu_kernel<<<nb, GPU_BLOCK, 0, s>>>(p, bins->tl.time_base, bins->ti_old, bins->ti_new,
                                                 hp, mats);
  gpu_check_launch(drift_bins_gpu_kernel);
}

/** See drift_stage_gpu_launch: one thread per particle, the block's largest
 *  error estimate into *err (non-negative doubles order as their bits). */
__global__ void drift_stage_gpu_kernel(struct parts p, struct drift_stage st, struct hydro_props hp,
                                       unsigned long long *err) {
  __shared__ double e_max[GPU_BLOCK];
  const size_t i = (size_t)blockIdx.x * blockDim.x + threadIdx.x;
  double e = 0.0;
  if (i < p.count) e = drift_rk_stage(&p, i, &st, &hp);
  e_max[threadIdx.x] = e;
  __syncthreads();
  for (int k = blockDim.x / 2; k > 0; k /= 2) {
    if ((int)threadIdx.x < k && e_max[threadIdx.x + k] > e_max[threadIdx.x])
      e_max[threadIdx.x] = e_max[threadIdx.x + k];
    __syncthreads();
  }
  if (threadIdx.x == 0 && e_max[0] > 0.0)
    atomicMax(err, (unsigned long long)__double_as_longlong(e_max[0]));
}

void drift_stage_gpu_launch(cudaStream_t s, struct parts p, const struct drift_stage *st,
                            struct hydro_props hp, unsigned long long *err) {
  if (p.count == 0) return;
  const unsigned nb = (unsigned)((p.count + GPU_BLOCK - 1) / GPU_BLOCK);
  drift_stage_gpu_kernel<<<nb, GPU_BLOCK, 0, s>>>(p, *st, hp, err);
  gpu_check_launch(drift_stage_gpu_kernel);
}

/** See drift_restore_gpu_launch. */
__global__ void drift_restore_gpu_kernel(struct parts p, const double *y0, const double *r1) {
  const size_t i = (size_t)blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= p.count) return;
  drift_rk_restore(&p, i, y0 + (size_t)DRIFT_RK_NY * i, r1 + (size_t)DRIFT_RK_NR * i);
}

void drift_restore_gpu_launch(cudaStream_t s, struct parts p, const double *y0, const double *r1) {
  if (p.count == 0) return;
  const unsigned nb = (unsigned)((p.count + GPU_BLOCK - 1) / GPU_BLOCK);
  drift_restore_gpu_kernel<<<nb, GPU_BLOCK, 0, s>>>(p, y0, r1);
  gpu_check_launch(drift_restore_gpu_kernel);
}
