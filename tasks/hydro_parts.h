/* Glue between the structure of arrays and the pair interactions: load what
 * a loop reads of particle i into the small structs of the _iact.h files, and
 * add an accumulator back.  Shared by the CPU loops and the CUDA kernels. */
#ifndef BOLIDE_HYDRO_PARTS_H
#define BOLIDE_HYDRO_PARTS_H

#include "tasks/density/density_iact.h"
#include "tasks/force/force_iact.h"
#include "tasks/gradient/gradient_iact.h"
#include "src/inline.h"
#include "src/part.h"
#include "src/timeline.h"

/** Zero the density accumulators of particle i. */
BOLIDE_INLINE void hydro_density_reset(struct parts *BOLIDE_RESTRICT p, size_t i) {
  p->rho[i] = p->rho_dh[i] = p->wcount[i] = p->wcount_dh[i] = 0.0;
  p->div_v[i] = p->curl_vx[i] = p->curl_vy[i] = p->curl_vz[i] = 0.0;
}

/** Particle i's density sums as they stand in the arrays, into a (the CPU
 *  loops' cache of a leaf's sums; hydro_density_sums_store writes them
 *  back). */
BOLIDE_INLINE void hydro_density_sums_load(const struct parts *BOLIDE_RESTRICT p, size_t i,
                                           struct density_acc *a) {
  a->rho = p->rho[i];
  a->rho_dh = p->rho_dh[i];
  a->wcount = p->wcount[i];
  a->wcount_dh = p->wcount_dh[i];
  a->div_v = p->div_v[i];
  a->curl_v[0] = p->curl_vx[i];
  a->curl_v[1] = p->curl_vy[i];
  a->curl_v[2] = p->curl_vz[i];
}

/** Write particle i's density sums a back into the arrays. */
BOLIDE_INLINE void hydro_density_sums_store(struct parts *BOLIDE_RESTRICT p, size_t i,
                                            const struct density_acc *a) {
  p->rho[i] = a->rho;
  p->rho_dh[i] = a->rho_dh;
  p->wcount[i] = a->wcount;
  p->wcount_dh[i] = a->wcount_dh;
  p->div_v[i] = a->div_v;
  p->curl_vx[i] = a->curl_v[0];
  p->curl_vy[i] = a->curl_v[1];
  p->curl_vz[i] = a->curl_v[2];
}

/** Add the density accumulator a to the sums s. */
BOLIDE_INLINE void density_acc_merge(struct density_acc *BOLIDE_RESTRICT s,
                                     const struct density_acc *BOLIDE_RESTRICT a) {
  s->rho += a->rho;
  s->rho_dh += a->rho_dh;
  s->wcount += a->wcount;
  s->wcount_dh += a->wcount_dh;
  s->div_v += a->div_v;
  s->curl_v[0] += a->curl_v[0];
  s->curl_v[1] += a->curl_v[1];
  s->curl_v[2] += a->curl_v[2];
}

/** Add a density accumulator to particle i (the sums loaded, merged and
 *  stored: one list of the fields). */
BOLIDE_INLINE void hydro_density_add(struct parts *BOLIDE_RESTRICT p, size_t i,
                                     const struct density_acc *a) {
  struct density_acc s;
  hydro_density_sums_load(p, i, &s);
  density_acc_merge(&s, a);
  hydro_density_sums_store(p, i, &s);
}

/** The contribution of j to i's density sums (gather form), dx = x_i - x_j. */
BOLIDE_INLINE void hydro_density_gather(struct parts *BOLIDE_RESTRICT p, size_t i, size_t j,
                                        double r2, const double dx[3], double hi_inv) {
  struct density_acc a = {0, 0, 0, 0, 0, {0, 0, 0}};
  const double dv[3] = {p->vpx[i] - p->vpx[j], p->vpy[i] - p->vpy[j], p->vpz[i] - p->vpz[j]};
  density_iact(r2, dx, hi_inv, p->m[j], dv, &a);
  hydro_density_add(p, i, &a);
}

/** Zero the gradient accumulators of particle i. */
BOLIDE_INLINE void hydro_gradient_reset(struct parts *BOLIDE_RESTRICT p, size_t i) {
  p->gmxx[i] = p->gmxy[i] = p->gmxz[i] = p->gmyy[i] = p->gmyz[i] = p->gmzz[i] = 0.0;
  p->gvxx[i] = p->gvxy[i] = p->gvxz[i] = 0.0;
  p->gvyx[i] = p->gvyy[i] = p->gvyz[i] = 0.0;
  p->gvzx[i] = p->gvzy[i] = p->gvzz[i] = 0.0;
  p->wvol[i] = 0.0;
}

/** Add a gradient accumulator to particle i. */
BOLIDE_INLINE void hydro_gradient_add(struct parts *BOLIDE_RESTRICT p, size_t i,
                                      const struct gradient_acc *a) {
  p->gmxx[i] += a->M[0];
  p->gmxy[i] += a->M[1];
  p->gmxz[i] += a->M[2];
  p->gmyy[i] += a->M[3];
  p->gmyz[i] += a->M[4];
  p->gmzz[i] += a->M[5];
  p->gvxx[i] += a->G[0];
  p->gvxy[i] += a->G[1];
  p->gvxz[i] += a->G[2];
  p->gvyx[i] += a->G[3];
  p->gvyy[i] += a->G[4];
  p->gvyz[i] += a->G[5];
  p->gvzx[i] += a->G[6];
  p->gvzy[i] += a->G[7];
  p->gvzz[i] += a->G[8];
  p->wvol[i] += a->Z;
}

/** The contribution of j to i's gradient sums (gather form), dx = x_i - x_j. */
BOLIDE_INLINE void hydro_gradient_gather(struct parts *BOLIDE_RESTRICT p, size_t i, size_t j,
                                         double r2, const double dx[3], double hi_inv) {
  struct gradient_acc a = {{0, 0, 0, 0, 0, 0}, {0, 0, 0, 0, 0, 0, 0, 0, 0}, 0};
  const double dv[3] = {p->vpx[i] - p->vpx[j], p->vpy[i] - p->vpy[j], p->vpz[i] - p->vpz[j]};
  gradient_iact(r2, dx, hi_inv, p->m[j] / p->rho[j], dv, &a);
  hydro_gradient_add(p, i, &a);
}

/** Load what the force loop reads of particle i. */
BOLIDE_INLINE void hydro_force_load(const struct parts *BOLIDE_RESTRICT p, size_t i,
                                    struct force_in *in, int solids) {
  in->m = p->m[i];
  in->h_inv = 1.0 / p->h[i];
  in->rho = p->rho[i];
  in->P = p->P[i];
  in->cs = p->cs[i];
  in->cl = solids ? p->cl[i] : in->cs;
  in->u = p->up[i];
  in->f = p->f_gradh[i];
  in->balsara = p->balsara[i];
  in->h = p->h[i];
  in->solid = (p->flags[i] & PART_SOLID) != 0;
  /* the stress tensors only where a material has strength: fluids skip twelve
   * arrays' worth of memory traffic per neighbour (force_iact reads S and R
   * only when hp->solids) */
  if (!solids) {
    for (int k = 0; k < 6; k++) in->S[k] = in->R[k] = 0.0;
    return;
  }
  /* damage reduces the deviatoric stress and the tension (Benz & Asphaug
   * 1994; theory/damage.md D5): sigma = -P_d I + (1 - d) S */
  const double d = p->dmg[i], f = 1.0 - d;
  if (in->P < 0.0) in->P *= f;
  in->S[0] = f * p->Spxx[i];
  in->S[1] = f * p->Spxy[i];
  in->S[2] = f * p->Spxz[i];
  in->S[3] = f * p->Spyy[i];
  in->S[4] = f * p->Spyz[i];
  in->S[5] = f * p->Spzz[i];
  in->R[0] = p->Rxx[i];
  in->R[1] = p->Rxy[i];
  in->R[2] = p->Rxz[i];
  in->R[3] = p->Ryy[i];
  in->R[4] = p->Ryz[i];
  in->R[5] = p->Rzz[i];
}

/** Zero the force accumulators of particle i (v_sig starts at the sound speed
 *  pair of a particle with itself). */
BOLIDE_INLINE void hydro_force_reset(struct parts *BOLIDE_RESTRICT p, size_t i) {
  p->ngb_bin_min[i] = 64; /* (above every bin: no neighbour yet) */
  p->ax[i] = p->ay[i] = p->az[i] = 0.0;
  p->du_dt[i] = p->drho_dt[i] = 0.0;
  p->v_sig[i] = 2.0 * p->cs[i];
  p->xsphx[i] = p->xsphy[i] = p->xsphz[i] = 0.0;
}

/** Particle i's force sums as they stand in the arrays, into a (the CPU
 *  loops' cache of a leaf's sums; hydro_force_sums_store writes them back). */
BOLIDE_INLINE void hydro_force_sums_load(const struct parts *BOLIDE_RESTRICT p, size_t i,
                                         struct force_acc *a) {
  a->a[0] = p->ax[i];
  a->a[1] = p->ay[i];
  a->a[2] = p->az[i];
  a->du_dt = p->du_dt[i];
  a->drho_dt = p->drho_dt[i];
  a->v_sig = p->v_sig[i];
  a->xsph[0] = p->xsphx[i];
  a->xsph[1] = p->xsphy[i];
  a->xsph[2] = p->xsphz[i];
}

/** Write particle i's force sums a back into the arrays. */
BOLIDE_INLINE void hydro_force_sums_store(struct parts *BOLIDE_RESTRICT p, size_t i,
                                          const struct force_acc *a) {
  p->ax[i] = a->a[0];
  p->ay[i] = a->a[1];
  p->az[i] = a->a[2];
  p->du_dt[i] = a->du_dt;
  p->drho_dt[i] = a->drho_dt;
  p->v_sig[i] = a->v_sig;
  p->xsphx[i] = a->xsph[0];
  p->xsphy[i] = a->xsph[1];
  p->xsphz[i] = a->xsph[2];
}

/** Add the force accumulator a to the sums s. */
BOLIDE_INLINE void force_acc_merge(struct force_acc *BOLIDE_RESTRICT s,
                                   const struct force_acc *BOLIDE_RESTRICT a) {
  s->a[0] += a->a[0];
  s->a[1] += a->a[1];
  s->a[2] += a->a[2];
  s->du_dt += a->du_dt;
  s->drho_dt += a->drho_dt;
  if (a->v_sig > s->v_sig) s->v_sig = a->v_sig;
  s->xsph[0] += a->xsph[0];
  s->xsph[1] += a->xsph[1];
  s->xsph[2] += a->xsph[2];
}

/** Add a force accumulator to particle i (the sums loaded, merged and
 *  stored: one list of the fields). */
BOLIDE_INLINE void hydro_force_add(struct parts *BOLIDE_RESTRICT p, size_t i,
                                   const struct force_acc *a) {
  struct force_acc s;
  hydro_force_sums_load(p, i, &s);
  force_acc_merge(&s, a);
  hydro_force_sums_store(p, i, &s);
}

/** The time-step limiter of individual time steps (TimeIntegration:
 *  max_bin_ratio = limit > 0; Saitoh & Makino 2009) for particle i, which
 *  ends its step now, and its neighbour j in the force loop: i's bound
 *  ngb_bin_min takes j's bin, and a neighbour j in the middle of a step
 *  more than limit bins longer than i's is asked to wake (wake; the
 *  kick ends its step, kick2_part_bins).  One function for the CPU loop
 *  and the CUDA kernel (which passes atomic = 1: several threads may ask
 *  the same j, and several lanes take the neighbours of one i). */
BOLIDE_INLINE void hydro_limiter_pair(struct parts *BOLIDE_RESTRICT p, size_t i, size_t j,
                                      int limit, int atomic) {
  const int bj = p->time_bin[j], bi = p->time_bin[i];
  if (bj < p->ngb_bin_min[i]) {
#if defined(__CUDA_ARCH__)
    /* (several lanes may take i's neighbours: tasks/iact_loop_gpu.h) */
    if (atomic) atomicMin(&p->ngb_bin_min[i], bj);
#endif
    if (!atomic) p->ngb_bin_min[i] = bj;
  }
  if ((p->flags[j] & PART_INACTIVE) && bj > bi + limit) {
    const int w = TIMELINE_NR_BINS + 1 - (bi + limit); /* > 0; larger: a shorter bin */
#if defined(__CUDA_ARCH__)
    if (atomic) {
      atomicMax(&p->wake[j], w);
      return;
    }
#endif
    (void)atomic;
    if (w > p->wake[j]) p->wake[j] = w;
  }
}

#endif
