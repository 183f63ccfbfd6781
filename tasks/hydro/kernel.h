/* SPH smoothing kernels in 3D, usable on the CPU and the GPU.
 *
 * Convention (Dehnen & Aly 2012, MNRAS 425, 1068; the one SWIFT uses):
 *   h  the smoothing length, h = 2 sigma where sigma^2 = (1/3) int r^2 W dV
 *      is the kernel's variance per dimension (Dehnen & Aly 2012, Sec. 2.1);
 *   H  the compact support, H = kernel_gamma * h; W = 0 for r >= H;
 *   q  = r / H in [0, 1];
 *   W(r, h) = w(q) / H^3 with w(q) = C * (shape), normalised so that
 *      int W dV = 1 (the constant C is included in w).
 * The ratio gamma = H / h depends on the kernel only (Dehnen & Aly 2012,
 * Table 1); the values below are 1 / (2 sigma) for H = 1, closed forms in
 * theory/kernels.md, and tests/unit/test_kernels.c recomputes them.
 *
 * Every kernel is available under its own name (kernel_cubic_eval, ...,
 * kernel_wendland_c6_eval); the one chosen by configure --with-kernel
 * (KERNEL_CUBIC_SPLINE, ... in config.h) under the generic names:
 *   kernel_gamma, kernel_name, kernel_norm    compile-time constants (macros)
 *   kernel_eval(q, &w, &dw_dq)                dimensionless w(q), dw/dq
 *   kernel_W(r, h), kernel_dW_dr(r, h), kernel_dW_dh(r, h)
 *   kernel_eval_r(r, h_inv, &W, &dW_dr, &dW_dh)   all three, one call (loops)
 *   (W includes the 1/H^3 factor: these are the dimensional kernel values)
 *   kernel_ngb_number(eta)                    target neighbour number
 * and, for code that works on every kernel (tests, tools), through the
 * enum kernel_type: kernel_eval_type(), kernel_eval_r_type(),
 * kernel_type_gamma(), kernel_type_name().
 *
 * Everything is a BOLIDE_INLINE function or a macro: no symbol is exported,
 * and the header compiles as C11 and as CUDA C++. */
#ifndef BOLIDE_KERNEL_H
#define BOLIDE_KERNEL_H

#ifdef HAVE_CONFIG_H
#include "config.h"
#endif

#include "src/inline.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* clang-format off */
/** The kernels: X(ENUM, fname, name, gamma, norm)
 *   ENUM   suffix of enum kernel_type and of the config.h macro KERNEL_ENUM
 *   fname  infix of the per-kernel function kernel_<fname>_eval
 *   name   the --with-kernel name
 *   gamma  H / h (Dehnen & Aly 2012, Table 1, 3D column)
 *   norm   C, the 3D normalisation: int_0^1 4 pi q^2 w(q) dq = 1
 *          (Dehnen & Aly 2012, Table 1; Wendland 1995, Table 1) */
#define BOLIDE_KERNELS(X)                                                                 \
  X(CUBIC_SPLINE,   cubic,        "cubic-spline",   1.825741858350554,  (16.0 / M_PI))    \
  X(QUARTIC_SPLINE, quartic,      "quartic-spline", 2.018932132718121,  (15625.0 / (512.0 * M_PI))) \
  X(WENDLAND_C2,    wendland_c2,  "wendland-C2",    1.936491673103709,  (21.0 / (2.0 * M_PI))) \
  X(WENDLAND_C4,    wendland_c4,  "wendland-C4",    2.207940216581962,  (495.0 / (32.0 * M_PI))) \
  X(WENDLAND_C6,    wendland_c6,  "wendland-C6",    2.449489742783178,  (1365.0 / (64.0 * M_PI)))
/* clang-format on */
/* gamma closed forms: sqrt(10/3), sqrt(375/92), sqrt(15/4), sqrt(39/8), sqrt(6). */

/** Every kernel of BOLIDE_KERNELS, for code that loops over all of them. */
enum kernel_type {
#define KERNEL_ENUM(E, f, n, g, c) KERNEL_TYPE_##E,
  BOLIDE_KERNELS(KERNEL_ENUM)
#undef KERNEL_ENUM
      KERNEL_NR_TYPES
};

/** Cube of a non-negative number (helper: x^3). */
BOLIDE_INLINE double kernel_pow3(double x) {
  return x * x * x;
}

/** Cubic spline M4 (Monaghan & Lattanzio 1985; Dehnen & Aly 2012, Table 1):
 *  w(q) = C [(1-q)^3_+ - 4 (1/2-q)^3_+], C = 16/pi.  Returns w and dw/dq in
 *  *w and *dw_dq (both 0 for q >= 1). */
BOLIDE_INLINE void kernel_cubic_eval(double q, double *w, double *dw_dq) {
  const double C = 16.0 / M_PI;
  if (q >= 1.0) {
    *w = 0.0;
    *dw_dq = 0.0;
    return;
  }
  const double a = 1.0 - q;
  double f = a * a * a, df = -3.0 * a * a;
  if (q < 0.5) {
    const double b = 0.5 - q;
    f -= 4.0 * b * b * b;
    df += 12.0 * b * b;
  }
  *w = C * f;
  *dw_dq = C * df;
}

/** Quartic spline M5 (Dehnen & Aly 2012, Table 1):
 *  w(q) = C [(1-q)^4_+ - 5 (3/5-q)^4_+ + 10 (1/5-q)^4_+], C = 15625/(512 pi). */
BOLIDE_INLINE void kernel_quartic_eval(double q, double *w, double *dw_dq) {
  const double C = 15625.0 / (512.0 * M_PI);
  if (q >= 1.0) {
    *w = 0.0;
    *dw_dq = 0.0;
    return;
  }
  const double a = 1.0 - q;
  double f = a * a * a * a, df = -4.0 * a * a * a;
  if (q < 0.6) {
    const double b = 0.6 - q;
    f -= 5.0 * b * b * b * b;
    df += 20.0 * b * b * b;
  }
  if (q < 0.2) {
    const double c = 0.2 - q;
    f += 10.0 * c * c * c * c;
    df -= 40.0 * c * c * c;
  }
  *w = C * f;
  *dw_dq = C * df;
}

/** Wendland C2 in 3D (Wendland 1995; Dehnen & Aly 2012, Table 1):
 *  w(q) = C (1-q)^4 (1+4q), C = 21/(2 pi); dw/dq = -20 C q (1-q)^3. */
BOLIDE_INLINE void kernel_wendland_c2_eval(double q, double *w, double *dw_dq) {
  const double C = 21.0 / (2.0 * M_PI);
  if (q >= 1.0) {
    *w = 0.0;
    *dw_dq = 0.0;
    return;
  }
  const double a = 1.0 - q, a3 = a * a * a;
  *w = C * a3 * a * (1.0 + 4.0 * q);
  *dw_dq = -20.0 * C * q * a3;
}

/** Wendland C4 in 3D (Wendland 1995; Dehnen & Aly 2012, Table 1):
 *  w(q) = C (1-q)^6 (1 + 6q + 35/3 q^2), C = 495/(32 pi);
 *  dw/dq = -(56/3) C q (1-q)^5 (1+5q). */
BOLIDE_INLINE void kernel_wendland_c4_eval(double q, double *w, double *dw_dq) {
  const double C = 495.0 / (32.0 * M_PI);
  if (q >= 1.0) {
    *w = 0.0;
    *dw_dq = 0.0;
    return;
  }
  const double a = 1.0 - q, a2 = a * a, a5 = a2 * a2 * a;
  *w = C * a5 * a * (1.0 + 6.0 * q + (35.0 / 3.0) * q * q);
  *dw_dq = -(56.0 / 3.0) * C * q * a5 * (1.0 + 5.0 * q);
}

/** Wendland C6 in 3D (Wendland 1995; Dehnen & Aly 2012, Table 1):
 *  w(q) = C (1-q)^8 (1 + 8q + 25q^2 + 32q^3), C = 1365/(64 pi);
 *  dw/dq = -22 C q (1-q)^7 (1 + 7q + 16q^2). */
BOLIDE_INLINE void kernel_wendland_c6_eval(double q, double *w, double *dw_dq) {
  const double C = 1365.0 / (64.0 * M_PI);
  if (q >= 1.0) {
    *w = 0.0;
    *dw_dq = 0.0;
    return;
  }
  const double a = 1.0 - q, a2 = a * a, a4 = a2 * a2, a7 = a4 * a2 * a;
  *w = C * a7 * a * (1.0 + q * (8.0 + q * (25.0 + 32.0 * q)));
  *dw_dq = -22.0 * C * q * a7 * (1.0 + q * (7.0 + 16.0 * q));
}

/** H / h of kernel t (Dehnen & Aly 2012, Table 1). */
BOLIDE_INLINE double kernel_type_gamma(enum kernel_type t) {
  switch (t) {
#define KERNEL_CASE(E, f, n, g, c) \
  case KERNEL_TYPE_##E:            \
    return g;
    BOLIDE_KERNELS(KERNEL_CASE)
#undef KERNEL_CASE
    default:
      return 0.0;
  }
}

/** --with-kernel name of kernel t ("cubic-spline", ...). */
BOLIDE_INLINE const char *kernel_type_name(enum kernel_type t) {
  switch (t) {
#define KERNEL_CASE(E, f, n, g, c) \
  case KERNEL_TYPE_##E:            \
    return n;
    BOLIDE_KERNELS(KERNEL_CASE)
#undef KERNEL_CASE
    default:
      return "unknown";
  }
}

/** w(q) and dw/dq of kernel t (dispatch for tests and tools; the loops use
 *  the compiled-in kernel_eval, with no switch). */
BOLIDE_INLINE void kernel_eval_type(enum kernel_type t, double q, double *w, double *dw_dq) {
  switch (t) {
#define KERNEL_CASE(E, f, n, g, c)  \
  case KERNEL_TYPE_##E:             \
    kernel_##f##_eval(q, w, dw_dq); \
    return;
    BOLIDE_KERNELS(KERNEL_CASE)
#undef KERNEL_CASE
    default:
      *w = *dw_dq = 0.0;
  }
}

/* ------------------------------------------------------------ compiled-in kernel */

/* KERNEL_ETA_DEFAULT: the default of SPH:resolution_eta (and of the initial
 * conditions' h) for each kernel, a plain number so that the parameter list
 * can quote it (theory/sph.md, section 1, "Choice of kernel and eta").
 * Wendland C2: 1.7 (149 neighbours), with which the Sod tube converges on
 * lattice and glass initial conditions; the cubic spline keeps 1.2348 (48
 * neighbours, SWIFT's value), the other kernels the same eta. */
#if defined(KERNEL_CUBIC_SPLINE)
#define KERNEL_TYPE KERNEL_TYPE_CUBIC_SPLINE
#define kernel_eval kernel_cubic_eval
#define KERNEL_ETA_DEFAULT 1.2348
#elif defined(KERNEL_QUARTIC_SPLINE)
#define KERNEL_TYPE KERNEL_TYPE_QUARTIC_SPLINE
#define kernel_eval kernel_quartic_eval
#define KERNEL_ETA_DEFAULT 1.2348
#elif defined(KERNEL_WENDLAND_C2)
#define KERNEL_TYPE KERNEL_TYPE_WENDLAND_C2
#define kernel_eval kernel_wendland_c2_eval
#define KERNEL_ETA_DEFAULT 1.7
#elif defined(KERNEL_WENDLAND_C4)
#define KERNEL_TYPE KERNEL_TYPE_WENDLAND_C4
#define kernel_eval kernel_wendland_c4_eval
#define KERNEL_ETA_DEFAULT 1.2348
#elif defined(KERNEL_WENDLAND_C6)
#define KERNEL_TYPE KERNEL_TYPE_WENDLAND_C6
#define kernel_eval kernel_wendland_c6_eval
#define KERNEL_ETA_DEFAULT 1.2348
#else
#error "no SPH kernel selected: configure --with-kernel=NAME defines KERNEL_<NAME> in config.h"
#endif

/* The constants of the compiled-in kernel, taken from BOLIDE_KERNELS (one
 * conditional per kernel: the closing parentheses below count the kernels,
 * adding one to the list means adding one ')' to each). */
#define KERNEL_PICK_GAMMA(E, f, n, g, c) (KERNEL_TYPE == KERNEL_TYPE_##E ? (g) :
#define KERNEL_PICK_NAME(E, f, n, g, c) (KERNEL_TYPE == KERNEL_TYPE_##E ? (n) :
#define KERNEL_PICK_NORM(E, f, n, g, c) (KERNEL_TYPE == KERNEL_TYPE_##E ? (c) :
/** H / h of the compiled-in kernel. */
#define kernel_gamma BOLIDE_KERNELS(KERNEL_PICK_GAMMA) 0.0)))))
/** KERNEL_ETA_DEFAULT as a string literal ("1.7"), for the parameter list. */
#define KERNEL_STR_(x) #x
#define KERNEL_STR(x) KERNEL_STR_(x)
#define KERNEL_ETA_DEFAULT_STR KERNEL_STR(KERNEL_ETA_DEFAULT)
/** Name of the compiled-in kernel ("cubic-spline", ...). */
#define kernel_name BOLIDE_KERNELS(KERNEL_PICK_NAME) "unknown")))))
/** Normalisation constant C of the compiled-in kernel. */
#define kernel_norm BOLIDE_KERNELS(KERNEL_PICK_NORM) 0.0)))))

/** W, dW/dr and dW/dh from w(q) and dw/dq (helper of every kernel):
 *  W = w / H^3, dW/dr = w' / H^4 and, for the grad-h terms (Springel &
 *  Hernquist 2002; Price 2012, JCP 231, 759), from q = r / (gamma h):
 *  dW/dh = -(3 w + q w') / (H^3 h). */
BOLIDE_INLINE void kernel_derivs(double q, double w, double dw_dq, double H_inv, double h_inv,
                                 double *W, double *dW_dr, double *dW_dh) {
  const double H3_inv = kernel_pow3(H_inv);
  *W = w * H3_inv;
  *dW_dr = dw_dq * H3_inv * H_inv;
  *dW_dh = -(3.0 * w + q * dw_dq) * H3_inv * h_inv;
}

/** W, dW/dr and dW/dh of kernel t at distance r and inverse smoothing length
 *  h_inv (tests and tools; the loops use kernel_eval_r). */
BOLIDE_INLINE void kernel_eval_r_type(enum kernel_type t, double r, double h_inv, double *W,
                                      double *dW_dr, double *dW_dh) {
  const double H_inv = h_inv / kernel_type_gamma(t), q = r * H_inv;
  double w, dw;
  kernel_eval_type(t, q, &w, &dw);
  kernel_derivs(q, w, dw, H_inv, h_inv, W, dW_dr, dW_dh);
}

/** W, dW/dr and dW/dh of the compiled-in kernel in one call, from r and 1/h
 *  (what the neighbour loops use: one evaluation, no division). */
BOLIDE_INLINE void kernel_eval_r(double r, double h_inv, double *W, double *dW_dr, double *dW_dh) {
  const double H_inv = h_inv * (1.0 / kernel_gamma), q = r * H_inv;
  double w, dw;
  kernel_eval(q, &w, &dw);
  kernel_derivs(q, w, dw, H_inv, h_inv, W, dW_dr, dW_dh);
}

/** W(r, h) = w(r/H) / H^3 with H = kernel_gamma h. */
BOLIDE_INLINE double kernel_W(double r, double h) {
  double W, dW_dr, dW_dh;
  kernel_eval_r(r, 1.0 / h, &W, &dW_dr, &dW_dh);
  return W;
}

/** dW/dr at fixed h: w'(q) / H^4. */
BOLIDE_INLINE double kernel_dW_dr(double r, double h) {
  double W, dW_dr, dW_dh;
  kernel_eval_r(r, 1.0 / h, &W, &dW_dr, &dW_dh);
  return dW_dr;
}

/** dW/dh at fixed r (grad-h terms): -(3 w + q w') / (H^3 h). */
BOLIDE_INLINE double kernel_dW_dh(double r, double h) {
  double W, dW_dr, dW_dh;
  kernel_eval_r(r, 1.0 / h, &W, &dW_dr, &dW_dh);
  return dW_dh;
}

/** Target (weighted) neighbour number for SPH:resolution_eta = eta, where
 *  h = eta times the mean interparticle spacing: the number of particles in
 *  the support sphere, N_ngb = (4 pi / 3) (gamma eta)^3 (Dehnen & Aly 2012,
 *  Sec. 2; SWIFT's resolution_eta). */
BOLIDE_INLINE double kernel_ngb_number(double eta) {
  return (4.0 * M_PI / 3.0) * kernel_pow3(kernel_gamma * eta);
}

#endif
