/* Restart files (see restart.h).  Layout of version 7:
 *
 *   header (RESTART_HEADER_BYTES = 128): magic "BOLIDE-RESTART\n\0" (16),
 *     uint32 version, uint32 byte-order mark 0x01020304, char build[48]
 *     ("VERSION git HASH"), uint64 particle count, uint64 hash of the
 *     parameters (restart_checksum of the text of restart_params_text),
 *     uint64 payload length, 24 bytes of zeros
 *   payload: int32 number of fields, per field char name[32] and int32 size;
 *     struct restart_state; uint64 length and the parameters' text; int64
 *     number of cells, their h_max and their dx_max; every field array in
 *     the order of part_fields[]; the Weibull flaws (uint64 number of
 *     thresholds, N + 1 int64 offsets, the thresholds); the reused far field
 *     of self-gravity (struct restart_gravity, since version 4): int64
 *     present, and when 1: int64 reused, int64 replays, double d_min, the
 *     3 N positions x0, int64 number of cells, int64 number of cells saved
 *     (those with particles), int64 doubles per cell, their int32 indices,
 *     their gravity data, int64 number of lists, per list int64 count and
 *     double d_min, then every list's interactions (4 int32 each)
 *   uint64 checksum of everything before it (restart_checksum).
 * Version 3 (before the far field) is refused with one line: a run
 * resumed from it would not repeat the uninterrupted run's reuse; version
 * 4 (before the integer time and the particles' time bins of individual
 * time steps) likewise, and version 5 (before the ranks of the run in the
 * state, which a run resumed on another number of ranks reads). */
#include "src/io/restart.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "src/error.h"
#include "src/io/ragged_io.h"
#include "src/timeline.h"
#include "src/version.h"

/** The most ranks a restart file may name (a check of the state). */
#define RESTART_MAX_RANKS (1 << 24)

static const char restart_magic[16] = "BOLIDE-RESTART\n";
#define RESTART_BOM 0x01020304u
#define RESTART_BUILD_LEN 48

uint64_t restart_checksum(const void *buf, size_t len, uint64_t h) {
  const unsigned char *b = buf;
  size_t i = 0;
  for (; i + 8 <= len; i += 8) {
    uint64_t w = 0;
    for (int k = 7; k >= 0; k--) w = (w << 8) | b[i + k]; /* little-endian word */
    h = (h ^ w) * 0x100000001b3ULL;
    h ^= h >> 29;
  }
  for (; i < len; i++) h = (h ^ b[i]) * 0x100000001b3ULL;
  return h;
}

/** The build string of the header. */
static void restart_build(char out[RESTART_BUILD_LEN]) {
  memset(out, 0, RESTART_BUILD_LEN);
  snprintf(out, RESTART_BUILD_LEN, "%s git %s", PACKAGE_VERSION, BOLIDE_GIT_HASH);
}

/** The parameters as the files record them: the text of params_to_string
 *  without comment lines and without the Restarts section (its settings may
 *  change between the parts of a run).  malloc'd. */
static char *restart_params_text(const char *params) {
  const size_t n = strlen(params);
  char *out = error_malloc(n + 1, "restart parameters");
  size_t m = 0;
  int skip = 0;
  for (const char *s = params; *s;) {
    const char *e = strchr(s, '\n');
    const size_t l = e ? (size_t)(e - s) + 1 : strlen(s);
    if (s[0] != ' ' && s[0] != '#') skip = !strncmp(s, "Restarts:", 9);
    if (!skip && s[0] != '#') {
      memcpy(out + m, s, l);
      m += l;
    }
    s += l;
  }
  out[m] = '\0';
  return out;
}

/* ------------------------------------------------------------------------ */
/* writing                                                                   */

/** A buffered writer that checksums what it writes. */
struct restart_out {
  FILE *f;
  const char *path;
  unsigned char buf[1 << 20]; /* a multiple of 8: the checksum's chunks */
  size_t n;
  uint64_t h;
};

static void restart_flush(struct restart_out *o) {
  o->h = restart_checksum(o->buf, o->n, o->h);
  if (o->n && fwrite(o->buf, 1, o->n, o->f) != o->n) {
    const int err = errno;
    fclose(o->f);
    error_exit("%s: cannot write the restart file: %s", o->path, strerror(err ? err : EIO));
  }
  o->n = 0;
}

static void restart_put(struct restart_out *o, const void *data, size_t bytes) {
  const unsigned char *d = data;
  while (bytes) {
    size_t k = sizeof o->buf - o->n;
    if (k > bytes) k = bytes;
    memcpy(o->buf + o->n, d, k);
    o->n += k;
    d += k;
    bytes -= k;
    if (o->n == sizeof o->buf) restart_flush(o);
  }
}

/** fsync the folder, so that a rename survives a crash of the machine. */
static void restart_sync_dir(const char *dir) {
  const int fd = open(dir, O_RDONLY);
  if (fd >= 0) {
    (void)fsync(fd);
    close(fd);
  }
}

/** Bytes of the far-field section (g NULL or not present: the flag alone). */
static uint64_t restart_gravity_bytes(const struct restart_gravity *g, size_t count) {
  if (!g || !g->present) return 8;
  uint64_t items = 0;
  for (int64_t k = 0; k < g->nr_lists; k++) items += (uint64_t)g->list_count[k];
  return 8 + 24 + 24 * (uint64_t)count + 24 + 4 * (uint64_t)g->nr_saved +
         8 * (uint64_t)(g->nr_saved * g->cell_doubles) + 8 + 16 * (uint64_t)g->nr_lists +
         16 * items;
}

void restart_write(const char *stem, const struct restart_state *st, const struct parts *p,
                   const double *flaw_eps, const struct restart_cells *cells, const char *params,
                   const struct restart_gravity *grav) {
  char path[2048], tmp[2100], prev[2100];
  snprintf(path, sizeof path, "%s.bin", stem);
  snprintf(tmp, sizeof tmp, "%s.tmp", path);
  snprintf(prev, sizeof prev, "%s.prev.bin", stem);
  char *ptext = restart_params_text(params);
  const uint64_t plen = strlen(ptext);
  /* flaws: the particles' slices of the engine's flat array, gathered in the
   * particle order of the file (bit-exact copies) */
  int64_t *off = error_malloc((p->count + 1) * sizeof *off, "restart: flaw offsets");
  off[0] = 0;
  for (size_t i = 0; i < p->count; i++)
    off[i + 1] = off[i] + (flaw_eps && p->n_flaws ? p->n_flaws[i] : 0);
  const uint64_t nflaws = (uint64_t)off[p->count];
  size_t per_part = 0;
  for (int k = 0; k < part_nr_fields; k++) per_part += part_fields[k].size;
  const uint64_t payload = 4 + (uint64_t)part_nr_fields * 36 + sizeof *st + 8 + plen + 8 +
                           16 * (uint64_t)cells->n + per_part * p->count + 8 + 8 * (p->count + 1) +
                           8 * nflaws + restart_gravity_bytes(grav, p->count);

  error_register_tmpfile(tmp);
  struct restart_out *o = error_malloc(sizeof *o, "restart buffer");
  o->f = fopen(tmp, "wb");
  if (!o->f) error_exit("%s: cannot create the restart file: %s", tmp, strerror(errno));
  o->path = tmp;
  o->n = 0;
  o->h = RESTART_HASH_INIT;
  /* header */
  unsigned char hdr[RESTART_HEADER_BYTES];
  memset(hdr, 0, sizeof hdr);
  memcpy(hdr, restart_magic, 16);
  const uint32_t version = RESTART_VERSION, bom = RESTART_BOM;
  memcpy(hdr + 16, &version, 4);
  memcpy(hdr + 20, &bom, 4);
  restart_build((char *)hdr + 24);
  const uint64_t count = p->count, phash = restart_checksum(ptext, plen, RESTART_HASH_INIT);
  memcpy(hdr + 72, &count, 8);
  memcpy(hdr + 80, &phash, 8);
  memcpy(hdr + 88, &payload, 8);
  restart_put(o, hdr, sizeof hdr);
  /* payload */
  const int32_t nf = part_nr_fields;
  restart_put(o, &nf, sizeof nf);
  for (int k = 0; k < part_nr_fields; k++) {
    char name[32] = {0};
    snprintf(name, sizeof name, "%s", part_fields[k].name);
    const int32_t size = (int32_t)part_fields[k].size;
    restart_put(o, name, sizeof name);
    restart_put(o, &size, sizeof size);
  }
  restart_put(o, st, sizeof *st);
  restart_put(o, &plen, 8);
  restart_put(o, ptext, plen);
  restart_put(o, &cells->n, 8);
  restart_put(o, cells->h_max, 8 * (size_t)cells->n);
  restart_put(o, cells->dx_max, 8 * (size_t)cells->n);
  for (int k = 0; k < part_nr_fields; k++) {
    const void *a = part_field_array(p, &part_fields[k]);
    if (a) {
      restart_put(o, a, part_fields[k].size * p->count);
    } else {
      /* a field the run does not hold (parts_drop): zeros, the file's
       * layout unchanged (the resumed run drops it again) */
      static const unsigned char zeros[4096];
      for (size_t left = part_fields[k].size * p->count; left;) {
        const size_t b = left < sizeof zeros ? left : sizeof zeros;
        restart_put(o, zeros, b);
        left -= b;
      }
    }
  }
  restart_put(o, &nflaws, 8);
  restart_put(o, off, 8 * (p->count + 1));
  for (size_t i = 0; i < p->count; i++)
    if (off[i + 1] > off[i])
      restart_put(o, flaw_eps + p->flaw_first[i], 8 * (size_t)(off[i + 1] - off[i]));
  const int64_t present = grav && grav->present ? 1 : 0;
  restart_put(o, &present, 8);
  if (present) {
    restart_put(o, &grav->reused, 8);
    restart_put(o, &grav->replays, 8);
    restart_put(o, &grav->d_min, 8);
    restart_put(o, grav->x0, 24 * p->count);
    restart_put(o, &grav->nr_cells, 8);
    restart_put(o, &grav->nr_saved, 8);
    restart_put(o, &grav->cell_doubles, 8);
    restart_put(o, grav->cell_index, 4 * (size_t)grav->nr_saved);
    restart_put(o, grav->cells, 8 * (size_t)(grav->nr_saved * grav->cell_doubles));
    restart_put(o, &grav->nr_lists, 8);
    int64_t items = 0;
    for (int64_t k = 0; k < grav->nr_lists; k++) {
      restart_put(o, &grav->list_count[k], 8);
      restart_put(o, &grav->list_d_min[k], 8);
      items += grav->list_count[k];
    }
    restart_put(o, grav->items, 16 * (size_t)items);
  }
  free(off);
  free(ptext);
  restart_flush(o);
  const uint64_t sum = o->h;
  if (fwrite(&sum, 8, 1, o->f) != 1 || fflush(o->f) || fsync(fileno(o->f))) {
    const int err = errno;
    fclose(o->f);
    error_exit("%s: cannot write the restart file: %s", tmp, strerror(err ? err : EIO));
  }
  if (fclose(o->f)) error_exit("%s: cannot close the restart file: %s", tmp, strerror(errno));
  free(o);
  /* rotation: restart.prev.bin becomes a second name of the current file,
   * then the new one replaces restart.bin in one rename: restart.bin exists
   * at every instant, restart.prev.bin at every instant but between the
   * unlink and the link */
  if (access(path, F_OK) == 0) {
    if (unlink(prev) && errno != ENOENT) error_exit("%s: cannot remove: %s", prev, strerror(errno));
    if (link(path, prev) && rename(path, prev)) /* no hard links: rename */
      error_exit("%s: cannot rename to %s: %s", path, prev, strerror(errno));
  }
  if (rename(tmp, path)) error_exit("%s: cannot rename to %s: %s", tmp, path, strerror(errno));
  error_unregister_tmpfile(tmp);
  char dir[2048]; /* the folder of the stem */
  snprintf(dir, sizeof dir, "%s", stem);
  char *slash = strrchr(dir, '/');
  if (slash)
    *slash = '\0';
  else
    snprintf(dir, sizeof dir, ".");
  restart_sync_dir(dir);
}

/* ------------------------------------------------------------------------ */
/* reading                                                                   */

/** A cursor over the buffer: every read checks the bounds. */
struct restart_in {
  const unsigned char *b;
  size_t len, pos;
  char *err;
  size_t errlen;
  const char *name;
};

static int restart_fail(struct restart_in *in, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
static int restart_fail(struct restart_in *in, const char *fmt, ...) {
  char msg[512];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  snprintf(in->err, in->errlen, "%s: %s", in->name, msg);
  return -1;
}

static int restart_get(struct restart_in *in, void *out, size_t bytes, const char *what) {
  if (bytes > in->len - in->pos)
    return restart_fail(in, "truncated restart file (%s: %zu bytes needed at offset %zu, %zu left)",
                        what, bytes, in->pos, in->len - in->pos);
  memcpy(out, in->b + in->pos, bytes);
  in->pos += bytes;
  return 0;
}

/** The first parameter line that differs between a (the file's) and b. */
static void restart_params_diff(const char *a, const char *b, char *msg, size_t len) {
  char sec[128] = "";
  for (;;) {
    const char *ea = strchr(a, '\n'), *eb = strchr(b, '\n');
    const size_t la = ea ? (size_t)(ea - a) : strlen(a), lb = eb ? (size_t)(eb - b) : strlen(b);
    if (la != lb || memcmp(a, b, la)) {
      if (!la)
        snprintf(msg, len, "this run has the parameter line '%.*s' that the file lacks",
                 (int)(lb > 120 ? 120 : lb), b);
      else if (!lb)
        snprintf(msg, len, "the file has the parameter line '%.*s' that this run lacks",
                 (int)(la > 120 ? 120 : la), a);
      else
        snprintf(msg, len,
                 "written with other parameters: %s'%.*s' in the file, '%.*s' in this run", sec,
                 (int)(la > 120 ? 120 : la), a, (int)(lb > 120 ? 120 : lb), b);
      return;
    }
    if (la && a[0] != ' ') snprintf(sec, sizeof sec, "section %.*s ", (int)(la > 60 ? 60 : la), a);
    if (!ea || !eb) break;
    a = ea + 1;
    b = eb + 1;
  }
  snprintf(msg, len, "written with other parameters");
}

#define FAIL(...)                   \
  do {                              \
    restart_fail(&in, __VA_ARGS__); \
    goto fail;                      \
  } while (0)
#define GET(ptr, bytes, what)                                \
  do {                                                       \
    if (restart_get(&in, (ptr), (bytes), (what))) goto fail; \
  } while (0)

static int restart_finite(const double *x, size_t n) {
  for (size_t i = 0; i < n; i++)
    if (!isfinite(x[i])) return 0;
  return 1;
}

static int restart_cmp_i64(const void *a, const void *b) {
  const int64_t x = *(const int64_t *)a, y = *(const int64_t *)b;
  return (x > y) - (x < y);
}

int restart_read_buffer(const void *buf, size_t len, const char *name,
                        const struct restart_expect *ex, struct restart_data *out, char *err,
                        size_t errlen) {
  struct restart_in in = {buf, len, 0, err, errlen, name};
  memset(out, 0, sizeof *out);
  char *ptext = NULL, *mine = NULL;
  int64_t *sorted = NULL;
  int64_t *fl_offset = NULL;
  double *fl_eps = NULL;
  unsigned char hdr[RESTART_HEADER_BYTES];
  if (len < 16 || memcmp(buf, restart_magic, 16)) FAIL("not a Bolide restart file (no magic line)");
  if (len < RESTART_HEADER_BYTES + 8) FAIL("truncated restart file (%zu bytes)", len);
  GET(hdr, sizeof hdr, "header");
  uint32_t version, bom;
  memcpy(&version, hdr + 16, 4);
  memcpy(&bom, hdr + 20, 4);
  if (bom != RESTART_BOM) FAIL("written on a machine of the other byte order");
  if (version != RESTART_VERSION)
    FAIL("restart format version %u, this build reads version %d%s", (unsigned)version,
         RESTART_VERSION,
         version < RESTART_VERSION
             ? " (an older Bolide's file: resume it with that build, or start the run again)"
             : "");
  char build[RESTART_BUILD_LEN], mybuild[RESTART_BUILD_LEN];
  memcpy(build, hdr + 24, RESTART_BUILD_LEN);
  if (build[RESTART_BUILD_LEN - 1] != '\0') FAIL("corrupt header (build string not terminated)");
  for (int k = 88 + 8; k < RESTART_HEADER_BYTES; k++)
    if (hdr[k]) FAIL("corrupt header (byte %d is not zero)", k);
  uint64_t count, phash, payload;
  memcpy(&count, hdr + 72, 8);
  memcpy(&phash, hdr + 80, 8);
  memcpy(&payload, hdr + 88, 8);
  if (payload != len - RESTART_HEADER_BYTES - 8)
    FAIL("truncated or extended restart file (%zu bytes, the header says %llu)", len,
         (unsigned long long)payload + RESTART_HEADER_BYTES + 8);
  uint64_t sum;
  memcpy(&sum, (const unsigned char *)buf + len - 8, 8);
  if (restart_checksum(buf, len - 8, RESTART_HASH_INIT) != sum)
    FAIL("checksum mismatch: the file is corrupt");
  in.len = len - 8; /* the payload ends at the checksum */
  restart_build(mybuild);
  if (strcmp(build, mybuild))
    error_warning("%s: written by Bolide %s, this is %s (same particle fields: resuming)", name,
                  build, mybuild);

  /* the particle-field table */
  int32_t nf = 0;
  GET(&nf, 4, "field count");
  if (nf != part_nr_fields)
    FAIL("written by a build with %d particle fields, this one has %d", (int)nf, part_nr_fields);
  for (int k = 0; k < nf; k++) {
    char fname[32];
    int32_t size = 0;
    GET(fname, 32, "field name");
    GET(&size, 4, "field size");
    fname[31] = '\0';
    if (strcmp(fname, part_fields[k].name) || size < 0 || (size_t)size != part_fields[k].size)
      FAIL("particle field %d is '%s' (%d bytes) in the file, '%s' in this build", k, fname,
           (int)size, part_fields[k].name);
  }

  /* the state */
  struct restart_state *st = &out->st;
  GET(st, sizeof *st, "state");
  if (!isfinite(st->time)) FAIL("time is %g", st->time);
  if (ex && (st->time < ex->time_begin || st->time > ex->time_end))
    FAIL("time %g outside [time_begin %g, time_end %g]", st->time, ex->time_begin, ex->time_end);
  if (!isfinite(st->dt) || st->dt < 0.0) FAIL("time step %g (must be finite, >= 0)", st->dt);
  if (!isfinite(st->dt_next) || !(st->dt_next > 0.0))
    FAIL("next time step %g (must be finite, > 0)", st->dt_next);
  if (st->step < 0 || st->step > ((int64_t)1 << 53)) FAIL("step %lld", (long long)st->step);
  if (st->updates < 0) FAIL("particle updates %lld (must be >= 0)", (long long)st->updates);
  if (st->nr_removed < 0 || st->nr_removed > ((int64_t)1 << 53))
    FAIL("removed particles %lld", (long long)st->nr_removed);
  const int64_t max_out = ex ? ex->nr_out : 100000000;
  if (st->next_out < 0 || st->next_out > max_out)
    FAIL("output index %lld (this run has %lld output times)", (long long)st->next_out,
         (long long)max_out);
  if (st->snap_index < 0 || st->snap_index > max_out + 1)
    FAIL("snapshot index %lld (this run writes at most %lld)", (long long)st->snap_index,
         (long long)max_out + 1);
  if (!isfinite(st->next_stats)) FAIL("next statistics time %g", st->next_stats);
  for (int k = 0; k < 3; k++)
    if (!isfinite(st->box[k]) || !(st->box[k] > 0.0))
      FAIL("box size %g (must be finite, > 0)", st->box[k]);
  if (st->periodic != 0 && st->periodic != 1)
    FAIL("periodic flag %lld (must be 0 or 1)", (long long)st->periodic);
  if (!restart_finite(&st->removed.m, sizeof st->removed / sizeof(double)) ||
      !restart_finite(&st->start.E_tot, sizeof st->start / sizeof(double)))
    FAIL("non-finite energy budget");
  if (st->start.set != 0.0 && st->start.set != 1.0)
    FAIL("budget flag %g (must be 0 or 1)", st->start.set);
  if (!isfinite(st->rebuild_h_max) || !(st->rebuild_h_max > 0.0))
    FAIL("smoothing length of the last rebuild %g (must be finite, > 0)", st->rebuild_h_max);
  if (st->need_rebuild != 0 && st->need_rebuild != 1)
    FAIL("rebuild flag %lld", (long long)st->need_rebuild);
  if (st->stats_offset < 0) FAIL("statistics file offset %lld", (long long)st->stats_offset);
  if (st->ti_current < 0 || st->ti_current > ((int64_t)1 << TIMELINE_NR_BINS))
    FAIL("integer time %lld (must be in [0, 2^%d])", (long long)st->ti_current, TIMELINE_NR_BINS);
  if (st->nr_ranks < 1 || st->nr_ranks > RESTART_MAX_RANKS || st->rank < 0 ||
      st->rank >= st->nr_ranks)
    FAIL("written by rank %lld of %lld ranks", (long long)st->rank, (long long)st->nr_ranks);

  /* the parameters */
  uint64_t plen = 0;
  GET(&plen, 8, "parameter length");
  if (plen > in.len - in.pos)
    FAIL("truncated restart file (parameters of %llu bytes)", (unsigned long long)plen);
  ptext = error_malloc(plen + 1, "restart parameters");
  GET(ptext, plen, "parameters");
  ptext[plen] = '\0';
  if (strlen(ptext) != plen) FAIL("corrupt parameters (NUL byte)");
  if (restart_checksum(ptext, plen, RESTART_HASH_INIT) != phash)
    FAIL("corrupt header (parameter hash)");
  if (ex && ex->params) {
    mine = restart_params_text(ex->params);
    if (strcmp(mine, ptext)) {
      char msg[400];
      restart_params_diff(ptext, mine, msg, sizeof msg);
      FAIL("%s", msg);
    }
  }

  /* the cells */
  int64_t nc = 0;
  GET(&nc, 8, "cell count");
  if (nc < 1 || (uint64_t)nc > (in.len - in.pos) / 16) FAIL("cell count %lld", (long long)nc);
  out->cells.n = nc;
  out->cells.h_max = error_malloc(8 * (size_t)nc, "restart cells");
  out->cells.dx_max = error_malloc(8 * (size_t)nc, "restart cells");
  GET(out->cells.h_max, 8 * (size_t)nc, "cells");
  GET(out->cells.dx_max, 8 * (size_t)nc, "cells");
  for (int64_t c = 0; c < nc; c++)
    if (!isfinite(out->cells.h_max[c]) || out->cells.h_max[c] < 0.0 ||
        !isfinite(out->cells.dx_max[c]) || out->cells.dx_max[c] < 0.0)
      FAIL("cell %lld: h_max %g, dx_max %g (must be finite, >= 0)", (long long)c,
           out->cells.h_max[c], out->cells.dx_max[c]);

  /* the particles */
  size_t per_part = 0;
  for (int k = 0; k < part_nr_fields; k++) per_part += part_fields[k].size;
  if (count == 0) FAIL("no particles");
  if (count > (in.len - in.pos) / (per_part + 8))
    FAIL("particle count %llu does not fit in the file", (unsigned long long)count);
  const size_t n = (size_t)count;
  parts_alloc(&out->p, n);
  struct parts *p = &out->p;
  for (int k = 0; k < part_nr_fields; k++) {
    const struct part_field *f = &part_fields[k];
    void *a = part_field_array(p, f);
    GET(a, f->size * n, f->name);
    if (f->type == PART_DOUBLE && !restart_finite(a, n)) {
      size_t i = 0;
      while (isfinite(((const double *)a)[i])) i++;
      FAIL("particle %zu: %s is %g", i, f->name, ((const double *)a)[i]);
    }
  }
  sorted = error_malloc(n * sizeof *sorted, "restart ids");
  for (size_t i = 0; i < n; i++) {
    if (!(p->h[i] > 0.0)) FAIL("particle %zu: smoothing length %g (must be > 0)", i, p->h[i]);
    if (!(p->m[i] > 0.0)) FAIL("particle %zu: mass %g (must be > 0)", i, p->m[i]);
    if (p->rho[i] < 0.0) FAIL("particle %zu: density %g (must be >= 0)", i, p->rho[i]);
    if (p->dmg[i] < 0.0 || p->dmg[i] > 1.0 || p->dmg_shear[i] < 0.0 || p->dmg_shear[i] > 1.0)
      FAIL("particle %zu: damage %g, shear damage %g (must be in [0, 1])", i, p->dmg[i],
           p->dmg_shear[i]);
    if (p->n_flaws[i] < 0 || p->n_act[i] < 0)
      FAIL("particle %zu: %d flaws, %d active", i, (int)p->n_flaws[i], (int)p->n_act[i]);
    if (p->time_bin[i] < 0 || p->time_bin[i] > TIMELINE_NR_BINS)
      FAIL("particle %zu: time bin %d (must be in [0, %d])", i, (int)p->time_bin[i],
           TIMELINE_NR_BINS);
    if (p->id[i] < 0) FAIL("particle %zu: id %lld (must be >= 0)", i, (long long)p->id[i]);
    const double x0[3] = {p->x0[i], p->y0[i], p->z0[i]};
    for (int k = 0; k < 3; k++)
      if (x0[k] < 0.0 || x0[k] >= st->box[k])
        FAIL("particle %zu: position at the last rebuild %g outside the box [0, %g)", i, x0[k],
             st->box[k]);
    if (ex && ex->mat_ids) {
      int found = -1;
      for (int k = 0; k < ex->nr_mats && found < 0; k++)
        if (ex->mat_ids[k] == p->mat[i]) found = k;
      if (found < 0)
        FAIL("particle %zu: material id %d is not a material of this run", i, (int)p->mat[i]);
      if (ex->u_floor && ex->u_floor[found] && p->u[i] < 0.0)
        FAIL("particle %zu: internal energy %g (material %d needs u >= 0)", i, p->u[i],
             (int)p->mat[i]);
    }
    sorted[i] = p->id[i];
  }
  qsort(sorted, n, sizeof *sorted, restart_cmp_i64);
  for (size_t i = 1; i < n; i++)
    if (sorted[i] == sorted[i - 1]) FAIL("particle id %lld appears twice", (long long)sorted[i]);

  /* the flaws */
  uint64_t nflaws = 0;
  GET(&nflaws, 8, "flaw count");
  if (nflaws > (in.len - in.pos) / 8)
    FAIL("flaw count %llu does not fit in the file", (unsigned long long)nflaws);
  fl_offset = error_malloc((n + 1) * sizeof *fl_offset, "restart: flaw offsets");
  fl_eps = error_malloc((nflaws ? nflaws : 1) * sizeof *fl_eps, "restart: flaw thresholds");
  GET(fl_offset, 8 * (n + 1), "flaw offsets");
  GET(fl_eps, 8 * (size_t)nflaws, "flaw thresholds");
  if (fl_offset[n] != (int64_t)nflaws)
    FAIL("corrupt restart file (flaw offsets end at %lld, %llu flaws)", (long long)fl_offset[n],
         (unsigned long long)nflaws);
  char msg[256];
  if (ragged_io_check_offsets("flaw offsets", n, fl_offset, (size_t)nflaws, msg, sizeof msg) ||
      (ex && ex->flaws_check && ex->flaws_check(n, fl_offset, fl_eps, msg, sizeof msg)))
    FAIL("corrupt restart file: %s", msg);
  for (size_t i = 0; i < n; i++) {
    if (fl_offset[i + 1] - fl_offset[i] != p->n_flaws[i])
      FAIL("corrupt restart file (particle %zu has %d flaws, its offsets say %lld)", i,
           (int)p->n_flaws[i], (long long)(fl_offset[i + 1] - fl_offset[i]));
    if (p->n_act[i] > p->n_flaws[i])
      FAIL("particle %zu: %d of %d flaws active", i, (int)p->n_act[i], (int)p->n_flaws[i]);
    p->flaw_first[i] = fl_offset[i];
  }

  /* the reused far field of self-gravity */
  struct restart_gravity *g = &out->grav;
  GET(&g->present, 8, "far-field flag");
  if (g->present != 0 && g->present != 1)
    FAIL("far-field flag %lld (must be 0 or 1)", (long long)g->present);
  if (g->present) {
    GET(&g->reused, 8, "far field");
    GET(&g->replays, 8, "far field");
    GET(&g->d_min, 8, "far field");
    if (g->reused < 0 || g->reused > st->step)
      FAIL("far field reused %lld times (step %lld)", (long long)g->reused, (long long)st->step);
    if (g->replays < 0 || g->replays > st->step)
      FAIL("far field reused in %lld steps (step %lld)", (long long)g->replays,
           (long long)st->step);
    if (!isfinite(g->d_min) || !(g->d_min > 0.0))
      FAIL("far-field distance %g (must be finite, > 0)", g->d_min);
    if (n > (in.len - in.pos) / 24) FAIL("truncated restart file (far-field positions)");
    g->x0 = error_malloc(24 * n, "restart: far-field positions");
    GET(g->x0, 24 * n, "far-field positions");
    if (!restart_finite(g->x0, 3 * n)) FAIL("non-finite far-field position");
    GET(&g->nr_cells, 8, "far-field cells");
    GET(&g->nr_saved, 8, "far-field cells");
    GET(&g->cell_doubles, 8, "far-field cells");
    if (g->nr_cells != out->cells.n)
      FAIL("far field of %lld cells, the file has %lld", (long long)g->nr_cells,
           (long long)out->cells.n);
    if (g->nr_saved < 1 || g->nr_saved > g->nr_cells)
      FAIL("far field of %lld cells saved of %lld", (long long)g->nr_saved, (long long)g->nr_cells);
    if (g->cell_doubles < 1) FAIL("far field of %lld doubles per cell", (long long)g->cell_doubles);
    if (ex && ex->grav_cell_doubles > 0 && g->cell_doubles != ex->grav_cell_doubles)
      FAIL("far field of %lld doubles per cell, this build has %lld (another expansion order?)",
           (long long)g->cell_doubles, (long long)ex->grav_cell_doubles);
    const size_t ncd = (size_t)g->nr_saved * (size_t)g->cell_doubles;
    if (ncd > (in.len - in.pos) / 8) FAIL("truncated restart file (far-field cells)");
    g->cell_index = error_malloc(4 * (size_t)g->nr_saved, "restart: far-field cells");
    GET(g->cell_index, 4 * (size_t)g->nr_saved, "far-field cells");
    for (int64_t c = 0; c < g->nr_saved; c++)
      if (g->cell_index[c] < 0 || g->cell_index[c] >= g->nr_cells ||
          (c > 0 && g->cell_index[c] <= g->cell_index[c - 1]))
        FAIL("far field: cell %lld saved is cell %d (indices must increase, below %lld)",
             (long long)c, (int)g->cell_index[c], (long long)g->nr_cells);
    g->cells = error_malloc(8 * ncd, "restart: far-field cells");
    GET(g->cells, 8 * ncd, "far-field cells");
    if (!restart_finite(g->cells, ncd)) FAIL("non-finite multipole or local expansion");
    GET(&g->nr_lists, 8, "far-field lists");
    if (g->nr_lists < 1 || (uint64_t)g->nr_lists > (in.len - in.pos) / 16)
      FAIL("far field of %lld interaction lists", (long long)g->nr_lists);
    g->list_count = error_malloc(8 * (size_t)g->nr_lists, "restart: interaction lists");
    g->list_d_min = error_malloc(8 * (size_t)g->nr_lists, "restart: interaction lists");
    uint64_t items = 0;
    for (int64_t k = 0; k < g->nr_lists; k++) {
      GET(&g->list_count[k], 8, "interaction list");
      GET(&g->list_d_min[k], 8, "interaction list");
      if (g->list_count[k] < 0 || (uint64_t)g->list_count[k] > (in.len - in.pos) / 16 ||
          !(g->list_d_min[k] >= 0.0))
        FAIL("interaction list %lld: %lld interactions, d_min %g", (long long)k,
             (long long)g->list_count[k], g->list_d_min[k]);
      items += (uint64_t)g->list_count[k];
      if (items > (in.len - in.pos) / 16) /* (checked as it grows: no overflow) */
        FAIL("truncated restart file (%llu interactions)", (unsigned long long)items);
    }
    if (items > (in.len - in.pos) / 16)
      FAIL("truncated restart file (%llu interactions)", (unsigned long long)items);
    g->items = error_malloc(16 * (items ? items : 1), "restart: interactions");
    GET(g->items, 16 * (size_t)items, "interactions");
    for (uint64_t q = 0; q < items; q++) {
      const int32_t *it = g->items + 4 * q;
      if (it[0] < 0 || it[0] >= g->nr_cells || it[1] < -1 || it[1] >= g->nr_cells ||
          (it[2] != 0 && it[2] != 1) || (it[3] != 0 && it[3] != 1) || (it[2] == 1 && it[1] < 0))
        FAIL("interaction %llu: cells %d and %d, kind %d, symmetric %d", (unsigned long long)q,
             (int)it[0], (int)it[1], (int)it[2], (int)it[3]);
    }
  }
  if (in.pos != in.len)
    FAIL("corrupt restart file (%zu bytes after the far field)", in.len - in.pos);
  free(fl_offset);
  free(sorted);
  free(ptext);
  free(mine);
  if (nflaws) {
    out->flaw_eps = fl_eps;
  } else {
    free(fl_eps);
    out->flaw_eps = NULL;
  }
  out->nr_flaws = (int64_t)nflaws;
  return 0;
fail:
  free(fl_offset);
  free(fl_eps);
  free(sorted);
  free(ptext);
  free(mine);
  restart_data_free(out);
  return -1;
}
#undef FAIL
#undef GET

void restart_gravity_free(struct restart_gravity *g) {
  free(g->x0);
  free(g->cells);
  free(g->cell_index);
  free(g->list_count);
  free(g->list_d_min);
  free(g->items);
  memset(g, 0, sizeof *g);
}

void restart_data_free(struct restart_data *d) {
  parts_free(&d->p);
  free(d->flaw_eps);
  free(d->cells.h_max);
  free(d->cells.dx_max);
  restart_gravity_free(&d->grav);
  memset(d, 0, sizeof *d);
}

/** Map and parse one file; 0, or -1 with one line in err. */
static int restart_read_file(const char *path, const struct restart_expect *ex,
                             struct restart_data *out, char *err, size_t errlen) {
  const int fd = open(path, O_RDONLY);
  if (fd < 0) {
    snprintf(err, errlen, "%s: cannot open the restart file: %s", path, strerror(errno));
    return -1;
  }
  struct stat sb;
  if (fstat(fd, &sb) || !S_ISREG(sb.st_mode)) {
    snprintf(err, errlen, "%s: not a regular file", path);
    close(fd);
    return -1;
  }
  const size_t len = (size_t)sb.st_size;
  if (len == 0) {
    snprintf(err, errlen, "%s: empty restart file", path);
    close(fd);
    return -1;
  }
  void *map = mmap(NULL, len, PROT_READ, MAP_PRIVATE, fd, 0);
  close(fd);
  if (map == MAP_FAILED) {
    snprintf(err, errlen, "%s: cannot read the restart file: %s", path, strerror(errno));
    return -1;
  }
  const int r = restart_read_buffer(map, len, path, ex, out, err, errlen);
  munmap(map, len);
  return r;
}

void restart_read(const char *stem, const struct restart_expect *ex, struct restart_data *out,
                  char *used, size_t usedlen) {
  char path[2048], prev[2048], err[1024], err2[1024];
  snprintf(path, sizeof path, "%s.bin", stem);
  snprintf(prev, sizeof prev, "%s.prev.bin", stem);
  if (restart_read_file(path, ex, out, err, sizeof err) == 0) {
    snprintf(used, usedlen, "%s", path);
    return;
  }
  if (restart_read_file(prev, ex, out, err2, sizeof err2) == 0) {
    error_warning("%s; resuming from the previous restart file %s", err, prev);
    if (access(path, F_OK) == 0) {
      /* kept for inspection; the next file written takes its name */
      char bad[2100];
      snprintf(bad, sizeof bad, "%s.bad", path);
      if (rename(path, bad) == 0) error_warning("%s: renamed to %s", path, bad);
    }
    snprintf(used, usedlen, "%s", prev);
    return;
  }
  if (access(path, F_OK) && access(prev, F_OK))
    error_exit("%s: no restart file to resume from (neither %s nor %s)", path, path, prev);
  if (access(prev, F_OK)) error_exit("%s", err);
  error_exit("%s (the previous file: %s)", err, err2);
}

void restart_remove_stale(const char *stem) {
  char tmp[2100];
  snprintf(tmp, sizeof tmp, "%s.bin.tmp", stem);
  if (unlink(tmp) == 0)
    error_log(0, "removed %s, left by a run that stopped while writing it", tmp);
}

/* ------------------------------------------- resuming on another number of ranks */

/** The state of the restart file at path without reading its particles
 *  (header, field table, state: no checksum); 0, or -1 if it cannot be
 *  read or is not of this format. */
static int restart_peek(const char *path, struct restart_state *st) {
  FILE *f = fopen(path, "rb");
  if (!f) return -1;
  unsigned char hdr[RESTART_HEADER_BYTES];
  uint32_t version = 0;
  int32_t nf = 0;
  int ok = fread(hdr, 1, sizeof hdr, f) == sizeof hdr && !memcmp(hdr, restart_magic, 16);
  if (ok) memcpy(&version, hdr + 16, 4);
  ok = ok && version == RESTART_VERSION && fread(&nf, 4, 1, f) == 1 && nf == part_nr_fields &&
       fseek(f, 36L * nf, SEEK_CUR) == 0 && fread(st, sizeof *st, 1, f) == 1;
  fclose(f);
  return ok ? 0 : -1;
}

int restart_layout(const char *base, int *ranks) {
  char path[2100];
  struct restart_state st;
  *ranks = 0;
  const char *ext[2] = {".bin", ".prev.bin"};
  for (int k = 0; k < 2 && *ranks <= 0; k++) {
    snprintf(path, sizeof path, "%s_rank0000%s", base, ext[k]);
    if (access(path, F_OK)) continue;
    *ranks = restart_peek(path, &st) == 0 && st.nr_ranks > 1 ? (int)st.nr_ranks : -1;
  }
  int one = 0;
  for (int k = 0; k < 2; k++) {
    snprintf(path, sizeof path, "%s%s", base, ext[k]);
    one |= access(path, F_OK) == 0;
  }
  return one;
}

void restart_read_ranks(const char *base, int n, const struct restart_expect *ex,
                        struct restart_data *out, char *used, size_t usedlen) {
  memset(out, 0, sizeof *out);
  const int nfiles = n > 0 ? n : 1;
  char stem[2100], name[2200], first[2200] = "";
  size_t nflaws = 0, capf = 0;
  for (int r = 0; r < nfiles; r++) {
    if (n > 0)
      snprintf(stem, sizeof stem, "%s_rank%04d", base, r);
    else
      snprintf(stem, sizeof stem, "%s", base);
    struct restart_data d;
    restart_read(stem, ex, &d, name, sizeof name);
    if (r == 0) {
      snprintf(first, sizeof first, "%s", name);
      out->st = d.st;
      memset(&out->st.removed, 0, sizeof out->st.removed);
      out->st.nr_removed = 0;
    }
    const int64_t want = n > 0 ? n : 1;
    if (d.st.nr_ranks != want || d.st.rank != r)
      error_exit(
          "%s: written by rank %lld of a run on %lld ranks, read as rank %d of %lld: resume "
          "from the files of one run, written together",
          name, (long long)d.st.rank, (long long)d.st.nr_ranks, r, (long long)want);
    if (d.st.step != out->st.step || d.st.time != out->st.time)
      error_exit(
          "%s: of step %lld (t = %g), %s of step %lld (t = %g): resume from the files of "
          "one run, written together",
          name, (long long)d.st.step, d.st.time, first, (long long)out->st.step, out->st.time);
    double *a = (double *)&out->st.removed;
    const double *b = (const double *)&d.st.removed;
    for (size_t k = 0; k < sizeof d.st.removed / sizeof(double); k++) a[k] += b[k];
    out->st.nr_removed += d.st.nr_removed;
    /* the next step: the smallest of the ranks' (each file holds its own cells') */
    if (d.st.dt_next < out->st.dt_next) out->st.dt_next = d.st.dt_next;
    /* the particles the rank owned (its foreign copies are other ranks') */
    struct parts *p = &out->p, *q = &d.p;
    size_t keep = 0;
    for (size_t i = 0; i < q->count; i++) keep += !(q->flags[i] & PART_FOREIGN);
    parts_reserve(p, p->count + keep);
    for (size_t i = 0; i < q->count; i++) {
      if (q->flags[i] & PART_FOREIGN) continue;
      const size_t j = p->count++;
      for (int k = 0; k < part_nr_fields; k++) {
        const struct part_field *f = &part_fields[k];
        memcpy((char *)part_field_array(p, f) + j * f->size,
               (const char *)part_field_array(q, f) + i * f->size, f->size);
      }
      const size_t nf = (size_t)(q->n_flaws[i] > 0 ? q->n_flaws[i] : 0);
      if (nflaws + nf > capf) {
        capf = 2 * (nflaws + nf) + 1024;
        out->flaw_eps = error_realloc(out->flaw_eps, capf * sizeof(double), "flaw thresholds");
      }
      if (nf) memcpy(out->flaw_eps + nflaws, d.flaw_eps + q->flaw_first[i], nf * sizeof(double));
      p->flaw_first[j] = (int64_t)nflaws;
      nflaws += nf;
    }
    restart_data_free(&d);
  }
  /* one run's files: every particle once */
  const size_t np = out->p.count;
  int64_t *ids = error_malloc((np ? np : 1) * sizeof *ids, "restart ids");
  for (size_t i = 0; i < np; i++) ids[i] = out->p.id[i];
  qsort(ids, np, sizeof *ids, restart_cmp_i64);
  for (size_t i = 1; i < np; i++)
    if (ids[i] == ids[i - 1])
      error_exit(
          "%s: particle id %lld is owned by two ranks' files: resume from the files of "
          "one run, written together",
          first, (long long)ids[i]);
  free(ids);
  if (np == 0) error_exit("%s: the ranks' files hold no particle", first);
  out->nr_flaws = (int64_t)nflaws;
  if (!nflaws) {
    free(out->flaw_eps);
    out->flaw_eps = NULL;
  }
  out->st.nr_ranks = 1;
  out->st.rank = 0;
  snprintf(used, usedlen, "%s", first);
}

/** Remove path if it exists (logged); 1 if it existed. */
static int restart_unlink(const char *path) {
  if (access(path, F_OK)) return 0;
  if (unlink(path))
    error_warning("%s: cannot remove the restart file of another layout: %s", path,
                  strerror(errno));
  else
    error_log(0, "removed %s (a restart file of the run on another number of ranks)", path);
  return 1;
}

void restart_remove_layouts(const char *base, int n, int stale_prev) {
  char path[2200];
  static const char *const ext[4] = {".bin", ".prev.bin", ".halo.bin", ".halo.prev.bin"};
  if (n > 1) {
    for (int k = 0; k < 2; k++) {
      snprintf(path, sizeof path, "%s%s", base, ext[k]);
      restart_unlink(path);
    }
  } else if (stale_prev) {
    snprintf(path, sizeof path, "%s.prev.bin", base);
    restart_unlink(path);
  }
  for (int r = 0; r < RESTART_MAX_RANKS; r++) {
    int found = 0;
    for (int k = 0; k < 4; k++) {
      snprintf(path, sizeof path, "%s_rank%04d%s", base, r, ext[k]);
      if (r >= n || n == 1 || (stale_prev && (k & 1)))
        found |= restart_unlink(path);
      else
        found |= access(path, F_OK) == 0;
    }
    if (!found) break;
  }
}
