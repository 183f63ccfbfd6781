/* MPI ranks: start-up, the rank and the number of ranks, and the few
 * collectives the start-up needs (theory/mpi.md).  In a build without MPI
 * (configure without --with-mpi) every function is there and there is one
 * rank, so that callers need no #ifdef. */
#ifndef BOLIDE_RANKS_H
#define BOLIDE_RANKS_H

/** Start MPI (MPI_Init_thread, MPI_THREAD_FUNNELED: only the main thread
 *  calls MPI).  An exit before ranks_finalize() (an error) finalizes a
 *  single rank and aborts the job of several, so that no rank waits for
 *  one that stopped. */
void ranks_init(int *argc, char ***argv);

/** This process's rank (0 without MPI) and the number of ranks (1). */
int ranks_rank(void);
int ranks_size(void);

/** This rank among the ranks of its node (MPI_COMM_TYPE_SHARED, found by
 *  ranks_init), and their number (0 and 1 without MPI); not a collective. */
void ranks_local(int *rank, int *size);

/** 1 if this build has MPI. */
int ranks_have_mpi(void);

/** Broadcast n ints from rank 0; the other ranks wait without spinning
 *  (rank 0 may take minutes to read the initial conditions). */
void ranks_bcast_ints(int *v, int n);

/** Gather one int from every rank on rank 0 (all: ranks_size() values). */
void ranks_gather_int(int v, int *all);

/** Reductions over the ranks, in place (nothing with one rank). */
enum ranks_op { RANKS_SUM, RANKS_MIN, RANKS_MAX };
void ranks_allreduce_doubles(double *v, int n, enum ranks_op op);
void ranks_allreduce_llongs(long long *v, int n, enum ranks_op op);
/** 1 on every rank if v is non-zero on any. */
int ranks_any(int v);

/** Finalize MPI (nothing without it); call once, before a normal exit. */
void ranks_finalize(void);

#endif
