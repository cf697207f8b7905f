/* lam_writer: the one output interface (file, stream, memory buffer).
 *
 * A file writer writes to a temporary file in the target's directory and
 * renames it over the target only on lam_writer_commit, so a run that fails
 * leaves no partial output. Write errors are sticky: the first one is kept
 * and reported by commit. There is no fsync: like compilers and other
 * slicers, lamina leaves durability across a power cut to the file system
 * (ext4 and others flush a file renamed over an old one); the rename makes
 * the output whole-or-absent for every other process and every failed run. */
#ifndef LAM_WRITER_H
#define LAM_WRITER_H

#include <stddef.h>
#include <stdio.h>

#include "error.h"

typedef struct lam_writer lam_writer;

/* Output to `path`, created atomically on commit. A symbolic link is
 * followed (the file it names is replaced, the link stays). An existing
 * target that is not a regular file (/dev/null, a terminal, a pipe) is
 * written to directly, as it comes: renaming over it would replace the
 * device with a plain file. A directory is an error (LAM_EIO). */
int lam_writer_file(const char *path, lam_writer **out, lam_error *err);

/* Output to an open stream the caller owns (e.g. stdout); commit flushes. */
int lam_writer_stream(FILE *f, const char *name, lam_writer **out, lam_error *err);

/* Output to a growing memory buffer; take it with lam_writer_take. */
int lam_writer_memory(lam_writer **out, lam_error *err);

/* Append bytes / formatted text. Returns LAM_OK or the sticky error code. */
int lam_writer_write(lam_writer *w, const void *data, size_t len);
int lam_writer_printf(lam_writer *w, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Finish: rename the temporary file into place / flush. Frees w. On error
 * (an earlier write failed, or the rename) nothing is left behind. */
int lam_writer_commit(lam_writer *w, lam_error *err);

/* Give up: remove the temporary file. Frees w (NULL is fine). */
void lam_writer_abort(lam_writer *w);

/* Memory writers: hand the buffer (NUL-terminated, caller frees) to the
 * caller and free w. */
int lam_writer_take(lam_writer *w, char **data, size_t *len, lam_error *err);

#endif
