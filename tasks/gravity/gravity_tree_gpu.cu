/* Self-gravity's tree on the GPU: the upward pass (P2M, M2M:
 * gravity_up_leaf and gravity_up_node of gravity_iact.h, as the CPU's
 * gravity_up) and the walks (gravity_walk.h, the CPU's decisions).
 *
 * Compiled without fused multiply-adds (src/gpu/local.am): the multipoles,
 * centres and radii then round as gcc rounds them on the CPU, bit for bit,
 * and the walks take the CPU's decisions on them (an acceptance test on a
 * radius that differs in the last bit can open a cell that the CPU does
 * not, which changes the forces by the expansion's truncation error, far
 * more than round-off).  Both are a few per cent of an evaluation's time.
 *
 *   up kernels:   every cell set empty (one thread each), then one thread
 *                 per leaf (P2M), then one launch per tree level from the
 *                 deepest, one thread per parent (M2M of its children)
 *   walk kernels: rounds of walkers (gravity_walk_gpu_launch).  The first
 *                 starts from the roots (pairs of top-level cells,
 *                 GRAVITY_WALK_ROOTS per thread); every walker takes at
 *                 most GRAVITY_WALK_BUDGET entries from its stack and hands
 *                 what is left to a queue, which the next round's walkers
 *                 take one entry each.  A walk that one thread would run
 *                 for seconds (the self walk of a top-level cell that holds
 *                 a planet's core) is so spread over the device in a few
 *                 rounds.  Entries go to the recorded lists in groups of
 *                 GRAVITY_WALK_BUF. */
#include <limits.h>

#include "src/gpu/gpu_kernels.h"
#include "tasks/gravity/gravity_gpu.h"
#include "tasks/gravity/gravity_iact.h"
#include "tasks/gravity/gravity_walk.h"

/** Every cell as an empty one (zero moments at its box centre). */
__global__ void gravity_up_empty_gpu_kernel(struct gravity_gpu_up u, int nr_cells) {
  const int c = blockIdx.x * blockDim.x + threadIdx.x;
  if (c >= nr_cells) return;
  gravity_up_leaf(u.mp + c, u.a_min + c, u.h_support + c, NULL, NULL, NULL, NULL, NULL, NULL, NULL,
                  NULL, 0, 0, 1, 0.0, u.centre + 3 * (size_t)c);
  if (u.active) u.active[c] = 0;
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
  if (u.active) {
    unsigned char act = 0;
    for (size_t i = i0; i < i0 + (size_t)u.count[c] && !act; i++) act = !PART_IS_INACTIVE(&p, i);
    u.active[c] = act;
  }
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
  unsigned char act = 0;
  for (int j = k; j < k1 && parent[j] == q && n < 8; j++, n++) {
    const int c = child[j];
    ch[n] = u.mp + c;
    ch_a[n] = u.a_min[c];
    ch_h[n] = u.h_support[c];
    if (u.active) act |= u.active[c];
  }
  if (u.active) u.active[q] = act;
  gravity_up_node(u.mp + q, u.a_min + q, u.h_support + q, ch, ch_a, ch_h, n, P,
                  u.centre + 3 * (size_t)q);
}

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
    GRAVITY_GPU_DISPATCH(gravity_up_node_gpu_kernel, (k1 - k0 + B - 1) / B, B, u, child, parent, k0,
                         k1);
  }
}

/** Roots (pairs of top-level cells) per thread of the first round, more
 *  only past GRAVITY_WALK_MAX_THREADS threads.  One: a thread's roots are
 *  walked one after the other, and at 16 the roots' round took 4.4 of a
 *  6.5-ms walk at 1e5 particles (BENCHMARKS.md, "The GPU walk's first
 *  round"). */
#define GRAVITY_WALK_ROOTS 1

/** Entries a walker takes from its stack before it hands the rest on
 *  (32: more walkers sooner, each round shorter; 64 took 1.15 times as
 *  long at 1.1e6). */
#define GRAVITY_WALK_BUDGET 32

/** Threads per block of the walk kernels. */
#define GRAVITY_WALK_BLOCK 64

/** Most threads of the roots' round (2^24 blocks): past them each thread
 *  takes more roots (below the device's 2^31 - 1 blocks). */
#define GRAVITY_WALK_MAX_THREADS (1LL << 30)

/** One walker's share: the n entries on its stack for at most
 *  GRAVITY_WALK_BUDGET steps (fewer where the stack fills), the rest to
 *  out; what does not fit there it walks to the end itself, and entries
 *  left then (its stack full, the queue too) count in *deep. */
__device__ static void gravity_walk_share(const struct gravity_walk_tree *T,
                                          const struct gravity_walk_params *wp,
                                          const struct gravity_walk_lists *L,
                                          struct gravity_walk_buf *B,
                                          const struct gravity_walk_queue *out, int *stack, int n,
                                          int *deep) {
  n = gravity_walk_run(T, wp, L, B, stack, GRAVITY_WALK_STACK, n, GRAVITY_WALK_BUDGET);
  if (n > 0) {
    n = gravity_walk_spill(out, stack, n);
    if (n > 0) n = gravity_walk_run(T, wp, L, B, stack, GRAVITY_WALK_STACK, n, LLONG_MAX);
  }
  if (n > 0) atomicAdd(deep, 1);
}

/** The first round: the roots [r0, r0 + per) of the nt x nt pairs of
 *  top-level cells (gravity_walk_root). */
__global__ void __launch_bounds__(GRAVITY_WALK_BLOCK)
    gravity_walk_roots_gpu_kernel(struct gravity_walk_tree T, struct gravity_walk_params wp,
                                  struct gravity_walk_lists L, struct gravity_walk_queue out,
                                  const double *__restrict__ lo_hi, int nt, double h_support_top,
                                  const unsigned char *__restrict__ skip,
                                  const int *__restrict__ top, long long per, int *deep) {
  const long long r0 = ((long long)blockIdx.x * blockDim.x + threadIdx.x) * per;
  const long long nroots = (long long)nt * nt;
  if (r0 >= nroots) return;
  int stack[3 * GRAVITY_WALK_STACK];
  struct gravity_walk_buf B;
  for (int k = 0; k < 4; k++) B.n[k] = 0;
  const long long r1 = r0 + per < nroots ? r0 + per : nroots;
  for (long long r = r0; r < r1; r++)
    if (gravity_walk_root(T.count, lo_hi, nt, wp.theta, h_support_top, skip, top, r, stack))
      gravity_walk_share(&T, &wp, &L, &B, &out, stack, 1, deep);
  for (int k = 0; k < 4; k++) gravity_walk_flush(&L, &B, k);
}

/** A later round: every entry the last round handed on (min(*in.n,
 *  in.cap) of them), one per walker, grid-stride. */
__global__ void __launch_bounds__(GRAVITY_WALK_BLOCK)
    gravity_walk_queue_gpu_kernel(struct gravity_walk_tree T, struct gravity_walk_params wp,
                                  struct gravity_walk_lists L, struct gravity_walk_queue in,
                                  struct gravity_walk_queue out, int *deep) {
  const unsigned long long n = *in.n < in.cap ? *in.n : in.cap;
  int stack[3 * GRAVITY_WALK_STACK];
  struct gravity_walk_buf B;
  for (int k = 0; k < 4; k++) B.n[k] = 0;
  for (unsigned long long q = blockIdx.x * (unsigned long long)blockDim.x + threadIdx.x; q < n;
       q += (unsigned long long)gridDim.x * blockDim.x) {
    for (int k = 0; k < 3; k++) stack[k] = in.item[3 * q + k];
    gravity_walk_share(&T, &wp, &L, &B, &out, stack, 1, deep);
  }
  for (int k = 0; k < 4; k++) gravity_walk_flush(&L, &B, k);
}

void gravity_walk_roots_gpu_launch(cudaStream_t s, struct gravity_walk_tree T,
                                   struct gravity_walk_params wp, struct gravity_walk_lists L,
                                   struct gravity_walk_queue out, const double *lo_hi, int nt,
                                   double h_support_top, const unsigned char *skip, const int *top,
                                   int *deep) {
  const long long nroots = (long long)nt * nt;
  long long per = (nroots + GRAVITY_WALK_MAX_THREADS - 1) / GRAVITY_WALK_MAX_THREADS;
  if (per < GRAVITY_WALK_ROOTS) per = GRAVITY_WALK_ROOTS;
  const long long threads = (nroots + per - 1) / per;
  if (threads == 0) return;
  const int block = GRAVITY_WALK_BLOCK;
  gravity_walk_roots_gpu_kernel<<<(unsigned)((threads + block - 1) / block), block, 0, s>>>(
      T, wp, L, out, lo_hi, nt, h_support_top, skip, top, per, deep);
  gpu_check_launch(gravity_walk_roots_gpu_kernel);
}

void gravity_walk_queue_gpu_launch(cudaStream_t s, struct gravity_walk_tree T,
                                   struct gravity_walk_params wp, struct gravity_walk_lists L,
                                   struct gravity_walk_queue in, unsigned long long n_in,
                                   struct gravity_walk_queue out, int *deep) {
  if (n_in == 0) return;
  const int block = GRAVITY_WALK_BLOCK;
  const unsigned long long blocks = (n_in + block - 1) / block;
  gravity_walk_queue_gpu_kernel<<<(unsigned)(blocks < 65536 ? blocks : 65536), block, 0, s>>>(
      T, wp, L, in, out, deep);
  gpu_check_launch(gravity_walk_queue_gpu_kernel);
}
