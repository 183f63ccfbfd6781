/* Porosity models of a material: P-alpha (porosity_palpha.h) and
 * epsilon-alpha (porosity_epsalpha.h), their shared pieces (porous pressure,
 * bounds of alpha, the start-up check of the IC densities) and the host
 * functions that read and check their parameters (porosity.c).
 *
 * A porous material has a matrix EOS (the material's eos:) evaluated at the
 * matrix density rho_s = alpha rho; the bulk pressure is P_s / alpha for
 * both models (Jutzi et al. 2008 eq. 4; Wuennemann et al. 2006 eq. 3).
 * In YAML, a sub-mapping of the material (theory/porosity.md):
 *   porosity: {model: palpha, alpha_0: 2.0, p_e: 1e6, p_s: 2e8, ...}
 * Everything here compiles as C11 and as CUDA C++. */
#ifndef BOLIDE_POROSITY_H
#define BOLIDE_POROSITY_H

#include <stddef.h>
#include <stdio.h>

#include "src/inline.h"
#include "src/materials/porosity_epsalpha.h"
#include "src/materials/porosity_palpha.h"

struct params;
struct param_node;
struct unit_system;

/** Porosity models: X(name, NAME, "doc"); name is the YAML value of
 *  porosity: model:, the member of struct porosity and the prefix of the
 *  model's functions. */
#define POROSITY_MODELS(X)                                                     \
  X(palpha, PALPHA, "P-alpha, crush curve alpha(P) (Jutzi et al. 2008, 2009)") \
  X(epsalpha, EPSALPHA, "epsilon-alpha, alpha(eps_v) (Wuennemann 2006; Collins 2011)")

/** Porosity model types (POROSITY_NONE: a non-porous material). */
enum porosity_model {
  POROSITY_NONE = 0,
#define POROSITY_MODEL_ENUM(name, NAME, doc) POROSITY_##NAME,
  POROSITY_MODELS(POROSITY_MODEL_ENUM)
#undef POROSITY_MODEL_ENUM
      POROSITY_COUNT
};

/** The porosity model of one material (no pointers: copied to a GPU as is). */
struct porosity {
  enum porosity_model model;         /**< POROSITY_NONE: not porous */
  struct porosity_palpha palpha;     /**< parameters when model is POROSITY_PALPHA */
  struct porosity_epsalpha epsalpha; /**< parameters when model is POROSITY_EPSALPHA */
};

/** Initial distention alpha_0 of the model (1 when not porous). */
BOLIDE_INLINE double porosity_alpha_0(const struct porosity *por) {
  if (por->model == POROSITY_PALPHA) return por->palpha.alpha_0;
  if (por->model == POROSITY_EPSALPHA) return por->epsalpha.alpha_0;
  return 1.0;
}

/** Bulk pressure from the matrix pressure P_s(alpha rho, u) (Jutzi et al.
 *  2008 eq. 4; theory/porosity.md PA1). */
BOLIDE_INLINE double porosity_pressure(double alpha, double P_s) {
  return P_s / alpha;
}

/** alpha limited to [1, alpha_max] (alpha_max = alpha_0): after each kick. */
BOLIDE_INLINE double porosity_clamp_alpha(double alpha, double alpha_max) {
  return alpha < 1.0 ? 1.0 : (alpha > alpha_max ? alpha_max : alpha);
}

/** The IC consistency that the engine checks at start-up: the bulk density
 *  times alpha is the matrix density expected (rho_bulk alpha = rho_s, e.g.
 *  the matrix EOS's rho0 for an uncompressed body).  Returns the relative
 *  difference |rho_bulk alpha - rho_s| / rho_s when it exceeds tol (or is
 *  not a number, or alpha < 1), 0 when consistent. */
BOLIDE_INLINE double porosity_check_ic(double rho_bulk, double alpha, double rho_matrix_expected,
                                       double tol) {
  const double err = fabs(rho_bulk * alpha - rho_matrix_expected) / rho_matrix_expected;
  if (!(alpha >= 1.0)) return err > 0.0 ? err : 1.0;
  return err <= tol ? 0.0 : (err == err ? err : 1.0);
}

/* ---- host functions (porosity.c) ---- */

/** Name of a model ("palpha"; "none"), and the model of a name (-1 if none). */
const char *porosity_model_name(enum porosity_model model);
int porosity_model_from_name(const char *name);

/** Start: the model, every key at its default (NAN where required). */
void porosity_init(struct porosity *por, enum porosity_model model);

/** Set a key of the model ("p_e").  Returns 0, or -1 with a one-line
 *  message "material 'MAT': key 'porosity: K' ..." in msg (unknown key, out
 *  of range). */
int porosity_set(struct porosity *por, const char *mat, const char *key, double value, char *msg,
                 size_t len);

/** Fill the derived values (alpha_e, alpha_t, p_t defaults; eps-alpha's
 *  alpha_e, alpha_x, eps_c) and check: required keys given, ranges, and
 *  1 <= alpha_e <= alpha_0, p_e <= p_t < p_s, 1 <= alpha_t <= alpha_e,
 *  c_e and c_s together with c_e <= c_s, eps_x <= eps_e, alpha_x > 1.
 *  Returns 0 or -1 with the message in msg. */
int porosity_finalize(struct porosity *por, const char *mat, char *msg, size_t len);

/** Read the `porosity:` sub-mapping `node` of material `mat` from file
 *  `owner` (model: and the model's keys) and finalize it; every error stops
 *  with "FILE:LINE: material 'MAT': key 'porosity: K' ...". */
void porosity_from_node(struct porosity *por, const char *mat, const struct params *owner,
                        const struct param_node *node);

/** Convert the dimensional parameters from SI to the internal units. */
void porosity_convert_units(struct porosity *por, const struct unit_system *us);

/** Write the documentation of the porosity keys as YAML comments. */
void porosity_write_keys(FILE *f);

#endif
