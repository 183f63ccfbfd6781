/* Near-field self-gravity on the GPU: the P2P interactions of the tree walk
 * (recorded by the CPU walk, gravity_p2p_record), gather form.  One block
 * per target leaf, one thread per particle i of it, summing gravity_p2p
 * (gravity_iact.h, the function of the CPU's direct summation) over every
 * particle j != i of the leaf's source leaves in registers; the sums are
 * added to the particle's potential and gravitational acceleration, which
 * already hold the far field of the walk. */
#include "gpu_kernels.h"
#include "gravity_iact.h"

/** See gravity_p2p_gpu_launch. */
__global__ void gravity_p2p_gpu_kernel(struct parts p, struct gpu_p2p_dev l, double G, double eps,
                                       int softening) {
  const int T = blockIdx.x;
  const size_t beg = l.t_offset[T];
  const int cnt = l.t_count[T];
  const int k0 = l.src_start[T], k1 = l.src_start[T + 1];
  const double *__restrict__ x = p.x, *__restrict__ y = p.y, *__restrict__ z = p.z;
  const double *__restrict__ m = p.m;
  for (int t = threadIdx.x; t < cnt; t += blockDim.x) {
    const size_t i = beg + (size_t)t;
    const double xi[3] = {x[i], y[i], z[i]};
    double pot = 0.0, a[3] = {0.0, 0.0, 0.0};
    for (int k = k0; k < k1; k++) {
      const size_t jb = l.s_offset[k], je = jb + (size_t)l.s_count[k];
      for (size_t j = jb; j < je; j++) {
        if (j == i) continue;
        const double dx[3] = {xi[0] - x[j], xi[1] - y[j], xi[2] - z[j]};
        const double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
        gravity_p2p(dx, r2, m[j], G, eps, softening, &pot, a);
      }
    }
    p.pot[i] += pot;
    p.gax[i] += a[0];
    p.gay[i] += a[1];
    p.gaz[i] += a[2];
  }
}

void gravity_p2p_gpu_launch(cudaStream_t s, struct parts p, struct gpu_p2p_dev l, double G,
                            double eps, int softening) {
  if (l.n == 0) return;
  gravity_p2p_gpu_kernel<<<l.n, l.block, 0, s>>>(p, l, G, eps, softening);
  gpu_check_launch(gravity_p2p_gpu_kernel);
}
