/* Restart files (see restart.h).  Layout: a magic line, the number of
 * fields, each field's name and element size, the state struct, the particle
 * count, every field array in the order of part_fields[], then the Weibull
 * flaws as DESIGN.md lays them out: the number of thresholds, N + 1 offsets
 * (particle i owns thresholds off[i] .. off[i+1]-1, in the particle order of
 * the file) and the flat threshold array. */
#include "restart.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "damage/flaws.h"
#include "error.h"

#define RESTART_MAGIC "BOLIDE-RESTART-2\n"

/** fwrite that stops with one line on failure. */
static void restart_put(FILE *f, const void *buf, size_t size, size_t n, const char *path) {
  if (n && fwrite(buf, size, n, f) != n) {
    const int err = errno;
    fclose(f);
    error_exit("%s: cannot write the restart file: %s", path, strerror(err ? err : EIO));
  }
}

/** fread that stops with one line on a short read. */
static void restart_get(FILE *f, void *buf, size_t size, size_t n, const char *path) {
  if (n && fread(buf, size, n, f) != n) {
    fclose(f);
    error_exit("%s: truncated or unreadable restart file", path);
  }
}

void restart_write(const char *dir, const struct restart_state *st, const struct parts *p,
                   const double *flaw_eps) {
  char path[2048], tmp[2100], prev[2100];
  snprintf(path, sizeof path, "%s/restart.bin", dir);
  snprintf(tmp, sizeof tmp, "%s.tmp", path);
  snprintf(prev, sizeof prev, "%s/restart.prev.bin", dir);
  error_register_tmpfile(tmp);
  FILE *f = fopen(tmp, "wb");
  if (!f) error_exit("%s: cannot create the restart file: %s", tmp, strerror(errno));
  restart_put(f, RESTART_MAGIC, 1, strlen(RESTART_MAGIC), tmp);
  const int32_t nf = part_nr_fields;
  restart_put(f, &nf, sizeof nf, 1, tmp);
  for (int k = 0; k < part_nr_fields; k++) {
    char name[32] = {0};
    snprintf(name, sizeof name, "%s", part_fields[k].name);
    const int32_t size = (int32_t)part_fields[k].size;
    restart_put(f, name, 1, sizeof name, tmp);
    restart_put(f, &size, sizeof size, 1, tmp);
  }
  restart_put(f, st, sizeof *st, 1, tmp);
  const uint64_t n = p->count;
  restart_put(f, &n, sizeof n, 1, tmp);
  for (int k = 0; k < part_nr_fields; k++)
    restart_put(f, part_field_array(p, &part_fields[k]), part_fields[k].size, p->count, tmp);
  /* flaws: the particles' slices of the engine's flat array, gathered in the
   * particle order of the file (bit-exact copies) */
  int64_t *off = error_malloc((p->count + 1) * sizeof *off, "restart: flaw offsets");
  off[0] = 0;
  for (size_t i = 0; i < p->count; i++) off[i + 1] = off[i] + (flaw_eps ? p->n_flaws[i] : 0);
  const uint64_t nflaws = (uint64_t)off[p->count];
  restart_put(f, &nflaws, sizeof nflaws, 1, tmp);
  restart_put(f, off, sizeof *off, p->count + 1, tmp);
  for (size_t i = 0; i < p->count; i++)
    if (off[i + 1] > off[i])
      restart_put(f, flaw_eps + p->flaw_first[i], sizeof(double), (size_t)(off[i + 1] - off[i]), tmp);
  free(off);
  if (fflush(f) || fsync(fileno(f))) {
    const int err = errno;
    fclose(f);
    error_exit("%s: cannot write the restart file: %s", tmp, strerror(err));
  }
  if (fclose(f)) error_exit("%s: cannot close the restart file: %s", tmp, strerror(errno));
  /* keep the previous file until the new one is complete */
  if (access(path, F_OK) == 0 && rename(path, prev))
    error_exit("%s: cannot rename to %s: %s", path, prev, strerror(errno));
  if (rename(tmp, path)) error_exit("%s: cannot rename to %s: %s", tmp, path, strerror(errno));
  error_unregister_tmpfile(tmp);
}

/** Bytes from the current position to the end of the file. */
static uint64_t restart_bytes_left(FILE *f) {
  const long pos = ftell(f);
  struct stat sb;
  if (pos < 0 || fstat(fileno(f), &sb) || sb.st_size < pos) return 0;
  return (uint64_t)(sb.st_size - pos);
}

void restart_read(const char *dir, struct restart_state *st, struct parts *p, double **flaw_eps,
                  int64_t *nr_flaws) {
  char path[2048];
  snprintf(path, sizeof path, "%s/restart.bin", dir);
  FILE *f = fopen(path, "rb");
  if (!f) error_exit("%s: cannot open the restart file: %s", path, strerror(errno));
  char magic[sizeof RESTART_MAGIC] = {0};
  restart_get(f, magic, 1, strlen(RESTART_MAGIC), path);
  if (memcmp(magic, RESTART_MAGIC, strlen(RESTART_MAGIC))) {
    fclose(f);
    error_exit("%s: not a Bolide restart file", path);
  }
  int32_t nf;
  restart_get(f, &nf, sizeof nf, 1, path);
  if (nf != part_nr_fields) {
    fclose(f);
    error_exit("%s: written by a build with %d particle fields, this one has %d", path, nf, part_nr_fields);
  }
  for (int k = 0; k < nf; k++) {
    char name[32];
    int32_t size;
    restart_get(f, name, 1, sizeof name, path);
    restart_get(f, &size, sizeof size, 1, path);
    name[31] = '\0';
    if (strcmp(name, part_fields[k].name) || (size_t)size != part_fields[k].size) {
      fclose(f);
      error_exit("%s: particle field %d is '%s' (%d bytes) in the file, '%s' in this build", path, k, name,
                 (int)size, part_fields[k].name);
    }
  }
  restart_get(f, st, sizeof *st, 1, path);
  uint64_t n;
  restart_get(f, &n, sizeof n, 1, path);
  /* counts are checked against the bytes left before anything is allocated */
  const uint64_t left = restart_bytes_left(f);
  size_t per_part = sizeof(int64_t); /* the particle's flaw offset */
  for (int k = 0; k < part_nr_fields; k++) per_part += part_fields[k].size;
  if (n > left / per_part) {
    fclose(f);
    error_exit("%s: corrupt restart file (%llu particles in %llu bytes)", path,
               (unsigned long long)n, (unsigned long long)left);
  }
  parts_alloc(p, (size_t)n);
  for (int k = 0; k < part_nr_fields; k++)
    restart_get(f, part_field_array(p, &part_fields[k]), part_fields[k].size, p->count, path);
  uint64_t nflaws;
  restart_get(f, &nflaws, sizeof nflaws, 1, path);
  if (nflaws > restart_bytes_left(f) / sizeof(double)) {
    fclose(f);
    error_exit("%s: corrupt restart file (%llu flaws)", path, (unsigned long long)nflaws);
  }
  struct flaws fl = {p->count, NULL, NULL};
  fl.offset = error_malloc((p->count + 1) * sizeof *fl.offset, "restart: flaw offsets");
  fl.eps = error_malloc((nflaws ? nflaws : 1) * sizeof *fl.eps, "restart: flaw thresholds");
  restart_get(f, fl.offset, sizeof *fl.offset, p->count + 1, path);
  restart_get(f, fl.eps, sizeof *fl.eps, (size_t)nflaws, path);
  if (fgetc(f) != EOF) {
    fclose(f);
    error_exit("%s: corrupt restart file (data after the flaws)", path);
  }
  fclose(f);
  char msg[256];
  if (fl.offset[p->count] != (int64_t)nflaws)
    error_exit("%s: corrupt restart file (flaw offsets end at %lld, %llu flaws)", path,
               (long long)fl.offset[p->count], (unsigned long long)nflaws);
  if (flaws_check(&fl, msg, sizeof msg)) error_exit("%s: corrupt restart file: %s", path, msg);
  for (size_t i = 0; i < p->count; i++) {
    if (fl.offset[i + 1] - fl.offset[i] != p->n_flaws[i])
      error_exit("%s: corrupt restart file (particle %zu has %d flaws, its offsets say %lld)", path,
                 i, (int)p->n_flaws[i], (long long)(fl.offset[i + 1] - fl.offset[i]));
    p->flaw_first[i] = fl.offset[i];
  }
  free(fl.offset);
  *flaw_eps = fl.eps;
  *nr_flaws = (int64_t)nflaws;
}
