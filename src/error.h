/* Errors, warnings and log messages.
 *
 * The contract of every Bolide program (theory/architecture.md, "Programs
 * and their contract"): on failure print one line
 * "PROGRAM: error: ..." to stderr and exit non-zero.  Log lines carry the
 * wall-clock time since start. */
#ifndef BOLIDE_ERROR_H
#define BOLIDE_ERROR_H

#include <stdarg.h>
#include <stddef.h>

/** Name of the running program, used as the prefix of error lines. */
extern const char *error_progname;

/** Verbosity: 0 normal, 1 with -v, 2 with -vv. */
extern int error_verbosity;
/** 1: error_log prints nothing (the MPI ranks other than 0). */
extern int error_log_quiet;
/** Several MPI ranks: this rank's number when it is not 0 (its warnings and
 *  notes then say "(rank N)"), and 1 while such a rank repeats what rank 0
 *  says anyway (reading the parameters and the initial conditions, which
 *  every rank does alike): its warnings and notes are not printed then.
 *  Errors are always printed. */
extern int error_rank, error_warn_quiet;

/** Set the program name (basename of argv[0]) and start the log clock. */
void error_init(const char *argv0);

/** Print "PROGRAM: error: MESSAGE" on one line to stderr and exit(1).
 *  Before exiting, runs the registered cleanup hooks (removal of temporary
 *  files), so that nothing half-written is left behind. */
void error_exit(const char *fmt, ...) __attribute__((format(printf, 1, 2), noreturn));
/** As error_exit, with exit status `status` (documented per use: 3 for a
 *  failed conservation check, README "Programs"). */
void error_exit_status(int status, const char *fmt, ...)
    __attribute__((format(printf, 2, 3), noreturn));

/** Test hook, NULL in every program: when set, error_exit calls it after
 *  printing and cleaning up, instead of exit(1).  It must not return (the
 *  fuzzing harnesses in tests/fuzz longjmp back to their entry point). */
extern void (*error_exit_hook)(void);

/** Print "PROGRAM: warning: MESSAGE" to stderr. */
void error_warning(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

/** Print "PROGRAM: note: MESSAGE" to stderr: information about the input
 *  (a key that has no effect, say) that needs no action. */
void error_note(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

/** Print "PROGRAM: error: MESSAGE" to stderr without exiting: one of several
 *  problems reported together before error_exit() gives the last. */
void error_report(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

/** A log line "[  12.345 s] MESSAGE" on stdout (level 0 always printed,
 *  level 1 only with -v, 2 with -vv). */
void error_log(int level, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/** An internal error (a bug, not bad input): names the source location. */
#define error_bug(...) error_bug_at(__FILE__, __LINE__, __VA_ARGS__)
void error_bug_at(const char *file, int line, const char *fmt, ...)
    __attribute__((format(printf, 3, 4), noreturn));

/** Register a file to be removed if the program exits on an error (a
 *  temporary output file being written).  error_unregister_tmpfile() when it
 *  has been renamed to its final name. */
void error_register_tmpfile(const char *path);
void error_unregister_tmpfile(const char *path);

/** Seconds of wall-clock time since error_init(). */
double error_walltime(void);

/** malloc/calloc/realloc that stop with a clear message on failure. */
void *error_malloc(size_t size, const char *what);
void *error_calloc(size_t n, size_t size, const char *what);
void *error_realloc(void *p, size_t size, const char *what);

#endif
