/* Porosity models: key tables from the X lists of porosity_palpha.h and
 * porosity_epsalpha.h, parsing of the `porosity:` sub-mapping, checks and
 * unit conversion.  See porosity.h and theory/porosity.md. */
#include "src/materials/porosity.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "src/error.h"
#include "src/materials/material.h"
#include "src/io/params.h"
#include "src/io/units.h"

/** One key of a porosity model (the format of material.c's key tables). */
struct porosity_key {
  const char *key;         /**< YAML key inside porosity: */
  size_t offset;           /**< byte offset of the double in struct porosity */
  double def;              /**< default; NAN: required */
  double lo, hi;           /**< allowed range */
  int lo_open;             /**< 1: lo itself is not allowed */
  enum material_unit unit; /**< unit kind */
  const char *doc;         /**< one-line meaning */
};

#define POROSITY_KEY_PALPHA(st, field, k, d, l, lopen, h, kind, doc) \
  {k, offsetof(struct porosity, palpha) + offsetof(struct st, field), d, l, h, lopen, kind, doc},
#define POROSITY_KEY_EPSALPHA(st, field, k, d, l, lopen, h, kind, doc) \
  {k, offsetof(struct porosity, epsalpha) + offsetof(struct st, field), d, l, h, lopen, kind, doc},

static const struct porosity_key porosity_keys_palpha[] = {
    POROSITY_PALPHA_PARAMS(POROSITY_KEY_PALPHA)};
static const struct porosity_key porosity_keys_epsalpha[] = {
    POROSITY_EPSALPHA_PARAMS(POROSITY_KEY_EPSALPHA)};

/** Key table and count of each model (index: enum porosity_model). */
static const struct porosity_key *const porosity_keys[POROSITY_COUNT] = {NULL, porosity_keys_palpha,
                                                                         porosity_keys_epsalpha};
static const int porosity_nkeys[POROSITY_COUNT] = {
    0, (int)(sizeof porosity_keys_palpha / sizeof porosity_keys_palpha[0]),
    (int)(sizeof porosity_keys_epsalpha / sizeof porosity_keys_epsalpha[0])};

static const char *const porosity_names[POROSITY_COUNT] = {"none",
#define POROSITY_MODEL_NAME(name, NAME, doc) #name,
                                                           POROSITY_MODELS(POROSITY_MODEL_NAME)};
static const char *const porosity_docs[POROSITY_COUNT] = {"not porous",
#define POROSITY_MODEL_DOC(name, NAME, doc) doc,
                                                          POROSITY_MODELS(POROSITY_MODEL_DOC)};

const char *porosity_model_name(enum porosity_model model) {
  return (int)model >= 0 && model < POROSITY_COUNT ? porosity_names[model] : "unknown";
}

int porosity_model_from_name(const char *name) {
  for (int k = 0; k < POROSITY_COUNT; k++)
    if (strcmp(name, porosity_names[k]) == 0) return k;
  return -1;
}

/** The double a key describes. */
static double *porosity_field(struct porosity *por, const struct porosity_key *k) {
  return (double *)((char *)por + k->offset);
}

void porosity_init(struct porosity *por, enum porosity_model model) {
  memset(por, 0, sizeof *por);
  por->model = model;
  for (int i = 0; i < porosity_nkeys[model]; i++)
    *porosity_field(por, &porosity_keys[model][i]) = porosity_keys[model][i].def;
}

/** Range check of one value: NULL or what is wrong (as material.c words it). */
static const char *porosity_range(const struct porosity_key *k, double v, char *buf, size_t len) {
  if (isnan(v)) return "must be a number";
  if (isinf(v)) return "must be finite";
  if (k->lo_open ? !(v > k->lo) : !(v >= k->lo)) {
    if (k->lo == 0.0) return k->lo_open ? "must be positive" : "must not be negative";
    snprintf(buf, len, "must be %s %g", k->lo_open ? ">" : ">=", k->lo);
    return buf;
  }
  if (v > k->hi) {
    snprintf(buf, len, "must be at most %g", k->hi);
    return buf;
  }
  return NULL;
}

int porosity_set(struct porosity *por, const char *mat, const char *key, double value, char *msg,
                 size_t len) {
  const int m = (int)por->model;
  for (int i = 0; i < porosity_nkeys[m]; i++) {
    const struct porosity_key *k = &porosity_keys[m][i];
    if (strcmp(k->key, key) != 0) continue;
    char buf[64];
    const char *bad = porosity_range(k, value, buf, sizeof buf);
    if (bad) {
      snprintf(msg, len, "material '%s': key 'porosity: %s' %s (got %g)", mat, key, bad, value);
      return -1;
    }
    *porosity_field(por, k) = value;
    return 0;
  }
  snprintf(msg, len, "material '%s': unknown key 'porosity: %s' for porosity model %s", mat, key,
           porosity_model_name(por->model));
  return -1;
}

/** Cross-checks of P-alpha after the defaults: NULL or the message. */
static const char *porosity_palpha_check(struct porosity_palpha *p, const char **key) {
  if (p->alpha_e == 0.0) p->alpha_e = p->alpha_0;
  if (p->alpha_t == 0.0) p->alpha_t = p->alpha_e;
  if (p->p_t == 0.0) p->p_t = p->p_e;
  *key = "alpha_e";
  if (!(p->alpha_e >= 1.0)) return "must be at least 1";
  if (!(p->alpha_e <= p->alpha_0)) return "must not exceed alpha_0";
  *key = "alpha_t";
  if (!(p->alpha_t >= 1.0 && p->alpha_t <= p->alpha_e)) return "must be between 1 and alpha_e";
  *key = "p_s";
  if (!(p->p_s > p->p_e)) return "must be larger than p_e";
  *key = "p_t";
  if (!(p->p_t >= p->p_e && p->p_t < p->p_s)) return "must be in [p_e, p_s)";
  if (p->p_t == p->p_e && p->alpha_t != p->alpha_e)
    return "must be larger than p_e when alpha_t differs from alpha_e";
  *key = "c_e";
  if ((p->c_e > 0.0) != (p->c_s > 0.0)) return "must be given together with c_s";
  if (p->c_e > p->c_s) return "must not exceed c_s (pores make the material softer)";
  return NULL;
}

/** Cross-checks of epsilon-alpha and its derived values: NULL or the message. */
static const char *porosity_epsalpha_check(struct porosity_epsalpha *p, const char **key) {
  *key = "eps_x";
  if (!(p->eps_x <= p->eps_e)) return "must not be larger than eps_e";
  porosity_epsalpha_derive(p);
  if (!(p->alpha_x > 1.0))
    return "is beyond full compaction: alpha_0 exp(kappa (eps_x - eps_e)) must exceed 1";
  return NULL;
}

int porosity_finalize(struct porosity *por, const char *mat, char *msg, size_t len) {
  const int m = (int)por->model;
  if (m < 0 || m >= POROSITY_COUNT) {
    snprintf(msg, len, "material '%s': key 'porosity: model' is not a known model", mat);
    return -1;
  }
  char buf[64];
  for (int i = 0; i < porosity_nkeys[m]; i++) {
    const struct porosity_key *k = &porosity_keys[m][i];
    const double v = *porosity_field(por, k);
    if (isnan(v)) {
      snprintf(msg, len, "material '%s': key 'porosity: %s' is required for porosity model %s", mat,
               k->key, porosity_names[m]);
      return -1;
    }
    const char *bad = porosity_range(k, v, buf, sizeof buf);
    if (bad) {
      snprintf(msg, len, "material '%s': key 'porosity: %s' %s (got %g)", mat, k->key, bad, v);
      return -1;
    }
  }
  const char *key = NULL, *bad = NULL;
  if (por->model == POROSITY_PALPHA) bad = porosity_palpha_check(&por->palpha, &key);
  if (por->model == POROSITY_EPSALPHA) bad = porosity_epsalpha_check(&por->epsalpha, &key);
  if (bad) {
    snprintf(msg, len, "material '%s': key 'porosity: %s' %s", mat, key, bad);
    return -1;
  }
  return 0;
}

void porosity_from_node(struct porosity *por, const char *mat, const struct params *owner,
                        const struct param_node *node) {
  char msg[512], what[160];
  if (param_node_kind(node) != 1)
    param_node_error(owner, node,
                     "material '%s': key 'porosity' must be a mapping (model: palpha|epsalpha "
                     "and the model's parameters)",
                     mat);
  const struct param_node *mn = param_node_get(node, "model");
  const char *ms = mn ? param_node_text(mn) : NULL;
  const int model = ms ? porosity_model_from_name(ms) : -1;
  if (model < 0) {
    char known[128] = "";
    for (int k = 0; k < POROSITY_COUNT; k++) {
      strncat(known, k ? "|" : "", sizeof known - strlen(known) - 1);
      strncat(known, porosity_names[k], sizeof known - strlen(known) - 1);
    }
    param_node_error(owner, mn ? mn : node,
                     "material '%s': key 'porosity: model' must be one of %s%s%s%s", mat, known,
                     ms ? " (got '" : "", ms ? ms : "", ms ? "')" : "");
  }
  porosity_init(por, (enum porosity_model)model);
  for (int i = 0; i < param_node_count(node); i++) {
    const char *key = param_node_key(node, i);
    if (strcmp(key, "model") == 0) continue;
    const struct param_node *v = param_node_child(node, i);
    snprintf(what, sizeof what, "material '%s': key 'porosity: %s'", mat, key);
    const double value = param_node_real(owner, v, what);
    if (porosity_set(por, mat, key, value, msg, sizeof msg)) param_node_error(owner, v, "%s", msg);
  }
  if (porosity_finalize(por, mat, msg, sizeof msg)) param_node_error(owner, node, "%s", msg);
}

void porosity_convert_units(struct porosity *por, const struct unit_system *us) {
  /* dimension M^a L^b T^c of each unit kind used by the porosity keys */
  struct unit_system si;
  units_init_si(&si);
  const int m = (int)por->model;
  for (int i = 0; i < porosity_nkeys[m]; i++) {
    const struct porosity_key *k = &porosity_keys[m][i];
    double f = 1.0;
    if (k->unit == MATERIAL_UNIT_PRESSURE) f = units_conversion_factor(&si, us, 1, -1, -2);
    if (k->unit == MATERIAL_UNIT_SPEED) f = units_conversion_factor(&si, us, 0, 1, -1);
    *porosity_field(por, k) *= f;
  }
}

void porosity_write_keys(FILE *f) {
  for (int m = 1; m < POROSITY_COUNT; m++) {
    fprintf(f, "# porosity: {model: %s, ...} -- %s\n", porosity_names[m], porosity_docs[m]);
    for (int i = 0; i < porosity_nkeys[m]; i++) {
      const struct porosity_key *k = &porosity_keys[m][i];
      fprintf(f, "#   %-18s %s%s\n", k->key, k->doc, isnan(k->def) ? " (required)" : "");
    }
  }
}
