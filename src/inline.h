/* Portability macros shared by the C11 build and the CUDA build.
 *
 * Every pair interaction (tasks/<name>/<name>_iact.h) and every material
 * model (src/materials/) is written once as a BOLIDE_INLINE function: under
 * nvcc it becomes __host__ __device__, under a C compiler a plain static
 * inline function.  Headers that use it compile as C11 and as CUDA C++: no
 * variable-length arrays, no compound literals, explicit enum casts, and
 * BOLIDE_RESTRICT instead of the C99 keyword. */
#ifndef BOLIDE_INLINE_H
#define BOLIDE_INLINE_H

#ifdef __CUDACC__
#define BOLIDE_HD __host__ __device__
#define BOLIDE_RESTRICT __restrict__
#else
#define BOLIDE_HD
#define BOLIDE_RESTRICT restrict
#endif

/* The pair functions sit in the innermost loops: inline them always (GCC
 * otherwise keeps some out of line when they are used in several loops). */
#if defined(__CUDACC__)
#define BOLIDE_INLINE static inline BOLIDE_HD
#elif defined(__GNUC__)
#define BOLIDE_INLINE static inline __attribute__((always_inline))
#else
#define BOLIDE_INLINE static inline
#endif

/** 1/sqrt(x): on the GPU the device's rsqrt (one approximation and Newton
 *  steps, at most 1 ulp off; a double division and square root are long
 *  instruction sequences there), on the CPU the correctly rounded
 *  1.0 / sqrt(x).  The two differ by round-off. */
#if defined(__CUDA_ARCH__)
#define BOLIDE_RSQRT(x) rsqrt(x)
#else
#define BOLIDE_RSQRT(x) (1.0 / sqrt(x))
#endif

/** For CPU-only helpers of the innermost loops. */
#if defined(__GNUC__)
#define BOLIDE_ALWAYS_INLINE static inline __attribute__((always_inline))
#else
#define BOLIDE_ALWAYS_INLINE static inline
#endif

#endif
