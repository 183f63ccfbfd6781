/* Checking every CUDA call (theory/architecture.md, rule 11): gpu_check(call)
 * stops the run with one line naming the call, the file and line and CUDA's message;
 * gpu_check_launch(name) does the same for the kernel launched just before. */
#ifndef BOLIDE_GPU_CHECK_H
#define BOLIDE_GPU_CHECK_H

#include <cuda_runtime.h>

/** Stop with "CUDA call WHAT failed at FILE:LINE: message" unless err is cudaSuccess. */
void gpu_check_fail(cudaError_t err, const char *what, const char *file, int line);

#define gpu_check(call)                                                                           \
  do {                                                                                            \
    const cudaError_t gpu_check_err_ = (call);                                                    \
    if (gpu_check_err_ != cudaSuccess) gpu_check_fail(gpu_check_err_, #call, __FILE__, __LINE__); \
  } while (0)

#define gpu_check_launch(name) gpu_check(cudaPeekAtLastError() /* launch of name */)

#endif
