/* Materials: keys, checks, the material table, unit conversion and the
 * loader of tabulated EOS.  See material.h. */
#include "src/materials/material.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "src/error.h"
#include "src/paths.h"
#include "src/io/units.h"

/* ------------------------------------------------------------ key tables */

/** One key of a material or of an EOS: where it lives in struct material
 *  and what it may be (from the X lists of material.h and eos_*.h). */
struct material_key {
  const char *key;         /**< YAML key */
  size_t offset;           /**< byte offset of the double in struct material */
  double def;              /**< default; NAN: required or derived */
  double lo, hi;           /**< allowed range */
  int lo_open;             /**< 1: lo itself is not allowed */
  enum material_unit unit; /**< unit kind */
  const char *doc;         /**< one-line meaning */
};

#define MATERIAL_KEY_OF_MATERIAL(st, field, k, d, l, lopen, h, kind, doc) \
  {k, offsetof(struct material, field), d, l, h, lopen, kind, doc},
#define MATERIAL_KEY_OF_EOS(st, field, k, d, l, lopen, h, kind, doc) \
  {k, offsetof(struct material, eos) + offsetof(struct st, field), d, l, h, lopen, kind, doc},

static const struct material_key material_keys[] = {MATERIAL_PARAMS(MATERIAL_KEY_OF_MATERIAL)};
#define MATERIAL_NKEYS ((int)(sizeof material_keys / sizeof material_keys[0]))

/* one key array per EOS type */
#define MATERIAL_EOS_KEY_ARRAY(name, NAME, doc) \
  static const struct material_key eos_keys_##name[] = {EOS_##NAME##_PARAMS(MATERIAL_KEY_OF_EOS)};
MATERIAL_EOS_TYPES(MATERIAL_EOS_KEY_ARRAY)

static const struct material_key *const eos_keys[EOS_COUNT] = {
#define MATERIAL_EOS_KEYS_PTR(name, NAME, doc) eos_keys_##name,
    MATERIAL_EOS_TYPES(MATERIAL_EOS_KEYS_PTR)};
static const int eos_nkeys[EOS_COUNT] = {
#define MATERIAL_EOS_KEYS_N(name, NAME, doc) \
  (int)(sizeof eos_keys_##name / sizeof(struct material_key)),
    MATERIAL_EOS_TYPES(MATERIAL_EOS_KEYS_N)};

static const char *const eos_names[EOS_COUNT] = {
#define MATERIAL_EOS_NAME(name, NAME, doc) #name,
    MATERIAL_EOS_TYPES(MATERIAL_EOS_NAME)};
static const char *const eos_docs[EOS_COUNT] = {
#define MATERIAL_EOS_DOC(name, NAME, doc) doc,
    MATERIAL_EOS_TYPES(MATERIAL_EOS_DOC)};
static const char *const strength_names[STRENGTH_COUNT] = {
#define MATERIAL_STRENGTH_NAME(name, NAME, doc) #name,
    MATERIAL_STRENGTH_TYPES(MATERIAL_STRENGTH_NAME)};

/** SI unit text and dimension of each unit kind. */
static const struct {
  const char *si;
  int a, b, c;
} material_units[] = {
#define MATERIAL_UNIT_ROW(name, si, a, b, c) {si, a, b, c},
    MATERIAL_UNITS(MATERIAL_UNIT_ROW)};

const char *material_eos_name(enum material_eos_type type) {
  return (int)type >= 0 && type < EOS_COUNT ? eos_names[type] : "unknown";
}

int material_eos_from_name(const char *name) {
  for (int k = 0; k < EOS_COUNT; k++)
    if (strcmp(name, eos_names[k]) == 0) return k;
  return -1;
}

const char *material_strength_name(enum material_strength_type type) {
  return (int)type >= 0 && type < STRENGTH_COUNT ? strength_names[type] : "unknown";
}

int material_strength_from_name(const char *name) {
  for (int k = 0; k < STRENGTH_COUNT; k++)
    if (strcmp(name, strength_names[k]) == 0) return k;
  return -1;
}

/** The double a key describes. */
static double *material_field(struct material *mat, const struct material_key *k) {
  return (double *)((char *)mat + k->offset);
}
static double material_value(const struct material *mat, const struct material_key *k) {
  return *(const double *)((const char *)mat + k->offset);
}

/** The key of that name of the material's EOS or of the material, or NULL. */
static const struct material_key *material_find_key(const struct material *mat, const char *key) {
  const int t = (int)mat->eos_type;
  for (int i = 0; i < eos_nkeys[t]; i++)
    if (strcmp(eos_keys[t][i].key, key) == 0) return &eos_keys[t][i];
  for (int i = 0; i < MATERIAL_NKEYS; i++)
    if (strcmp(material_keys[i].key, key) == 0) return &material_keys[i];
  return NULL;
}

/** Range check of one value: NULL, or what is wrong ("must be positive"). */
static const char *material_range(const struct material_key *k, double v, char *buf, size_t len) {
  if (isnan(v)) return "must be a number";
  /* infinities only as a default, and P_min = -inf: no floor (tension allowed) */
  if (isinf(v) && !(v == k->def) && !(v < 0.0 && strcmp(k->key, "P_min") == 0))
    return "must be finite";
  if (k->lo_open ? !(v > k->lo) : !(v >= k->lo)) {
    if (k->lo == 0.0) return k->lo_open ? "must be positive" : "must not be negative";
    if (k->lo == 1.0 && k->lo_open) return "must be larger than 1";
    snprintf(buf, len, "must be %s %g", k->lo_open ? ">" : ">=", k->lo);
    return buf;
  }
  if (v > k->hi) {
    snprintf(buf, len, "must be at most %g", k->hi);
    return buf;
  }
  return NULL;
}

void material_init(struct material *mat, int32_t id, const char *name,
                   enum material_eos_type type) {
  memset(mat, 0, sizeof *mat);
  mat->id = id;
  mat->swift_id = -1;
  snprintf(mat->name, sizeof mat->name, "%s", name ? name : "");
  mat->eos_type = type;
  mat->strength = STRENGTH_NONE;
  for (int i = 0; i < MATERIAL_NKEYS; i++)
    *material_field(mat, &material_keys[i]) = material_keys[i].def;
  for (int i = 0; i < eos_nkeys[type]; i++)
    *material_field(mat, &eos_keys[type][i]) = eos_keys[type][i].def;
}

int material_set(struct material *mat, const char *key, double value, char *msg, size_t len) {
  const struct material_key *k = material_find_key(mat, key);
  if (!k) {
    snprintf(msg, len, "material '%s': unknown key '%s' for EOS %s", mat->name, key,
             material_eos_name(mat->eos_type));
    return -1;
  }
  char buf[64];
  const char *bad = material_range(k, value, buf, sizeof buf);
  if (bad) {
    snprintf(msg, len, "material '%s': key '%s' %s (got %g)", mat->name, key, bad, value);
    return -1;
  }
  *material_field(mat, k) = value;
  return 0;
}

/** Per-key checks of one list: required keys given, values in range.
 *  Keys whose NAN default means "derived" are skipped while still NAN. */
static int material_check_keys(const struct material *mat, const struct material_key *keys, int n,
                               char *msg, size_t len) {
  char buf[64];
  for (int i = 0; i < n; i++) {
    const double v = material_value(mat, &keys[i]);
    if (isnan(v)) {
      if (!isnan(keys[i].def) || keys == eos_keys[mat->eos_type]) {
        snprintf(msg, len, "material '%s': key '%s' is required for EOS %s", mat->name, keys[i].key,
                 material_eos_name(mat->eos_type));
        return -1;
      }
      continue; /* derived material-level key, not yet filled */
    }
    const char *bad = material_range(&keys[i], v, buf, sizeof buf);
    if (bad) {
      snprintf(msg, len, "material '%s': key '%s' %s (got %g)", mat->name, keys[i].key, bad, v);
      return -1;
    }
  }
  return 0;
}

/** The EOS's own cross-checks (one switch, generated from the list). */
static const char *material_eos_check(const struct material *mat, const char **key) {
  switch (mat->eos_type) {
#define MATERIAL_EOS_CHECK(name, NAME, doc) \
  case EOS_##NAME:                          \
    return eos_##name##_check(&mat->eos.name, key);
    MATERIAL_EOS_TYPES(MATERIAL_EOS_CHECK)
#undef MATERIAL_EOS_CHECK
    default:
      *key = "eos";
      return "is not a known EOS";
  }
}

/** Strength-model requirements (the models come later; their parameters
 *  are checked now so that a library entry cannot be incomplete). */
static const char *material_strength_check(const struct material *mat, const char **key) {
  const enum material_strength_type s = mat->strength;
  if (s != STRENGTH_NONE && !(mat->shear_modulus > 0.0)) {
    *key = "shear_modulus";
    return "must be positive for a material with strength";
  }
  if ((s == STRENGTH_VON_MISES || s == STRENGTH_DRUCKER_PRAGER || s == STRENGTH_MOHR_COULOMB ||
       s == STRENGTH_COLLINS) &&
      !(mat->yield_stress > 0.0)) {
    *key = "yield_stress";
    return "must be positive for this strength model";
  }
  if ((s == STRENGTH_DRUCKER_PRAGER || s == STRENGTH_COLLINS) &&
      !(mat->yield_stress_max >= mat->yield_stress)) {
    *key = "yield_stress_max";
    return "must be at least yield_stress for this strength model";
  }
  if (s == STRENGTH_JOHNSON_COOK) {
    if (!(mat->jc_A > 0.0)) {
      *key = "jc_A";
      return "must be positive for the Johnson-Cook model";
    }
    if (!(mat->T_melt > mat->T_ref)) {
      *key = "T_melt";
      return "must be larger than T_ref for the Johnson-Cook model";
    }
    if (!(mat->specific_heat > 0.0) && !material_has_temperature(mat)) {
      *key = "specific_heat";
      return "must be positive for the Johnson-Cook model when the EOS defines no temperature";
    }
    if (!(mat->specific_heat > 0.0) && mat->eos_type == EOS_MIE_GRUNEISEN) {
      /* the Mie-Grueneisen temperature u / cv is 0 K at u = 0, the state of
       * initial conditions at room temperature: T* would start at 0 */
      *key = "specific_heat";
      return "must be positive for the Johnson-Cook model with the Mie-Grueneisen EOS "
             "(its temperature u/cv starts at 0 K, not at T_ref)";
    }
    if ((mat->jc_D1 != 0.0 || mat->jc_D2 != 0.0) && mat->shear_failure_strain > 0.0) {
      *key = "shear_failure_strain";
      return "cannot be combined with Johnson-Cook fracture (jc_D1, jc_D2)";
    }
  } else if (mat->jc_D1 != 0.0 || mat->jc_D2 != 0.0) {
    *key = mat->jc_D1 != 0.0 ? "jc_D1" : "jc_D2";
    return "(Johnson-Cook fracture) needs strength johnson_cook";
  }
  if (mat->spall_pressure > 0.0 &&
      !(s == STRENGTH_JOHNSON_COOK && (mat->jc_D1 != 0.0 || mat->jc_D2 != 0.0))) {
    *key = "spall_pressure";
    return "needs Johnson-Cook fracture (strength johnson_cook with jc_D1 or jc_D2)";
  }
  if (mat->viscosity > 0.0 && s != STRENGTH_NONE) {
    /* a Newtonian viscous stress belongs to fluids; a solid's deviatoric
     * stress is its elastic-plastic one */
    *key = "viscosity";
    return "is for fluids (strength none) only";
  }
  if ((mat->weibull_k > 0.0) != (mat->weibull_m > 0.0)) {
    *key = mat->weibull_k > 0.0 ? "weibull_m" : "weibull_k";
    return "must be given together with the other Weibull parameter";
  }
  return NULL;
}

int material_check(const struct material *mat, char *msg, size_t len) {
  if ((int)mat->eos_type < 0 || mat->eos_type >= EOS_COUNT) {
    snprintf(msg, len, "material '%s': key 'eos' is not a known EOS", mat->name);
    return -1;
  }
  if (mat->id < 0) {
    snprintf(msg, len, "material '%s': id %d must not be negative", mat->name, (int)mat->id);
    return -1;
  }
  const int t = (int)mat->eos_type;
  if (material_check_keys(mat, eos_keys[t], eos_nkeys[t], msg, len)) return -1;
  if (material_check_keys(mat, material_keys, MATERIAL_NKEYS, msg, len)) return -1;
  const char *key = NULL, *bad = material_eos_check(mat, &key);
  if (!bad) bad = material_strength_check(mat, &key);
  if (bad) {
    snprintf(msg, len, "material '%s': key '%s' %s", mat->name, key, bad);
    return -1;
  }
  return 0;
}

/** Reference density of the EOS (every EOS struct has rho0). */
static double material_eos_rho0(const struct material *mat) {
  switch (mat->eos_type) {
#define MATERIAL_EOS_RHO0(name, NAME, doc) \
  case EOS_##NAME:                         \
    return mat->eos.name.rho0;
    MATERIAL_EOS_TYPES(MATERIAL_EOS_RHO0)
#undef MATERIAL_EOS_RHO0
    default:
      return 0.0;
  }
}

int material_has_temperature(const struct material *mat) {
  switch (mat->eos_type) {
#define MATERIAL_EOS_HAS_T(name, NAME, doc) \
  case EOS_##NAME:                          \
    return eos_##name##_has_temperature(&mat->eos.name);
    MATERIAL_EOS_TYPES(MATERIAL_EOS_HAS_T)
#undef MATERIAL_EOS_HAS_T
    default:
      return 0;
  }
}

int material_finalize(struct material *mat, char *msg, size_t len) {
  if (material_check(mat, msg, len)) return -1;
  mat->rho0 = material_eos_rho0(mat);
  /* u < 0, the undershoot of a cold body's energy in one step, is as u = 0
   * for Tillotson (and does not enter the cold EOS), but would give the
   * ideal gas a negative pressure and fall off a table's grid */
  mat->u_floor = mat->eos_type == EOS_IDEAL_GAS || mat->eos_type == EOS_TABLE;
  if (isnan(mat->P_min)) {
    /* a fluid carries no tension (SWIFT's planetary Tillotson materials
     * floor P at 0.01 Pa, its ice at 0); a solid keeps the EOS's tension
     * (Benz & Asphaug 1999): theory/eos.md, "Pressure floor" */
    mat->P_min = mat->strength == STRENGTH_NONE ? 0.0 : -INFINITY;
  }
  if (isnan(mat->cs_min)) {
    /* Tillotson: c^2 falls to zero and below in tension and in the expanded
     * states; a floor of 10% of the bulk sound speed sqrt(A/rho0) keeps the
     * time step and the artificial viscosity finite (SWIFT floors c^2 at
     * A/rho0 itself, which is more conservative).  Other EOS: no floor. */
    mat->cs_min = mat->eos_type == EOS_TILLOTSON
                      ? 0.1 * sqrt(mat->eos.tillotson.A / mat->eos.tillotson.rho0)
                      : 0.0;
  }
  if (isnan(mat->bulk_modulus)) {
    double P = 0.0, cs = 0.0;
    if (mat->rho0 > 0.0) material_eos(mat, mat->rho0, 0.0, &P, &cs);
    mat->bulk_modulus = mat->rho0 * cs * cs;
  }
  return material_check(mat, msg, len);
}

/* ------------------------------------------------------------ the table */

void material_table_init(struct material_table *t) {
  memset(t, 0, sizeof *t);
  for (int i = 0; i < MATERIAL_ID_DIRECT; i++) t->index_of_id[i] = -1;
}

struct material *material_table_add(struct material_table *t, const struct material *mat) {
  if (material_table_find(t, mat->id)) error_exit("material id %d is defined twice", (int)mat->id);
  if (t->n >= MATERIAL_MAX)
    error_exit("too many materials (at most %d; raise MATERIAL_MAX in src/materials/material.h)",
               MATERIAL_MAX);
  t->mats[t->n] = *mat;
  if (mat->id >= 0 && mat->id < MATERIAL_ID_DIRECT) t->index_of_id[mat->id] = (int16_t)t->n;
  return &t->mats[t->n++];
}

void material_table_free(struct material_table *t) {
  for (int k = 0; k < t->n; k++) {
    struct material *m = &t->mats[k];
    if (m->eos_type != EOS_TABLE) continue;
    free((void *)m->eos.table.P);
    free((void *)m->eos.table.c2);
    free((void *)m->eos.table.T);
    free((void *)m->eos.table.ln_rho);
    free((void *)m->eos.table.ln_u);
    m->eos.table.P = m->eos.table.c2 = m->eos.table.T = NULL;
    m->eos.table.ln_rho = m->eos.table.ln_u = NULL;
  }
  t->n = 0;
}

void material_table_log(const struct material_table *t) {
  for (int k = 0; k < t->n; k++) {
    const struct material *m = &t->mats[k];
    error_log(0, "material %d '%s': EOS %s, rho0 %g, strength %s%s%s", (int)m->id, m->name,
              material_eos_name(m->eos_type), m->rho0, material_strength_name(m->strength),
              m->reference[0] ? "; " : "", m->reference);
  }
}

/* ------------------------------------------------------------ units */

/** Factor from SI to the internal system for dimension M^a L^b T^c (written
 *  here from the unit_system members so as not to depend on units.c). */
static double material_si_to_internal(const struct unit_system *us, int a, int b, int c) {
  return pow(1000.0 / us->mass_cgs, a) * pow(100.0 / us->length_cgs, b) *
         pow(1.0 / us->time_cgs, c);
}

/** Convert the keys of one list of one material. */
static void material_convert_keys(struct material *mat, const struct material_key *keys, int n,
                                  const struct unit_system *us) {
  for (int i = 0; i < n; i++) {
    const int u = (int)keys[i].unit;
    const double f =
        material_si_to_internal(us, material_units[u].a, material_units[u].b, material_units[u].c);
    *material_field(mat, &keys[i]) *= f;
  }
}

void material_table_convert_units(struct material_table *t, const struct unit_system *us) {
  const double f_rho = material_si_to_internal(us, 1, -3, 0);
  const double f_u = material_si_to_internal(us, 0, 2, -2);
  const double f_P = material_si_to_internal(us, 1, -1, -2);
  for (int k = 0; k < t->n; k++) {
    struct material *m = &t->mats[k];
    const int e = (int)m->eos_type;
    material_convert_keys(m, eos_keys[e], eos_nkeys[e], us);
    material_convert_keys(m, material_keys, MATERIAL_NKEYS, us);
    porosity_convert_units(&m->porosity, us);
    m->rho0 *= f_rho;
    if (m->eos_type == EOS_TABLE) {
      struct eos_table *tab = &m->eos.table;
      const size_t nn = (size_t)tab->n_rho * (size_t)tab->n_u;
      double *P = (double *)tab->P, *c2 = (double *)tab->c2;
      for (size_t i = 0; i < nn; i++) {
        P[i] *= f_P;
        c2[i] *= f_u; /* velocity^2 has the dimension of specific energy */
      }
      tab->ln_rho_min += log(f_rho);
      tab->ln_u_min += log(f_u);
      double *lr = (double *)tab->ln_rho, *lu = (double *)tab->ln_u;
      for (int i = 0; lr && i < tab->n_rho; i++) lr[i] += log(f_rho);
      for (int j = 0; lu && j < tab->n_u; j++) lu[j] += log(f_u);
    }
  }
}

/* ------------------------------------------------------------ EOS tables */

/** Next non-comment, non-blank line of f into buf; 0 at end of file. */
static int material_table_line(FILE *f, char *buf, int len, int *lineno) {
  while (fgets(buf, len, f)) {
    (*lineno)++;
    char *s = buf;
    while (*s == ' ' || *s == '\t') s++;
    if (*s == '#' || *s == '\n' || *s == '\r' || *s == 0) continue;
    return 1;
  }
  return 0;
}

/** Parse up to maxn numbers of a line; returns the count. */
static int material_table_numbers(const char *s, double *v, int maxn) {
  int n = 0;
  char *end;
  while (n < maxn) {
    const double x = strtod(s, &end);
    if (end == s) break;
    v[n++] = x;
    s = end;
  }
  while (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\n') s++;
  return *s ? -1 : n;
}

/** Check that x[0], x[stride], ... (n values) are log-spaced; returns the
 *  ln of the first and the spacing. */
static void material_table_axis(const char *file, const char *what, const double *x, int n,
                                size_t stride, double *ln0, double *dln) {
  for (int i = 0; i < n; i++)
    if (!(x[i * stride] > 0.0))
      error_exit("%s: %s node %d is %g: table axes must be positive (log-spaced)", file, what, i,
                 x[i * stride]);
  *ln0 = log(x[0]);
  *dln = (log(x[(n - 1) * stride]) - *ln0) / (n - 1);
  if (!(*dln > 0.0)) error_exit("%s: %s nodes must increase", file, what);
  for (int i = 0; i < n; i++) {
    const double expect = *ln0 + i * *dln;
    if (fabs(log(x[i * stride]) - expect) > 1e-6 * fmax(1.0, fabs(*dln)))
      error_exit("%s: %s node %d (%g) is not on the log-spaced grid (expected %g)", file, what, i,
                 x[i * stride], exp(expect));
  }
}

/** Strictly increasing, positive nodes x[0], x[stride], ... (n values) of
 *  any spacing (format miluphcuda).  Log-spaced nodes (each within 1e-9 of
 *  the grid in ln x, below the rounding of a file's 10 significant digits)
 *  give *ln0, *dln and *nodes = NULL (the division of eos_table_locate);
 *  others an array of their ln in *nodes (bisection, eos_table_search). */
static void material_table_axis_any(const char *file, const char *what, const double *x, int n,
                                    size_t stride, double *ln0, double *dln, const double **nodes) {
  double *l = error_malloc((size_t)n * sizeof(double), "EOS table axis");
  for (int i = 0; i < n; i++) {
    if (!(x[i * stride] > 0.0))
      error_exit("%s: %s node %d is %g: table axes must be positive (interpolated in ln)", file,
                 what, i, x[i * stride]);
    l[i] = log(x[i * stride]);
    if (i > 0 && !(l[i] > l[i - 1]))
      error_exit("%s: %s node %d (%g) after %g: the nodes must increase", file, what, i,
                 x[i * stride], x[(i - 1) * stride]);
  }
  *ln0 = l[0];
  *dln = (l[n - 1] - l[0]) / (n - 1);
  int regular = 1;
  for (int i = 0; i < n; i++)
    if (fabs(l[i] - (*ln0 + i * *dln)) > 1e-9) regular = 0;
  if (regular) {
    free(l);
    *nodes = NULL;
  } else {
    *nodes = l;
  }
}

/** c^2 = dP/drho + P/rho^2 dP/du at the nodes by centred (one-sided at the
 *  edges) differences in ln rho and ln u. */
static void material_table_sound_speed(struct eos_table *tab, double *c2) {
  const int nr = tab->n_rho, nu = tab->n_u;
  for (int i = 0; i < nr; i++) {
    const int i0 = i > 0 ? i - 1 : 0, i1 = i < nr - 1 ? i + 1 : nr - 1;
    const double rho = exp(eos_table_ln_rho_node(tab, i));
    const double hr = eos_table_ln_rho_node(tab, i1) - eos_table_ln_rho_node(tab, i0);
    for (int j = 0; j < nu; j++) {
      const int j0 = j > 0 ? j - 1 : 0, j1 = j < nu - 1 ? j + 1 : nu - 1;
      const double u = exp(eos_table_ln_u_node(tab, j));
      const double hu = eos_table_ln_u_node(tab, j1) - eos_table_ln_u_node(tab, j0);
      const double P = tab->P[i * nu + j];
      const double dPdlr = (tab->P[i1 * nu + j] - tab->P[i0 * nu + j]) / hr;
      const double dPdlu = (tab->P[i * nu + j1] - tab->P[i * nu + j0]) / hu;
      c2[i * nu + j] = dPdlr / rho + P / (rho * rho) * dPdlu / u;
    }
  }
}

static void material_table_build(struct eos_table *tab, const char *filename, int format, int nr,
                                 int nu, double *rho, double *x, double *uu, double *P, double *cs,
                                 int has_cs);

void material_eos_table_load(struct eos_table *tab, const char *filename, int format) {
  if (format == 2) {
    material_eos_table_load_swift(tab, filename);
    return;
  }
  if (format == 3) {
    material_eos_table_load_miluphcuda(tab, filename, 0, 0);
    return;
  }
  FILE *f = fopen(filename, "r");
  if (!f) error_exit("%s: cannot open the EOS table: %s", filename, strerror(errno));
  char line[1024];
  int lineno = 0;
  double v[8];
  if (!material_table_line(f, line, sizeof line, &lineno) ||
      material_table_numbers(line, v, 2) != 2 || v[0] < 2 || v[1] < 2 || v[0] > 1e5 || v[1] > 1e5 ||
      v[0] != floor(v[0]) || v[1] != floor(v[1]))
    error_exit("%s:%d: the first line must be 'N_RHO N_U' (two integers >= 2)", filename, lineno);
  const int nr = (int)v[0], nu = (int)v[1];
  const size_t nn = (size_t)nr * (size_t)nu;
  /* columns: rho u P [cs] (format 0) or rho T u P [cs] (format 1) */
  const int ncol = format == 0 ? 3 : 4;
  double *rho = error_malloc(nn * sizeof(double), "EOS table");
  double *x = error_malloc(nn * sizeof(double), "EOS table"); /* u or T */
  double *uu = format == 1 ? error_malloc(nn * sizeof(double), "EOS table") : NULL;
  double *P = error_malloc(nn * sizeof(double), "EOS table");
  double *cs = error_malloc(nn * sizeof(double), "EOS table");
  int has_cs = -1;
  for (size_t k = 0; k < nn; k++) {
    if (!material_table_line(f, line, sizeof line, &lineno))
      error_exit("%s:%d: the table ends after %zu of %zu rows", filename, lineno, k, nn);
    const int n = material_table_numbers(line, v, 6);
    if (n != ncol && n != ncol + 1)
      error_exit("%s:%d: expected %d or %d numbers (%s [cs])", filename, lineno, ncol, ncol + 1,
                 format == 0 ? "rho u P" : "rho T u P");
    if (has_cs < 0) has_cs = n == ncol + 1;
    if (has_cs != (n == ncol + 1))
      error_exit("%s:%d: every row must have the same number of columns", filename, lineno);
    rho[k] = v[0];
    x[k] = v[1];
    if (format == 1) uu[k] = v[2];
    P[k] = v[ncol - 1];
    cs[k] = has_cs ? v[ncol] : 0.0;
    if (!isfinite(P[k]) || (has_cs && !(cs[k] >= 0.0)))
      error_exit("%s:%d: pressure must be finite and sound speed >= 0", filename, lineno);
  }
  if (material_table_line(f, line, sizeof line, &lineno))
    error_exit("%s:%d: more rows than N_RHO x N_U = %zu", filename, lineno, nn);
  fclose(f);
  material_table_build(tab, filename, format, nr, nu, rho, x, uu, P, cs, has_cs);
}

/** Fill tab from the nr x nu rows read from a table file (rho varies
 *  slowest): format 0, x holds u; format 1, x holds T and uu holds u;
 *  format 3 (miluphcuda), x holds u on increasing axes of any spacing.
 *  Takes the arrays (P and cs may be replaced, all are freed or kept). */
static void material_table_build(struct eos_table *tab, const char *filename, int format, int nr,
                                 int nu, double *rho, double *x, double *uu, double *P, double *cs,
                                 int has_cs) {
  const size_t nn = (size_t)nr * (size_t)nu;
  /* rows: rho varies slowest; the same rho within a block of n_u rows */
  for (int i = 0; i < nr; i++)
    for (int j = 1; j < nu; j++)
      if (rho[i * nu + j] != rho[i * nu])
        error_exit("%s: row %d: density %g differs from %g at the start of its block of %d rows",
                   filename, i * nu + j + 1, rho[i * nu + j], rho[i * nu], nu);
  tab->n_rho = nr;
  tab->n_u = nu;
  tab->ln_rho = tab->ln_u = NULL;
  tab->rho_extrapolate = 0;
  if (format == 3)
    material_table_axis_any(filename, "density", rho, nr, (size_t)nu, &tab->ln_rho_min,
                            &tab->dln_rho, &tab->ln_rho);
  else
    material_table_axis(filename, "density", rho, nr, (size_t)nu, &tab->ln_rho_min, &tab->dln_rho);
  double *T = NULL;
  if (format == 3) {
    material_table_axis_any(filename, "energy", x, nu, 1, &tab->ln_u_min, &tab->dln_u, &tab->ln_u);
  } else if (format == 0) {
    for (int i = 0; i < nr; i++)
      if (memcmp(x + i * nu, x, nu * sizeof(double)) != 0)
        error_exit("%s: the energy nodes of density block %d differ from the first block", filename,
                   i + 1);
    material_table_axis(filename, "energy", x, nu, 1, &tab->ln_u_min, &tab->dln_u);
  } else {
    /* (rho, T) -> (rho, u): per density row, u(T) must increase; the u grid
     * is log-spaced over the range every row covers (no extrapolation), and
     * P, cs and T are linear in ln u between a row's points. */
    double umin = 0.0, umax = INFINITY;
    for (int i = 0; i < nr; i++) {
      for (int j = 1; j < nu; j++)
        if (!(uu[i * nu + j] > uu[i * nu + j - 1]) || !(x[i * nu + j] > x[i * nu + j - 1]))
          error_exit("%s: density block %d: T and u must increase along the block", filename,
                     i + 1);
      umin = fmax(umin, uu[i * nu]);
      umax = fmin(umax, uu[i * nu + nu - 1]);
    }
    if (!(umin > 0.0) || !(umax > umin))
      error_exit("%s: the density rows share no positive range of u (%g to %g)", filename, umin,
                 umax);
    tab->ln_u_min = log(umin);
    tab->dln_u = (log(umax) - log(umin)) / (nu - 1);
    double *P2 = error_malloc(nn * sizeof(double), "EOS table");
    double *cs2 = error_malloc(nn * sizeof(double), "EOS table");
    T = error_malloc(nn * sizeof(double), "EOS table");
    for (int i = 0; i < nr; i++) {
      int m = 0;
      for (int j = 0; j < nu; j++) {
        const double lu = j == nu - 1 ? log(umax) : tab->ln_u_min + j * tab->dln_u;
        while (m < nu - 2 && log(uu[i * nu + m + 1]) < lu) m++;
        const double l0 = log(uu[i * nu + m]), l1 = log(uu[i * nu + m + 1]);
        double w = (lu - l0) / (l1 - l0);
        w = w < 0.0 ? 0.0 : (w > 1.0 ? 1.0 : w);
        const size_t a = (size_t)i * nu + m;
        P2[i * nu + j] = (1 - w) * P[a] + w * P[a + 1];
        cs2[i * nu + j] = (1 - w) * cs[a] + w * cs[a + 1];
        T[i * nu + j] = (1 - w) * x[a] + w * x[a + 1];
      }
    }
    free(P);
    free(cs);
    P = P2;
    cs = cs2;
  }
  tab->P = P;
  double *c2 = error_malloc(nn * sizeof(double), "EOS table");
  if (has_cs)
    for (size_t k = 0; k < nn; k++) c2[k] = cs[k] * cs[k];
  else
    material_table_sound_speed(tab, c2);
  tab->c2 = c2;
  tab->T = T;
  free(cs);
  free(rho);
  free(x);
  free(uu);
}

/** Next number of a SWIFT table (whitespace-separated, any line layout),
 *  or a one-line error naming the file and what was being read. */
static double material_swift_number(FILE *f, const char *file, const char *what) {
  double v;
  if (fscanf(f, "%lf", &v) != 1)
    error_exit("%s: SWIFT EOS table: cannot read %s (the file ends or holds text there)", file,
               what);
  return v;
}

void material_eos_table_load_swift(struct eos_table *tab, const char *filename) {
  FILE *f = fopen(filename, "r");
  if (!f) error_exit("%s: cannot open the EOS table: %s", filename, strerror(errno));
  /* SWIFT's planetary tables (SESAME-like, as woma writes them): 12 header
   * lines, version date, N_RHO N_T, the densities, the temperatures, then
   * u P c s for every (rho, T), rho varying fastest; SI units */
  for (int k = 0; k < 12; k++) {
    int c;
    long len = 0;
    while ((c = fgetc(f)) != '\n' && c != EOF)
      if (++len > 65536)
        error_exit("%s: SWIFT EOS table: header line %d is longer than 64 KiB (not a table?)",
                   filename, k + 1);
    if (c == EOF)
      error_exit("%s: SWIFT EOS table: the file ends within its 12 header lines", filename);
  }
  (void)material_swift_number(f, filename, "the version date");
  const double dnr = material_swift_number(f, filename, "N_RHO");
  const double dnt = material_swift_number(f, filename, "N_T");
  if (dnr < 2 || dnt < 2 || dnr > 1e5 || dnt > 1e5 || dnr != floor(dnr) || dnt != floor(dnt))
    error_exit("%s: SWIFT EOS table: N_RHO N_T must be integers >= 2 (got %g %g)", filename, dnr,
               dnt);
  const int nr = (int)dnr, nt = (int)dnt;
  const size_t nn = (size_t)nr * (size_t)nt;
  double *rho_axis = error_malloc((size_t)nr * sizeof(double), "EOS table");
  double *T_axis = error_malloc((size_t)nt * sizeof(double), "EOS table");
  for (int i = 0; i < nr; i++) rho_axis[i] = material_swift_number(f, filename, "a density");
  for (int j = 0; j < nt; j++) T_axis[j] = material_swift_number(f, filename, "a temperature");
  /* SWIFT moves a first node of 0 to 1e-5 of the second (its axes are
   * logarithmic); so does Bolide */
  if (rho_axis[0] == 0.0) rho_axis[0] = 1e-5 * rho_axis[1];
  if (T_axis[0] == 0.0) T_axis[0] = 1e-5 * T_axis[1];
  double *rho = error_malloc(nn * sizeof(double), "EOS table");
  double *T = error_malloc(nn * sizeof(double), "EOS table");
  double *u = error_malloc(nn * sizeof(double), "EOS table");
  double *P = error_malloc(nn * sizeof(double), "EOS table");
  double *cs = error_malloc(nn * sizeof(double), "EOS table");
  char what[96];
  for (int j = 0; j < nt; j++)
    for (int i = 0; i < nr; i++) {
      const size_t k = (size_t)i * nt + j; /* Bolide's rows: rho slowest */
      snprintf(what, sizeof what, "u P c s of density node %d, temperature node %d", i, j);
      rho[k] = rho_axis[i];
      T[k] = T_axis[j];
      u[k] = material_swift_number(f, filename, what);
      P[k] = material_swift_number(f, filename, what);
      cs[k] = material_swift_number(f, filename, what);
      (void)material_swift_number(f, filename, what); /* entropy: not used */
      if (!isfinite(P[k]) || !(cs[k] >= 0.0))
        error_exit("%s: SWIFT EOS table: %s: pressure must be finite and sound speed >= 0",
                   filename, what);
    }
  double extra;
  if (fscanf(f, "%lf", &extra) == 1)
    error_exit("%s: SWIFT EOS table: more numbers than N_RHO x N_T = %zu rows", filename, nn);
  fclose(f);
  free(rho_axis);
  free(T_axis);
  material_table_build(tab, filename, 1, nr, nt, rho, T, u, P, cs, 1);
}

/** Append x to a growing array (doubling its capacity). */
static void material_push(double **a, size_t *cap, size_t n, double x) {
  if (n == *cap) {
    *cap = *cap ? 2 * *cap : 1024;
    double *b = realloc(*a, *cap * sizeof(double));
    if (!b) error_exit("out of memory reading an EOS table");
    *a = b;
  }
  (*a)[n] = x;
}

void material_eos_table_load_miluphcuda(struct eos_table *tab, const char *filename, int n_rho,
                                        int n_e) {
  FILE *f = fopen(filename, "r");
  if (!f) error_exit("%s: cannot open the EOS table: %s", filename, strerror(errno));
  /* miluphcuda's ANEOS lookup tables (eos.type = 7; its src/aneos.cu): 3
   * header lines, then one row per (rho, e) node, "rho e P T cs [s
   * phase_flag ...]", e varying fastest; SI units; the counts are the
   * material file's n_rho and n_e (here optional, else taken from the file) */
  int lineno = 0;
  for (int k = 0; k < 3; k++) {
    int c;
    long len = 0;
    while ((c = fgetc(f)) != '\n' && c != EOF)
      if (++len > 65536)
        error_exit(
            "%s: miluphcuda ANEOS table: header line %d is longer than 64 KiB (not a table?)",
            filename, k + 1);
    if (c == EOF)
      error_exit("%s: miluphcuda ANEOS table: the file ends within its 3 header lines", filename);
    lineno++;
  }
  double *rho = NULL, *e = NULL, *P = NULL, *T = NULL, *cs = NULL;
  size_t cap[5] = {0, 0, 0, 0, 0}, m = 0;
  char line[1024];
  double v[16];
  while (material_table_line(f, line, sizeof line, &lineno)) {
    const int n = material_table_numbers(line, v, 16);
    if (n < 5)
      error_exit("%s:%d: miluphcuda ANEOS table: expected the numbers 'rho e P T cs [s phase]'",
                 filename, lineno);
    for (int k = 0; k < 5; k++)
      if (!isfinite(v[k]))
        error_exit("%s:%d: miluphcuda ANEOS table: column %d is %g (rho e P T cs must be finite)",
                   filename, lineno, k + 1, v[k]);
    if (!(v[4] >= 0.0))
      error_exit("%s:%d: miluphcuda ANEOS table: sound speed %g < 0", filename, lineno, v[4]);
    if (m > 0 && rho && v[0] != rho[m - 1] && !(v[0] > rho[m - 1]))
      error_exit("%s:%d: miluphcuda ANEOS table: density %g after %g: the densities must increase",
                 filename, lineno, v[0], rho[m - 1]);
    material_push(&rho, &cap[0], m, v[0]);
    material_push(&e, &cap[1], m, v[1]);
    material_push(&P, &cap[2], m, v[2]);
    material_push(&T, &cap[3], m, v[3]);
    material_push(&cs, &cap[4], m, v[4]);
    m++;
  }
  fclose(f);
  if (m == 0) error_exit("%s: miluphcuda ANEOS table: no rows after the 3 header lines", filename);
  /* the energies of one density: the first block of equal densities */
  size_t ne = 1;
  while (ne < m && rho[ne] == rho[0]) ne++;
  if (n_e > 0 || n_rho > 0) {
    if (n_e <= 0 || n_rho <= 0)
      error_exit("%s: miluphcuda ANEOS table: give both n_rho and n_e, or neither", filename);
    if (m != (size_t)n_rho * (size_t)n_e)
      error_exit("%s: miluphcuda ANEOS table: %zu rows, but n_rho x n_e = %d x %d = %zu", filename,
                 m, n_rho, n_e, (size_t)n_rho * (size_t)n_e);
    if (ne != (size_t)n_e)
      error_exit("%s: miluphcuda ANEOS table: the first density has %zu energies, but n_e = %d",
                 filename, ne, n_e);
  }
  if (ne < 2 || m % ne != 0 || m / ne < 2)
    error_exit(
        "%s: miluphcuda ANEOS table: %zu rows are not N_RHO >= 2 blocks of the %zu energies "
        "of the first density",
        filename, m, ne);
  const int nr = (int)(m / ne), nu = (int)ne;
  for (int j = 1; j < nu; j++)
    if (!(e[j] > e[j - 1]))
      error_exit(
          "%s: miluphcuda ANEOS table: energy node %d (%g) after %g: the energies must "
          "increase",
          filename, j, e[j], e[j - 1]);
  for (int i = 1; i < nr; i++) {
    const size_t b = (size_t)i * nu;
    if (!(rho[b] > rho[b - 1]))
      error_exit(
          "%s: miluphcuda ANEOS table: row %zu: density block %d has %g, not above %g "
          "(each density must have n_e = %d rows)",
          filename, b + 1, i + 1, rho[b], rho[b - 1], nu);
    for (int j = 0; j < nu; j++) {
      /* miluphcuda's tolerance: one energy axis for all densities */
      if (fabs(e[b + j] - e[j]) > 1e-6 * fabs(e[nu - 1]))
        error_exit(
            "%s: miluphcuda ANEOS table: row %zu: energy %g differs from %g of the first "
            "density (one energy axis for all densities)",
            filename, b + j + 1, e[b + j], e[j]);
      if (rho[b + j] != rho[b])
        error_exit(
            "%s: miluphcuda ANEOS table: row %zu: density %g differs from %g at the start "
            "of its block of %d rows",
            filename, b + j + 1, rho[b + j], rho[b], nu);
      e[b + j] = e[j];
    }
  }
  /* the builder takes rho, e, P, cs (rows: rho slowest, as here); T is
   * kept as the table's temperature */
  material_table_build(tab, filename, 3, nr, nu, rho, e, NULL, P, cs, 1);
  tab->T = T;
  tab->rho_extrapolate = 1; /* miluphcuda: linear in rho beyond the density nodes */
}

/* ------------------------------------------------------------ library */

const char *material_default_library(void) {
  static char path[PATH_MAX];
  /* $BOLIDE_MATERIALS, else PREFIX/share/bolide/materials.yml beside an
   * install (PREFIX/bin/PROGRAM), else the source tree's examples/ (paths.h) */
  paths_find(path, sizeof path, "BOLIDE_MATERIALS", "../share/bolide/materials.yml",
             "examples/materials.yml");
  return path;
}

void material_write_keys(FILE *f) {
  for (int e = 0; e < EOS_COUNT; e++) {
    fprintf(f, "# eos: %s -- %s\n", eos_names[e], eos_docs[e]);
    for (int i = 0; i < eos_nkeys[e]; i++) {
      const struct material_key *k = &eos_keys[e][i];
      fprintf(f, "#   %-18s [%s] %s%s\n", k->key, material_units[k->unit].si, k->doc,
              isnan(k->def) ? " (required)" : "");
    }
  }
  fprintf(f, "# every material:\n");
  for (int i = 0; i < MATERIAL_NKEYS; i++) {
    const struct material_key *k = &material_keys[i];
    fprintf(f, "#   %-18s [%s] %s\n", k->key, material_units[k->unit].si, k->doc);
  }
  fprintf(f, "#   strength: ");
  for (int s = 0; s < STRENGTH_COUNT; s++) fprintf(f, "%s%s", s ? "|" : "", strength_names[s]);
  fprintf(f, "\n");
  porosity_write_keys(f);
}
