/* lam_writer: the one output interface (file, stream, memory buffer).
 *
 * A file writer writes to a temporary file in the target's directory and
 * renames it over the target only on lam_writer_commit, so a run that fails
 * leaves no partial output. Write errors are sticky: the first one is kept
 * and reported by commit. There is no fsync: like compilers and other
 * slicers, lamina leaves durability across a power cut to the file system
 * (ext4 and others flush a file renamed over an old one); the rename makes
 * the output whole-or-absent for every other process and every failed run.
 *
 * Temporary files. A file writer's temporary is `TARGET.tmp-PID-XXXXXX` (PID
 * the writer's process id, XXXXXX made unique by mkstemp). While the writer
 * lives it holds an exclusive flock on it and it is listed in a registry
 * that lam_writer_unlink_temps, safe in a signal handler, clears. A process
 * killed outright (SIGKILL, a crash) leaves its temporary behind, with no
 * lock on it any more: the kernel drops a dead process's locks. So the next
 * file writer for the same target removes every `TARGET.tmp-DIGITS-XXXXXX`
 * beside it that is a regular file of the same owner and whose lock it can
 * take: provably a lamina temporary of that target whose writer is gone. */
#ifndef LAM_WRITER_H
#define LAM_WRITER_H

#include <stddef.h>
#include <stdio.h>

#include "error.h"

typedef struct lam_writer lam_writer;

/* Output to `path`, created atomically on commit. A symbolic link is
 * followed (the file it names is replaced, the link stays). A file that is
 * replaced keeps its permission bits (a new one gets 0666 less the umask).
 * Stale temporaries of the target are removed first (see above). An existing
 * target that is not a regular file (/dev/null, a terminal, a pipe) is
 * written to directly, as it comes: renaming over it would replace the
 * device with a plain file. A directory is an error (LAM_EIO); a file the
 * command read is refused (LAM_EUSAGE, lam_writer_check). */
int lam_writer_file(const char *path, lam_writer **out, lam_error *err);

/* Output to an open stream the caller owns (e.g. stdout); commit flushes.
 * A stream on a file the command read (standard output sent to an input
 * with >>) is refused as lam_writer_check says. */
int lam_writer_stream(FILE *f, const char *name, lam_writer **out, lam_error *err);

/* Whether `path` may be an output: LAM_EUSAGE, with the message "PATH is an
 * input of this command (read as READ): refusing to overwrite it", when it
 * names (by device and inode: any spelling, link or hard link) a file
 * recorded as read (lam_file_track, file.h); LAM_OK otherwise, also when
 * nothing is recorded. lam_writer_file and lam_writer_stream ask it when
 * they open, and lam_writer_commit again before the rename (a file read
 * after the output was opened: the temporary is removed, the target left
 * as it was). A caller that opens an output only at its end (a picture
 * made in memory) asks it up front, before the work. */
int lam_writer_check(const char *path, lam_error *err);

/* The same for the file an open stream writes to (standard output sent to
 * an input with > or >>), named `name` in the message. */
int lam_writer_check_stream(FILE *f, const char *name, lam_error *err);

/* Output to a growing memory buffer; take it with lam_writer_take. */
int lam_writer_memory(lam_writer **out, lam_error *err);

/* Most bytes the writer may take (0, the default: no limit). A write that
 * would pass it fails (sticky), and lam_writer_error / commit say
 * "output exceeds the limit of N bytes". */
void lam_writer_set_limit(lam_writer *w, unsigned long long max_bytes);

/* Whether a write failed for passing that limit. */
int lam_writer_over_limit(const lam_writer *w);

/* Bytes written so far. */
unsigned long long lam_writer_bytes(const lam_writer *w);

/* Set err from the writer's sticky write error: "PATH: cannot write output:
 * REASON" (strerror, or the limit). Returns the error code (LAM_EIO,
 * LAM_ELIMIT past the limit, or LAM_ENOMEM for a memory writer), LAM_OK
 * when no write failed. For sinks
 * that must report a failed write at once, with the path and the reason. */
int lam_writer_error(const lam_writer *w, lam_error *err);

/* Remove the temporary files of every file writer not yet committed or
 * aborted. Async-signal-safe (unlink only): for a handler of SIGINT,
 * SIGTERM and the like, before the process ends. The writers themselves
 * are left as they are. */
void lam_writer_unlink_temps(void);

/* Append bytes / formatted text. Returns LAM_OK or the sticky error code. */
int lam_writer_write(lam_writer *w, const void *data, size_t len);
int lam_writer_printf(lam_writer *w, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Finish: rename the temporary file into place / flush. Frees w. On error
 * (an earlier write failed, the rename, or the target is now a file the
 * command read: LAM_EUSAGE, lam_writer_check) nothing is left behind. */
int lam_writer_commit(lam_writer *w, lam_error *err);

/* Give up: remove the temporary file. Frees w (NULL is fine). */
void lam_writer_abort(lam_writer *w);

/* Memory writers: hand the buffer (NUL-terminated, caller frees) to the
 * caller and free w. */
int lam_writer_take(lam_writer *w, char **data, size_t *len, lam_error *err);

#endif
