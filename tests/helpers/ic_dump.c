/* Test driver: read initial conditions with ic_read and print the particle
 * count, total mass and a checksum of every field read; optionally write the
 * particles back as a snapshot.
 *   ic_dump FILE [--mat ID,ID,...] [--cgs] [--write OUT [--acc] [--gzip L]] */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "src/error.h"
#include "src/io/ic.h"
#include "src/io/snapshot.h"

/** FNV-1a over the bytes of a buffer. */
static uint64_t fnv1a(uint64_t h, const void *data, size_t n) {
  const unsigned char *c = data;
  for (size_t i = 0; i < n; i++) h = (h ^ c[i]) * 0x100000001b3ULL;
  return h;
}

int main(int argc, char **argv) {
  error_init(argv[0]);
  if (argc < 2) error_exit("usage: ic_dump FILE [--mat IDS] [--cgs] [--write OUT [--acc]]");
  const char *in = argv[1], *out = NULL;
  int32_t mats[64];
  int nmat = -1, acc = 0, gzip = 0;
  struct unit_system us;
  units_init_si(&us);
  for (int a = 2; a < argc; a++) {
    if (strcmp(argv[a], "--mat") == 0 && a + 1 < argc) {
      nmat = 0;
      for (char *t = strtok(argv[++a], ","); t && nmat < 64; t = strtok(NULL, ","))
        mats[nmat++] = (int32_t)atoi(t);
    } else if (strcmp(argv[a], "--cgs") == 0) {
      units_init_cgs(&us);
    } else if (strcmp(argv[a], "--write") == 0 && a + 1 < argc) {
      out = argv[++a];
    } else if (strcmp(argv[a], "--acc") == 0) {
      acc = 1;
    } else if (strcmp(argv[a], "--gzip") == 0 && a + 1 < argc) {
      gzip = atoi(argv[++a]);
    } else {
      error_exit("unknown argument %s", argv[a]);
    }
  }
  struct parts p;
  struct ic_info info;
  ic_read(in, &us, nmat >= 0 ? mats : NULL, nmat, &p, &info);
  double mtot = 0;
  uint64_t h = 0xcbf29ce484222325ULL;
  for (size_t i = 0; i < p.count; i++) mtot += p.m[i];
  for (int k = 0; k < part_nr_fields; k++)
    if (ic_field_read(&info, k))
      h = fnv1a(h, part_field_array(&p, &part_fields[k]), p.count * part_fields[k].size);
  printf("count %zu\nmass_total %.17g\nchecksum %016llx\nbox %.17g %.17g %.17g\nperiodic %d\n",
         p.count, mtot, (unsigned long long)h, info.box_size[0], info.box_size[1], info.box_size[2],
         info.periodic);
  printf("fields");
  for (int k = 0; k < part_nr_fields; k++)
    if (ic_field_read(&info, k)) printf(" %s", part_fields[k].name);
  printf("\n");
  if (out) {
    /* deterministic stand-ins for the derived fields, so that a snapshot
     * has non-trivial values everywhere: an ideal gas, gamma = 5/3 */
    for (size_t i = 0; i < p.count; i++) {
      p.P[i] = 2.0 / 3.0 * p.rho[i] * p.u[i];
      p.cs[i] = sqrt(5.0 / 3.0 * 2.0 / 3.0 * fabs(p.u[i]));
      p.ax[i] = -p.x[i];
      p.ay[i] = -p.y[i];
      p.az[i] = -p.z[i];
      p.pot[i] = -1.0 / (1.0 + p.x[i] * p.x[i]);
    }
    struct snapshot_meta meta = {.time = info.time,
                                 .periodic = info.periodic > 0,
                                 .compression = gzip,
                                 .run_name = "ic_dump",
                                 .params = "MetaData:\n  run_name: ic_dump\n",
                                 .hydro = 1};
    memcpy(meta.box_size, info.box_size, sizeof meta.box_size);
    snapshot_write(out, &meta, &p, &us, acc);
  }
  parts_free(&p);
  return 0;
}
