/* Glue between the structure of arrays and the pair interactions: load what
 * a loop reads of particle i into the small structs of the _iact.h files, and
 * add an accumulator back.  Shared by the CPU loops and the CUDA kernels. */
#ifndef BOLIDE_HYDRO_PARTS_H
#define BOLIDE_HYDRO_PARTS_H

#include "density/density_iact.h"
#include "force/force_iact.h"
#include "inline.h"
#include "part.h"

/** Zero the density accumulators of particle i. */
BOLIDE_INLINE void hydro_density_reset(struct parts *BOLIDE_RESTRICT p, size_t i) {
  p->rho[i] = p->rho_dh[i] = p->wcount[i] = p->wcount_dh[i] = 0.0;
  p->div_v[i] = p->curl_vx[i] = p->curl_vy[i] = p->curl_vz[i] = 0.0;
}

/** Add a density accumulator to particle i. */
BOLIDE_INLINE void hydro_density_add(struct parts *BOLIDE_RESTRICT p, size_t i,
                                     const struct density_acc *a) {
  p->rho[i] += a->rho;
  p->rho_dh[i] += a->rho_dh;
  p->wcount[i] += a->wcount;
  p->wcount_dh[i] += a->wcount_dh;
  p->div_v[i] += a->div_v;
  p->curl_vx[i] += a->curl_v[0];
  p->curl_vy[i] += a->curl_v[1];
  p->curl_vz[i] += a->curl_v[2];
}

/** The contribution of j to i's density sums (gather form), dx = x_i - x_j. */
BOLIDE_INLINE void hydro_density_gather(struct parts *BOLIDE_RESTRICT p, size_t i, size_t j,
                                        double r2, const double dx[3], double hi_inv) {
  struct density_acc a = {0, 0, 0, 0, 0, {0, 0, 0}};
  const double dv[3] = {p->vpx[i] - p->vpx[j], p->vpy[i] - p->vpy[j], p->vpz[i] - p->vpz[j]};
  density_iact(r2, dx, hi_inv, p->m[j], dv, &a);
  hydro_density_add(p, i, &a);
}

/** Load what the force loop reads of particle i. */
BOLIDE_INLINE void hydro_force_load(const struct parts *BOLIDE_RESTRICT p, size_t i,
                                    struct force_in *in) {
  in->m = p->m[i];
  in->h_inv = 1.0 / p->h[i];
  in->rho = p->rho[i];
  in->P = p->P[i];
  in->cs = p->cs[i];
  in->u = p->up[i];
  in->f = p->f_gradh[i];
  in->balsara = p->balsara[i];
}

/** Zero the force accumulators of particle i (v_sig starts at the sound speed
 *  pair of a particle with itself). */
BOLIDE_INLINE void hydro_force_reset(struct parts *BOLIDE_RESTRICT p, size_t i) {
  p->ax[i] = p->ay[i] = p->az[i] = 0.0;
  p->du_dt[i] = p->drho_dt[i] = 0.0;
  p->v_sig[i] = 2.0 * p->cs[i];
}

/** Add a force accumulator to particle i. */
BOLIDE_INLINE void hydro_force_add(struct parts *BOLIDE_RESTRICT p, size_t i,
                                   const struct force_acc *a) {
  p->ax[i] += a->a[0];
  p->ay[i] += a->a[1];
  p->az[i] += a->a[2];
  p->du_dt[i] += a->du_dt;
  p->drho_dt[i] += a->drho_dt;
  if (a->v_sig > p->v_sig[i]) p->v_sig[i] = a->v_sig;
}

#endif
