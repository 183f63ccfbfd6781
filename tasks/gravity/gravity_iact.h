/* Self-gravity: the Cartesian fast multipole method, written once.
 *
 * These inline functions are the physics of every gravity task: the CPU walk
 * (tasks/gravity/gravity_cpu.c) and, later, the CUDA kernels call them.  They
 * compile as C11 and as CUDA C++ (no tables in global memory, no VLAs).
 * theory/gravity.md derives every formula; the equation numbers (G1)...(G14)
 * below refer to it.
 *
 * Method (Greengard & Rokhlin 1987 for the idea; Dehnen 2000, ApJ 536, L39
 * and Dehnen 2002, JCP 179, 27 for the Cartesian form):
 *   - a cell's multipole moments about its centre of mass z_A,
 *       M_n = sum_j m_j (x_j - z_A)^n / n!                        (G1)
 *     for multi-indices n = (nx, ny, nz), |n| = nx + ny + nz <= p;
 *   - its potential at x, with R = x - z_A,
 *       phi(x) = -G sum_n (-1)^|n| M_n D_n(R),  D_n = d^n (1/|R|) (G3)
 *   - the local expansion ("field tensor") of a cell B about z_B,
 *       phi(z_B + s) = G sum_k F_k s^k / k!                       (G5)
 *     accumulated from cells A by M2L:
 *       F_k += - sum_{|n| <= p - |k|} (-1)^|n| M^A_n D_{n+k}(z_B - z_A) (G6)
 *   - the shift operators M2M (G2) and L2L (G7), and the evaluation L2P (G8).
 * The expansion order p (1 <= p <= GRAVITY_ORDER_MAX) is a run-time argument;
 * arrays are sized for GRAVITY_ORDER_MAX.  Potential and acceleration are
 * both carried: the potential is exact to order p, the acceleration to order
 * p - 1 in the local expansion (it is a derivative of (G5)).
 *
 * Multi-indices are stored in graded order: all of order 0, then order 1
 * (x, y, z), order 2 (xx, xy, xz, yy, yz, zz), ...; gravity_index() maps
 * (nx, ny, nz) to the position without a table.
 *
 * Softening (theory/gravity.md, "Softening"):
 *   GRAVITY_SOFTENING_SPLINE (default): the potential of a Wendland C2 mass
 *     distribution of compact support H = 3 eps (Wendland 1995; used by
 *     SWIFT, Schaller et al. 2024, MNRAS 530, 2378), exactly Newtonian for
 *     r >= H, with the same central potential -G m / eps as a Plummer sphere
 *     of softening eps.  Multipoles are used only between cells further than
 *     H apart, so the expansions stay those of 1/r.
 *   GRAVITY_SOFTENING_PLUMMER: phi = -G m / sqrt(r^2 + eps^2) (Plummer 1911;
 *     Aarseth 1963).  It is never Newtonian, so the expansions use the
 *     derivatives of the softened 1/sqrt(R^2 + eps^2) (same formula (G4) with
 *     r^2 -> r^2 + eps^2): far field and near field stay consistent. */
#ifndef BOLIDE_GRAVITY_IACT_H
#define BOLIDE_GRAVITY_IACT_H

#include <math.h>

#include "src/inline.h"

/** Full unrolling of the loops over multi-indices, for a translation unit
 *  that defines GRAVITY_UNROLL_LOOPS before including this header and calls
 *  the operators with the order a compile-time constant (gravity_cpu.c
 *  instantiates each order): the compiler then folds every index
 *  (gravity_index) and factorial, several times faster.  Elsewhere (run-time
 *  order) the loops stay loops.  In CUDA the device pass unrolls. */
#if defined(GRAVITY_UNROLL_LOOPS) && defined(__CUDA_ARCH__)
#define GRAVITY_UNROLL _Pragma("unroll")
#elif defined(__CUDACC__)
/* the host pass of a .cu file: its host copies of the operators are unused */
#define GRAVITY_UNROLL
#elif defined(GRAVITY_UNROLL_LOOPS) && defined(__GNUC__) && !defined(__clang__)
#define GRAVITY_UNROLL _Pragma("GCC unroll 16")
#else
#define GRAVITY_UNROLL
#endif

/** Highest expansion order the arrays hold (p = 5: 56 coefficients). */
#define GRAVITY_ORDER_MAX 5
/** Default expansion order (theory/gravity.md, "Accuracy"). */
#define GRAVITY_ORDER_DEFAULT 5
/** Number of multi-indices n with |n| <= p. */
#define GRAVITY_NCOMP(p) (((p) + 1) * ((p) + 2) * ((p) + 3) / 6)
/** Coefficients of a multipole or field tensor of the highest order. */
#define GRAVITY_NM GRAVITY_NCOMP(GRAVITY_ORDER_MAX)
/** Derivative tensors go one order higher (M2P needs D_{n + e_i}). */
#define GRAVITY_ND GRAVITY_NCOMP(GRAVITY_ORDER_MAX + 1)
/** Support of the spline softening kernel in units of the Plummer-equivalent
 *  softening: H = 3 eps gives the central potential -G m / eps. */
#define GRAVITY_SPLINE_H_OVER_EPS 3.0

/** Softening kernels of the particle-particle interaction. */
enum gravity_softening {
  GRAVITY_SOFTENING_SPLINE = 0,  /**< Wendland C2, compact support 3 eps (default) */
  GRAVITY_SOFTENING_PLUMMER = 1, /**< Plummer sphere, 1/sqrt(r^2 + eps^2) */
};

/** Multipole of one cell about its centre of mass. */
struct gravity_multipole {
  double M[GRAVITY_NM]; /**< moments (G1); M[0] is the mass, M[1..3] vanish (centre of mass) */
  double com[3];        /**< centre of mass z_A (expansion centre) */
  double r_max;         /**< radius about com enclosing every particle of the cell */
  double power[GRAVITY_ORDER_MAX + 1]; /**< power P_n of the moments of order n <= p (G15;
                                            P_0 the mass, P_1 = 0), for the opening criterion */
};

/** Local expansion (field tensor) of one cell about its centre of mass. */
struct gravity_field {
  double F[GRAVITY_NM]; /**< coefficients of (G5), without the factor G */
};

/** Position of multi-index (nx, ny, nz) in graded order. */
BOLIDE_INLINE int gravity_index(int nx, int ny, int nz) {
  const int n = nx + ny + nz;
  const int j = ny + nz;
  return n * (n + 1) * (n + 2) / 6 + j * (j + 1) / 2 + nz;
}

/** k! for 0 <= k <= 12 (exact in double). */
BOLIDE_INLINE double gravity_factorial(int k) {
  double f = 1.0;
  for (int i = 2; i <= k; i++) f *= i;
  return f;
}

/** (-1)^k. */
BOLIDE_INLINE double gravity_sign(int k) {
  return (k & 1) ? -1.0 : 1.0;
}

/** Scaled powers t^k / k! for k = 0..q (q <= GRAVITY_ORDER_MAX + 1). */
BOLIDE_INLINE void gravity_scaled_powers(double t, int q, double *BOLIDE_RESTRICT out) {
  out[0] = 1.0;
  for (int k = 1; k <= q; k++) out[k] = out[k - 1] * t / k;
}

/** Zero every coefficient of a multipole (com and r_max untouched). */
BOLIDE_INLINE void gravity_multipole_zero(struct gravity_multipole *mp) {
  for (int i = 0; i < GRAVITY_NM; i++) mp->M[i] = 0.0;
  for (int n = 0; n <= GRAVITY_ORDER_MAX; n++) mp->power[n] = 0.0;
}

/** The power of the moments of each order n <= p (Dehnen 2014, section
 *  3.2.2), (G15):
 *    P_n^2 = n! sum_{|k| = n} k! M_k^2
 *  the Frobenius norm of the order-n moment tensor sum_j m_j d_j^(x n)
 *  (M_k carry 1/k!, (G1)): m s^n for one mass m at distance s, at most
 *  sum_j m_j |d_j|^n, and 0 for n = 1 about the centre of mass.  Orders
 *  above p are left 0. */
BOLIDE_INLINE void gravity_multipole_power(struct gravity_multipole *mp, int p) {
  int i = 0;
  double nfact = 1.0;
  for (int n = 0; n <= GRAVITY_ORDER_MAX; n++) {
    if (n > 0) nfact *= n;
    if (n > p) {
      mp->power[n] = 0.0;
      continue;
    }
    double s = 0.0;
    for (int nx = n; nx >= 0; nx--)
      for (int ny = n - nx; ny >= 0; ny--, i++) {
        const double kf =
            gravity_factorial(nx) * gravity_factorial(ny) * gravity_factorial(n - nx - ny);
        s += kf * mp->M[i] * mp->M[i];
      }
    mp->power[n] = sqrt(nfact * s);
  }
}

/** Zero a field tensor. */
BOLIDE_INLINE void gravity_field_zero(struct gravity_field *f) {
  for (int i = 0; i < GRAVITY_NM; i++) f->F[i] = 0.0;
}

/** P2M: add particle of mass m at offset d = x - com from the expansion
 *  centre to the moments up to order p (G1). */
BOLIDE_INLINE void gravity_p2m(struct gravity_multipole *mp, const double d[3], double m, int p) {
  double px[GRAVITY_ORDER_MAX + 2], py[GRAVITY_ORDER_MAX + 2], pz[GRAVITY_ORDER_MAX + 2];
  gravity_scaled_powers(d[0], p, px);
  gravity_scaled_powers(d[1], p, py);
  gravity_scaled_powers(d[2], p, pz);
  int i = 0;
  for (int n = 0; n <= p; n++)
    for (int nx = n; nx >= 0; nx--)
      for (int ny = n - nx; ny >= 0; ny--, i++) mp->M[i] += m * px[nx] * py[ny] * pz[n - nx - ny];
}

/** M2M: add the moments of a child, expanded about its centre, to those of
 *  the parent about the parent's centre; t = child com - parent com (G2):
 *    M'_n = sum_{k <= n} M_k t^(n-k) / (n-k)!  */
BOLIDE_INLINE void gravity_m2m(struct gravity_multipole *BOLIDE_RESTRICT parent,
                               const struct gravity_multipole *BOLIDE_RESTRICT child,
                               const double t[3], int p) {
  double px[GRAVITY_ORDER_MAX + 2], py[GRAVITY_ORDER_MAX + 2], pz[GRAVITY_ORDER_MAX + 2];
  gravity_scaled_powers(t[0], p, px);
  gravity_scaled_powers(t[1], p, py);
  gravity_scaled_powers(t[2], p, pz);
  int i = 0;
  for (int n = 0; n <= p; n++)
    for (int nx = n; nx >= 0; nx--)
      for (int ny = n - nx; ny >= 0; ny--, i++) {
        const int nz = n - nx - ny;
        double s = 0.0;
        for (int kx = 0; kx <= nx; kx++)
          for (int ky = 0; ky <= ny; ky++)
            for (int kz = 0; kz <= nz; kz++)
              s += child->M[gravity_index(kx, ky, kz)] * px[nx - kx] * py[ny - ky] * pz[nz - kz];
        parent->M[i] += s;
      }
}

/** The upward pass of one cell (the CPU's gravity_up and the GPU's
 *  gravity_up kernels call these two; theory/gravity.md G1, G2).
 *
 *  Leaf: mass, centre of mass, moments and r_max of the particles
 *  [i0, i1); a_min = the smallest |ga| of their previous pass (0 when a
 *  particle was never computed: "unknown"); h_support = GRAVITY_SPLINE_H_OVER_EPS
 *  h_factor max h (0 when h_factor = 0).  A massless cell keeps centre[]
 *  as its expansion centre. */
BOLIDE_INLINE void gravity_up_leaf(struct gravity_multipole *BOLIDE_RESTRICT mp, double *a_min,
                                   double *h_support, const double *BOLIDE_RESTRICT x,
                                   const double *BOLIDE_RESTRICT y, const double *BOLIDE_RESTRICT z,
                                   const double *BOLIDE_RESTRICT m, const double *BOLIDE_RESTRICT h,
                                   const double *BOLIDE_RESTRICT gax,
                                   const double *BOLIDE_RESTRICT gay,
                                   const double *BOLIDE_RESTRICT gaz, size_t i0, size_t i1,
                                   int order, double h_factor, const double centre[3]) {
  gravity_multipole_zero(mp);
  for (int k = 0; k < 3; k++) mp->com[k] = centre[k];
  mp->r_max = 0.0;
  *a_min = 0.0;
  *h_support = 0.0;
  if (i1 <= i0) return;
  double mass = 0.0, s[3] = {0.0, 0.0, 0.0}, a2_min = HUGE_VAL, h_max = 0.0;
  for (size_t i = i0; i < i1; i++) {
    mass += m[i];
    if (h[i] > h_max) h_max = h[i];
    s[0] += m[i] * x[i];
    s[1] += m[i] * y[i];
    s[2] += m[i] * z[i];
    const double a2 = gax[i] * gax[i] + gay[i] * gay[i] + gaz[i] * gaz[i];
    if (a2 < a2_min) a2_min = a2;
  }
  *a_min = sqrt(a2_min);
  if (h_factor > 0.0) *h_support = GRAVITY_SPLINE_H_OVER_EPS * h_factor * h_max;
  if (mass > 0.0)
    for (int k = 0; k < 3; k++) mp->com[k] = s[k] / mass;
  double r2max = 0.0;
  for (size_t i = i0; i < i1; i++) {
    const double d[3] = {x[i] - mp->com[0], y[i] - mp->com[1], z[i] - mp->com[2]};
    gravity_p2m(mp, d, m[i], order);
    const double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    if (r2 > r2max) r2max = r2;
  }
  mp->r_max = sqrt(r2max);
  gravity_multipole_power(mp, order);
}

/** Split cell from its n > 0 non-empty children (in progeny order):
 *  child k's multipole ch[k], a_min ch_a[k], h_support ch_h[k]. */
BOLIDE_INLINE void gravity_up_node(struct gravity_multipole *BOLIDE_RESTRICT mp, double *a_min,
                                   double *h_support, const struct gravity_multipole *const *ch,
                                   const double *ch_a, const double *ch_h, int n, int order,
                                   const double centre[3]) {
  gravity_multipole_zero(mp);
  for (int k = 0; k < 3; k++) mp->com[k] = centre[k];
  mp->r_max = 0.0;
  *h_support = 0.0;
  double mass = 0.0, s[3] = {0.0, 0.0, 0.0}, amin = HUGE_VAL;
  for (int q = 0; q < n; q++) {
    const struct gravity_multipole *mq = ch[q];
    mass += mq->M[0];
    if (ch_h[q] > *h_support) *h_support = ch_h[q];
    for (int k = 0; k < 3; k++) s[k] += mq->M[0] * mq->com[k];
    if (ch_a[q] < amin) amin = ch_a[q];
  }
  *a_min = n > 0 ? amin : 0.0;
  if (mass > 0.0)
    for (int k = 0; k < 3; k++) mp->com[k] = s[k] / mass;
  for (int q = 0; q < n; q++) {
    const struct gravity_multipole *mq = ch[q];
    const double t[3] = {mq->com[0] - mp->com[0], mq->com[1] - mp->com[1], mq->com[2] - mp->com[2]};
    gravity_m2m(mp, mq, t, order);
    const double r = sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]) + mq->r_max;
    if (r > mp->r_max) mp->r_max = r;
  }
  gravity_multipole_power(mp, order);
}

/** Coefficient of R^(n-2k) in the one-dimensional factor of (G4),
 *  n! / (2^k k! (n-2k)!) (the coefficients of the Hermite polynomials
 *  He_n): an integer, so that gravity_derivatives multiplies by exact
 *  constants instead of dividing (a double division is a long sequence of
 *  instructions on the GPU).  0 <= 2k <= n <= 12. */
BOLIDE_INLINE double gravity_hermite_coeff(int n, int k) {
  long num = 1, den = 1;
  for (int i = n - 2 * k + 1; i <= n; i++) num *= i; /* n! / (n-2k)! */
  for (int i = 2; i <= k; i++) den *= i;             /* k! */
  return (double)(num / (den << k));
}

/** Derivatives D_n(R) = d^n f(|R|) for |n| <= q of f = 1/sqrt(|R|^2 + eps2)
 *  (eps2 = 0: Newtonian 1/r; eps2 = eps^2: Plummer-softened).  For a radial
 *  function f(u), u = r^2/2, (G4):
 *    D_n = sum_{2k <= n} n! / (2^|k| k! (n-2k)!) R^(n-2k) f^(|n|-|k|)(u)
 *  with f^(m) = (-1)^m (2m-1)!! (r^2 + eps2)^(-(2m+1)/2).  The coefficient
 *  is the product of the three integers gravity_hermite_coeff(n_i, k_i).
 *  D has GRAVITY_NCOMP(q) entries, q <= GRAVITY_ORDER_MAX + 1. */
BOLIDE_INLINE void gravity_derivatives(const double R[3], double eps2, int q,
                                       double *BOLIDE_RESTRICT D) {
  const double r2 = R[0] * R[0] + R[1] * R[1] + R[2] * R[2] + eps2;
  const double inv_r2 = 1.0 / r2;
  double fm[GRAVITY_ORDER_MAX + 2]; /* f^(m) */
  double xp[GRAVITY_ORDER_MAX + 2], yp[GRAVITY_ORDER_MAX + 2], zp[GRAVITY_ORDER_MAX + 2];
  fm[0] = sqrt(inv_r2);
  xp[0] = yp[0] = zp[0] = 1.0;
  GRAVITY_UNROLL
  for (int m = 1; m <= q; m++) {
    fm[m] = -(2 * m - 1) * fm[m - 1] * inv_r2;
    xp[m] = xp[m - 1] * R[0];
    yp[m] = yp[m - 1] * R[1];
    zp[m] = zp[m - 1] * R[2];
  }
  int i = 0;
  GRAVITY_UNROLL
  for (int n = 0; n <= q; n++) GRAVITY_UNROLL
  for (int nx = n; nx >= 0; nx--) GRAVITY_UNROLL
  for (int ny = n - nx; ny >= 0; ny--, i++) {
    const int nz = n - nx - ny;
    double s = 0.0;
    GRAVITY_UNROLL
    for (int kx = 0; 2 * kx <= nx; kx++) {
      const double cx = gravity_hermite_coeff(nx, kx) * xp[nx - 2 * kx];
      GRAVITY_UNROLL
      for (int ky = 0; 2 * ky <= ny; ky++) {
        const double cy = gravity_hermite_coeff(ny, ky) * yp[ny - 2 * ky];
        GRAVITY_UNROLL
        for (int kz = 0; 2 * kz <= nz; kz++) {
          const double cz = gravity_hermite_coeff(nz, kz) * zp[nz - 2 * kz];
          s += cx * cy * cz * fm[n - kx - ky - kz];
        }
      }
    }
    D[i] = s;
  }
}

/** M2L, one direction: add to the field tensor of B the contribution of the
 *  multipole of A; D = gravity_derivatives(z_B - z_A) to order >= p (G6). */
BOLIDE_INLINE void gravity_m2l(struct gravity_field *BOLIDE_RESTRICT fb,
                               const struct gravity_multipole *BOLIDE_RESTRICT ma,
                               const double *BOLIDE_RESTRICT D, int p) {
#ifdef __CUDA_ARCH__
  /* The device: the same terms with the moments in the outer loop, each
   * M_n loaded once and added to every F_k it reaches (|k| <= p - |n|, the
   * first GRAVITY_NCOMP(p - |n|) entries in graded order).  A GPU thread
   * then holds F and D in registers but not the moments as well: at p = 5
   * the other order needs more than the 255 registers a thread has. */
  int j = 0;
  GRAVITY_UNROLL
  for (int n = 0; n <= p; n++) {
    if (n == 1) { /* the dipole vanishes about the centre of mass */
      j += 3;
      continue;
    }
    GRAVITY_UNROLL
    for (int nx = n; nx >= 0; nx--) GRAVITY_UNROLL
    for (int ny = n - nx; ny >= 0; ny--, j++) {
      const int nz = n - nx - ny;
      const double m = gravity_sign(n) * ma->M[j];
      int i = 0;
      GRAVITY_UNROLL
      for (int k = 0; k <= p - n; k++) GRAVITY_UNROLL
      for (int kx = k; kx >= 0; kx--) GRAVITY_UNROLL
      for (int ky = k - kx; ky >= 0; ky--, i++)
        fb->F[i] -= m * D[gravity_index(nx + kx, ny + ky, nz + k - kx - ky)];
    }
  }
#else
  int i = 0;
  GRAVITY_UNROLL
  for (int k = 0; k <= p; k++) GRAVITY_UNROLL
  for (int kx = k; kx >= 0; kx--) GRAVITY_UNROLL
  for (int ky = k - kx; ky >= 0; ky--, i++) {
    const int kz = k - kx - ky;
    double s = 0.0;
    int j = 0;
    GRAVITY_UNROLL
    for (int n = 0; n <= p - k; n++) {
      if (n == 1) { /* the dipole vanishes about the centre of mass */
        j += 3;
        continue;
      }
      const double sg = gravity_sign(n);
      GRAVITY_UNROLL
      for (int nx = n; nx >= 0; nx--) GRAVITY_UNROLL
      for (int ny = n - nx; ny >= 0; ny--, j++)
        s += sg * ma->M[j] * D[gravity_index(nx + kx, ny + ky, n - nx - ny + kz)];
    }
    fb->F[i] -= s;
  }
#endif
}

/** M2L, both directions at once (the symmetric pair interaction): with
 *  D = D(z_B - z_A), D_n(-R) = (-1)^|n| D_n(R) gives A's field from the same
 *  tensor (G6'). */
BOLIDE_INLINE void gravity_m2l_sym(struct gravity_field *BOLIDE_RESTRICT fa,
                                   struct gravity_field *BOLIDE_RESTRICT fb,
                                   const struct gravity_multipole *BOLIDE_RESTRICT ma,
                                   const struct gravity_multipole *BOLIDE_RESTRICT mb,
                                   const double *BOLIDE_RESTRICT D, int p) {
  int i = 0;
  GRAVITY_UNROLL
  for (int k = 0; k <= p; k++) GRAVITY_UNROLL
  for (int kx = k; kx >= 0; kx--) GRAVITY_UNROLL
  for (int ky = k - kx; ky >= 0; ky--, i++) {
    const int kz = k - kx - ky;
    double sa = 0.0, sb = 0.0;
    int j = 0;
    GRAVITY_UNROLL
    for (int n = 0; n <= p - k; n++) {
      if (n == 1) { /* the dipoles vanish about the centres of mass */
        j += 3;
        continue;
      }
      const double sg = gravity_sign(n);
      GRAVITY_UNROLL
      for (int nx = n; nx >= 0; nx--) GRAVITY_UNROLL
      for (int ny = n - nx; ny >= 0; ny--, j++) {
        const double d = D[gravity_index(nx + kx, ny + ky, n - nx - ny + kz)];
        sb += sg * ma->M[j] * d;
        sa += mb->M[j] * d;
      }
    }
    fb->F[i] -= sb;
    fa->F[i] -= gravity_sign(k) * sa;
  }
}

/** L2L: add the parent's local expansion, re-expanded about the child's
 *  centre, to the child's; t = child com - parent com (G7):
 *    F'_m = sum_{k >= m, |k| <= p} F_k t^(k-m) / (k-m)!  */
BOLIDE_INLINE void gravity_l2l(struct gravity_field *BOLIDE_RESTRICT child,
                               const struct gravity_field *BOLIDE_RESTRICT parent,
                               const double t[3], int p) {
  double px[GRAVITY_ORDER_MAX + 2], py[GRAVITY_ORDER_MAX + 2], pz[GRAVITY_ORDER_MAX + 2];
  gravity_scaled_powers(t[0], p, px);
  gravity_scaled_powers(t[1], p, py);
  gravity_scaled_powers(t[2], p, pz);
  int i = 0;
  for (int m = 0; m <= p; m++)
    for (int mx = m; mx >= 0; mx--)
      for (int my = m - mx; my >= 0; my--, i++) {
        const int mz = m - mx - my;
        double s = 0.0;
        for (int kx = mx; kx <= p; kx++)
          for (int ky = my; kx + ky <= p; ky++)
            for (int kz = mz; kx + ky + kz <= p; kz++)
              s += parent->F[gravity_index(kx, ky, kz)] * px[kx - mx] * py[ky - my] * pz[kz - mz];
        child->F[i] += s;
      }
}

/** L2P: evaluate a local expansion at offset s from its centre (G8):
 *    phi = G sum_k F_k s^k/k!,  a_i = -G sum_{|k| <= p-1} F_{k+e_i} s^k/k!
 *  adding to *pot and a[3]. */
BOLIDE_INLINE void gravity_l2p(const struct gravity_field *BOLIDE_RESTRICT f, const double s[3],
                               int p, double G, double *BOLIDE_RESTRICT pot,
                               double *BOLIDE_RESTRICT a) {
  double px[GRAVITY_ORDER_MAX + 2], py[GRAVITY_ORDER_MAX + 2], pz[GRAVITY_ORDER_MAX + 2];
  gravity_scaled_powers(s[0], p, px);
  gravity_scaled_powers(s[1], p, py);
  gravity_scaled_powers(s[2], p, pz);
  double phi = 0.0, ax = 0.0, ay = 0.0, az = 0.0;
  int i = 0;
  for (int k = 0; k <= p; k++)
    for (int kx = k; kx >= 0; kx--)
      for (int ky = k - kx; ky >= 0; ky--, i++) {
        const int kz = k - kx - ky;
        const double w = px[kx] * py[ky] * pz[kz];
        phi += f->F[i] * w;
        if (k < p) {
          ax += f->F[gravity_index(kx + 1, ky, kz)] * w;
          ay += f->F[gravity_index(kx, ky + 1, kz)] * w;
          az += f->F[gravity_index(kx, ky, kz + 1)] * w;
        }
      }
  *pot += G * phi;
  a[0] -= G * ax;
  a[1] -= G * ay;
  a[2] -= G * az;
}

/** M2P (Barnes & Hut 1986 style, to order p): potential and acceleration at
 *  R = x - com from a multipole, from (G3) and its gradient (G9):
 *    a_i = G sum_n (-1)^|n| M_n D_{n+e_i}(R).
 *  eps2 as in gravity_derivatives.  Adds to *pot and a[3]. */
BOLIDE_INLINE void gravity_m2p(const struct gravity_multipole *BOLIDE_RESTRICT mp,
                               const double R[3], double eps2, int p, double G,
                               double *BOLIDE_RESTRICT pot, double *BOLIDE_RESTRICT a) {
  double D[GRAVITY_ND];
  gravity_derivatives(R, eps2, p + 1, D);
  double phi = 0.0, ax = 0.0, ay = 0.0, az = 0.0;
  int i = 0;
  for (int n = 0; n <= p; n++) {
    if (n == 1) { /* the dipole vanishes about the centre of mass */
      i += 3;
      continue;
    }
    const double sg = gravity_sign(n);
    for (int nx = n; nx >= 0; nx--)
      for (int ny = n - nx; ny >= 0; ny--, i++) {
        const int nz = n - nx - ny;
        const double m = sg * mp->M[i];
        phi += m * D[i];
        ax += m * D[gravity_index(nx + 1, ny, nz)];
        ay += m * D[gravity_index(nx, ny + 1, nz)];
        az += m * D[gravity_index(nx, ny, nz + 1)];
      }
  }
  *pot -= G * phi;
  a[0] += G * ax;
  a[1] += G * ay;
  a[2] += G * az;
}

/** Mutual interaction of a point mass m at x with a cell B (multipole mb
 *  about z_B): M2L (G6, G6') with the point as the other cell, a multipole
 *  of mass m and no higher moments.  D = gravity_derivatives(z_B - x) to
 *  order >= p.  The point receives (G14)
 *    phi = -G sum_{|n| <= p} M_n D_n,  a_i = -G sum_{|n| <= p-1} M_n D_{n+e_i}
 *  (M2P truncated as M2L truncates, so that the pair conserves momentum) and,
 *  when fb is not NULL, B's field receives F_k -= m D_k (P2L). */
BOLIDE_INLINE void gravity_m2p_p2l(double m, const struct gravity_multipole *BOLIDE_RESTRICT mb,
                                   struct gravity_field *BOLIDE_RESTRICT fb,
                                   const double *BOLIDE_RESTRICT D, int p, double G,
                                   double *BOLIDE_RESTRICT pot, double *BOLIDE_RESTRICT a) {
  double phi = 0.0, ax = 0.0, ay = 0.0, az = 0.0;
  int i = 0;
  GRAVITY_UNROLL
  for (int n = 0; n <= p; n++) GRAVITY_UNROLL
  for (int nx = n; nx >= 0; nx--) GRAVITY_UNROLL
  for (int ny = n - nx; ny >= 0; ny--, i++) {
    const int nz = n - nx - ny;
    if (n != 1) phi += mb->M[i] * D[i]; /* B's dipole vanishes (centre of mass) */
    if (n < p && n != 1) {
      ax += mb->M[i] * D[gravity_index(nx + 1, ny, nz)];
      ay += mb->M[i] * D[gravity_index(nx, ny + 1, nz)];
      az += mb->M[i] * D[gravity_index(nx, ny, nz + 1)];
    }
    if (fb) fb->F[i] -= m * D[i];
  }
  *pot -= G * phi;
  a[0] -= G * ax;
  a[1] -= G * ay;
  a[2] -= G * az;
}

/** The spline softening kernel (theory/gravity.md G10, G11) in u = r/H for
 *  u < 1, Horner form: H wpot and H^3 wacc.  Macros, not functions, so that
 *  the one expression serves the scalar kernel below and the SSE2 P2P of
 *  gravity_cpu.c, whose operands are GCC vectors (the constants broadcast):
 *  GCC does not vectorise a plain loop over gravity_spline_kernel (sqrt may
 *  set errno, and a select between divisions may trap). */
#define GRAVITY_SPLINE_POT(u, u2) \
  (3.0 + (u2) * (-7.0 + (u2) * (21.0 + (u) * (-28.0 + (u) * (15.0 - 3.0 * (u))))))
#define GRAVITY_SPLINE_ACC(u, u2) \
  (14.0 + (u2) * (-84.0 + (u) * (140.0 + (u) * (-90.0 + 21.0 * (u)))))

/** Softened pair kernel with the spline softening of support H, without
 *  branches (the selects compile to masks or conditional moves): the spline
 *  for r2 < H2, Newtonian beyond; wpot and wacc as in
 *  gravity_softened_kernel.  inv_H = 1/H, or 0 with H = 0 (Newtonian
 *  everywhere); H2 = H^2.  The Newtonian side divides by r only where it is
 *  taken, so that coincident particles inside the support (r2 = 0) raise no
 *  division by zero. */
BOLIDE_INLINE void gravity_spline_kernel(double r2, double inv_H, double H2,
                                         double *BOLIDE_RESTRICT wpot,
                                         double *BOLIDE_RESTRICT wacc) {
  const int in = r2 < H2;
  const double r = sqrt(r2);
  const double inv_r = 1.0 / (in ? 1.0 : r);
  const double u = r * inv_H, u2 = u * u;
  *wpot = in ? inv_H * GRAVITY_SPLINE_POT(u, u2) : inv_r;
  *wacc = in ? inv_H * inv_H * inv_H * GRAVITY_SPLINE_ACC(u, u2) : inv_r * inv_r * inv_r;
}

/** Softened pair kernel: for separation r^2 and softening eps (Plummer
 *  equivalent), the potential is -G m * (*wpot) and the acceleration of i
 *  -G m * (*wacc) * (x_i - x_j).  Newtonian: wpot = 1/r, wacc = 1/r^3.
 *  Spline (G10, G11; gravity_spline_kernel), u = r/H, H = 3 eps, for u < 1:
 *    wpot = (3 - 7u^2 + 21u^4 - 28u^5 + 15u^6 - 3u^7) / H
 *    wacc = (14 - 84u^2 + 140u^3 - 90u^4 + 21u^5) / H^3
 *  Plummer (G12): wpot = (r^2+eps^2)^(-1/2), wacc = (r^2+eps^2)^(-3/2).
 *  r2 must be > 0 unless eps > 0. */
BOLIDE_INLINE void gravity_softened_kernel(double r2, double eps, int softening,
                                           double *BOLIDE_RESTRICT wpot,
                                           double *BOLIDE_RESTRICT wacc) {
  if (softening == (int)GRAVITY_SOFTENING_PLUMMER) {
    const double q = 1.0 / sqrt(r2 + eps * eps);
    *wpot = q;
    *wacc = q * q * q;
    return;
  }
  const double H = GRAVITY_SPLINE_H_OVER_EPS * eps;
#ifdef __CUDA_ARCH__
  /* The device: both sides from one reciprocal square root, then a select.
   * Near neighbours' leaves mix pairs inside and outside the support in one
   * warp, and a branch would run both sides with a square root on one of
   * them.  The same formulas; r2 = 0 (coincident particles, only inside
   * the support with eps > 0) takes the spline at u = 0. */
  {
    const double inv_H = 1.0 / H;
    const double q = r2 > 0.0 ? BOLIDE_RSQRT(r2) : 0.0;
    const double u = r2 * q * inv_H, u2 = u * u;
    const int in = r2 < H * H;
    *wpot = in ? inv_H * GRAVITY_SPLINE_POT(u, u2) : q;
    *wacc = in ? inv_H * inv_H * inv_H * GRAVITY_SPLINE_ACC(u, u2) : q * q * q;
    return;
  }
#endif
  if (r2 >= H * H) { /* outside the support: no polynomial */
    const double q = BOLIDE_RSQRT(r2);
    *wpot = q;
    *wacc = q * q * q;
    return;
  }
  gravity_spline_kernel(r2, 1.0 / H, H * H, wpot, wacc);
}

/** Softening of the pair (i, j) (Plummer equivalent): the constant eps, or,
 *  when h_factor > 0 (Gravity:softening_h_factor, spline kernel only),
 *  h_factor * max(h_i, h_j): eps_ij = max(eps_i, eps_j) with eps_i =
 *  h_factor h_i, the same for both particles of the pair, so that the pair
 *  forces are equal and opposite (momentum). */
BOLIDE_INLINE double gravity_pair_softening(double eps, double h_factor, double hi, double hj) {
  if (h_factor <= 0.0) return eps;
  return h_factor * (hi > hj ? hi : hj);
}

/** P2P: potential and acceleration of particle i from particle j of mass mj
 *  at dx = x_i - x_j, r2 = |dx|^2, with softening; adds to *pot and a[3]. */
BOLIDE_INLINE void gravity_p2p(const double dx[3], double r2, double mj, double G, double eps,
                               int softening, double *BOLIDE_RESTRICT pot,
                               double *BOLIDE_RESTRICT a) {
  double wpot, wacc;
  gravity_softened_kernel(r2, eps, softening, &wpot, &wacc);
  const double gm = G * mj;
  *pot -= gm * wpot;
  a[0] -= gm * wacc * dx[0];
  a[1] -= gm * wacc * dx[1];
  a[2] -= gm * wacc * dx[2];
}

/** Geometric multipole acceptance criterion (Dehnen 2002, with
 *  constant theta): cells A and B with centres r2 = |z_A - z_B|^2 apart and
 *  radii r_max_a, r_max_b interact through multipoles when
 *    r_max_a + r_max_b < theta |z_A - z_B|
 *  and, for the spline softening, every particle pair is further apart than
 *  the kernel support h_support (r - r_max_a - r_max_b > h_support), so the
 *  expansions of 1/r hold (pass h_support = 0 for Plummer). */
BOLIDE_INLINE int gravity_mac(double r_max_a, double r_max_b, double r2, double theta,
                              double h_support) {
  const double rs = r_max_a + r_max_b;
  if (rs * rs >= theta * theta * r2) return 0;
  const double gap = rs + h_support;
  return gap * gap < r2;
}

/** Error-based (adaptive) acceptance, one direction (Dehnen 2014, Comput.
 *  Astrophys. Cosmol. 1, 1, section 3.2; the idea of SWIFT's epsilon_fmm,
 *  Schaller et al. 2024, MNRAS 530, 2378): the acceleration error that
 *  the truncation at order p makes at any point of the sink cell A (radius
 *  rho_a about its centre) from the multipole of the source cell B (radius
 *  rho_b, powers pw_b[n] = P_n, G15) is estimated as (G13)
 *    E_{B->A} = 8 max(rho_a, rho_b) / (rho_a + rho_b)
 *               G sum_{n=0}^{p} C(p, n) P_n rho_a^(p-n) / R^(p+2)
 *  (the bound G sum_j m_j (rho_a + |d_j|)^p / R^(p+2) of the first omitted
 *  term, expanded binomially, with sum_j m_j |d_j|^n replaced by the power
 *  P_n of the moments: cancellations in B count), and the interaction is
 *  accepted when E < eps_fmm * a_min, a_min the smallest gravitational
 *  acceleration of A's particles (the previous pass's, or the first pass's
 *  estimate).  a_min <= 0 (not known) or eps_fmm <= 0 accepts: the
 *  geometric criterion then decides alone. */
BOLIDE_INLINE int gravity_mac_power(double G, const double *BOLIDE_RESTRICT pw_b, double rho_a,
                                    double rho_b, double r2, int p, double eps_fmm, double a_min) {
  if (eps_fmm <= 0.0 || a_min <= 0.0) return 1;
  const double rs = rho_a + rho_b;
  if (rs <= 0.0) return 1; /* two points: no truncation error */
  /* sum_n C(p, n) P_n rho_a^(p-n) by Horner in rho_a, from n = 0 up */
  double sum = 0.0, c = 1.0; /* c = C(p, n) */
  for (int n = 0; n <= p; n++) {
    sum = sum * rho_a + c * pw_b[n];
    c = c * (p - n) / (n + 1);
  }
  const double r = sqrt(r2);
  double den = r2;
  for (int k = 0; k < p; k++) den *= r;
  const double f = 8.0 * fmax(rho_a, rho_b) / rs;
  return f * G * sum < eps_fmm * a_min * den;
}

/** Gravitational time step (Power et al. 2003, MNRAS 338, 14, in
 *  SWIFT's form): dt = sqrt(2 eta eps / |a|) for softening eps and
 *  acceleration a; 1e300 when a = 0. */
BOLIDE_INLINE double gravity_timestep(const double a[3], double eps, double eta) {
  const double a2 = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
  if (a2 <= 0.0) return 1e300;
  return sqrt(2.0 * eta * eps / sqrt(a2));
}

#endif
