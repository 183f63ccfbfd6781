/* Run-time parameters: one YAML file per run, parsed with libyaml.
 *
 * Every key Bolide knows is declared once in src/io/param_list.h
 * (BOLIDE_PARAMS), with its type, default, range, unit and documentation.
 * params_read() parses the file, checks every key against that table (unknown
 * or misspelt keys, wrong types, values out of range, missing required keys)
 * and stops with "bolide: error: FILE:LINE: ..." before any work is done.
 * Sections that hold free-form structure (Materials) are kept as a tree of
 * nodes and validated by their own module through the node API below.
 *
 * Keys are named "Section:key" as in SWIFT's parameter files. */
#ifndef BOLIDE_PARAMS_H
#define BOLIDE_PARAMS_H

#include <stdio.h>

enum param_type {
  PARAM_INT,        /**< integer (long) */
  PARAM_REAL,       /**< floating point (double) */
  PARAM_BOOL,       /**< true/false, yes/no, 1/0 */
  PARAM_STRING,     /**< free text */
  PARAM_ENUM,       /**< one of a '|'-separated list of choices */
  PARAM_REAL_ARRAY, /**< [a, b, c] of reals */
  PARAM_SECTION,    /**< a free-form mapping validated by its own module */
  PARAM_WORDS,      /**< a word, or a [list, of, words]: read as text (params_get_string),
                         a list as "[list, of, words]"; its module checks the words */
};

/** One known key (an entry of BOLIDE_PARAMS). */
struct param_spec {
  const char *name; /**< "Section:key" */
  enum param_type type;
  const char *def;     /**< default as text; NULL = required */
  double min, max;     /**< allowed range for INT/REAL/REAL_ARRAY (inclusive); for
                            STRING the allowed length in bytes (max 0: any) */
  const char *choices; /**< "a|b|c" for ENUM; for REAL_ARRAY the allowed numbers
                            of values ("0|1|3"; NULL: any) */
  const char *unit;    /**< unit, documentation only ("internal length", "s", "-") */
  const char *doc;     /**< one-line meaning */
};

/** The table entry of a key ("Section:key", or a PARAM_SECTION name), or
 *  NULL when Bolide has no such key. */
const struct param_spec *params_spec(const char *name);

struct params;     /* opaque: the parsed file */
struct param_node; /* opaque: a node of a free-form section */

/** Parse and validate a parameter file; exits with a one-line error on any
 *  problem.  overrides: n strings "Section:key:value" from -P, applied (and
 *  validated) after the file. */
struct params *params_read(const char *filename, int n_overrides, char *const *overrides);

/** Free everything. */
void params_free(struct params *p);

/** Name of the file the parameters came from. */
const char *params_filename(const struct params *p);

/** 1 if the key was given in the file (or by -P), 0 if it takes its default. */
int params_given(const struct params *p, const char *name);

/** Line of a section in the file (1-based), 0 when the file has none. */
int params_section_line(const struct params *p, const char *section);

/** The text the file itself gives for "Section:key" (before any -P), or NULL
 *  when the file does not set it or sets it to a collection. */
const char *params_file_text(const struct params *p, const char *name);

/** Typed getters: the value given, or the table's default.  Asking for a key
 *  that is not in the table, or with the wrong type, is a bug (error_bug). */
long params_get_int(const struct params *p, const char *name);
double params_get_real(const struct params *p, const char *name);
int params_get_bool(const struct params *p, const char *name);
const char *params_get_string(const struct params *p, const char *name); /* STRING, WORDS */
/** Index of the chosen value in the spec's choices list. */
int params_get_enum(const struct params *p, const char *name);
/** Fill up to maxn reals, return the count. */
int params_get_real_array(const struct params *p, const char *name, double *out, int maxn);

/** A STRING key holding a path, made relative to the parameter file's folder
 *  when it is relative (absolute and empty values are returned unchanged).
 *  The caller frees the result. */
char *params_get_path(const struct params *p, const char *name);

/** Stop with "FILE:LINE: KEY: MESSAGE" for a semantic error found by a module
 *  (a value inconsistent with another, say). */
void params_error(const struct params *p, const char *name, const char *fmt, ...)
    __attribute__((format(printf, 3, 4), noreturn));

/** Number of typing slips between two names (optimal-string-alignment edit
 *  distance, case-insensitive), for "did you mean" hints. */
int params_edit_distance(const char *a, const char *b);

/** Write the full parameter set in use (given values and defaults) as YAML. */
void params_write_yaml(const struct params *p, FILE *f);
/** The same text in a malloc'd string (for /Parameters in snapshots). */
char *params_to_string(const struct params *p);
/** Write used_parameters.yml (or another name) atomically (temporary + rename). */
void params_write_used(const struct params *p, const char *filename);

/** The reference documentation of every key, as a commented YAML file
 *  (what examples/parameters.yml holds). */
void params_write_reference(FILE *f);

/* ---- free-form sections (Materials) ---- */

/** The node of a PARAM_SECTION key, or NULL if absent. */
const struct param_node *params_section(const struct params *p, const char *name);
/** Kind of node: 0 scalar, 1 mapping, 2 sequence. */
int param_node_kind(const struct param_node *n);
/** Number of children of a mapping or sequence. */
int param_node_count(const struct param_node *n);
/** Key of the i-th entry of a mapping (NULL for a sequence). */
const char *param_node_key(const struct param_node *n, int i);
/** The i-th child. */
const struct param_node *param_node_child(const struct param_node *n, int i);
/** Child of a mapping by key, NULL if absent. */
const struct param_node *param_node_get(const struct param_node *n, const char *key);
/** Scalar text of a node (NULL if not a scalar). */
const char *param_node_text(const struct param_node *n);
/** Line in the file where the node starts (1-based). */
int param_node_line(const struct param_node *n);
/** Scalar conversions that stop with FILE:LINE: errors naming `what`. */
double param_node_real(const struct params *p, const struct param_node *n, const char *what);
long param_node_int(const struct params *p, const struct param_node *n, const char *what);
/** Stop with "FILE:LINE: MESSAGE" at a node. */
void param_node_error(const struct params *p, const struct param_node *n, const char *fmt, ...)
    __attribute__((format(printf, 3, 4), noreturn));

/** Parse a free-standing YAML file (a material library) into a node tree;
 *  errors name that file.  The returned params holds the tree under the
 *  pseudo-section "" (params_section(p, "")). */
struct params *params_read_tree(const char *filename);

#endif
