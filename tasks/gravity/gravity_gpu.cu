/* Self-gravity on the GPU: the operators of the fast multipole method on
 * the recorded interactions (of the CPU's walks, gravity_gpu_record, or of
 * the device's, gravity_tree_gpu.cu) and on the cell tree as index arrays
 * (tasks/gravity/gpu_gravity.cu uploads or groups both).  Each kernel calls the inline
 * operators of gravity_iact.h that the CPU walk calls (gravity_derivatives,
 * gravity_m2l, gravity_m2p_p2l, gravity_l2l, gravity_l2p, gravity_p2p),
 * with the expansion order a template constant so that nvcc unrolls their
 * loops as gcc does for gravity_cpu.c's M2L_ORDER.
 *
 *   field kernel: one warp per cell, its M2L and P2L summed in
 *                 registers by the lanes, added across the warp, then
 *                 stored (the cells' expansions start at 0)
 *   L2L kernel:   one thread per parent-child pair of one tree level, the
 *                 levels one launch after the other (parents first)
 *   P2P, M2P:     one block per leaf, one thread per particle (a small
 *                 leaf's idle threads take slices of its sources),
 *                 its P2P (gather form: a leaf with itself skips i == j),
 *                 then (second kernel) its M2P summed in registers, added
 *                 to pot and ga
 *   L2P kernel:   one block per leaf, one thread per particle.
 *
 * Compared with the CPU the sums run in another order (the CPU adds each
 * interaction to the field or particle as the walk meets it): the results
 * differ by round-off (tests/gpu/test_gpu.c). */
#define GRAVITY_UNROLL_LOOPS 1
#include "src/gpu/gpu_kernels.h"
#include "tasks/gravity/gravity_gpu.h"
#include "tasks/gravity/gravity_iact.h"

/** Every cell c with sources: the M2L of its multipole sources and the P2L
 *  of its leaf sources (struct gravity_gpu_rec.field), stored as its field.
 *  One warp per cell: lane l takes the sources l, l + 32, ... of the list
 *  (a cell has hundreds: the lanes stay busy whatever the lists' lengths),
 *  sums them in registers, and the warp adds the 32 partial fields by a
 *  butterfly of shuffles (every lane ends with the same sums; the order is
 *  fixed, so the result is reproducible). */
template <int P>
__global__ void gravity_field_gpu_kernel(struct parts p, struct gravity_gpu_dev d,
                                         struct gravity_gpu_groups l) {
  const int lane = threadIdx.x & 31;
  const int c = (int)((blockIdx.x * (size_t)blockDim.x + threadIdx.x) >> 5);
  if (c >= l.nr_cells) return; /* the whole warp */
  const int *__restrict__ src = l.source + l.start[c];
  const int ns = (int)(l.start[c + 1] - l.start[c]); /* (one cell's: fewer than 2^31) */
  if (ns == 0) return;
  const struct gravity_multipole *mc = d.mp + c;
  const double zc[3] = {mc->com[0], mc->com[1], mc->com[2]};
  struct gravity_field f;
#pragma unroll
  for (int i = 0; i < GRAVITY_NCOMP(P); i++) f.F[i] = 0.0;
  for (int k = lane; k < ns; k += 32) {
    const int s = src[k];
    double D[GRAVITY_NCOMP(P)];
    if (s >= 0) {
      /* M2L, one way: target c, source s, the tensor at z_c - z_s */
      const struct gravity_multipole *ms = d.mp + s;
      const double R[3] = {zc[0] - ms->com[0], zc[1] - ms->com[1], zc[2] - ms->com[2]};
      gravity_derivatives(R, d.eps2, P, D);
      gravity_m2l(&f, ms, D, P);
    } else {
      /* P2L: every particle of leaf -1 - s as a point mass */
      const int q = -1 - s;
      const size_t j1 = d.offset[q] + (size_t)d.count[q];
      for (size_t j = d.offset[q]; j < j1; j++) {
        const double R[3] = {zc[0] - p.x[j], zc[1] - p.y[j], zc[2] - p.z[j]};
        double pot = 0.0, a[3] = {0.0, 0.0, 0.0};
        gravity_derivatives(R, d.eps2, P, D);
        gravity_m2p_p2l(p.m[j], mc, &f, D, P, d.G, &pot, a);
      }
    }
  }
  struct gravity_field *out = d.field + c;
#pragma unroll
  for (int i = 0; i < GRAVITY_NCOMP(P); i++) {
    double v = f.F[i];
#pragma unroll
    for (int o = 16; o > 0; o >>= 1) v += __shfl_xor_sync(0xffffffffu, v, o);
    if ((i & 31) == lane) out->F[i] = v;
  }
}

/** L2L of the pairs [k0, k1) of one level: parent's expansion shifted to
 *  the child's centre, added to the child's. */
template <int P>
__global__ void gravity_l2l_gpu_kernel(struct gravity_gpu_dev d, const int *__restrict__ child,
                                       const int *__restrict__ parent, int k0, int k1) {
  const int k = k0 + blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= k1) return;
  const int c = child[k], q = parent[k];
  const double t[3] = {d.mp[c].com[0] - d.mp[q].com[0], d.mp[c].com[1] - d.mp[q].com[1],
                       d.mp[c].com[2] - d.mp[q].com[2]};
  gravity_l2l(d.field + c, d.field + q, t, P);
}

/** P2P of particle i from the source leaves source[k0], source[k0 +
 *  stride], ... below k1 (entries < 0, M2P, skipped), added to *pot, a. */
__device__ static void gravity_p2p_sources(struct parts p, const struct gravity_gpu_dev &d,
                                           const int *__restrict__ source, size_t i, int k0, int k1,
                                           int stride, double *pot, double a[3]) {
  const double *__restrict__ x = p.x, *__restrict__ y = p.y, *__restrict__ z = p.z;
  const double *__restrict__ m = p.m;
  const double xi[3] = {x[i], y[i], z[i]};
  for (int k = k0; k < k1; k += stride) {
    const int s = source[k];
    if (s < 0) continue;
    const size_t jb = d.offset[s], je = jb + (size_t)d.count[s];
    for (size_t j = jb; j < je; j++) {
      if (j == i) continue;
      const double dx[3] = {xi[0] - x[j], xi[1] - y[j], xi[2] - z[j]};
      const double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
      gravity_p2p(dx, r2, m[j], d.G, d.eps, d.softening, pot, a);
    }
  }
}

/** Every leaf (one block of B threads): its particles' P2P with the
 *  source leaves (struct gravity_gpu_rec.part, sources >= 0).  A leaf of
 *  cnt < B particles splits its source list into B / cnt slices (thread t:
 *  particle t % cnt, sources t / cnt, t / cnt + slices, ...), so that the
 *  threads a small leaf would leave idle share its sources; the slices'
 *  sums are then added in slice order (shared memory, 4 doubles per
 *  thread: launch with 4 B doubles). */
__global__ void gravity_p2p_gpu_kernel(struct parts p, struct gravity_gpu_dev d,
                                       struct gravity_gpu_groups l, const int *__restrict__ leaf) {
  extern __shared__ double part_sum[];
  const int c = leaf[blockIdx.x];
  const size_t beg = d.offset[c];
  const int cnt = d.count[c];
  if (cnt == 0) return; /* the whole block */
  const int *__restrict__ src = l.source + l.start[c];
  const int ns = (int)(l.start[c + 1] - l.start[c]);
  const int B = (int)blockDim.x;
  const int slices = cnt >= B ? 1 : B / cnt;
  if (slices == 1) {
    for (int t = threadIdx.x; t < cnt; t += B) {
      const size_t i = beg + (size_t)t;
      double pot = 0.0, a[3] = {0.0, 0.0, 0.0};
      gravity_p2p_sources(p, d, src, i, 0, ns, 1, &pot, a);
      p.pot[i] += pot;
      p.gax[i] += a[0];
      p.gay[i] += a[1];
      p.gaz[i] += a[2];
    }
    return;
  }
  const int t = threadIdx.x, slice = t / cnt;
  double pot = 0.0, a[3] = {0.0, 0.0, 0.0};
  if (slice < slices)
    gravity_p2p_sources(p, d, src, beg + (size_t)(t % cnt), slice, ns, slices, &pot, a);
  part_sum[4 * t] = pot;
  part_sum[4 * t + 1] = a[0];
  part_sum[4 * t + 2] = a[1];
  part_sum[4 * t + 3] = a[2];
  __syncthreads();
  if (t < cnt) {
    double sum[4] = {0.0, 0.0, 0.0, 0.0};
    for (int q = 0; q < slices; q++)
      for (int r = 0; r < 4; r++) sum[r] += part_sum[4 * (q * cnt + t) + r];
    const size_t i = beg + (size_t)t;
    p.pot[i] += sum[0];
    p.gax[i] += sum[1];
    p.gay[i] += sum[2];
    p.gaz[i] += sum[3];
  }
}

/** Every leaf (one block): its particles' M2P from the source
 *  cells (sources < 0).  A kernel of its own: the derivative tensors need
 *  registers that would slow the P2P loop down.  As the hydro loops
 *  (tasks/iact_loop_gpu.h), a small leaf takes g lanes per particle, g the
 *  largest power of two with g cnt <= B: lane s of i's group takes the
 *  sources k0 + s, k0 + s + g, ..., and the group's sums are added by a
 *  butterfly of shuffles in a fixed order. */
template <int P>
__global__ void gravity_m2p_gpu_kernel(struct parts p, struct gravity_gpu_dev d,
                                       struct gravity_gpu_groups l, const int *__restrict__ leaf) {
  const int c = leaf[blockIdx.x];
  const size_t beg = d.offset[c];
  const int cnt = d.count[c];
  const int *__restrict__ src = l.source + l.start[c];
  const int ns = (int)(l.start[c + 1] - l.start[c]);
  int any = 0;
  for (int k = 0; k < ns && !any; k++) any = src[k] < 0;
  if (!any) return;
  const int B = (int)blockDim.x;
  const struct gpu_lanes ln = gpu_lanes_of(cnt);
  const int g = ln.g, sub = ln.sub;
  const unsigned mask = ln.mask;
  for (int t = (int)threadIdx.x / g; t < cnt; t += B / g) {
    const size_t i = beg + (size_t)t;
    const double xi[3] = {p.x[i], p.y[i], p.z[i]};
    double v[4] = {0.0, 0.0, 0.0, 0.0}; /* pot, a */
    for (int k = sub; k < ns; k += g) {
      const int s = src[k];
      if (s >= 0) continue;
      const struct gravity_multipole *ms = d.mp + (-1 - s);
      const double R[3] = {ms->com[0] - xi[0], ms->com[1] - xi[1], ms->com[2] - xi[2]};
      double D[GRAVITY_NCOMP(P)];
      gravity_derivatives(R, d.eps2, P, D);
      gravity_m2p_p2l(p.m[i], ms, NULL, D, P, d.G, v, v + 1);
    }
    for (int o = g / 2; o > 0; o /= 2) gpu_lanes_add(v, 4, mask, o);
    if (sub == 0) {
      p.pot[i] += v[0];
      p.gax[i] += v[1];
      p.gay[i] += v[2];
      p.gaz[i] += v[3];
    }
  }
}

/** L2P at every leaf (one block each): its complete local expansion
 *  evaluated at its particles, added to pot and ga. */
template <int P>
__global__ void gravity_l2p_gpu_kernel(struct parts p, struct gravity_gpu_dev d,
                                       const int *__restrict__ leaf) {
  const int c = leaf[blockIdx.x];
  if (d.active && !d.active[c]) return; /* (its particles keep their last ga and pot) */
  const size_t beg = d.offset[c];
  const int cnt = d.count[c];
  const struct gravity_multipole *mc = d.mp + c;
  for (int t = threadIdx.x; t < cnt; t += blockDim.x) {
    const size_t i = beg + (size_t)t;
    const double s[3] = {p.x[i] - mc->com[0], p.y[i] - mc->com[1], p.z[i] - mc->com[2]};
    double pot = 0.0, a[3] = {0.0, 0.0, 0.0};
    gravity_l2p(d.field + c, s, P, d.G, &pot, a);
    p.pot[i] += pot;
    p.gax[i] += a[0];
    p.gay[i] += a[1];
    p.gaz[i] += a[2];
  }
}

/** ga and pot of the particles of every leaf that receives (d.active) set
 *  to zero, one block per leaf; the others keep those of their last
 *  evaluation (the CPU's up_rec). */
__global__ void gravity_zero_gpu_kernel(struct parts p, struct gravity_gpu_dev d,
                                        const int *__restrict__ leaf) {
  const int c = leaf[blockIdx.x];
  if (!d.active[c]) return;
  const size_t beg = d.offset[c];
  for (int t = threadIdx.x; t < d.count[c]; t += blockDim.x) {
    const size_t i = beg + (size_t)t;
    p.gax[i] = p.gay[i] = p.gaz[i] = p.pot[i] = 0.0;
  }
}

void gravity_zero_gpu_launch(cudaStream_t s, struct parts p, struct gravity_gpu_dev d,
                             const int *leaf, int nr_leaves, int block) {
  if (nr_leaves == 0) return;
  gravity_zero_gpu_kernel<<<nr_leaves, block, 0, s>>>(p, d, leaf);
  gpu_check_launch(gravity_zero_gpu_kernel);
}

void gravity_field_gpu_launch(cudaStream_t s, struct parts p, struct gravity_gpu_dev d,
                              struct gravity_gpu_groups l) {
  if (l.nr_cells == 0) return;
  /* one warp per cell */
  const int grid =
      (int)(((size_t)l.nr_cells * 32 + GRAVITY_GPU_FIELD_BLOCK - 1) / GRAVITY_GPU_FIELD_BLOCK);
  GRAVITY_GPU_DISPATCH(gravity_field_gpu_kernel, grid, GRAVITY_GPU_FIELD_BLOCK, p, d, l);
}

void gravity_l2l_gpu_launch(cudaStream_t s, struct gravity_gpu_dev d, const int *child,
                            const int *parent, int k0, int k1) {
  if (k1 <= k0) return;
  const int grid = (k1 - k0 + GRAVITY_GPU_CELL_BLOCK - 1) / GRAVITY_GPU_CELL_BLOCK;
  GRAVITY_GPU_DISPATCH(gravity_l2l_gpu_kernel, grid, GRAVITY_GPU_CELL_BLOCK, d, child, parent, k0,
                       k1);
}

void gravity_part_gpu_launch(cudaStream_t s, struct parts p, struct gravity_gpu_dev d,
                             struct gravity_gpu_groups l, const int *leaf, int nr_leaves,
                             int block) {
  if (nr_leaves == 0) return;
  gravity_p2p_gpu_kernel<<<nr_leaves, block, 4 * block * sizeof(double), s>>>(p, d, l, leaf);
  gpu_check_launch(gravity_p2p_gpu_kernel);
  GRAVITY_GPU_DISPATCH(gravity_m2p_gpu_kernel, nr_leaves, block, p, d, l, leaf);
}

void gravity_l2p_gpu_launch(cudaStream_t s, struct parts p, struct gravity_gpu_dev d,
                            const int *leaf, int nr_leaves, int block) {
  if (nr_leaves == 0) return;
  GRAVITY_GPU_DISPATCH(gravity_l2p_gpu_kernel, nr_leaves, block, p, d, leaf);
}

/** The gravity family's step of the FORCE phase (tasks/task_families.h):
 *  self-gravity joins before the kick.  Hybrid runs compute ga beside the
 *  phase; the runner's hook (gpu_set_kick_wait) waits for it there and
 *  completes it on the device (its device part, if any, queued on stream
 *  0).  Without a hook ga is already complete. */
int gravity_gpu_phase(struct gpu_phase *ph) {
  if (ph->wait) ph->wait(ph->wait_ctx);
  return 0;
}
