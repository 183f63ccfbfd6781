/* Particles: allocation and reordering of the structure of arrays. */
#include "src/part.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "src/error.h"

#define PART_TYPE_ID(type) \
  _Generic((type)0, double : PART_DOUBLE, int64_t : PART_INT64, int32_t : PART_INT32)

#define PART_FIELD_ENTRY(ctype, name_, h5, c, nc, m, l, t, fl, desc) \
  {.name = #name_,                                                   \
   .h5name = h5,                                                     \
   .comp = c,                                                        \
   .ncomp = nc,                                                      \
   .uM = m,                                                          \
   .uL = l,                                                          \
   .uT = t,                                                          \
   .flags = fl,                                                      \
   .type = PART_TYPE_ID(ctype),                                      \
   .size = sizeof(ctype),                                            \
   .offset = offsetof(struct parts, name_),                          \
   .description = desc},
const struct part_field part_fields[] = {BOLIDE_PART_FIELDS(PART_FIELD_ENTRY)};
#undef PART_FIELD_ENTRY
const int part_nr_fields = sizeof(part_fields) / sizeof(part_fields[0]);

void *part_field_array(const struct parts *p, const struct part_field *f) {
  return *(void *const *)((const char *)p + f->offset);
}

/* (read in blocks up to the first that is not zero: most fields are not
 * zero after the first rebuild, and reading them whole cost as much as
 * reordering them) */
#define PART_ZERO_BLOCK 512

int part_field_zero(const struct parts *p, int k, size_t lo, size_t hi) {
  const struct part_field *f = &part_fields[k];
  const void *a = part_field_array(p, f);
  if (!a) return 1; /* (absent: zero wherever it is read) */
  for (size_t b = lo; b < hi; b += PART_ZERO_BLOCK) {
    const size_t e = hi - b < PART_ZERO_BLOCK ? hi : b + PART_ZERO_BLOCK;
    if (f->size == 8) {
      const uint64_t *v = a;
      uint64_t any = 0;
      for (size_t i = b; i < e; i++) any |= v[i];
      if (any) return 0;
    } else {
      const uint32_t *v = a;
      uint32_t any = 0;
      for (size_t i = b; i < e; i++) any |= v[i];
      if (any) return 0;
    }
  }
  return 1;
}

static void **part_field_slot(struct parts *p, const struct part_field *f) {
  return (void **)((char *)p + f->offset);
}

/** Where field k's array starts in its allocation: large allocations are
 *  whole pages (mmap), so without an offset element i of every field would
 *  sit at the same address modulo 4096 and map to the same set of the L1
 *  cache; a loop over many fields (the drift and kick read and write about
 *  forty) would then evict its own lines.  Field k starts k cache lines
 *  (modulo 64) into its allocation. */
static size_t part_field_pad(int k) {
  return (size_t)(k % 64) * 64;
}

void parts_alloc(struct parts *p, size_t n) {
  parts_alloc_like(p, n, NULL);
}

void parts_alloc_like(struct parts *p, size_t n, const struct parts *like) {
  memset(p, 0, sizeof *p);
  p->count = n;
  p->capacity = n;
  if (like) memcpy(p->absent, like->absent, sizeof p->absent);
  for (int k = 0; k < part_nr_fields; k++) {
    if (p->absent[k]) continue;
    const size_t pad = part_field_pad(k);
    char *a = error_calloc(n * part_fields[k].size + pad, 1, part_fields[k].name);
    *part_field_slot(p, &part_fields[k]) = a + pad;
  }
}

void parts_reserve(struct parts *p, size_t n) {
  if (n <= p->capacity) return;
  for (int k = 0; k < part_nr_fields; k++) {
    if (p->absent[k]) continue;
    const struct part_field *f = &part_fields[k];
    void **slot = part_field_slot(p, f);
    const size_t pad = part_field_pad(k);
    char *a = error_realloc(*slot ? (char *)*slot - pad : NULL, n * f->size + pad, f->name);
    *slot = a + pad;
    memset((char *)*slot + p->capacity * f->size, 0, (n - p->capacity) * f->size);
  }
  p->capacity = n;
}

void parts_free(struct parts *p) {
  for (int k = 0; k < part_nr_fields; k++) {
    void **slot = part_field_slot(p, &part_fields[k]);
    if (*slot) free((char *)*slot - part_field_pad(k));
    *slot = NULL;
  }
  p->count = p->capacity = 0;
}

void parts_permute(struct parts *p, const size_t *perm) {
  const size_t n = p->count;
  size_t maxsize = 0;
  for (int k = 0; k < part_nr_fields; k++)
    if (part_fields[k].size > maxsize) maxsize = part_fields[k].size;
  char *tmp = error_malloc(n * maxsize, "particle reordering buffer");
  for (int k = 0; k < part_nr_fields; k++) {
    const struct part_field *f = &part_fields[k];
    char *a = *part_field_slot(p, f);
    if (!a) continue; /* (absent) */
    const size_t s = f->size;
    for (size_t i = 0; i < n; i++) memcpy(tmp + i * s, a + perm[i] * s, s);
    memcpy(a, tmp, n * s);
  }
  free(tmp);
}

void parts_copy_one(struct parts *p, size_t dst, size_t src) {
  for (int k = 0; k < part_nr_fields; k++) {
    const struct part_field *f = &part_fields[k];
    char *a = *part_field_slot(p, f);
    if (a) memcpy(a + dst * f->size, a + src * f->size, f->size);
  }
}

size_t parts_bytes_per_particle(void) {
  size_t b = 0;
  for (int k = 0; k < part_nr_fields; k++) b += part_fields[k].size;
  return b;
}

size_t parts_bytes_held(const struct parts *p) {
  size_t b = 0;
  for (int k = 0; k < part_nr_fields; k++)
    if (!p->absent[k]) b += part_fields[k].size;
  return b;
}

const char *const part_solid_fields[] = {
    "Sxx",  "Sxy",  "Sxz",  "Syy",  "Syz",   "Szz",       "Spxx",     "Spxy", "Spxz",
    "Spyy", "Spyz", "Spzz", "dSxx", "dSxy",  "dSxz",      "dSyy",     "dSyz", "dSzz",
    "Rxx",  "Rxy",  "Rxz",  "Ryy",  "Ryz",   "Rzz",       "gmxx",     "gmxy", "gmxz",
    "gmyy", "gmyz", "gmzz", "gvxx", "gvxy",  "gvxz",      "gvyx",     "gvyy", "gvyz",
    "gvzx", "gvzy", "gvzz", "wvol", "eps_p", "w_plastic", "dmg_shear"};
const int part_nr_solid_fields = (int)(sizeof part_solid_fields / sizeof(char *));
const char *const part_damage_fields[] = {"dmg",   "dcbrt",   "dmg_rate",
                                          "n_act", "n_flaws", "flaw_first"};
const int part_nr_damage_fields = (int)(sizeof part_damage_fields / sizeof(char *));

size_t parts_drop(struct parts *p, const char *const *names, int n) {
  size_t bytes = 0;
  for (int q = 0; q < n; q++) {
    int k = 0;
    while (k < part_nr_fields && strcmp(part_fields[k].name, names[q])) k++;
    if (k == part_nr_fields) error_bug("parts_drop: no particle field '%s'", names[q]);
    if (p->absent[k]) continue;
    void **slot = part_field_slot(p, &part_fields[k]);
    if (*slot) free((char *)*slot - part_field_pad(k));
    *slot = NULL;
    p->absent[k] = 1;
    bytes += part_fields[k].size;
  }
  return bytes;
}
