/* Run-time parameters: see params.h.
 *
 * A file is loaded with libyaml's document API and copied at once into a
 * small tree of param_node that keeps the line of every key and value, so
 * that any later error (ours or a module's) can name its line.  Every key of
 * the table (BOLIDE_PARAMS, src/io/param_list.h) then gets one parsed value:
 * its default first, then the file's, then the -P override's, each checked by
 * the same function (value_parse).  Getters only read those values. */
#include "src/io/params.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <yaml.h>

#include "src/error.h"
#include "src/io/param_list.h"
#include "src/io/param_swift.h"

/* ================================================================ the table */

#define PARAMS_SPEC_ENTRY(name, type, def, min, max, choices, unit, doc) \
  {name, type, def, min, max, choices, unit, doc},
/** Every known key, in the order of param_list.h (also the output order). */
static const struct param_spec params_table[] = {BOLIDE_PARAMS(PARAMS_SPEC_ENTRY)};
#define PARAMS_N ((int)(sizeof params_table / sizeof params_table[0]))

/** A key or section of SWIFT's that Bolide accepts without effect. */
struct param_swift {
  const char *name;   /**< "Section:key", "Section" or "Prefix*" */
  int level;          /**< PARAM_SWIFT_NOTE or PARAM_SWIFT_WARN */
  const char *reason; /**< why it has no effect */
};
#define PARAMS_SWIFT_ENTRY(name, level, reason) {name, level, reason},
/** Every entry of BOLIDE_SWIFT_IGNORED (param_swift.h). */
static const struct param_swift params_swift[] = {BOLIDE_SWIFT_IGNORED(PARAMS_SWIFT_ENTRY)};
#define PARAMS_NSWIFT ((int)(sizeof params_swift / sizeof params_swift[0]))

/** The entry of SWIFT's key "Section:key" accepted without effect, or NULL. */
static const struct param_swift *swift_key(const char *name) {
  for (int i = 0; i < PARAMS_NSWIFT; i++)
    if (strcmp(params_swift[i].name, name) == 0) return &params_swift[i];
  return NULL;
}

/** The entry of SWIFT's section accepted without effect, or NULL. */
static const struct param_swift *swift_section(const char *sec) {
  for (int i = 0; i < PARAMS_NSWIFT; i++) {
    const char *n = params_swift[i].name;
    const size_t l = strlen(n);
    if (strchr(n, ':')) continue;
    if (strcmp(n, sec) == 0 || (l > 1 && n[l - 1] == '*' && strncmp(n, sec, l - 1) == 0))
      return &params_swift[i];
  }
  return NULL;
}

/** Nesting deeper than this (or a recursive alias) is refused. */
#define PARAMS_MAX_DEPTH 64
/** Nodes per file beyond which alias expansion is refused ("billion laughs"). */
#define PARAMS_MAX_NODES 100000L
/** Longest name for which a spelling suggestion is searched. */
#define PARAMS_MAX_NAME 80

/** Index of a key in params_table, or -1. */
static int spec_find(const char *name) {
  for (int i = 0; i < PARAMS_N; i++)
    if (strcmp(params_table[i].name, name) == 0) return i;
  return -1;
}

const struct param_spec *params_spec(const char *name) {
  int i = spec_find(name);
  return i < 0 ? NULL : &params_table[i];
}

/** Length of the section part of a table name ("SPH" of "SPH:gamma"; the
 *  whole name for a PARAM_SECTION entry). */
static size_t spec_section_len(const struct param_spec *s) {
  const char *colon = strchr(s->name, ':');
  return colon ? (size_t)(colon - s->name) : strlen(s->name);
}

/** 1 if table entry i is in the section named by the first len chars of sec. */
static int spec_in_section(int i, const char *sec, size_t len) {
  return spec_section_len(&params_table[i]) == len && strncmp(params_table[i].name, sec, len) == 0;
}

/** 1 if entries i and j are in the same section. */
static int spec_same_section(int i, int j) {
  return spec_in_section(j, params_table[i].name, spec_section_len(&params_table[i]));
}

/** 1 if some table entry belongs to section `sec`. */
static int section_known(const char *sec) {
  for (int i = 0; i < PARAMS_N; i++)
    if (spec_in_section(i, sec, strlen(sec))) return 1;
  return 0;
}

/** 1 if table entry i is the first of its section: sections are visited in
 *  the order of their first appearance in the table. */
static int spec_starts_section(int i) {
  for (int j = 0; j < i; j++)
    if (spec_same_section(i, j)) return 0;
  return 1;
}

/* ================================================================ errors */

/** Stop with "WHERE:LINE: MESSAGE", or "WHERE: MESSAGE" when line <= 0. */
static void fail(const char *where, int line, const char *fmt, ...)
    __attribute__((format(printf, 3, 4), noreturn));
static void fail(const char *where, int line, const char *fmt, ...) {
  char msg[2048];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  if (line > 0) error_exit("%s:%d: %s", where, line, msg);
  error_exit("%s: %s", where, msg);
}

/** Optimal-string-alignment edit distance (Levenshtein plus transpositions),
 *  case-insensitive: the number of typing slips between two names. */
int params_edit_distance(const char *a, const char *b) {
  int la = (int)strlen(a), lb = (int)strlen(b);
  if (la > PARAMS_MAX_NAME || lb > PARAMS_MAX_NAME) return 1 << 20;
  int d[PARAMS_MAX_NAME + 1][PARAMS_MAX_NAME + 1];
  for (int i = 0; i <= la; i++) d[i][0] = i;
  for (int j = 0; j <= lb; j++) d[0][j] = j;
  for (int i = 1; i <= la; i++)
    for (int j = 1; j <= lb; j++) {
      int cost = tolower((unsigned char)a[i - 1]) != tolower((unsigned char)b[j - 1]);
      int best = d[i - 1][j - 1] + cost;
      if (d[i - 1][j] + 1 < best) best = d[i - 1][j] + 1;
      if (d[i][j - 1] + 1 < best) best = d[i][j - 1] + 1;
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] &&
          d[i - 2][j - 2] + 1 < best)
        best = d[i - 2][j - 2] + 1;
      d[i][j] = best;
    }
  return d[la][lb];
}

/** Name of candidate k for a suggestion: the entries of params_table, then
 *  SWIFT's keys and sections accepted without effect (NULL past the end). */
static const char *candidate_name(int k) {
  if (k < PARAMS_N) return params_table[k].name;
  if (k < PARAMS_N + PARAMS_NSWIFT) return params_swift[k - PARAMS_N].name;
  return NULL;
}

/** Fill buf with " (did you mean 'X'?)" for the known name nearest to `name`
 *  (a section name when `section` is set, else a "Section:key"), or with ""
 *  when nothing is within three slips.  A key is looked for among the keys
 *  of its own section first, then (put in the wrong section) among the keys
 *  of every section, where the same key name in another section wins.
 *  Returns the index in params_table of the key suggested, or -1 (also when
 *  the name suggested is one of SWIFT's, which has no entry in the table). */
static int suggest(const char *name, int section, char *buf, size_t len) {
  int best = 4, best_k = -1;
  const char *colon = strchr(name, ':');
  const char *typed = section || !colon ? name : colon + 1;
  const size_t seclen = colon ? (size_t)(colon - name) : strlen(name);
  for (int pass = section ? 1 : 0; pass < 2 && best_k < 0; pass++)
    for (int k = 0; candidate_name(k); k++) {
      const char *c = candidate_name(k);
      const char *cc = strchr(c, ':');
      if (section) {
        if (k < PARAMS_N && cc) { /* the section of a key */
          char sec[PARAMS_MAX_NAME + 1];
          snprintf(sec, sizeof sec, "%.*s", (int)(cc - c), c);
          const int d = params_edit_distance(name, sec);
          if (d < best && d < (int)strlen(typed)) best = d, best_k = k;
        } else if (!cc && c[strlen(c) - 1] != '*') {
          const int d = params_edit_distance(name, c);
          if (d < best && d < (int)strlen(typed)) best = d, best_k = k;
        }
        continue;
      }
      if (!cc) continue; /* a whole section */
      const int same = (size_t)(cc - c) == seclen && strncmp(c, name, seclen) == 0;
      if (pass == 0 && !same) continue;
      const int d = params_edit_distance(typed, cc + 1);
      if (d < best && d < (int)strlen(typed)) best = d, best_k = k;
    }
  if (best_k < 0) {
    buf[0] = '\0';
    return -1;
  }
  const char *c = candidate_name(best_k);
  if (section && strchr(c, ':'))
    snprintf(buf, len, " (did you mean '%.*s'?)", (int)(strchr(c, ':') - c), c);
  else
    snprintf(buf, len, " (did you mean '%s'?)", c);
  return section || best_k >= PARAMS_N ? -1 : best_k;
}

/* ================================================================ the tree */

enum { NODE_SCALAR = 0, NODE_MAPPING = 1, NODE_SEQUENCE = 2 };

/** A node of a parsed YAML file. */
struct param_node {
  int kind;                  /**< NODE_SCALAR, NODE_MAPPING or NODE_SEQUENCE */
  int line;                  /**< 1-based line where the node starts */
  int quoted;                /**< scalar written in quotes or as a block (always text) */
  char *text;                /**< scalar: its text; NULL otherwise */
  int n;                     /**< mapping, sequence: number of children */
  char **keys;               /**< mapping: the n keys */
  int *key_lines;            /**< mapping: line of each key */
  struct param_node **child; /**< mapping, sequence: the n children */
};

/** A new empty node. */
static struct param_node *node_new(int kind, int line) {
  struct param_node *n = error_calloc(1, sizeof *n, "parameter node");
  n->kind = kind;
  n->line = line;
  return n;
}

/** Free a node and everything below it. */
static void node_free(struct param_node *n) {
  if (!n) return;
  for (int i = 0; i < n->n; i++) {
    node_free(n->child[i]);
    if (n->keys) free(n->keys[i]);
  }
  free(n->child);
  free(n->keys);
  free(n->key_lines);
  free(n->text);
  free(n);
}

/** 1 for a plain scalar with no text (YAML's "key:" with nothing after). */
static int node_is_null(const struct param_node *n) {
  return n->kind == NODE_SCALAR && !n->quoted && n->text[0] == '\0';
}

/** Words for a node's kind, for error messages. */
static const char *node_kind_name(const struct param_node *n) {
  return n->kind == NODE_MAPPING    ? "a mapping"
         : n->kind == NODE_SEQUENCE ? "a sequence"
                                    : "a scalar";
}

/** State of the copy of one libyaml document into a param_node tree. */
struct tree_builder {
  yaml_document_t *doc; /**< the document being copied */
  const char *where;    /**< prefix of error messages (file name or -P argument) */
  int with_lines;       /**< 1 to put line numbers in error messages */
  long budget;          /**< nodes still allowed (alias expansion bound) */
};

static struct param_node *tree_copy(struct tree_builder *b, yaml_node_t *y, const char *path,
                                    int depth);

/** Order of mapping entries by key, then by position (for qsort). */
static const struct param_node *sort_node;
static int key_order(const void *a, const void *b) {
  const int i = *(const int *)a, j = *(const int *)b;
  const int c = strcmp(sort_node->keys[i], sort_node->keys[j]);
  return c ? c : (i > j) - (i < j);
}

/** Stop on a key given twice in mapping n, naming the first repetition in
 *  the file's order and the line of its first occurrence.  Sorting keeps it
 *  O(n log n): a file with 1e5 keys is checked in milliseconds. */
static void mapping_check_duplicates(struct tree_builder *b, const struct param_node *n,
                                     const char *path) {
  if (n->n < 2) return;
  int *order = error_malloc((size_t)n->n * sizeof *order, "parameter keys");
  for (int i = 0; i < n->n; i++) order[i] = i;
  sort_node = n;
  qsort(order, (size_t)n->n, sizeof *order, key_order);
  int first = -1, later = n->n; /* the earliest repetition: entries first and later */
  for (int k = 1; k < n->n; k++)
    if (strcmp(n->keys[order[k]], n->keys[order[k - 1]]) == 0 && order[k] < later) {
      later = order[k];
      int g = k - 1; /* the first entry of this key */
      while (g > 0 && strcmp(n->keys[order[g - 1]], n->keys[order[k]]) == 0) g--;
      first = order[g];
    }
  free(order);
  if (first < 0) return;
  fail(b->where, b->with_lines ? n->key_lines[later] : 0,
       "duplicate key '%s%s%s' (first given at line %d)", path, path[0] ? ":" : "", n->keys[later],
       n->key_lines[first]);
}

/** Copy the pairs of a libyaml mapping into n; path names the mapping in errors. */
static void tree_copy_mapping(struct tree_builder *b, yaml_node_t *y, struct param_node *n,
                              const char *path, int depth) {
  int count = (int)(y->data.mapping.pairs.top - y->data.mapping.pairs.start);
  n->keys = error_calloc((size_t)count, sizeof *n->keys, "parameter keys");
  n->key_lines = error_calloc((size_t)count, sizeof *n->key_lines, "parameter lines");
  n->child = error_calloc((size_t)count, sizeof *n->child, "parameter nodes");
  for (int i = 0; i < count; i++) {
    yaml_node_pair_t *pair = &y->data.mapping.pairs.start[i];
    yaml_node_t *k = yaml_document_get_node(b->doc, pair->key);
    yaml_node_t *v = yaml_document_get_node(b->doc, pair->value);
    int line = b->with_lines ? (int)k->start_mark.line + 1 : 0;
    if (k->type != YAML_SCALAR_NODE)
      fail(b->where, line, "%s%sa key must be a scalar, not a collection", path,
           path[0] ? ": " : "");
    const char *key = (const char *)k->data.scalar.value;
    char sub[1024];
    snprintf(sub, sizeof sub, "%s%s%s", path, path[0] ? ":" : "", key);
    n->keys[i] = strdup(key);
    if (!n->keys[i]) error_exit("out of memory copying parameter keys");
    n->key_lines[i] = (int)k->start_mark.line + 1;
    n->child[i] = tree_copy(b, v, sub, depth + 1);
    n->n = i + 1;
  }
  mapping_check_duplicates(b, n, path);
}

/** Copy libyaml node y (and its children) into a new param_node. */
static struct param_node *tree_copy(struct tree_builder *b, yaml_node_t *y, const char *path,
                                    int depth) {
  int line = (int)y->start_mark.line + 1;
  if (depth > PARAMS_MAX_DEPTH || --b->budget < 0)
    fail(b->where, b->with_lines ? line : 0,
         "more than %d levels of nesting or %ld values (a recursive or exploding alias?)",
         PARAMS_MAX_DEPTH, PARAMS_MAX_NODES);
  struct param_node *n = node_new(NODE_SCALAR, line);
  if (y->type == YAML_SCALAR_NODE) {
    n->text = error_malloc(y->data.scalar.length + 1, "parameter text");
    memcpy(n->text, y->data.scalar.value, y->data.scalar.length);
    n->text[y->data.scalar.length] = '\0';
    n->quoted = y->data.scalar.style != YAML_PLAIN_SCALAR_STYLE;
  } else if (y->type == YAML_SEQUENCE_NODE) {
    int count = (int)(y->data.sequence.items.top - y->data.sequence.items.start);
    n->kind = NODE_SEQUENCE;
    n->child = error_calloc((size_t)count, sizeof *n->child, "parameter nodes");
    for (int i = 0; i < count; i++) {
      yaml_node_t *item = yaml_document_get_node(b->doc, y->data.sequence.items.start[i]);
      n->child[i] = tree_copy(b, item, path, depth + 1);
      n->n = i + 1;
    }
  } else {
    n->kind = NODE_MAPPING;
    tree_copy_mapping(b, y, n, path, depth);
  }
  return n;
}

/** Stop on a libyaml parse error. */
static void tree_parse_error(const yaml_parser_t *parser, const char *where, int with_lines) {
  if (parser->error == YAML_MEMORY_ERROR) error_exit("%s: out of memory parsing YAML", where);
  if (parser->error == YAML_READER_ERROR)
    fail(where, 0, "YAML error at byte %zu: %s", parser->problem_offset,
         parser->problem ? parser->problem : "unreadable input");
  int line = with_lines ? (int)parser->problem_mark.line + 1 : 0;
  if (parser->context && with_lines)
    fail(where, line, "YAML syntax error: %s (%s started at line %d)", parser->problem,
         parser->context, (int)parser->context_mark.line + 1);
  fail(where, line, "YAML syntax error: %s", parser->problem ? parser->problem : "unknown");
}

/** Load the one YAML document of an initialised parser into a tree (an empty
 *  mapping for an empty stream); errors start with `where`. */
static struct param_node *tree_parse(yaml_parser_t *parser, const char *where, int with_lines) {
  yaml_document_t doc;
  if (!yaml_parser_load(parser, &doc)) tree_parse_error(parser, where, with_lines);
  yaml_node_t *root = yaml_document_get_root_node(&doc);
  struct param_node *tree;
  if (root) {
    struct tree_builder b = {&doc, where, with_lines, PARAMS_MAX_NODES};
    tree = tree_copy(&b, root, "", 0);
  } else {
    tree = node_new(NODE_MAPPING, 1);
  }
  yaml_document_delete(&doc);
  if (!yaml_parser_load(parser, &doc)) tree_parse_error(parser, where, with_lines);
  root = yaml_document_get_root_node(&doc);
  if (root)
    fail(where, with_lines ? (int)root->start_mark.line + 1 : 0,
         "a second YAML document (after '---'); a parameter file holds only one");
  yaml_document_delete(&doc);
  return tree;
}

/** Parse a YAML file into a tree; stops on a missing file or bad YAML. */
static struct param_node *tree_load_file(const char *filename) {
  FILE *f = fopen(filename, "rb");
  if (!f) error_exit("%s: cannot open: %s", filename, strerror(errno));
  struct stat st;
  if (fstat(fileno(f), &st) == 0 && S_ISDIR(st.st_mode))
    error_exit("%s: cannot open: %s", filename, strerror(EISDIR));
  yaml_parser_t parser;
  if (!yaml_parser_initialize(&parser)) error_exit("out of memory starting the YAML parser");
  yaml_parser_set_input_file(&parser, f);
  struct param_node *tree = tree_parse(&parser, filename, 1);
  yaml_parser_delete(&parser);
  fclose(f);
  return tree;
}

/** Parse YAML text (a -P value, a table default) into a tree. */
static struct param_node *tree_load_text(const char *text, const char *where) {
  yaml_parser_t parser;
  if (!yaml_parser_initialize(&parser)) error_exit("out of memory starting the YAML parser");
  yaml_parser_set_input_string(&parser, (const unsigned char *)text, strlen(text));
  struct param_node *tree = tree_parse(&parser, where, 0);
  yaml_parser_delete(&parser);
  return tree;
}

/* ================================================================ values */

/** The value in use for one key of the table. */
struct param_value {
  int given;                     /**< 1 if set by the file or by -P */
  int line;                      /**< line of the key in the file; 0 if not from the file */
  char *override;                /**< the -P argument that set it, or NULL */
  long i;                        /**< PARAM_INT */
  double r;                      /**< PARAM_REAL */
  int b;                         /**< PARAM_BOOL (0/1); PARAM_ENUM: index of the choice */
  char *s;                       /**< PARAM_STRING */
  double *a;                     /**< PARAM_REAL_ARRAY: the values */
  int n;                         /**< PARAM_REAL_ARRAY: their number */
  const struct param_node *node; /**< PARAM_SECTION: the subtree (owned by the file's tree) */
  int tried;                     /**< 1 when the file or -P had a problem with this key (or a
                                      misspelling of it): it is not reported missing as well */
};

/** The parsed file. */
struct params {
  char *filename;             /**< the file read */
  struct param_node *root;    /**< its whole tree */
  struct param_value *values; /**< one per params_table entry */
  char **problems;            /**< the problems found so far, reported together */
  int n_problems;             /**< their number */
};

/** Remember one problem "WHERE:LINE: MESSAGE" (WHERE: MESSAGE when line
 *  <= 0); params_read reports every problem of a file in one pass. */
static void problem(struct params *p, const char *where, int line, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static void problem(struct params *p, const char *where, int line, const char *fmt, ...) {
  char msg[2048], full[2600];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  if (line > 0)
    snprintf(full, sizeof full, "%s:%d: %s", where, line, msg);
  else
    snprintf(full, sizeof full, "%s: %s", where, msg);
  p->problems = error_realloc(p->problems, (size_t)(p->n_problems + 1) * sizeof *p->problems,
                              "parameter problems");
  p->problems[p->n_problems] = strdup(full);
  if (!p->problems[p->n_problems]) error_exit("out of memory");
  p->n_problems++;
}

/** Stop when problems were found: one line each, the last through
 *  error_exit. */
static void problems_report(struct params *p) {
  if (p->n_problems == 0) return;
  for (int k = 0; k < p->n_problems - 1; k++) error_report("%s", p->problems[k]);
  error_exit("%s%s", p->problems[p->n_problems - 1],
             p->n_problems > 1 ? " (and the problems above)" : "");
}

/** The one line for a SWIFT key or section that has no effect. */
static void swift_note(const char *where, int line, const char *what, const struct param_swift *s) {
  if (s->level == PARAM_SWIFT_WARN)
    error_warning("%s:%d: %s (SWIFT's) has no effect in Bolide: %s", where, line, what, s->reason);
  else
    error_note("%s:%d: %s (SWIFT's) has no effect in Bolide: %s", where, line, what, s->reason);
}

/** Parse a number: decimal digits, sign, point and exponent only (1e5,
 *  1.0e+05, .5), finite.  Returns 1 on success. */
static int parse_real(const char *t, double *x) {
  if (!t[0] || strspn(t, "0123456789+-.eE") != strlen(t)) return 0;
  char *end;
  double v = strtod(t, &end);
  if (end == t || *end || !isfinite(v)) return 0;
  *x = v;
  return 1;
}

/** Parse a decimal integer that fits a long.  Returns 1 on success. */
static int parse_int(const char *t, long *x) {
  const char *digits = (t[0] == '-' || t[0] == '+') ? t + 1 : t;
  if (!digits[0] || strspn(digits, "0123456789") != strlen(digits)) return 0;
  errno = 0;
  long v = strtol(t, NULL, 10);
  if (errno == ERANGE) return 0;
  *x = v;
  return 1;
}

/** Parse a boolean: true/false, yes/no, on/off, 1/0 (any case). */
static int parse_bool(const char *t, int *x) {
  static const char *const yes[] = {"true", "yes", "on", "1"};
  static const char *const no[] = {"false", "no", "off", "0"};
  for (int i = 0; i < 4; i++) {
    if (strcasecmp(t, yes[i]) == 0) return *x = 1, 1;
    if (strcasecmp(t, no[i]) == 0) return *x = 0, 1;
  }
  return 0;
}

/** Index of t in the '|'-separated choices, or -1. */
static int parse_enum(const char *t, const char *choices) {
  size_t len = strlen(t);
  const char *c = choices;
  for (int index = 0;; index++) {
    size_t clen = strcspn(c, "|");
    if (clen == len && strncmp(c, t, len) == 0) return index;
    if (!c[clen]) return -1;
    c += clen + 1;
  }
}

/** Text of the range of s: "in [a, b]", ">= a", "> 0", "<= b", or "" when
 *  unbounded. */
static void range_text(const struct param_spec *s, char *buf, size_t len) {
  int lo = s->min > -PARAM_INF, hi = s->max < PARAM_INF;
  if (lo && hi) {
    snprintf(buf, len, "in [%.15g, %.15g]", s->min, s->max);
  } else if (lo) {
    /* a tiny positive bound (1e-300) means "strictly positive" */
    if (s->min > 0 && s->min < 1e-200)
      snprintf(buf, len, "> 0");
    else
      snprintf(buf, len, ">= %.15g", s->min);
  } else if (hi) {
    snprintf(buf, len, "<= %.15g", s->max);
  } else {
    buf[0] = '\0';
  }
}

/** Check x against the range of s; on failure write the message into err. */
static int check_range(const struct param_spec *s, double x, const char *text, char *err,
                       size_t len) {
  if (x >= s->min && x <= s->max) return 1;
  char range[96];
  range_text(s, range, sizeof range);
  snprintf(err, len, "%s: %s is out of range (must be %s)", s->name, text, range);
  return 0;
}

/** Parse one real of a REAL_ARRAY (element `index`, 1-based) into *x. */
static int parse_array_element(const struct param_spec *s, const struct param_node *n, int index,
                               double *x, char *err, size_t len) {
  if (n->kind != NODE_SCALAR || !parse_real(n->text, x)) {
    snprintf(err, len, "%s: element %d: expected a number, got %s%s%s", s->name, index,
             n->kind == NODE_SCALAR ? "'" : node_kind_name(n),
             n->kind == NODE_SCALAR ? n->text : "", n->kind == NODE_SCALAR ? "'" : "");
    return 0;
  }
  return check_range(s, *x, n->text, err, len);
}

/** 1 if count is one of the '|'-separated numbers of choices. */
static int count_allowed(const char *choices, int count) {
  for (const char *c = choices; c; c = strchr(c, '|'), c = c ? c + 1 : NULL)
    if (atoi(c) == count) return 1;
  return 0;
}

/** The '|'-separated numbers as "3" or "0, 1 or 3". */
static void counts_list(const char *choices, char *buf, size_t len) {
  size_t n = 0;
  buf[0] = '\0';
  for (const char *c = choices; *c && n + 6 < len; c++) {
    if (*c == '|') {
      const char *sep = strchr(c + 1, '|') ? ", " : " or ";
      n += (size_t)snprintf(buf + n, len - n, "%s", sep);
    } else {
      buf[n++] = *c;
      buf[n] = '\0';
    }
  }
}

/** Check the length of a STRING value against the table's bounds. */
static int check_length(const struct param_spec *s, const char *t, char *err, size_t len) {
  const size_t l = strlen(t);
  if (l < (size_t)s->min) {
    snprintf(err, len, "%s: must not be empty", s->name);
    return 0;
  }
  if (s->max > 0 && l > (size_t)s->max) {
    snprintf(err, len, "%s: '%.32s...' is %zu bytes long (at most %.0f)", s->name, t, l, s->max);
    return 0;
  }
  return 1;
}

/** Parse a REAL_ARRAY: a sequence of reals (a single number counts as one). */
static int parse_array(const struct param_spec *s, const struct param_node *n,
                       struct param_value *v, char *err, size_t len) {
  if (n->kind == NODE_MAPPING) {
    snprintf(err, len, "%s: expected a sequence of numbers such as [1, 2, 3], got a mapping",
             s->name);
    return 0;
  }
  int count = n->kind == NODE_SEQUENCE ? n->n : 1;
  if (s->choices && !count_allowed(s->choices, count)) {
    char list[64];
    counts_list(s->choices, list, sizeof list);
    snprintf(err, len, "%s: %d value%s given (expected %s)", s->name, count, count == 1 ? "" : "s",
             list);
    return 0;
  }
  double *a = error_calloc((size_t)count, sizeof *a, "parameter array");
  for (int k = 0; k < count; k++)
    if (!parse_array_element(s, n->kind == NODE_SEQUENCE ? n->child[k] : n, k + 1, &a[k], err,
                             len)) {
      free(a);
      return 0;
    }
  v->a = a;
  v->n = count;
  return 1;
}

/** Parse a WORDS value: one scalar, kept as it is, or a sequence of
 *  scalars, kept as the text "[a, b, c]". */
static int parse_words(const struct param_spec *s, const struct param_node *n,
                       struct param_value *v, char *err, size_t len) {
  if (n->kind == NODE_SCALAR) {
    v->s = strdup(n->text);
    if (!v->s) error_exit("out of memory copying a parameter");
    return 1;
  }
  size_t total = 3;
  for (int k = 0; n->kind == NODE_SEQUENCE && k < n->n; k++) {
    if (n->child[k]->kind != NODE_SCALAR) {
      snprintf(err, len, "%s: element %d: expected a word, got %s", s->name, k + 1,
               node_kind_name(n->child[k]));
      return 0;
    }
    total += strlen(n->child[k]->text) + 2;
  }
  if (n->kind != NODE_SEQUENCE) {
    snprintf(err, len, "%s: expected a word or a list of words such as [a, b], got %s", s->name,
             node_kind_name(n));
    return 0;
  }
  char *t = error_malloc(total, "parameter text");
  strcpy(t, "[");
  for (int k = 0; k < n->n; k++) {
    if (k) strcat(t, ", ");
    strcat(t, n->child[k]->text);
  }
  strcat(t, "]");
  v->s = t;
  return 1;
}

/** Release what a value owns. */
static void value_clear(struct param_value *v) {
  free(v->s);
  free(v->a);
  free(v->override);
  memset(v, 0, sizeof *v);
}

/** Copy the '|'-separated choices into buf as "a, b, c". */
static void choices_list(const char *choices, char *buf, size_t len) {
  size_t n = 0;
  for (const char *c = choices; *c && n + 3 < len; c++) {
    if (*c == '|')
      buf[n++] = ',', buf[n++] = ' ';
    else
      buf[n++] = *c;
  }
  buf[n] = '\0';
}

/** Copy choice number `index` of the '|'-separated choices into buf. */
static void choice_text(const char *choices, int index, char *buf, size_t len) {
  const char *c = choices;
  for (int k = 0; k < index && c; k++) c = strchr(c, '|'), c = c ? c + 1 : NULL;
  snprintf(buf, len, "%.*s", c ? (int)strcspn(c, "|") : 0, c ? c : "");
}

/** Parse a scalar of type INT, REAL, BOOL or ENUM into out.  Returns 1, or 0
 *  with the message in err. */
static int parse_scalar(const struct param_spec *s, const char *t, struct param_value *out,
                        char *err, size_t len) {
  char list[512];
  switch (s->type) {
    case PARAM_INT:
      if (parse_int(t, &out->i)) return check_range(s, (double)out->i, t, err, len);
      snprintf(err, len, "%s: expected an integer, got '%s'", s->name, t);
      return 0;
    case PARAM_REAL:
      if (parse_real(t, &out->r)) return check_range(s, out->r, t, err, len);
      snprintf(err, len, "%s: expected a number, got '%s'", s->name, t);
      return 0;
    case PARAM_BOOL:
      if (parse_bool(t, &out->b)) return 1;
      snprintf(err, len, "%s: expected true or false (yes/no, on/off, 1/0), got '%s'", s->name, t);
      return 0;
    default: /* PARAM_ENUM */
      out->b = parse_enum(t, s->choices);
      if (out->b >= 0) return 1;
      choices_list(s->choices, list, sizeof list);
      snprintf(err, len, "%s: '%s' is not one of: %s", s->name, t, list);
      return 0;
  }
}

/** Parse node n as the value of key s into v (cleared first).  Returns 1, or
 *  0 with a message naming the key in err. */
static int value_parse(const struct param_spec *s, const struct param_node *n,
                       struct param_value *v, char *err, size_t len) {
  struct param_value out = {0};
  int ok = 1;
  if (s->type == PARAM_SECTION) {
    out.node = n;
  } else if (s->type == PARAM_REAL_ARRAY) {
    ok = parse_array(s, n, &out, err, len);
  } else if (s->type == PARAM_WORDS) {
    ok = parse_words(s, n, &out, err, len);
  } else if (n->kind != NODE_SCALAR) {
    snprintf(err, len, "%s: expected a single value, got %s", s->name, node_kind_name(n));
    ok = 0;
  } else if (s->type == PARAM_STRING) {
    if (!check_length(s, n->text, err, len)) return 0;
    out.s = strdup(n->text);
    if (!out.s) error_exit("out of memory copying a parameter");
  } else {
    ok = parse_scalar(s, n->text, &out, err, len);
  }
  if (!ok) return 0;
  value_clear(v);
  *v = out;
  return 1;
}

/** A tree for a value given as text: YAML-parsed for arrays (so that
 *  "[1, 2, 3]" works), one scalar holding the text otherwise. */
static struct param_node *node_from_text(const struct param_spec *s, const char *text,
                                         const char *where) {
  if (s->type == PARAM_REAL_ARRAY || s->type == PARAM_WORDS) return tree_load_text(text, where);
  struct param_node *n = node_new(NODE_SCALAR, 0);
  n->text = strdup(text);
  if (!n->text) error_exit("out of memory copying a parameter");
  return n;
}

/** Set every value to its table default (required keys stay zero). */
static void params_set_defaults(struct params *p) {
  char err[1024];
  p->values = error_calloc((size_t)PARAMS_N, sizeof *p->values, "parameter values");
  for (int i = 0; i < PARAMS_N; i++) {
    const struct param_spec *s = &params_table[i];
    if (!s->def || s->type == PARAM_SECTION) continue;
    struct param_node *n = node_from_text(s, s->def, s->name);
    if (!value_parse(s, n, &p->values[i], err, sizeof err))
      error_bug("bad default in param_list.h: %s", err);
    node_free(n);
  }
}

/** Check the keys of one section and take their values; every problem is
 *  remembered (problem()) and the next key is looked at. */
static void params_take_section(struct params *p, const char *sec, int line,
                                const struct param_node *n) {
  char name[1024], err[1024], hint[160];
  if (node_is_null(n)) return; /* "Section:" with no keys */
  if (n->kind != NODE_MAPPING) {
    problem(p, p->filename, line, "section '%s' must be a mapping of keys, got %s", sec,
            node_kind_name(n));
    return;
  }
  for (int k = 0; k < n->n; k++) {
    snprintf(name, sizeof name, "%s:%s", sec, n->keys[k]);
    int i = spec_find(name);
    if (i < 0 || params_table[i].type == PARAM_SECTION) {
      const struct param_swift *sw = swift_key(name);
      if (sw) {
        swift_note(p->filename, n->key_lines[k], name, sw);
        continue;
      }
      const int near = suggest(name, 0, hint, sizeof hint);
      if (near >= 0) p->values[near].tried = 1;
      problem(p, p->filename, n->key_lines[k], "unknown key '%s'%s", name, hint);
      continue;
    }
    if (!value_parse(&params_table[i], n->child[k], &p->values[i], err, sizeof err)) {
      p->values[i].tried = 1;
      problem(p, p->filename, n->key_lines[k], "%s", err);
      continue;
    }
    p->values[i].given = 1;
    p->values[i].line = n->key_lines[k];
  }
}

/** Check the file's tree against the table and take its values. */
static void params_take_file(struct params *p) {
  const struct param_node *root = p->root;
  char hint[160];
  if (node_is_null(root)) return;
  if (root->kind != NODE_MAPPING)
    fail(p->filename, root->line, "the file must be a mapping of sections (Section: {key: value})");
  for (int k = 0; k < root->n; k++) {
    const char *sec = root->keys[k];
    int i = spec_find(sec);
    const struct param_swift *sw = swift_section(sec);
    if (i >= 0 && params_table[i].type == PARAM_SECTION) {
      if (node_is_null(root->child[k])) continue;
      p->values[i].node = root->child[k];
      p->values[i].given = 1;
      p->values[i].line = root->key_lines[k];
    } else if (section_known(sec)) {
      params_take_section(p, sec, root->key_lines[k], root->child[k]);
    } else if (sw) {
      char what[300];
      snprintf(what, sizeof what, "section '%s'", sec);
      swift_note(p->filename, root->key_lines[k], what, sw);
    } else {
      suggest(sec, 1, hint, sizeof hint);
      problem(p, p->filename, root->key_lines[k], "unknown section '%s'%s", sec, hint);
    }
  }
}

/** Apply one -P "Section:key:value" (the value may itself contain ':'). */
static void params_apply_override(struct params *p, const char *arg) {
  char name[1024], where[1100], err[1024], hint[160];
  const char *c1 = strchr(arg, ':');
  const char *c2 = c1 ? strchr(c1 + 1, ':') : NULL;
  snprintf(where, sizeof where, "-P %s", arg);
  if (!c2 || c1 == arg || c2 == c1 + 1) {
    problem(p, where, 0, "expected Section:key:value");
    return;
  }
  snprintf(name, sizeof name, "%.*s", (int)(c2 - arg), arg);
  int i = spec_find(name);
  char section[1024];
  snprintf(section, sizeof section, "%.*s", (int)(c1 - arg), arg);
  if (params_spec(section) && params_spec(section)->type == PARAM_SECTION) {
    problem(p, where, 0, "section '%s' cannot be set with -P", section);
    return;
  }
  if (i < 0 || params_table[i].type == PARAM_SECTION) {
    const struct param_swift *sw = swift_key(name);
    if (sw) {
      if (sw->level == PARAM_SWIFT_WARN)
        error_warning("%s: %s (SWIFT's) has no effect in Bolide: %s", where, name, sw->reason);
      else
        error_note("%s: %s (SWIFT's) has no effect in Bolide: %s", where, name, sw->reason);
      return;
    }
    const int near = suggest(name, 0, hint, sizeof hint);
    if (near >= 0) p->values[near].tried = 1;
    problem(p, where, 0, "unknown key '%s'%s", name, hint);
    return;
  }
  /* trim the blanks a quoted shell argument may carry */
  const char *value = c2 + 1;
  while (isspace((unsigned char)*value)) value++;
  char *text = strdup(value); /* whole: a long value must reach the length check */
  if (!text) error_exit("out of memory copying a parameter");
  for (size_t l = strlen(text); l > 0 && isspace((unsigned char)text[l - 1]); l--) text[l - 1] = 0;
  struct param_node *n = node_from_text(&params_table[i], text, where);
  free(text);
  const int ok = value_parse(&params_table[i], n, &p->values[i], err, sizeof err);
  node_free(n);
  if (!ok) {
    p->values[i].tried = 1;
    problem(p, where, 0, "%s", err);
    return;
  }
  p->values[i].given = 1;
  free(p->values[i].override);
  p->values[i].override = strdup(arg);
}

/** SWIFT's keys that change other keys' meaning, and the notes on SWIFT
 *  keys Bolide understands but whose value it cannot follow. */
static void params_apply_swift(struct params *p) {
  const int mac = spec_find("Gravity:MAC"), eps = spec_find("Gravity:epsilon_fmm");
  if (p->values[mac].b == 1) { /* geometric: theta_cr alone, as in SWIFT */
    if (p->values[eps].given && p->values[eps].r != 0.0)
      error_note(
          "%s:%d: Gravity:epsilon_fmm has no effect with Gravity:MAC: geometric (as in SWIFT)",
          p->filename, p->values[eps].line);
    p->values[eps].r = 0.0;
  } else if (p->values[mac].b == 2) {
    error_note(
        "%s:%d: Gravity:MAC: gadget is read as adaptive (Bolide's adaptive criterion, "
        "Gravity:epsilon_fmm)",
        p->filename, p->values[mac].line);
  }
  const int save = spec_find("Restarts:save"), onexit = spec_find("Restarts:onexit");
  if (p->values[save].given && !p->values[save].b)
    error_note(
        "%s:%d: Restarts:save: false has no effect in Bolide: the previous restart file is "
        "always kept (BASENAME.prev.bin), so that a complete one exists at every instant",
        p->filename, p->values[save].line);
  if (p->values[onexit].given && !p->values[onexit].b)
    error_note(
        "%s:%d: Restarts:onexit: false has no effect in Bolide: with Restarts:enable a "
        "restart file is always written when the run ends",
        p->filename, p->values[onexit].line);
}

struct params *params_read(const char *filename, int n_overrides, char *const *overrides) {
  struct params *p = error_calloc(1, sizeof *p, "parameters");
  p->filename = strdup(filename);
  if (!p->filename) error_exit("out of memory");
  p->root = tree_load_file(filename);
  params_set_defaults(p);
  params_take_file(p);
  for (int k = 0; k < n_overrides; k++) params_apply_override(p, overrides[k]);
  for (int i = 0; i < PARAMS_N; i++)
    if (!params_table[i].def && !p->values[i].given && !p->values[i].tried)
      problem(p, filename, 0, "missing required key '%s' (%s)", params_table[i].name,
              params_table[i].doc);
  problems_report(p);
  params_apply_swift(p);
  return p;
}

struct params *params_read_tree(const char *filename) {
  struct params *p = error_calloc(1, sizeof *p, "parameters");
  p->filename = strdup(filename);
  if (!p->filename) error_exit("out of memory");
  p->root = tree_load_file(filename);
  params_set_defaults(p);
  return p;
}

void params_free(struct params *p) {
  if (!p) return;
  for (int i = 0; i < PARAMS_N; i++) value_clear(&p->values[i]);
  free(p->values);
  for (int k = 0; k < p->n_problems; k++) free(p->problems[k]);
  free(p->problems);
  node_free(p->root);
  free(p->filename);
  free(p);
}

const char *params_filename(const struct params *p) {
  return p->filename;
}

/* ================================================================ getters */

/** The value of a key, checking that the caller asks for the right type. */
static const struct param_value *value_get(const struct params *p, const char *name,
                                           enum param_type type) {
  int i = spec_find(name);
  if (i < 0) error_bug("no parameter '%s' in param_list.h", name);
  if (params_table[i].type != type) error_bug("parameter '%s' read with the wrong type", name);
  return &p->values[i];
}

int params_section_line(const struct params *p, const char *section) {
  const struct param_node *r = p->root;
  for (int k = 0; r && r->kind == NODE_MAPPING && k < r->n; k++)
    if (strcmp(r->keys[k], section) == 0) return r->key_lines[k];
  return 0;
}

const char *params_file_text(const struct params *p, const char *name) {
  const char *colon = strchr(name, ':');
  if (!colon) return NULL;
  char sec[PARAMS_MAX_NAME + 1];
  snprintf(sec, sizeof sec, "%.*s", (int)(colon - name), name);
  const struct param_node *s = param_node_get(p->root, sec);
  return param_node_text(param_node_get(s, colon + 1));
}

int params_given(const struct params *p, const char *name) {
  int i = spec_find(name);
  if (i < 0) error_bug("no parameter '%s' in param_list.h", name);
  return p->values[i].given;
}

long params_get_int(const struct params *p, const char *name) {
  return value_get(p, name, PARAM_INT)->i;
}

double params_get_real(const struct params *p, const char *name) {
  return value_get(p, name, PARAM_REAL)->r;
}

int params_get_bool(const struct params *p, const char *name) {
  return value_get(p, name, PARAM_BOOL)->b;
}

const char *params_get_string(const struct params *p, const char *name) {
  const int i = spec_find(name);
  const char *s =
      value_get(p, name, i >= 0 && params_table[i].type == PARAM_WORDS ? PARAM_WORDS : PARAM_STRING)
          ->s;
  return s ? s : "";
}

int params_get_enum(const struct params *p, const char *name) {
  return value_get(p, name, PARAM_ENUM)->b;
}

int params_get_real_array(const struct params *p, const char *name, double *out, int maxn) {
  const struct param_value *v = value_get(p, name, PARAM_REAL_ARRAY);
  int n = v->n < maxn ? v->n : maxn;
  for (int k = 0; k < n; k++) out[k] = v->a[k];
  return n;
}

char *params_get_path(const struct params *p, const char *name) {
  const char *s = params_get_string(p, name);
  const char *slash = strrchr(p->filename, '/');
  size_t dir = (s[0] == '/' || s[0] == '\0' || !slash) ? 0 : (size_t)(slash - p->filename) + 1;
  char *path = error_malloc(dir + strlen(s) + 1, "path");
  memcpy(path, p->filename, dir);
  strcpy(path + dir, s);
  return path;
}

void params_error(const struct params *p, const char *name, const char *fmt, ...) {
  char msg[2048];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  int i = spec_find(name);
  const struct param_value *v = i >= 0 ? &p->values[i] : NULL;
  if (v && v->line > 0 && !v->override)
    error_exit("%s:%d: %s: %s", p->filename, v->line, name, msg);
  if (v && v->override) error_exit("%s: -P %s: %s", p->filename, v->override, msg);
  error_exit("%s: %s (default value): %s", p->filename, name, msg);
}

/* ================================================================ node API */

const struct param_node *params_section(const struct params *p, const char *name) {
  if (name[0] == '\0') return p->root;
  return value_get(p, name, PARAM_SECTION)->node;
}

int param_node_kind(const struct param_node *n) {
  return n ? n->kind : -1;
}

int param_node_count(const struct param_node *n) {
  return n && n->kind != NODE_SCALAR ? n->n : 0;
}

const char *param_node_key(const struct param_node *n, int i) {
  return n && n->kind == NODE_MAPPING && i >= 0 && i < n->n ? n->keys[i] : NULL;
}

const struct param_node *param_node_child(const struct param_node *n, int i) {
  return n && n->kind != NODE_SCALAR && i >= 0 && i < n->n ? n->child[i] : NULL;
}

const struct param_node *param_node_get(const struct param_node *n, const char *key) {
  if (!n || n->kind != NODE_MAPPING) return NULL;
  for (int i = 0; i < n->n; i++)
    if (strcmp(n->keys[i], key) == 0) return n->child[i];
  return NULL;
}

const char *param_node_text(const struct param_node *n) {
  return n && n->kind == NODE_SCALAR ? n->text : NULL;
}

int param_node_line(const struct param_node *n) {
  return n ? n->line : 0;
}

void param_node_error(const struct params *p, const struct param_node *n, const char *fmt, ...) {
  char msg[2048];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  fail(p->filename, n ? n->line : 0, "%s", msg);
}

double param_node_real(const struct params *p, const struct param_node *n, const char *what) {
  double x;
  if (!n || n->kind != NODE_SCALAR || !parse_real(n->text, &x))
    param_node_error(p, n, "%s: expected a number, got %s%s%s", what,
                     n && n->kind == NODE_SCALAR ? "'" : "",
                     n ? (n->kind == NODE_SCALAR ? n->text : node_kind_name(n)) : "nothing",
                     n && n->kind == NODE_SCALAR ? "'" : "");
  return x;
}

long param_node_int(const struct params *p, const struct param_node *n, const char *what) {
  long x;
  if (!n || n->kind != NODE_SCALAR || !parse_int(n->text, &x))
    param_node_error(p, n, "%s: expected an integer, got %s%s%s", what,
                     n && n->kind == NODE_SCALAR ? "'" : "",
                     n ? (n->kind == NODE_SCALAR ? n->text : node_kind_name(n)) : "nothing",
                     n && n->kind == NODE_SCALAR ? "'" : "");
  return x;
}

/* ================================================================ output */

/** A growing string that the YAML emitter writes into. */
struct text_buf {
  char *s;    /**< the text, NUL-terminated */
  size_t n;   /**< its length */
  size_t cap; /**< allocated bytes */
};

/** Append size bytes to a text_buf (also the emitter's write handler). */
static int text_buf_write(void *data, unsigned char *bytes, size_t size) {
  struct text_buf *t = data;
  if (t->n + size + 1 > t->cap) {
    t->cap = 2 * (t->n + size + 1);
    t->s = error_realloc(t->s, t->cap, "parameter text");
  }
  memcpy(t->s + t->n, bytes, size);
  t->n += size;
  t->s[t->n] = '\0';
  return 1;
}

/** Emit one event; a failure is a bug (we build the events). */
static void emit(yaml_emitter_t *e, yaml_event_t *ev) {
  if (!yaml_emitter_emit(e, ev)) error_bug("YAML emitter: %s", e->problem ? e->problem : "?");
}

/** Emit a scalar, plain when YAML allows it (the emitter quotes otherwise). */
static void emit_scalar(yaml_emitter_t *e, const char *text, int quoted) {
  yaml_event_t ev;
  yaml_scalar_event_initialize(
      &ev, NULL, NULL, (yaml_char_t *)text, (int)strlen(text), 1, 1,
      quoted || !text[0] ? YAML_DOUBLE_QUOTED_SCALAR_STYLE : YAML_PLAIN_SCALAR_STYLE);
  emit(e, &ev);
}

/** Emit the start (start = 1) or end of a mapping or a flow sequence. */
static void emit_collection(yaml_emitter_t *e, int kind, int start) {
  yaml_event_t ev;
  if (kind == NODE_MAPPING && start)
    yaml_mapping_start_event_initialize(&ev, NULL, NULL, 1, YAML_BLOCK_MAPPING_STYLE);
  else if (kind == NODE_MAPPING)
    yaml_mapping_end_event_initialize(&ev);
  else if (start)
    yaml_sequence_start_event_initialize(&ev, NULL, NULL, 1, YAML_FLOW_SEQUENCE_STYLE);
  else
    yaml_sequence_end_event_initialize(&ev);
  emit(e, &ev);
}

/** Shortest "%.Ng" text of x that reads back as exactly x. */
static void format_real(double x, char *buf, size_t len) {
  for (int digits = 15; digits <= 17; digits++) {
    snprintf(buf, len, "%.*g", digits, x);
    if (strtod(buf, NULL) == x) return;
  }
}

/** Emit a free-form subtree as it was read. */
static void emit_node(yaml_emitter_t *e, const struct param_node *n) {
  if (n->kind == NODE_SCALAR) {
    emit_scalar(e, n->text, n->quoted);
    return;
  }
  emit_collection(e, n->kind, 1);
  for (int i = 0; i < n->n; i++) {
    if (n->kind == NODE_MAPPING) emit_scalar(e, n->keys[i], 0);
    emit_node(e, n->child[i]);
  }
  emit_collection(e, n->kind, 0);
}

/** Emit the value in use of table entry i. */
static void emit_value(yaml_emitter_t *e, const struct param_spec *s, const struct param_value *v) {
  char buf[64];
  switch (s->type) {
    case PARAM_INT:
      snprintf(buf, sizeof buf, "%ld", v->i);
      emit_scalar(e, buf, 0);
      break;
    case PARAM_REAL:
      format_real(v->r, buf, sizeof buf);
      emit_scalar(e, buf, 0);
      break;
    case PARAM_BOOL:
      emit_scalar(e, v->b ? "true" : "false", 0);
      break;
    case PARAM_ENUM:
      choice_text(s->choices, v->b, buf, sizeof buf);
      emit_scalar(e, buf, 0);
      break;
    case PARAM_STRING:
    case PARAM_WORDS: /* a list as its text "[a, b]": quoted, it reads back the same */
      emit_scalar(e, v->s ? v->s : "", 0);
      break;
    case PARAM_REAL_ARRAY:
      emit_collection(e, NODE_SEQUENCE, 1);
      for (int k = 0; k < v->n; k++) {
        format_real(v->a[k], buf, sizeof buf);
        emit_scalar(e, buf, 0);
      }
      emit_collection(e, NODE_SEQUENCE, 0);
      break;
    case PARAM_SECTION:
      emit_node(e, v->node);
      break;
  }
}

/** Emit the sections from table entry `first` on (mapping keys only). */
static void emit_section(yaml_emitter_t *e, const struct params *p, int first) {
  const struct param_spec *s0 = &params_table[first];
  char sec[PARAMS_MAX_NAME + 1];
  snprintf(sec, sizeof sec, "%.*s", (int)spec_section_len(s0), s0->name);
  if (s0->type == PARAM_SECTION) {
    if (!p->values[first].node) return;
    emit_scalar(e, sec, 0);
    emit_value(e, s0, &p->values[first]);
    return;
  }
  emit_scalar(e, sec, 0);
  emit_collection(e, NODE_MAPPING, 1);
  for (int i = first; i < PARAMS_N; i++) {
    if (!spec_same_section(first, i)) continue;
    emit_scalar(e, params_table[i].name + strlen(sec) + 1, 0);
    emit_value(e, &params_table[i], &p->values[i]);
  }
  emit_collection(e, NODE_MAPPING, 0);
}

char *params_to_string(const struct params *p) {
  struct text_buf t = {NULL, 0, 0};
  const char *head =
      "# Bolide parameters in use: values given and defaults (numbers in internal units).\n";
  text_buf_write(&t, (unsigned char *)head, strlen(head));
  yaml_emitter_t e;
  yaml_event_t ev;
  if (!yaml_emitter_initialize(&e)) error_exit("out of memory starting the YAML emitter");
  yaml_emitter_set_output(&e, text_buf_write, &t);
  yaml_emitter_set_width(&e, -1);
  yaml_emitter_set_unicode(&e, 1);
  yaml_stream_start_event_initialize(&ev, YAML_UTF8_ENCODING);
  emit(&e, &ev);
  yaml_document_start_event_initialize(&ev, NULL, NULL, NULL, 1);
  emit(&e, &ev);
  emit_collection(&e, NODE_MAPPING, 1);
  for (int i = 0; i < PARAMS_N; i++)
    if (spec_starts_section(i)) emit_section(&e, p, i);
  emit_collection(&e, NODE_MAPPING, 0);
  yaml_document_end_event_initialize(&ev, 1);
  emit(&e, &ev);
  yaml_stream_end_event_initialize(&ev);
  emit(&e, &ev);
  yaml_emitter_delete(&e);
  return t.s;
}

void params_write_yaml(const struct params *p, FILE *f) {
  char *s = params_to_string(p);
  fputs(s, f);
  free(s);
}

void params_write_used(const struct params *p, const char *filename) {
  size_t len = strlen(filename) + 5;
  char *tmp = error_malloc(len, "file name");
  snprintf(tmp, len, "%s.tmp", filename);
  FILE *f = fopen(tmp, "w");
  if (!f) error_exit("%s: cannot write: %s", tmp, strerror(errno));
  error_register_tmpfile(tmp);
  params_write_yaml(p, f);
  if (ferror(f) | fclose(f)) error_exit("%s: cannot write: %s", tmp, strerror(errno));
  if (rename(tmp, filename) != 0)
    error_exit("%s: cannot rename to %s: %s", tmp, filename, strerror(errno));
  error_unregister_tmpfile(tmp);
  free(tmp);
}

/* ---------------------------------------------------------------- reference */

/** Placeholder values shown in the reference for required keys, where the
 *  generic one (by type, see reference_value) would read badly. */
static const struct {
  const char *name;  /**< a required key */
  const char *value; /**< the value shown */
} params_placeholders[] = {
    {"InitialConditions:file_name", "ics.hdf5"},
};

/** Text of the value shown in the reference for entry s: its default, or a
 *  placeholder for a required key. */
static const char *reference_value(const struct param_spec *s) {
  if (s->def) return s->def;
  for (size_t k = 0; k < sizeof params_placeholders / sizeof params_placeholders[0]; k++)
    if (strcmp(params_placeholders[k].name, s->name) == 0) return params_placeholders[k].value;
  switch (s->type) {
    case PARAM_INT:
    case PARAM_REAL:
      return s->min <= 1 && s->max >= 1 ? "1" : "0";
    case PARAM_BOOL:
      return "false";
    case PARAM_REAL_ARRAY:
      return "[]";
    default:
      return "CHANGE_ME";
  }
}

/** Write a scalar text for the reference: plain when that is safe, else in
 *  double quotes with '"' and '\' escaped. */
static void reference_scalar(FILE *f, const char *text) {
  int plain = text[0] && !strpbrk(text, ":#[]{},&*!|>'\"%@`\\") &&
              !isspace((unsigned char)text[0]) && !isspace((unsigned char)text[strlen(text) - 1]) &&
              text[0] != '-' && text[0] != '?';
  if (plain) {
    fputs(text, f);
    return;
  }
  fputc('"', f);
  for (const char *c = text; *c; c++) {
    if (*c == '"' || *c == '\\') fputc('\\', f);
    fputc(*c, f);
  }
  fputc('"', f);
}

/** Write text as "  # " comment lines of at most 88 columns, broken at blanks. */
static void reference_wrap(FILE *f, const char *text) {
  const int width = 88 - 4;
  while (*text) {
    int n = (int)strlen(text);
    if (n > width) {
      n = width;
      while (n > 0 && text[n] != ' ') n--;
      if (n == 0) n = (int)strcspn(text, " "); /* one long word */
    }
    fprintf(f, "  # %.*s\n", n, text);
    text += n;
    while (*text == ' ') text++;
  }
}

/** The "# meaning [unit] (type, range; default)" comment of entry s. */
static void reference_comment(FILE *f, const struct param_spec *s) {
  static const char *const type_name[] = {
      [PARAM_INT] = "integer",     [PARAM_REAL] = "real",
      [PARAM_BOOL] = "boolean",    [PARAM_STRING] = "text",
      [PARAM_ENUM] = "one of",     [PARAM_REAL_ARRAY] = "list of reals",
      [PARAM_SECTION] = "section", [PARAM_WORDS] = "word or [list of words]"};
  char range[96] = "", list[512] = "", unit[128] = "", text[2048];
  if (s->type == PARAM_INT || s->type == PARAM_REAL || s->type == PARAM_REAL_ARRAY)
    range_text(s, range, sizeof range);
  if (s->type == PARAM_ENUM) choices_list(s->choices, list, sizeof list);
  if (s->type == PARAM_REAL_ARRAY && s->choices) {
    char counts[64];
    counts_list(s->choices, counts, sizeof counts);
    snprintf(list, sizeof list, "of %s values", counts);
  }
  if (s->type == PARAM_STRING && (s->min > 0 || s->max > 0))
    snprintf(range, sizeof range, "%.0f to %.0f bytes", s->min, s->max);
  if (strcmp(s->unit, "-") != 0) snprintf(unit, sizeof unit, " [%s]", s->unit);
  const char *def = !s->def ? NULL : s->def[0] ? s->def : "\"\"";
  snprintf(text, sizeof text, "%s%s (%s%s%s%s%s; %s%s)", s->doc, unit, type_name[s->type],
           list[0] ? " " : "", list, range[0] ? " " : "", range, def ? "default " : "REQUIRED",
           def ? def : "");
  reference_wrap(f, text);
}

void params_write_reference(FILE *f) {
  fputs(
      "# Bolide: reference of every parameter.\n"
      "#\n"
      "# Generated from src/io/param_list.h by params_write_reference(); do not edit by\n"
      "# hand.  Regenerate with: tests/unit/test_params_reference --write examples/parameters.yml\n"
      "#\n"
      "# Each key is shown with its default value, under a comment giving its meaning,\n"
      "# unit, type, allowed range and default.  Keys marked REQUIRED have no default:\n"
      "# the value shown is a placeholder to replace.  Every number is in the internal\n"
      "# unit system (section InternalUnitSystem, SI by default) unless its unit says\n"
      "# otherwise.  Unknown or misspelt keys, values of the wrong type or out of range\n"
      "# and missing required keys stop the run before it starts.  A key can be\n"
      "# overridden on the command line with -P Section:key:value.\n"
      "#\n"
      "# Materials: a mapping from material id to a mapping of material parameters\n"
      "# (equation of state, strength, damage, porosity); see the materials library\n"
      "# documentation for its keys.  Without it, every particle is the ideal gas of\n"
      "# material id 0 (SPH:gamma).\n"
      "#\n"
      "# EoS (SWIFT's section, read as Materials entries): planetary_use_NAME: 1 enables\n"
      "# SWIFT's planetary material NAME with SWIFT's id: idg_def 0, Til_iron 100,\n"
      "# Til_granite 101, Til_water 102, Til_basalt 103, Til_ice 104 (the library entries\n"
      "# with that swift_id); SESAME_iron 300, SESAME_basalt 301, SESAME_water 302,\n"
      "# SS08_water 303, AQUA 304, CMS19_H 305, CMS19_He 306, CD21_HHe 307,\n"
      "# ANEOS_forsterite 400, ANEOS_iron 401, ANEOS_Fe85Si15 402, custom_0..9 900-909\n"
      "# (tables in SWIFT's format, planetary_NAME_table_file: FILE, relative to this\n"
      "# file).  A material of the Materials section wins over the EoS entry of its id.\n"
      "# HM80 (200-202) and Til_custom (190-199) files are not read yet: define those\n"
      "# materials in Materials.  A SWIFT parameter file runs unchanged: the keys and\n"
      "# sections of SWIFT's that Bolide does not use are listed at the end of this file.\n",
      f);
  for (int i = 0; i < PARAMS_N; i++) {
    if (!spec_starts_section(i)) continue;
    const struct param_spec *s0 = &params_table[i];
    int len = (int)spec_section_len(s0);
    fprintf(f, "\n");
    if (s0->type == PARAM_SECTION) {
      fprintf(f, "# %s (optional section): see the paragraph on %s at the top of this file.\n",
              s0->name, s0->name);
      continue;
    }
    fprintf(f, "%.*s:\n", len, s0->name);
    for (int j = i; j < PARAMS_N; j++) {
      if (!spec_same_section(i, j)) continue;
      reference_comment(f, &params_table[j]);
      fprintf(f, "  %s: ", params_table[j].name + len + 1);
      if (params_table[j].type == PARAM_STRING || params_table[j].type == PARAM_WORDS)
        reference_scalar(f, reference_value(&params_table[j]));
      else
        fputs(reference_value(&params_table[j]), f);
      fputc('\n', f);
    }
  }
  fputs(
      "\n# SWIFT's keys and sections accepted without effect in Bolide (each one given\n"
      "# gets one note on stderr, a warning where ignoring it changes what is\n"
      "# simulated), and why:\n",
      f);
  for (int i = 0; i < PARAMS_NSWIFT; i++) {
    char text[1024];
    snprintf(text, sizeof text, "%s%s%s: %s", strchr(params_swift[i].name, ':') ? "" : "section ",
             params_swift[i].name, params_swift[i].level == PARAM_SWIFT_WARN ? " (warning)" : "",
             params_swift[i].reason);
    reference_wrap(f, text);
  }
}
