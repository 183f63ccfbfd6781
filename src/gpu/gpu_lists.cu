/* The hydro neighbour lists built on the device (gpu_lists.h): one thread
 * per leaf walks the flattened trees of its task cell's neighbours with
 * gpu_list_accept; a counting pass, a scan of the counts (which become
 * ngb_start) and a filling pass.  Buffers are allocated once and grown. */
#include <stdlib.h>
#include <string.h>

extern "C" {
#include "src/error.h"
}
#include "src/gpu/gpu_kernels.h"
#include "src/gpu/gpu_lists.h"

/** Threads per block of the walk. */
#define GPU_LISTS_BLOCK 128

struct gpu_lists {
  struct gpu *g;                   /**< the runner (its stream 1 and bus counters) */
  struct gpu_list_node *node_host; /**< pinned staging of the nodes */
  struct gpu_list_node *node_dev;  /**< their device copy */
  int node_cap;                    /**< allocated nodes (both sides) */
  char *in_host, *in_dev;          /**< pinned staging and device copy of the other inputs */
  size_t in_cap;                   /**< their allocated bytes */
  int *start_dev;                  /**< counts, then ngb_start (nr_leaves + 1) */
  int start_cap;                   /**< allocated length */
  int *leaf_dev;                   /**< ngb_leaf */
  unsigned char *shift_dev;        /**< the shifts' codes (gpu_shift_code), 1 per entry */
  double dim[3];                   /**< the box of the codes (gpu_shift_dims) */
  long ngb_cap;                    /**< allocated entries */
  int *total_host;                 /**< pinned: the number of entries */
  int n;                           /**< leaves of the last build */
  long nr_ngb;                     /**< entries of the last build */
  cudaEvent_t ev[2];               /**< around the last build */
  int pending;                     /**< ev holds a build not yet added to ms */
  double ms;                       /**< accumulated device milliseconds */
  long builds;                     /**< builds run */
};

/** The inputs as device pointers. */
struct gpu_lists_args {
  int n;                             /**< leaves */
  const struct gpu_list_node *node;  /**< nodes */
  const int *leaf_node, *leaf_tc;    /**< node and task cell of each leaf */
  const int *tc_node, *tc_ngb_start; /**< by task cell, nr_tc + 1 each */
  const int *tc_ngb;                 /**< neighbouring task cells */
  const double *tc_ngb_shift;        /**< 3 per neighbour */
  double growth;                     /**< reach factor */
};

/** Walk of leaf L: FILL = 0 counts its entries into start[L]; FILL = 1
 *  writes them from start[L] on. */
template <int FILL>
__global__ void gpu_lists_walk_kernel(struct gpu_lists_args a, int *start, int *ngb_leaf,
                                      unsigned char *ngb_code) {
  const int L = blockIdx.x * blockDim.x + threadIdx.x;
  if (L >= a.n) return;
  const struct gpu_list_box A = a.node[a.leaf_node[L]].box;
  const int t = a.leaf_tc[L];
  int c = FILL ? start[L] : 0;
  for (int k = a.tc_ngb_start[t]; k < a.tc_ngb_start[t + 1]; k++) {
    const int u = a.tc_ngb[k];
    const double s[3] = {a.tc_ngb_shift[3 * k], a.tc_ngb_shift[3 * k + 1],
                         a.tc_ngb_shift[3 * k + 2]};
    int q = a.tc_node[u];
    const int qe = a.tc_node[u + 1];
    while (q < qe) {
      const struct gpu_list_node *B = &a.node[q];
      const int leaf = B->leaf;
      if (gpu_list_accept(&A, &B->box, s, a.growth, leaf < 0)) {
        if (leaf >= 0) {
          if (FILL) {
            ngb_leaf[c] = leaf;
            ngb_code[c] = gpu_shift_code(s);
          }
          c++;
        }
        q++; /* into the sub-tree, or past the leaf */
      } else {
        q = B->skip;
      }
    }
  }
  if (!FILL) start[L] = c;
}

/** The counts c[0..n) become their exclusive prefix sums, c[n] the total (one block). */
__global__ void gpu_lists_scan_kernel(int *c, int n) {
  gpu_block_exclusive_scan(c, n);
}

extern "C" struct gpu_lists *gpu_lists_new(struct gpu *g) {
  struct gpu_lists *l = (struct gpu_lists *)error_calloc(1, sizeof *l, "GPU neighbour lists");
  l->g = g;
  gpu_check(cudaMallocHost((void **)&l->total_host, sizeof(int)));
  for (int k = 0; k < 2; k++) gpu_check(cudaEventCreate(&l->ev[k]));
  return l;
}

extern "C" void gpu_lists_free(struct gpu_lists *l) {
  if (!l) return;
  if (l->node_host) gpu_check(cudaFreeHost(l->node_host));
  if (l->node_dev) gpu_dfree(l->node_dev);
  if (l->in_host) gpu_check(cudaFreeHost(l->in_host));
  if (l->in_dev) gpu_dfree(l->in_dev);
  if (l->start_dev) gpu_dfree(l->start_dev);
  if (l->leaf_dev) gpu_dfree(l->leaf_dev);
  if (l->shift_dev) gpu_dfree(l->shift_dev);
  gpu_check(cudaFreeHost(l->total_host));
  for (int k = 0; k < 2; k++) gpu_check(cudaEventDestroy(l->ev[k]));
  free(l);
}

extern "C" struct gpu_list_node *gpu_lists_nodes(struct gpu_lists *l, int n) {
  if (n > l->node_cap) {
    if (l->node_host) gpu_check(cudaFreeHost(l->node_host));
    if (l->node_dev) gpu_dfree(l->node_dev);
    l->node_cap = n + n / 4 + 64;
    char what[128];
    snprintf(what, sizeof what, "cell nodes of the neighbour-list build (%d)", l->node_cap);
    l->node_dev =
        (struct gpu_list_node *)gpu_alloc((size_t)l->node_cap * sizeof(struct gpu_list_node), what);
    gpu_check(
        cudaMallocHost((void **)&l->node_host, (size_t)l->node_cap * sizeof(struct gpu_list_node)));
  }
  return l->node_host;
}

/** Add the device time of the last build, once it has ended. */
static void gpu_lists_account(struct gpu_lists *l) {
  if (!l->pending) return;
  gpu_check(cudaEventSynchronize(l->ev[1]));
  float ms = 0.0f;
  gpu_check(cudaEventElapsedTime(&ms, l->ev[0], l->ev[1]));
  l->ms += ms;
  l->pending = 0;
}

/** Round up to a multiple of 16 bytes. */
static size_t gpu_lists_align(size_t b) {
  return (b + 15) & ~(size_t)15;
}

extern "C" int gpu_shift_dims(const double *shift, long n, double dim[3]) {
  dim[0] = dim[1] = dim[2] = 0.0;
  for (long k = 0; k < n; k++)
    for (int d = 0; d < 3; d++)
      if (fabs(shift[3 * k + d]) > dim[d]) dim[d] = fabs(shift[3 * k + d]);
  for (long k = 0; k < n; k++)
    for (int d = 0; d < 3; d++)
      if (shift[3 * k + d] != 0.0 && fabs(shift[3 * k + d]) != dim[d]) return 0;
  return 1;
}

extern "C" long gpu_lists_build(struct gpu_lists *l, const struct gpu_list_input *in) {
  cudaStream_t s = gpu_stream(l->g, 1);
  gpu_lists_account(l);
  if (in->nr_nodes > l->node_cap) error_bug("GPU list build: more nodes than staged");
  const int n = in->nr_leaves, nt = in->nr_tc;
  const int nk = nt > 0 ? in->tc_ngb_start[nt] : 0;
  if (!gpu_shift_dims(in->tc_ngb_shift, nk, l->dim))
    error_bug("GPU list build: a periodic shift is not 0 or the box's side");
  /* the other inputs, packed */
  const size_t sz[6] = {(size_t)n * sizeof(int),        (size_t)n * sizeof(int),
                        (size_t)(nt + 1) * sizeof(int), (size_t)(nt + 1) * sizeof(int),
                        (size_t)nk * sizeof(int),       3 * (size_t)nk * sizeof(double)};
  const void *src[6] = {in->leaf_node,    in->leaf_tc, in->tc_node,
                        in->tc_ngb_start, in->tc_ngb,  in->tc_ngb_shift};
  size_t off[6], total = 0;
  for (int k = 0; k < 6; k++) {
    off[k] = total;
    total += gpu_lists_align(sz[k]);
  }
  if (total > l->in_cap) {
    if (l->in_host) gpu_check(cudaFreeHost(l->in_host));
    if (l->in_dev) gpu_dfree(l->in_dev);
    l->in_cap = total + total / 2;
    l->in_dev = (char *)gpu_alloc(l->in_cap, "task cells and leaves of the neighbour-list build");
    gpu_check(cudaMallocHost((void **)&l->in_host, l->in_cap));
  }
  for (int k = 0; k < 6; k++)
    if (sz[k]) memcpy(l->in_host + off[k], src[k], sz[k]);
  if (n + 1 > l->start_cap) {
    if (l->start_dev) gpu_dfree(l->start_dev);
    l->start_cap = n + n / 4 + 64;
    l->start_dev = (int *)gpu_alloc((size_t)l->start_cap * sizeof(int), "neighbour-list starts");
  }
  gpu_check(cudaEventRecord(l->ev[0], s));
  const size_t node_bytes = (size_t)in->nr_nodes * sizeof(struct gpu_list_node);
  if (node_bytes)
    gpu_check(cudaMemcpyAsync(l->node_dev, l->node_host, node_bytes, cudaMemcpyHostToDevice, s));
  gpu_check(cudaMemcpyAsync(l->in_dev, l->in_host, total, cudaMemcpyHostToDevice, s));
  gpu_bytes_add(l->g, (double)(node_bytes + total), 0.0);
  struct gpu_lists_args a;
  a.n = n;
  a.node = l->node_dev;
  a.leaf_node = (const int *)(l->in_dev + off[0]);
  a.leaf_tc = (const int *)(l->in_dev + off[1]);
  a.tc_node = (const int *)(l->in_dev + off[2]);
  a.tc_ngb_start = (const int *)(l->in_dev + off[3]);
  a.tc_ngb = (const int *)(l->in_dev + off[4]);
  a.tc_ngb_shift = (const double *)(l->in_dev + off[5]);
  a.growth = in->growth;
  const int blocks = (n + GPU_LISTS_BLOCK - 1) / GPU_LISTS_BLOCK;
  if (n > 0) {
    gpu_lists_walk_kernel<0><<<blocks, GPU_LISTS_BLOCK, 0, s>>>(a, l->start_dev, NULL, NULL);
    gpu_check_launch(gpu_lists_walk_kernel<0>);
  }
  gpu_lists_scan_kernel<<<1, 1024, 0, s>>>(l->start_dev, n);
  gpu_check_launch(gpu_lists_scan_kernel);
  gpu_check(
      cudaMemcpyAsync(l->total_host, l->start_dev + n, sizeof(int), cudaMemcpyDeviceToHost, s));
  gpu_check(cudaStreamSynchronize(s));
  gpu_bytes_add(l->g, 0.0, (double)sizeof(int));
  const long nr = *l->total_host;
  if (nr < 0)
    error_exit(
        "GPU neighbour lists: more than 2^31 entries (%d leaves); lower h or use coarser leaves",
        n);
  if (nr > l->ngb_cap) {
    if (l->leaf_dev) gpu_dfree(l->leaf_dev);
    if (l->shift_dev) gpu_dfree(l->shift_dev);
    l->ngb_cap = nr + nr / 4 + 1024;
    char what[128];
    snprintf(what, sizeof what, "neighbour lists (%ld entries)", l->ngb_cap);
    l->leaf_dev = (int *)gpu_alloc((size_t)l->ngb_cap * sizeof(int), what);
    l->shift_dev = (unsigned char *)gpu_alloc((size_t)l->ngb_cap, what);
  }
  if (n > 0) {
    gpu_lists_walk_kernel<1>
        <<<blocks, GPU_LISTS_BLOCK, 0, s>>>(a, l->start_dev, l->leaf_dev, l->shift_dev);
    gpu_check_launch(gpu_lists_walk_kernel<1>);
  }
  gpu_check(cudaEventRecord(l->ev[1], s));
  l->pending = 1;
  l->builds++;
  l->n = n;
  l->nr_ngb = nr;
  return nr;
}

extern "C" void gpu_lists_download(const struct gpu_lists *l, int *ngb_start, int *ngb_leaf,
                                   double *ngb_shift) {
  cudaStream_t s = gpu_stream(l->g, 1);
  gpu_check(cudaMemcpyAsync(ngb_start, l->start_dev, ((size_t)l->n + 1) * sizeof(int),
                            cudaMemcpyDeviceToHost, s));
  unsigned char *code = (unsigned char *)error_malloc((size_t)l->nr_ngb + 1, "GPU list codes");
  if (l->nr_ngb) {
    gpu_check(cudaMemcpyAsync(ngb_leaf, l->leaf_dev, (size_t)l->nr_ngb * sizeof(int),
                              cudaMemcpyDeviceToHost, s));
    gpu_check(cudaMemcpyAsync(code, l->shift_dev, (size_t)l->nr_ngb, cudaMemcpyDeviceToHost, s));
  }
  gpu_check(cudaStreamSynchronize(s));
  for (long k = 0; k < l->nr_ngb; k++) gpu_shift_of(code[k], l->dim, ngb_shift + 3 * k);
  free(code);
}

extern "C" void gpu_lists_view(const struct gpu_lists *l, const int **ngb_start,
                               const int **ngb_leaf, const unsigned char **ngb_code,
                               double dim[3]) {
  *ngb_start = l->start_dev;
  *ngb_leaf = l->leaf_dev;
  *ngb_code = l->shift_dev;
  for (int d = 0; d < 3; d++) dim[d] = l->dim[d];
}

extern "C" double gpu_lists_device_ms(struct gpu_lists *l, long *builds) {
  gpu_lists_account(l);
  *builds = l->builds;
  return l->ms;
}
