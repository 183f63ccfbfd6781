/* Threads pinned near their GPU (runner_near_place, src/runner.c) on a
 * machine described in hwloc's XML: two packages, each a NUMA node of 4
 * cores with 2 hardware threads, a GPU on a PCI bridge under each package
 * (and, for the last case, a third GPU attached to the machine, near every
 * CPU).  Each case states where the threads of each local rank go. */
#include <hwloc.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "src/runner.h"

static int failures = 0;

#define CHECK(cond, ...)                          \
  do {                                            \
    if (!(cond)) {                                \
      printf("FAIL %s:%d: ", __FILE__, __LINE__); \
      printf(__VA_ARGS__);                        \
      printf("\n");                               \
      failures++;                                 \
    }                                             \
  } while (0)

/** Append to the XML buffer. */
static void put(char **b, size_t *n, size_t *cap, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
#include <stdarg.h>
static void put(char **b, size_t *n, size_t *cap, const char *fmt, ...) {
  va_list ap;
  for (;;) {
    va_start(ap, fmt);
    const int k = vsnprintf(*b + *n, *cap - *n, fmt, ap);
    va_end(ap);
    if (k >= 0 && (size_t)k < *cap - *n) {
      *n += (size_t)k;
      return;
    }
    *cap *= 2;
    *b = realloc(*b, *cap);
  }
}

/** The machine's XML: 2 packages x 4 cores x 2 PUs (core c of package k
 *  holds PUs 8k + 2c and 8k + 2c + 1), GPU 0000:17:00.0 near package 0,
 *  0000:b1:00.0 near package 1, and 0000:02:00.0 on a bridge of the
 *  machine itself. */
static char *machine_xml(void) {
  size_t n = 0, cap = 4096;
  char *b = malloc(cap);
  int gp = 1;
  put(&b, &n, &cap,
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<!DOCTYPE topology SYSTEM \"hwloc2.dtd\">\n"
      "<topology version=\"2.0\">\n<object type=\"Machine\" os_index=\"0\" cpuset=\"0x0000ffff\" "
      "complete_cpuset=\"0x0000ffff\" allowed_cpuset=\"0x0000ffff\" nodeset=\"0x00000003\" "
      "complete_nodeset=\"0x00000003\" allowed_nodeset=\"0x00000003\" gp_index=\"%d\">\n",
      gp++);
  const char *bus[2] = {"17", "b1"};
  for (int k = 0; k < 2; k++) {
    const unsigned set = 0xffu << (8 * k), node = 1u << k;
    put(&b, &n, &cap,
        "<object type=\"Package\" os_index=\"%d\" cpuset=\"0x%08x\" complete_cpuset=\"0x%08x\" "
        "nodeset=\"0x%08x\" complete_nodeset=\"0x%08x\" gp_index=\"%d\">\n",
        k, set, set, node, node, gp++);
    put(&b, &n, &cap,
        "<object type=\"NUMANode\" os_index=\"%d\" cpuset=\"0x%08x\" complete_cpuset=\"0x%08x\" "
        "nodeset=\"0x%08x\" complete_nodeset=\"0x%08x\" gp_index=\"%d\" "
        "local_memory=\"1073741824\"/>\n",
        k, set, set, node, node, gp++);
    for (int c = 0; c < 4; c++) {
      const int core = 4 * k + c;
      const unsigned cs = 3u << (2 * core);
      put(&b, &n, &cap,
          "<object type=\"Core\" os_index=\"%d\" cpuset=\"0x%08x\" complete_cpuset=\"0x%08x\" "
          "nodeset=\"0x%08x\" complete_nodeset=\"0x%08x\" gp_index=\"%d\">\n",
          core, cs, cs, node, node, gp++);
      for (int t = 0; t < 2; t++)
        put(&b, &n, &cap,
            "<object type=\"PU\" os_index=\"%d\" cpuset=\"0x%08x\" complete_cpuset=\"0x%08x\" "
            "nodeset=\"0x%08x\" complete_nodeset=\"0x%08x\" gp_index=\"%d\"/>\n",
            2 * core + t, 1u << (2 * core + t), 1u << (2 * core + t), node, node, gp++);
      put(&b, &n, &cap, "</object>\n");
    }
    put(&b, &n, &cap,
        "<object type=\"Bridge\" gp_index=\"%d\" bridge_type=\"0-1\" depth=\"0\" "
        "bridge_pci=\"0000:[%s-%s]\">\n"
        "<object type=\"PCIDev\" gp_index=\"%d\" pci_busid=\"0000:%s:00.0\" "
        "pci_type=\"0302 [10de:2330] [10de:16c1] a1\" pci_link_speed=\"0.000000\"/>\n"
        "</object>\n</object>\n",
        gp, bus[k], bus[k], gp + 1, bus[k]);
    gp += 2;
  }
  put(&b, &n, &cap,
      "<object type=\"Bridge\" gp_index=\"%d\" bridge_type=\"0-1\" depth=\"0\" "
      "bridge_pci=\"0000:[02-02]\">\n"
      "<object type=\"PCIDev\" gp_index=\"%d\" pci_busid=\"0000:02:00.0\" "
      "pci_type=\"0302 [10de:2330] [10de:16c1] a1\" pci_link_speed=\"0.000000\"/>\n"
      "</object>\n</object>\n</topology>\n",
      gp, gp + 1);
  return b;
}

/** One case: local ranks ln of nt threads each over the GPUs bus[0 ..
 *  nd); want[r] the first CPU (os index) of rank r's thread 0 and the
 *  type, or want_ok 0 (no rank pinned near its GPU). */
static void near_case(hwloc_topology_t topo, const char *name, const char (*bus)[RUNNER_BUS_ID_LEN],
                      int nd, int ln, int nt, int want_ok, const int *want_pu,
                      const char *want_why) {
  for (int r = 0; r < ln; r++) {
    hwloc_bitmap_t set = hwloc_bitmap_alloc();
    const hwloc_obj_type_t type = HWLOC_OBJ_CORE;
    int first = -1;
    char why[256] = "";
    const int ok = runner_near_place(topo, bus, nd, r, ln, nt, set, &first, why, sizeof why);
    CHECK(ok == want_ok, "%s: rank %d of %d: placed %d, expected %d (%s)", name, r, ln, ok, want_ok,
          why);
    if (ok && want_ok) {
      /* every thread on its own object within the set, none outside it */
      for (int t = 0; t < nt; t++) {
        hwloc_obj_t o = hwloc_get_obj_inside_cpuset_by_type(topo, set, type, (unsigned)(first + t));
        CHECK(o != NULL, "%s: rank %d thread %d: no object %d", name, r, t, first + t);
        if (!o) continue;
        const int pu = hwloc_bitmap_first(o->cpuset);
        if (t == 0)
          CHECK(pu == want_pu[r], "%s: rank %d: thread 0 on CPU %d, expected %d", name, r, pu,
                want_pu[r]);
      }
      printf(
          "%s: rank %d of %d, %d threads: cores from number %d near its GPU, thread 0 on CPU %d\n",
          name, r, ln, nt, first, want_pu[r]);
    }
    if (!ok && !want_ok) {
      CHECK(strstr(why, want_why) != NULL, "%s: rank %d: reason '%s', expected '%s'", name, r, why,
            want_why);
      if (r == 0) printf("%s: not placed: %s\n", name, why);
    }
    hwloc_bitmap_free(set);
  }
}

int main(void) {
  hwloc_topology_t topo;
  char *xml = machine_xml();
  if (hwloc_topology_init(&topo) != 0 ||
      hwloc_topology_set_io_types_filter(topo, HWLOC_TYPE_FILTER_KEEP_IMPORTANT) != 0 ||
      hwloc_topology_set_xmlbuffer(topo, xml, (int)strlen(xml) + 1) != 0 ||
      hwloc_topology_load(topo) != 0) {
    printf("FAIL: hwloc cannot load the test machine\n");
    return 1;
  }
  CHECK(hwloc_get_nbobjs_by_type(topo, HWLOC_OBJ_CORE) == 8, "cores %d",
        hwloc_get_nbobjs_by_type(topo, HWLOC_OBJ_CORE));
  CHECK(hwloc_get_nbobjs_by_type(topo, HWLOC_OBJ_PCI_DEVICE) == 3, "PCI devices %d",
        hwloc_get_nbobjs_by_type(topo, HWLOC_OBJ_PCI_DEVICE));
  const char two[2][RUNNER_BUS_ID_LEN] = {"0000:17:00.0", "0000:b1:00.0"};
  const char one[1][RUNNER_BUS_ID_LEN] = {"0000:b1:00.0"};
  const char central[1][RUNNER_BUS_ID_LEN] = {"0000:02:00.0"};
  const char absent[1][RUNNER_BUS_ID_LEN] = {"0000:65:00.0"};
  /* two ranks, a GPU each: each its package's cores */
  near_case(topo, "2 GPUs, 2 ranks x 4", two, 2, 2, 4, 1, (const int[]){0, 8}, "");
  /* four ranks on two GPUs: ranks 0 and 2 share package 0, 1 and 3 package 1 */
  near_case(topo, "2 GPUs, 4 ranks x 2", two, 2, 4, 2, 1, (const int[]){0, 8, 4, 12}, "");
  /* one rank, fewer threads than the package's cores: near its GPU */
  near_case(topo, "1 GPU, 1 rank x 3", one, 1, 1, 3, 1, (const int[]){8}, "");
  /* more threads than the cores near the GPU: as without GPUs (the
   * package's hardware threads would hold them, but not as fast) */
  near_case(topo, "1 GPU, 2 ranks x 4", one, 1, 2, 4, 0, NULL, "do not fit the 4 core(s)");
  near_case(topo, "2 GPUs, 2 ranks x 5", two, 2, 2, 5, 0, NULL, "do not fit");
  near_case(topo, "2 GPUs, 3 ranks x 2", two, 2, 3, 2, 1, (const int[]){0, 8, 4}, "");
  near_case(topo, "2 GPUs, 3 ranks x 3", two, 2, 3, 3, 0, NULL, "2 rank(s) of 3 thread(s)");
  /* a GPU near every CPU: nothing to choose */
  near_case(topo, "GPU on the machine", central, 1, 2, 2, 0, NULL, "near every CPU");
  /* a bus id hwloc does not know (a virtual machine that hides the PCI tree) */
  near_case(topo, "unknown GPU", absent, 1, 1, 2, 0, NULL, "does not find GPU 0");
  near_case(topo, "no GPU", two, 0, 1, 2, 0, NULL, "no GPU");
  hwloc_topology_destroy(topo);
  free(xml);
  if (failures) {
    printf("test_runner_near: %d failure(s)\n", failures);
    return 1;
  }
  printf("test_runner_near: PASS\n");
  return 0;
}
