/* MPI ranks (src/mpi/ranks.h). */
#define _POSIX_C_SOURCE 200809L /* nanosleep */
#include "src/mpi/ranks.h"

#include <stdlib.h>
#include <time.h>

#include "config.h"
#include "src/error.h"

#ifdef HAVE_MPI
#include <mpi.h>

static int ranks_me = 0, ranks_n = 1, ranks_started = 0, ranks_done = 0;
static int ranks_local_me = 0, ranks_local_n = 1; /**< (ranks_init, collective) */

/** At exit without ranks_finalize (an error): one rank finalizes, as the
 *  serial program would simply exit; several abort the job. */
static void ranks_atexit(void) {
  if (!ranks_started || ranks_done) return;
  ranks_done = 1;
  if (ranks_n > 1)
    MPI_Abort(MPI_COMM_WORLD, 1);
  else
    MPI_Finalize();
}

void ranks_init(int *argc, char ***argv) {
  int provided = 0;
  if (MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
    error_exit("MPI_Init_thread failed");
  ranks_started = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &ranks_me);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks_n);
  atexit(ranks_atexit);
  if (provided < MPI_THREAD_FUNNELED)
    error_exit("the MPI library gives no MPI_THREAD_FUNNELED (threads %d)", provided);
  /* the node-local rank, once here where every rank passes (a collective:
   * ranks_local is called where only some ranks may be) */
  if (ranks_n > 1) {
    MPI_Comm node;
    MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, ranks_me, MPI_INFO_NULL, &node);
    MPI_Comm_rank(node, &ranks_local_me);
    MPI_Comm_size(node, &ranks_local_n);
    MPI_Comm_free(&node);
  }
}

int ranks_rank(void) {
  return ranks_me;
}

int ranks_size(void) {
  return ranks_n;
}

int ranks_have_mpi(void) {
  return 1;
}

void ranks_local(int *rank, int *size) {
  *rank = ranks_local_me;
  *size = ranks_local_n;
}

void ranks_bcast_ints(int *v, int n) {
  if (ranks_n == 1) return;
  MPI_Request req;
  MPI_Ibcast(v, n, MPI_INT, 0, MPI_COMM_WORLD, &req);
  int done = 0;
  const struct timespec nap = {0, 1000000}; /* 1 ms */
  while (!done) {
    MPI_Test(&req, &done, MPI_STATUS_IGNORE);
    if (!done) nanosleep(&nap, NULL);
  }
}

void ranks_gather_int(int v, int *all) {
  if (ranks_n == 1) {
    all[0] = v;
    return;
  }
  MPI_Gather(&v, 1, MPI_INT, all, 1, MPI_INT, 0, MPI_COMM_WORLD);
}

static MPI_Op ranks_mpi_op(enum ranks_op op) {
  return op == RANKS_SUM ? MPI_SUM : op == RANKS_MIN ? MPI_MIN : MPI_MAX;
}

void ranks_allreduce_doubles(double *v, int n, enum ranks_op op) {
  if (ranks_n == 1) return;
  MPI_Allreduce(MPI_IN_PLACE, v, n, MPI_DOUBLE, ranks_mpi_op(op), MPI_COMM_WORLD);
}

void ranks_allreduce_llongs(long long *v, int n, enum ranks_op op) {
  if (ranks_n == 1) return;
  MPI_Allreduce(MPI_IN_PLACE, v, n, MPI_LONG_LONG, ranks_mpi_op(op), MPI_COMM_WORLD);
}

int ranks_any(int v) {
  if (ranks_n == 1) return v != 0;
  int x = v != 0;
  MPI_Allreduce(MPI_IN_PLACE, &x, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return x;
}

void ranks_finalize(void) {
  if (!ranks_started || ranks_done) return;
  ranks_done = 1;
  MPI_Finalize();
}

#else /* no MPI: one rank */

void ranks_init(int *argc, char ***argv) {
  (void)argc;
  (void)argv;
}

int ranks_rank(void) {
  return 0;
}

int ranks_size(void) {
  return 1;
}

int ranks_have_mpi(void) {
  return 0;
}

void ranks_local(int *rank, int *size) {
  *rank = 0;
  *size = 1;
}

void ranks_bcast_ints(int *v, int n) {
  (void)v;
  (void)n;
}

void ranks_gather_int(int v, int *all) {
  all[0] = v;
}

void ranks_allreduce_doubles(double *v, int n, enum ranks_op op) {
  (void)v;
  (void)n;
  (void)op;
}

void ranks_allreduce_llongs(long long *v, int n, enum ranks_op op) {
  (void)v;
  (void)n;
  (void)op;
}

int ranks_any(int v) {
  return v != 0;
}

void ranks_finalize(void) {}

#endif
