/* The damage task on the GPU: one thread per particle running damage_part
 * (damage_part.h, the function the CPU task calls) with the flaw thresholds
 * resident in device memory (gpu_set_flaws). */
#include "tasks/damage/damage_part.h"
#include "src/gpu/gpu_kernels.h"

/** See damage_gpu_launch. */
__global__ void damage_gpu_kernel(struct parts p, const struct material_table *mats,
                                  const double *eps, double dt, struct gpu_bins bins) {
  const size_t i = (size_t)blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= p.count || PART_IS_INACTIVE(&p, i)) return;
  /* with time bins over the particle's own step (it ends now) */
  damage_part(&p, i, mats, eps,
              bins.on && !bins.first ? timeline_dt_of_bin(&bins.tl, p.time_bin[i]) : dt);
}

void damage_gpu_launch(cudaStream_t s, struct parts p, const struct material_table *mats,
                       const double *eps, double dt, struct gpu_bins bins) {
  if (p.count == 0) return;
  const unsigned nb = (unsigned)((p.count + GPU_BLOCK - 1) / GPU_BLOCK);
  damage_gpu_kernel<<<nb, GPU_BLOCK, 0, s>>>(p, mats, eps, dt, bins);
  gpu_check_launch(damage_gpu_kernel);
}

/** The damage family's step of the FORCE phase (tasks/task_families.h;
 *  brittle materials only): force -> damage -> kick2. */
int damage_gpu_phase(struct gpu_phase *ph) {
  damage_gpu_launch(ph->s, ph->dev, ph->mats, ph->flaws, ph->dmg_dt, ph->bins);
  return 0;
}
