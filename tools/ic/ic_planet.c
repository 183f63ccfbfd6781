/* Hydrostatic profiles of layered planets (Kegerreis et al. 2019, MNRAS
 * 487, 5029, Appendix A; Ruiz-Bonilla et al. 2021, MNRAS 500, 2861, woma).
 *
 * From the surface (r = R, m = M, P = P_s, T = T_s) the profile is
 * integrated inward in n thin shells of width dr = R / n:
 *   m(r - dr) = m(r) - 4 pi r^2 rho dr,  P(r - dr) = P(r) + G m rho / r^2 dr
 * with rho from the EOS at the new P and the layer's temperature relation
 * (the explicit scheme of Kegerreis et al. 2019, eqs. A1-A2, as in woma).
 * If mass is left at the centre the planet is too small, if it runs out
 * before the centre too large: R (or M when R is given) is bisected until
 * the mass is used up at the centre.  See theory/planets.md. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "src/error.h"
#include "tools/ic/ic_planet.h"

uint64_t ic_rng_next(uint64_t *s) {
  uint64_t z = (*s += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

double ic_rng_uniform(uint64_t *s) {
  return (double)(ic_rng_next(s) >> 11) / 9007199254740992.0;
}

int ic_planet_parse_trho(const char *s, struct ic_planet_layer *l) {
  char *end;
  if (strcmp(s, "isothermal") == 0) {
    l->trho = IC_PLANET_TRHO_POWER;
    l->alpha = 0;
  } else if (strcmp(s, "adiabatic") == 0) {
    l->trho = IC_PLANET_TRHO_ADIABATIC;
  } else if (strncmp(s, "power=", 6) == 0) {
    l->trho = IC_PLANET_TRHO_POWER;
    l->alpha = strtod(s + 6, &end);
    if (end == s + 6 || *end || !isfinite(l->alpha)) return -1;
  } else {
    return -1;
  }
  return 0;
}

/** Pressure of material mat at (rho, u). */
static double ic_planet_P(const struct material *mat, double rho, double u) {
  double P, cs;
  material_eos(mat, rho, u, &P, &cs);
  return P;
}

/** Tabulate woma's cold energy of a Tillotson layer: du/drho = P(rho, u) /
 *  rho^2 from u(rho0) = 0 (the isentrope through the reference state;
 *  Ruiz-Bonilla et al. 2021, Sect. 2.3), by Heun steps on a uniform grid
 *  from 0.05 to 30 rho0, both ways from rho0. */
static void ic_planet_cold_table(struct ic_planet_layer *l) {
  const struct material *mat = &l->mat;
  const double rho0 = mat->rho0;
  l->cold_n = 60000;
  l->cold_lo = 0.05 * rho0;
  l->cold_drho = (30.0 - 0.05) * rho0 / (l->cold_n - 1);
  l->u_cold = error_malloc(sizeof(double) * (size_t)l->cold_n, "planet profile");
  const int k0 = (int)floor((rho0 - l->cold_lo) / l->cold_drho);
  /* first step from rho0 to the grid points on either side */
  for (int dir = -1; dir <= 1; dir += 2) {
    int k = dir < 0 ? k0 : k0 + 1;
    double rho = rho0, u = 0.0;
    for (; k >= 0 && k < l->cold_n; k += dir) {
      const double rho1 = l->cold_lo + k * l->cold_drho;
      const double d = rho1 - rho;
      const double f0 = ic_planet_P(mat, rho, u) / (rho * rho);
      const double f1 = ic_planet_P(mat, rho1, u + d * f0) / (rho1 * rho1);
      u += 0.5 * d * (f0 + f1);
      rho = rho1;
      l->u_cold[k] = u;
    }
  }
}

/** Cold energy at rho (linear interpolation, linear extrapolation). */
static double ic_planet_u_cold(const struct ic_planet_layer *l, double rho) {
  double x = (rho - l->cold_lo) / l->cold_drho;
  int k = (int)floor(x);
  if (k < 0) k = 0;
  if (k > l->cold_n - 2) k = l->cold_n - 2;
  x -= k;
  return l->u_cold[k] + x * (l->u_cold[k + 1] - l->u_cold[k]);
}

double ic_planet_u_rho_T(const struct ic_planet_layer *l, double rho, double T) {
  const struct material *mat = &l->mat;
  if (l->u_cold) return ic_planet_u_cold(l, rho) + mat->eos.tillotson.cv * T;
  if (!material_has_temperature(mat)) return 0.0;
  /* invert T(rho, u), increasing in u, by bracketing and bisection */
  double lo = 0.0, hi = 1e3;
  for (int i = 0; i < 200 && material_temperature(mat, rho, hi) < T; i++) lo = hi, hi *= 4;
  for (int i = 0; i < 200 && hi - lo > 1e-14 * hi; i++) {
    const double mid = 0.5 * (lo + hi);
    if (material_temperature(mat, rho, mid) < T)
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

double ic_planet_T_rho_u(const struct ic_planet_layer *l, double rho, double u) {
  if (l->u_cold) return (u - ic_planet_u_cold(l, rho)) / l->mat.eos.tillotson.cv;
  return material_temperature(&l->mat, rho, u);
}

void ic_planet_spec_prepare(struct ic_planet_spec *s, const char *what) {
  if (s->n_layers < 1) error_exit("%s: no layer materials given", what);
  if (!(s->M > 0) && !(s->R > 0)) error_exit("%s: give the total mass or the radius", what);
  if (s->M > 0 && s->R > 0) error_exit("%s: give the total mass or the radius, not both", what);
  double fsum = 0;
  for (int k = 0; k < s->n_layers; k++) {
    struct ic_planet_layer *l = &s->layer[k];
    fsum += l->mass_frac;
    if (s->M > 0 && s->n_layers > 1 && !(l->mass_frac > 0))
      error_exit("%s: a planet of given mass needs a mass fraction per layer", what);
    if (s->R > 0 && s->n_layers > 1 && !(l->r_out > 0))
      error_exit("%s: a planet of given radius needs a radius per layer", what);
    if (k > 0 && s->R > 0 && l->r_out <= s->layer[k - 1].r_out)
      error_exit("%s: layer radii must increase outward", what);
    if (!(l->mat.rho0 > 0))
      error_exit(
          "%s: material '%s' has no reference density (a gas?): the profile needs one to "
          "bracket the radius",
          what, l->mat.name);
    if (l->mat.eos_type == EOS_TILLOTSON) {
      if (!(l->mat.eos.tillotson.cv > 0))
        error_exit("%s: Tillotson material '%s' needs cv for temperatures", what, l->mat.name);
      if (!l->u_cold) ic_planet_cold_table(l);
    }
  }
  if (s->M > 0 && s->n_layers > 1 && fabs(fsum - 1) > 1e-6)
    error_exit("%s: the mass fractions add up to %g, not 1", what, fsum);
  if (s->R > 0 && s->n_layers > 1 && fabs(s->layer[s->n_layers - 1].r_out - s->R) > 1e-9 * s->R)
    error_exit("%s: the last layer radius must equal the radius", what);
  if (s->n_layers == 1) s->layer[0].mass_frac = 1, s->layer[0].r_out = s->R;
  if (!(s->P_s >= 0) || !(s->T_s >= 0)) error_exit("%s: negative surface P or T", what);
  if (s->n_prof < 100) error_exit("%s: at least 100 profile steps", what);
}

/** State of the inward integration in one layer. */
struct ic_planet_state {
  const struct ic_planet_layer *l; /**< current layer */
  double K;                        /**< power law: T = K rho^alpha */
  double rho, u, P;                /**< previous point (adiabatic step) */
};

/** u at density rho and target pressure P in the current layer. */
static double ic_planet_state_u(const struct ic_planet_state *st, double rho, double P) {
  const struct ic_planet_layer *l = st->l;
  if (l->trho ==
      IC_PLANET_TRHO_ADIABATIC) /* trapezoidal du = P / rho^2 drho from the previous point */
    return st->u + 0.5 * (st->P / (st->rho * st->rho) + P / (rho * rho)) * (rho - st->rho);
  return ic_planet_u_rho_T(l, rho, st->K * pow(rho, l->alpha));
}

/** Density at pressure P: bracket from rho_guess geometrically, then bisect. */
static double ic_planet_solve_rho(const struct ic_planet_state *st, double P, double rho_guess) {
  const struct material *mat = &st->l->mat;
#define IC_PLANET_F(r) (ic_planet_P(mat, (r), ic_planet_state_u(st, (r), P)) - P)
  double lo = rho_guess, hi = rho_guess;
  if (IC_PLANET_F(rho_guess) < 0) {
    for (int i = 0; i < 400 && IC_PLANET_F(hi) < 0; i++) lo = hi, hi *= 1.05;
  } else {
    for (int i = 0; i < 400 && IC_PLANET_F(lo) >= 0; i++) hi = lo, lo /= 1.05;
  }
  for (int i = 0; i < 100 && hi - lo > 1e-13 * hi; i++) {
    const double mid = 0.5 * (lo + hi);
    if (IC_PLANET_F(mid) < 0)
      lo = mid;
    else
      hi = mid;
  }
#undef IC_PLANET_F
  return 0.5 * (lo + hi);
}

/** Start layer k at pressure P and temperature T (continuous across the
 *  boundary); returns the density at the top of the layer. */
static double ic_planet_state_enter(struct ic_planet_state *st, const struct ic_planet_spec *s,
                                    int k, double P, double T, double rho_guess) {
  st->l = &s->layer[k];
  /* the density at (P, T): isothermal relation for the first solve */
  st->K = T;
  const enum ic_planet_trho trho = st->l->trho;
  const double alpha = st->l->alpha;
  st->l = &s->layer[k];
  struct ic_planet_layer tmp = *st->l;
  tmp.trho = IC_PLANET_TRHO_POWER;
  tmp.alpha = 0;
  struct ic_planet_state iso = {.l = &tmp, .K = T};
  const double rho = ic_planet_solve_rho(&iso, P, rho_guess > 0 ? rho_guess : st->l->mat.rho0);
  st->K = trho == IC_PLANET_TRHO_POWER ? T / pow(rho, alpha) : 0;
  st->rho = rho;
  st->u = ic_planet_u_rho_T(st->l, rho, T);
  st->P = P;
  return rho;
}

/** One inward integration at (R, M).  Fills the arrays of prof (n + 1
 *  points, surface first) when prof is not NULL; returns the mass left at
 *  the centre, or minus the radius where the mass ran out (scaled to be
 *  negative). */
static double ic_planet_integrate(const struct ic_planet_spec *s, double R, double M, double G,
                                  struct ic_planet_profile *prof) {
  const int n = s->n_prof;
  const double dr = R / n;
  /* layer boundaries: enclosed masses (mass mode) or radii */
  double m_in[IC_PLANET_MAX_LAYERS];
  double acc = 0;
  for (int k = 0; k < s->n_layers; k++) m_in[k] = acc * M, acc += s->layer[k].mass_frac;
  const int mass_mode = s->M > 0;
  int k = s->n_layers - 1;
  struct ic_planet_state st;
  double r = R, m = M, P = s->P_s, T = s->T_s;
  double rho = ic_planet_state_enter(&st, s, k, P, T, 0), u = st.u;
  for (int i = 0;; i++) {
    if (prof) {
      prof->r[i] = r, prof->m[i] = m, prof->rho[i] = rho, prof->P[i] = P, prof->u[i] = u;
      prof->T[i] = ic_planet_T_rho_u(st.l, rho, u);
      prof->layer[i] = k;
    }
    if (i == n) break;
    const double r1 = i == n - 1 ? 0.0 : r - dr;
    const double m1 = m - 4 * M_PI * r * r * rho * dr;
    const double P1 = P + G * m * rho / (r * r) * dr;
    if (m1 <= 0 && i < n - 1) return -r1 / R;
    /* entering the next layer inward? */
    while (k > 0 && (mass_mode ? m1 < m_in[k] : r1 < s->layer[k - 1].r_out)) {
      T = ic_planet_T_rho_u(st.l, rho, u);
      k--;
      if (prof) prof->r_layer[k] = r1;
      rho = ic_planet_state_enter(&st, s, k, P1, T, 0);
    }
    const double rho1 = ic_planet_solve_rho(&st, P1, rho);
    u = ic_planet_state_u(&st, rho1, P1);
    st.rho = rho1, st.u = u, st.P = P1;
    r = r1, m = m1, P = P1, rho = rho1;
  }
  return m / M;
}

void ic_planet_profile_make(struct ic_planet_spec *s, struct ic_planet_profile *prof, double G) {
  const int mass_mode = s->M > 0;
  double rho_max = 0, rho_min = INFINITY;
  for (int k = 0; k < s->n_layers; k++) {
    rho_max = fmax(rho_max, s->layer[k].mat.rho0);
    rho_min = fmin(rho_min, s->layer[k].mat.rho0);
  }
  double lo, hi, R = s->R, M = s->M;
  if (mass_mode) {
    /* R between uniform spheres of 50 rho0 and 0.05 rho0 */
    lo = cbrt(3 * M / (4 * M_PI * 50 * rho_max));
    hi = cbrt(3 * M / (4 * M_PI * 0.05 * rho_min));
  } else {
    lo = 4.0 / 3.0 * M_PI * R * R * R * 0.05 * rho_min;
    hi = 4.0 / 3.0 * M_PI * R * R * R * 50 * rho_max;
  }
  /* bisection: mass left at the centre means R too small (M too large) */
  for (int it = 0; it < 100 && hi - lo > 1e-10 * hi; it++) {
    const double mid = 0.5 * (lo + hi);
    const double left = mass_mode ? ic_planet_integrate(s, mid, M, G, NULL)
                                  : ic_planet_integrate(s, R, mid, G, NULL);
    if ((left > 0) == mass_mode)
      lo = mid;
    else
      hi = mid;
  }
  if (mass_mode)
    R = lo;
  else
    M = hi;
  const size_t n = (size_t)s->n_prof + 1;
  memset(prof, 0, sizeof *prof);
  prof->n = n;
  double **arr[] = {&prof->r, &prof->m, &prof->rho, &prof->P, &prof->T, &prof->u};
  for (size_t a = 0; a < sizeof arr / sizeof arr[0]; a++)
    *arr[a] = error_malloc(n * sizeof(double), "planet profile");
  prof->layer = error_malloc(n * sizeof(int), "planet profile");
  prof->n_layers = s->n_layers;
  const double left = ic_planet_integrate(s, R, M, G, prof);
  if (!(left >= 0 && left <= 1e-3) || !isfinite(R) || !isfinite(M))
    error_exit("planet: the profile did not converge (mass left at the centre %g of the total)",
               left);
  /* centre first */
  for (size_t i = 0; i < n / 2; i++) {
    const size_t j = n - 1 - i;
    for (size_t a = 0; a < sizeof arr / sizeof arr[0]; a++) {
      double *v = *arr[a];
      const double t = v[i];
      v[i] = v[j], v[j] = t;
    }
    const int t = prof->layer[i];
    prof->layer[i] = prof->layer[j], prof->layer[j] = t;
  }
  prof->R = R, prof->M = M;
  prof->r_layer[s->n_layers - 1] = R;
  s->R = R, s->M = M;
}

void ic_planet_profile_uniform(struct ic_planet_profile *prof, const struct material *mat, double R,
                               double rho, double u, int n) {
  memset(prof, 0, sizeof *prof);
  prof->n = (size_t)n + 1;
  double **arr[] = {&prof->r, &prof->m, &prof->rho, &prof->P, &prof->T, &prof->u};
  for (size_t a = 0; a < sizeof arr / sizeof arr[0]; a++)
    *arr[a] = error_malloc(prof->n * sizeof(double), "planet profile");
  prof->layer = error_malloc(prof->n * sizeof(int), "planet profile");
  for (size_t i = 0; i < prof->n; i++) {
    const double r = R * (double)i / n;
    prof->r[i] = r;
    prof->m[i] = 4.0 / 3.0 * M_PI * r * r * r * rho;
    prof->rho[i] = rho;
    prof->u[i] = u;
    prof->P[i] = ic_planet_P(mat, rho, u);
    prof->T[i] = material_temperature(mat, rho, u);
    prof->layer[i] = 0;
  }
  prof->n_layers = 1;
  prof->R = R;
  prof->M = prof->m[prof->n - 1];
  prof->r_layer[0] = R;
}

void ic_planet_profile_write(const struct ic_planet_profile *prof, const char *path) {
  char tmp[4096];
  snprintf(tmp, sizeof tmp, "%s.tmp", path);
  FILE *f = fopen(tmp, "w");
  if (!f) error_exit("%s: cannot write the profile", tmp);
  fprintf(f, "# r[m] m[kg] rho[kg/m^3] P[Pa] T[K] u[J/kg] layer\n");
  for (size_t i = 0; i < prof->n; i++)
    fprintf(f, "%.10e %.10e %.10e %.10e %.10e %.10e %d\n", prof->r[i], prof->m[i], prof->rho[i],
            prof->P[i], prof->T[i], prof->u[i], prof->layer[i]);
  if (fclose(f) != 0 || rename(tmp, path) != 0) {
    remove(tmp);
    error_exit("%s: cannot write the profile", path);
  }
}

void ic_planet_profile_free(struct ic_planet_profile *prof) {
  free(prof->r), free(prof->m), free(prof->rho), free(prof->P), free(prof->T), free(prof->u);
  free(prof->layer);
  memset(prof, 0, sizeof *prof);
}

void ic_planet_spec_free(struct ic_planet_spec *s) {
  for (int k = 0; k < s->n_layers; k++) free(s->layer[k].u_cold), s->layer[k].u_cold = NULL;
}
