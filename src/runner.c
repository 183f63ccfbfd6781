/* CPU worker threads: see runner.h. */
#include "src/runner.h"

#include <hwloc.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "src/error.h"

/** hwloc state: the topology restricted to the process's CPU set, where each
 *  thread goes, and the caller's binding before runner_start(). */
struct runner_pinning {
  hwloc_topology_t topo;   /**< restricted to the CPUs the process may use */
  hwloc_obj_type_t target; /**< HWLOC_OBJ_CORE or HWLOC_OBJ_PU */
  hwloc_bitmap_t saved;    /**< binding of thread 0 before it was pinned */
  hwloc_bitmap_t near;     /**< the CPUs near the GPU the objects are counted in (NULL: all) */
  int first;               /**< the object of thread 0 (runner_share_node) */
};

/** This process's place among those of the run on this node. */
static int runner_local_rank = 0, runner_local_ranks = 1;

void runner_share_node(int local_rank, int local_ranks) {
  runner_local_rank = local_rank;
  runner_local_ranks = local_ranks > 0 ? local_ranks : 1;
}

/** The node's GPUs (runner_near_devices). */
#define RUNNER_MAX_DEVICES 64
static char runner_bus[RUNNER_MAX_DEVICES][RUNNER_BUS_ID_LEN];
static int runner_nr_devices = 0;

void runner_near_devices(const char (*bus_id)[RUNNER_BUS_ID_LEN], int nr_devices) {
  if (nr_devices > RUNNER_MAX_DEVICES) nr_devices = RUNNER_MAX_DEVICES;
  for (int d = 0; d < nr_devices; d++) snprintf(runner_bus[d], RUNNER_BUS_ID_LEN, "%s", bus_id[d]);
  runner_nr_devices = nr_devices > 0 ? nr_devices : 0;
}

int runner_near_place(hwloc_topology_t topo, const char (*bus_id)[RUNNER_BUS_ID_LEN],
                      int nr_devices, int local_rank, int local_ranks, int nr_threads,
                      hwloc_bitmap_t set, int *first, char *why, size_t len) {
  if (nr_devices <= 0 || local_ranks < 1 || local_rank < 0 || local_rank >= local_ranks) {
    snprintf(why, len, "no GPU");
    return 0;
  }
  /* the CPUs near each device */
  hwloc_const_cpuset_t near[RUNNER_MAX_DEVICES];
  const int nd = nr_devices > RUNNER_MAX_DEVICES ? RUNNER_MAX_DEVICES : nr_devices;
  for (int d = 0; d < nd; d++) {
    hwloc_obj_t pci = hwloc_get_pcidev_by_busidstring(topo, bus_id[d]);
    hwloc_obj_t anc = pci ? hwloc_get_non_io_ancestor_obj(topo, pci) : NULL;
    if (!anc || !anc->cpuset || hwloc_bitmap_iszero(anc->cpuset)) {
      snprintf(why, len, "hwloc does not find GPU %d (PCI %s) or the CPUs near it", d, bus_id[d]);
      return 0;
    }
    near[d] = anc->cpuset;
  }
  const hwloc_const_cpuset_t all = hwloc_topology_get_topology_cpuset(topo);
  const hwloc_const_cpuset_t mine = near[local_rank % nd];
  if (hwloc_bitmap_isincluded(all, mine)) {
    snprintf(why, len, "GPU %d (PCI %s) is near every CPU of the process", local_rank % nd,
             bus_id[local_rank % nd]);
    return 0;
  }
  /* every rank's share of the CPUs near its GPU, so that all decide alike */
  for (int r = 0; r < local_ranks; r++) {
    const hwloc_const_cpuset_t cr = near[r % nd];
    int share = 0;
    for (int k = 0; k < local_ranks; k++) share += hwloc_bitmap_isequal(near[k % nd], cr);
    const int cores = hwloc_get_nbobjs_inside_cpuset_by_type(topo, cr, HWLOC_OBJ_CORE);
    if (share * nr_threads > cores) {
      snprintf(why, len,
               "%d rank(s) of %d thread(s) do not fit the %d core(s) near GPU %d (PCI %s)", share,
               nr_threads, cores, r % nd, bus_id[r % nd]);
      return 0;
    }
    if (r != local_rank) continue;
    int slot = 0;
    for (int k = 0; k < r; k++) slot += hwloc_bitmap_isequal(near[k % nd], cr);
    *first = slot * nr_threads;
    hwloc_bitmap_copy(set, cr);
  }
  return 1;
}

/** Pinning problems are reported once per process, not once per thread. */
static atomic_int runner_warned;

static void runner_warn_once(const char *what) {
  if (atomic_exchange(&runner_warned, 1) == 0)
    error_warning("could not pin threads to cores (%s); carrying on unpinned", what);
}

/** Bind the calling thread to target object number `id`. */
static void runner_pin(struct runner_pinning *p, int id) {
  hwloc_obj_t obj = p->near ? hwloc_get_obj_inside_cpuset_by_type(p->topo, p->near, p->target,
                                                                  (unsigned)(p->first + id))
                            : hwloc_get_obj_by_type(p->topo, p->target, (unsigned)(p->first + id));
  if (!obj || hwloc_set_cpubind(p->topo, obj->cpuset, HWLOC_CPUBIND_THREAD) != 0)
    runner_warn_once("hwloc_set_cpubind");
}

/** Place the threads on the cores near this rank's GPU (runner_near_place)
 *  and say so; 0 (and why) where they are not. */
static int runner_pin_near(struct runner_pinning *p, int nr_threads) {
  char why[256] = "";
  p->near = hwloc_bitmap_alloc();
  if (!runner_near_place(p->topo, (const char(*)[RUNNER_BUS_ID_LEN])runner_bus, runner_nr_devices,
                         runner_local_rank, runner_local_ranks, nr_threads, p->near, &p->first, why,
                         sizeof why)) {
    hwloc_bitmap_free(p->near);
    p->near = NULL;
    error_log(1, "threads not pinned near a GPU: %s", why);
    return 0;
  }
  p->target = HWLOC_OBJ_CORE;
  char cpus[256];
  hwloc_bitmap_list_snprintf(cpus, sizeof cpus, p->near);
  const int d = runner_local_rank % runner_nr_devices;
  error_log(1, "threads pinned near GPU %d (PCI %s): cores %d-%d of those of CPUs %s", d,
            runner_bus[d], p->first, p->first + nr_threads - 1, cpus);
  return 1;
}

/** Decide where threads go; NULL when they stay unpinned. */
static struct runner_pinning *runner_pinning_new(int nr_threads) {
  struct runner_pinning *p = error_calloc(1, sizeof *p, "thread pinning");
  if (hwloc_topology_init(&p->topo) != 0) {
    free(p);
    runner_warn_once("hwloc_topology_init");
    return NULL;
  }
  /* only the CPUs this process may run on (taskset, cgroups, batch systems) */
  unsigned long flags = HWLOC_TOPOLOGY_FLAG_IS_THISSYSTEM;
#if HWLOC_API_VERSION >= 0x00020100
  flags |= HWLOC_TOPOLOGY_FLAG_RESTRICT_TO_CPUBINDING | HWLOC_TOPOLOGY_FLAG_DONT_CHANGE_BINDING;
#endif
  /* the PCI devices too where GPUs may be used (their CPUs) */
  if (runner_nr_devices > 0)
    hwloc_topology_set_io_types_filter(p->topo, HWLOC_TYPE_FILTER_KEEP_IMPORTANT);
  if (hwloc_topology_set_flags(p->topo, flags) != 0 || hwloc_topology_load(p->topo) != 0) {
    hwloc_topology_destroy(p->topo);
    free(p);
    runner_warn_once("hwloc_topology_load");
    return NULL;
  }
  int nr_cores = hwloc_get_nbobjs_by_type(p->topo, HWLOC_OBJ_CORE);
  int nr_pus = hwloc_get_nbobjs_by_type(p->topo, HWLOC_OBJ_PU);
  /* the processes of this node that see every CPU share them out: near
   * their GPUs where they fit there */
  const int all = runner_local_ranks * nr_threads;
  if (runner_nr_devices > 0 && all <= nr_pus && runner_pin_near(p, nr_threads)) {
    /* (the cores near this rank's GPU) */
  } else if (runner_local_ranks > 1 && all <= nr_pus) {
    p->target = all <= nr_cores ? HWLOC_OBJ_CORE : HWLOC_OBJ_PU;
    p->first = runner_local_rank * nr_threads;
  } else if (nr_threads <= nr_cores)
    p->target = HWLOC_OBJ_CORE;
  else if (nr_threads <= nr_pus)
    p->target = HWLOC_OBJ_PU;
  else {
    /* oversubscribed: pinning would only stack threads; let the OS share */
    error_log(1, "%d threads on %d hardware threads: not pinned", nr_threads, nr_pus);
    hwloc_topology_destroy(p->topo);
    free(p);
    return NULL;
  }
  p->saved = hwloc_bitmap_alloc();
  if (hwloc_get_cpubind(p->topo, p->saved, HWLOC_CPUBIND_THREAD) != 0) {
    hwloc_bitmap_free(p->saved);
    p->saved = NULL;
  }
  return p;
}

/** A worker: wait for a run, work, report, until shutdown. */
static void *runner_main(void *arg) {
  struct runner *r = arg;
  struct runner_pool *s = r->pool;
  if (s->pinning) runner_pin(s->pinning, r->id);
  int gen = 0;
  for (;;) {
    pthread_mutex_lock(&s->run_mutex);
    while (s->run_gen == gen && !s->shutdown) pthread_cond_wait(&s->run_cond, &s->run_mutex);
    int stop = s->shutdown;
    gen = s->run_gen;
    pthread_mutex_unlock(&s->run_mutex);
    if (stop) break;
    s->work(s->ctx, r->id);
    pthread_mutex_lock(&s->run_mutex);
    if (++s->nr_finished == s->nr_threads - 1) pthread_cond_signal(&s->done_cond);
    pthread_mutex_unlock(&s->run_mutex);
  }
  return NULL;
}

void runner_start(struct runner_pool *s, int nr_threads, void (*work)(void *, int), void *ctx) {
  s->nr_threads = nr_threads;
  s->work = work;
  s->ctx = ctx;
  pthread_mutex_init(&s->run_mutex, NULL);
  pthread_cond_init(&s->run_cond, NULL);
  pthread_cond_init(&s->done_cond, NULL);
  s->run_gen = 0;
  s->nr_finished = 0;
  s->shutdown = 0;
  s->pinning = runner_pinning_new(s->nr_threads);
  if (s->pinning) runner_pin(s->pinning, 0);
  s->runners = error_calloc(s->nr_threads, sizeof(struct runner), "runners");
  for (int i = 1; i < s->nr_threads; i++) {
    struct runner *r = &s->runners[i];
    r->id = i;
    r->pool = s;
    if (pthread_create(&r->thread, NULL, runner_main, r) != 0)
      error_exit("could not start worker thread %d of %d", i, s->nr_threads);
  }
}
void runner_stop(struct runner_pool *s) {
  pthread_mutex_lock(&s->run_mutex);
  s->shutdown = 1;
  pthread_cond_broadcast(&s->run_cond);
  pthread_mutex_unlock(&s->run_mutex);
  for (int i = 1; i < s->nr_threads; i++) pthread_join(s->runners[i].thread, NULL);
  free(s->runners);
  s->runners = NULL;
  struct runner_pinning *p = s->pinning;
  if (p) {
    if (p->saved) {
      hwloc_set_cpubind(p->topo, p->saved, HWLOC_CPUBIND_THREAD);
      hwloc_bitmap_free(p->saved);
    }
    if (p->near) hwloc_bitmap_free(p->near);
    hwloc_topology_destroy(p->topo);
    free(p);
    s->pinning = NULL;
  }
  pthread_cond_destroy(&s->run_cond);
  pthread_cond_destroy(&s->done_cond);
  pthread_mutex_destroy(&s->run_mutex);
}

void runner_launch(struct runner_pool *s) {
  pthread_mutex_lock(&s->run_mutex);
  s->nr_finished = 0;
  s->run_gen++;
  pthread_cond_broadcast(&s->run_cond);
  pthread_mutex_unlock(&s->run_mutex);
}

void runner_wait(struct runner_pool *s) {
  pthread_mutex_lock(&s->run_mutex);
  while (s->nr_finished < s->nr_threads - 1) pthread_cond_wait(&s->done_cond, &s->run_mutex);
  pthread_mutex_unlock(&s->run_mutex);
}

void runner_unpin_self(const struct runner_pool *s) {
  const struct runner_pinning *p = s->pinning;
  if (!p || !p->saved) return;
  if (hwloc_set_cpubind(p->topo, p->saved, HWLOC_CPUBIND_THREAD) != 0)
    runner_warn_once("hwloc_set_cpubind");
}

void runner_repin_self(const struct runner_pool *s) {
  if (s->pinning) runner_pin(s->pinning, 0);
}
