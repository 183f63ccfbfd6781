/* Self-gravity on the GPU: every operator of the fast multipole method,
 * the upward pass (P2M, M2M: gravity_up_leaf and gravity_up_node, as the
 * CPU's gravity_up) and, on interactions that the CPU walks recorded
 * (gravity_gpu_record) and on the cell tree as index arrays
 * (src/gpu/gpu_gravity.cu uploads both).  Each kernel calls the inline
 * operators of gravity_iact.h that the CPU walk calls (gravity_derivatives,
 * gravity_m2l, gravity_m2p_p2l, gravity_l2l, gravity_l2p, gravity_p2p),
 * with the expansion order a template constant so that nvcc unrolls their
 * loops as gcc does for gravity_cpu.c's M2L_ORDER.
 *
 *   up kernels:   every cell set empty (one thread each), then one thread
 *                 per leaf (P2M), then one launch per tree level from the
 *                 deepest, one thread per parent (M2M of its children)
 *   walk kernel:  the walks of gravity_walk.h (the CPU's decisions) from
 *                 every root (pair of top-level cells), a few roots per
 *                 thread, each with its own stack, appending to the
 *                 recorded lists in groups of GRAVITY_WALK_BUF
 *   field kernel: one thread per cell, its M2L and P2L summed in
 *                 registers, then stored (the cells' expansions start at 0)
 *   L2L kernel:   one thread per parent-child pair of one tree level, the
 *                 levels one launch after the other (parents first)
 *   P2P, M2P:     one block per leaf, one thread per particle,
 *                 its P2P (gather form: a leaf with itself skips i == j),
 *                 then (second kernel) its M2P summed in registers, added
 *                 to pot and ga
 *   L2P kernel:   one block per leaf, one thread per particle.
 *
 * Compared with the CPU the sums run in another order (the CPU adds each
 * interaction to the field or particle as the walk meets it): the results
 * differ by round-off (tests/test_gpu.c). */
#define GRAVITY_UNROLL_LOOPS 1
#include "gpu_kernels.h"
#include "gravity_iact.h"
#include "gravity_walk.h"

/** Every cell as an empty one (zero moments at its box centre). */
__global__ void gravity_up_empty_gpu_kernel(struct gravity_gpu_up u, int nr_cells) {
  const int c = blockIdx.x * blockDim.x + threadIdx.x;
  if (c >= nr_cells) return;
  gravity_up_leaf(u.mp + c, u.a_min + c, u.h_support + c, NULL, NULL, NULL, NULL, NULL, NULL, NULL,
                  NULL, 0, 0, 1, 0.0, u.centre + 3 * (size_t)c);
}

/** P2M of every non-empty leaf (one thread each). */
template <int P>
__global__ void gravity_up_leaf_gpu_kernel(struct parts p, struct gravity_gpu_up u,
                                           const int *__restrict__ leaf, int nr_leaves) {
  const int k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= nr_leaves) return;
  const int c = leaf[k];
  const size_t i0 = u.offset[c];
  gravity_up_leaf(u.mp + c, u.a_min + c, u.h_support + c, p.x, p.y, p.z, p.m, p.h, p.gax, p.gay,
                  p.gaz, i0, i0 + (size_t)u.count[c], P, u.h_factor, u.centre + 3 * (size_t)c);
}

/** M2M of one level: the thread of the first pair of each parent sums
 *  that parent's children (the pairs that follow with the same parent). */
template <int P>
__global__ void gravity_up_node_gpu_kernel(struct gravity_gpu_up u, const int *__restrict__ child,
                                           const int *__restrict__ parent, int k0, int k1) {
  const int k = k0 + blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= k1 || (k > k0 && parent[k - 1] == parent[k])) return;
  const int q = parent[k];
  const struct gravity_multipole *ch[8];
  double ch_a[8], ch_h[8];
  int n = 0;
  for (int j = k; j < k1 && parent[j] == q && n < 8; j++, n++) {
    const int c = child[j];
    ch[n] = u.mp + c;
    ch_a[n] = u.a_min[c];
    ch_h[n] = u.h_support[c];
  }
  gravity_up_node(u.mp + q, u.a_min + q, u.h_support + q, ch, ch_a, ch_h, n, P,
                  u.centre + 3 * (size_t)q);
}

/** Roots (pairs of top-level cells) per thread of the walk kernel. */
#define GRAVITY_WALK_ROOTS 16

/** The walks from the roots [r0, r0 + GRAVITY_WALK_ROOTS) of the nt x nt
 *  pairs (i, j) of top-level cells: i == j the self walk, a near pair
 *  (gravity_walk_top_near on the boxes lo_hi, 6 per top cell) with j > i
 *  the symmetric walk, a far pair the long-range walk of i; as the CPU's
 *  tasks.  *deep counts walks that ran out of stack. */
__global__ void __launch_bounds__(64)
gravity_walk_gpu_kernel(struct gravity_walk_tree T, struct gravity_walk_params wp,
                        struct gravity_walk_lists L, const double *__restrict__ lo_hi, int nt,
                        double h_support_top, int *deep) {
  const long long r0 =
      ((long long)blockIdx.x * blockDim.x + threadIdx.x) * (long long)GRAVITY_WALK_ROOTS;
  const long long nroots = (long long)nt * nt;
  if (r0 >= nroots) return;
  int stack[3 * GRAVITY_WALK_STACK];
  struct gravity_walk_buf B;
  for (int k = 0; k < 4; k++) B.n[k] = 0;
  const long long r1 = r0 + GRAVITY_WALK_ROOTS < nroots ? r0 + GRAVITY_WALK_ROOTS : nroots;
  for (long long r = r0; r < r1; r++) {
    const int i = (int)(r / nt), j = (int)(r % nt);
    if (T.count[i] == 0 || T.count[j] == 0) continue;
    int ok = 1;
    if (i == j) {
      ok = gravity_walk_run(&T, &wp, &L, &B, i, i, 1, stack);
    } else {
      const int near = gravity_walk_top_near(lo_hi + 6 * i, lo_hi + 6 * i + 3, lo_hi + 6 * j,
                                             lo_hi + 6 * j + 3, wp.theta, h_support_top);
      if (near && j > i)
        ok = gravity_walk_run(&T, &wp, &L, &B, i, j, 1, stack);
      else if (!near)
        ok = gravity_walk_run(&T, &wp, &L, &B, i, j, 0, stack);
    }
    if (!ok) atomicAdd(deep, 1);
  }
  for (int k = 0; k < 4; k++) gravity_walk_flush(&L, &B, k);
}

void gravity_walk_gpu_launch(cudaStream_t s, struct gravity_walk_tree T,
                             struct gravity_walk_params wp, struct gravity_walk_lists L,
                             const double *lo_hi, int nt, double h_support_top, int *deep) {
  const long long nroots = (long long)nt * nt;
  const long long threads = (nroots + GRAVITY_WALK_ROOTS - 1) / GRAVITY_WALK_ROOTS;
  if (threads == 0) return;
  const int block = 64;
  gravity_walk_gpu_kernel<<<(unsigned)((threads + block - 1) / block), block, 0, s>>>(
      T, wp, L, lo_hi, nt, h_support_top, deep);
  gpu_check_launch(gravity_walk_gpu_kernel);
}

/** Every cell c with sources: the M2L of its multipole sources and the P2L
 *  of its leaf sources (struct gravity_gpu_rec.field), stored as its field. */
template <int P>
__global__ void gravity_field_gpu_kernel(struct parts p, struct gravity_gpu_dev d,
                                         struct gravity_gpu_groups l) {
  const int c = blockIdx.x * blockDim.x + threadIdx.x;
  if (c >= l.nr_cells) return;
  const int k0 = l.start[c], k1 = l.start[c + 1];
  if (k0 == k1) return;
  const struct gravity_multipole *mc = d.mp + c;
  const double zc[3] = {mc->com[0], mc->com[1], mc->com[2]};
  struct gravity_field f;
#pragma unroll
  for (int i = 0; i < GRAVITY_NCOMP(P); i++) f.F[i] = 0.0;
  for (int k = k0; k < k1; k++) {
    const int s = l.source[k];
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
  for (int i = 0; i < GRAVITY_NCOMP(P); i++) out->F[i] = f.F[i];
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

/** Every leaf (one block): its particles' P2P with the source
 *  leaves (struct gravity_gpu_rec.part, sources >= 0). */
__global__ void gravity_p2p_gpu_kernel(struct parts p, struct gravity_gpu_dev d,
                                       struct gravity_gpu_groups l, const int *__restrict__ leaf) {
  const int c = leaf[blockIdx.x];
  const size_t beg = d.offset[c];
  const int cnt = d.count[c];
  const int k0 = l.start[c], k1 = l.start[c + 1];
  const double *__restrict__ x = p.x, *__restrict__ y = p.y, *__restrict__ z = p.z;
  const double *__restrict__ m = p.m;
  for (int t = threadIdx.x; t < cnt; t += blockDim.x) {
    const size_t i = beg + (size_t)t;
    const double xi[3] = {x[i], y[i], z[i]};
    double pot = 0.0, a[3] = {0.0, 0.0, 0.0};
    for (int k = k0; k < k1; k++) {
      const int s = l.source[k];
      if (s < 0) continue;
      const size_t jb = d.offset[s], je = jb + (size_t)d.count[s];
      for (size_t j = jb; j < je; j++) {
        if (j == i) continue;
        const double dx[3] = {xi[0] - x[j], xi[1] - y[j], xi[2] - z[j]};
        const double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
        gravity_p2p(dx, r2, m[j], d.G, d.eps, d.softening, &pot, a);
      }
    }
    p.pot[i] += pot;
    p.gax[i] += a[0];
    p.gay[i] += a[1];
    p.gaz[i] += a[2];
  }
}

/** Every leaf (one block): its particles' M2P from the source
 *  cells (sources < 0).  A kernel of its own: the derivative tensors need
 *  registers that would slow the P2P loop down. */
template <int P>
__global__ void gravity_m2p_gpu_kernel(struct parts p, struct gravity_gpu_dev d,
                                       struct gravity_gpu_groups l, const int *__restrict__ leaf) {
  const int c = leaf[blockIdx.x];
  const size_t beg = d.offset[c];
  const int cnt = d.count[c];
  const int k0 = l.start[c], k1 = l.start[c + 1];
  int any = 0;
  for (int k = k0; k < k1 && !any; k++) any = l.source[k] < 0;
  if (!any) return;
  for (int t = threadIdx.x; t < cnt; t += blockDim.x) {
    const size_t i = beg + (size_t)t;
    const double xi[3] = {p.x[i], p.y[i], p.z[i]};
    double pot = 0.0, a[3] = {0.0, 0.0, 0.0};
    for (int k = k0; k < k1; k++) {
      const int s = l.source[k];
      if (s >= 0) continue;
      const struct gravity_multipole *ms = d.mp + (-1 - s);
      const double R[3] = {ms->com[0] - xi[0], ms->com[1] - xi[1], ms->com[2] - xi[2]};
      double D[GRAVITY_NCOMP(P)];
      gravity_derivatives(R, d.eps2, P, D);
      gravity_m2p_p2l(p.m[i], ms, NULL, D, P, d.G, &pot, a);
    }
    p.pot[i] += pot;
    p.gax[i] += a[0];
    p.gay[i] += a[1];
    p.gaz[i] += a[2];
  }
}

/** L2P at every leaf (one block each): its complete local expansion
 *  evaluated at its particles, added to pot and ga. */
template <int P>
__global__ void gravity_l2p_gpu_kernel(struct parts p, struct gravity_gpu_dev d,
                                       const int *__restrict__ leaf) {
  const int c = leaf[blockIdx.x];
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

/** Threads per block of the one-thread-per-cell kernels. */
#define GRAVITY_GPU_CELL_BLOCK 64

/** Instantiate kernel K for the orders 1..GRAVITY_ORDER_MAX and launch the
 *  one of d.order. */
#define GRAVITY_GPU_DISPATCH(K, grid, block, ...)                                           \
  switch (d.order) {                                                                        \
    case 1: K<1><<<(grid), (block), 0, s>>>(__VA_ARGS__); break;                            \
    case 2: K<2><<<(grid), (block), 0, s>>>(__VA_ARGS__); break;                            \
    case 3: K<3><<<(grid), (block), 0, s>>>(__VA_ARGS__); break;                            \
    case 4: K<4><<<(grid), (block), 0, s>>>(__VA_ARGS__); break;                            \
    default: K<GRAVITY_ORDER_MAX><<<(grid), (block), 0, s>>>(__VA_ARGS__); break;           \
  }                                                                                         \
  gpu_check_launch(K)

void gravity_up_gpu_launch(cudaStream_t s, struct parts p, struct gravity_gpu_up u, int nr_cells,
                           const int *leaf, int nr_leaves, const int *child, const int *parent,
                           const int *level_start, int nr_levels) {
  if (nr_cells == 0) return;
  const int B = GRAVITY_GPU_CELL_BLOCK;
  gravity_up_empty_gpu_kernel<<<(nr_cells + B - 1) / B, B, 0, s>>>(u, nr_cells);
  gpu_check_launch(gravity_up_empty_gpu_kernel);
  struct gravity_gpu_dev d; /* GRAVITY_GPU_DISPATCH reads d.order */
  d.order = u.order;
  if (nr_leaves > 0) {
    GRAVITY_GPU_DISPATCH(gravity_up_leaf_gpu_kernel, (nr_leaves + B - 1) / B, B, p, u, leaf,
                         nr_leaves);
  }
  for (int L = nr_levels - 1; L >= 0; L--) {
    const int k0 = level_start[L], k1 = level_start[L + 1];
    if (k1 <= k0) continue;
    GRAVITY_GPU_DISPATCH(gravity_up_node_gpu_kernel, (k1 - k0 + B - 1) / B, B, u, child, parent,
                         k0, k1);
  }
}

void gravity_field_gpu_launch(cudaStream_t s, struct parts p, struct gravity_gpu_dev d,
                              struct gravity_gpu_groups l) {
  if (l.nr_cells == 0) return;
  const int grid = (l.nr_cells + GRAVITY_GPU_CELL_BLOCK - 1) / GRAVITY_GPU_CELL_BLOCK;
  GRAVITY_GPU_DISPATCH(gravity_field_gpu_kernel, grid, GRAVITY_GPU_CELL_BLOCK, p, d, l);
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
  gravity_p2p_gpu_kernel<<<nr_leaves, block, 0, s>>>(p, d, l, leaf);
  gpu_check_launch(gravity_p2p_gpu_kernel);
  GRAVITY_GPU_DISPATCH(gravity_m2p_gpu_kernel, nr_leaves, block, p, d, l, leaf);
}

void gravity_l2p_gpu_launch(cudaStream_t s, struct parts p, struct gravity_gpu_dev d,
                            const int *leaf, int nr_leaves, int block) {
  if (nr_leaves == 0) return;
  GRAVITY_GPU_DISPATCH(gravity_l2p_gpu_kernel, nr_leaves, block, p, d, leaf);
}
