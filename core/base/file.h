/* File input, the one way lamina reads a model, a Unigrafix include, a
 * machine profile, a program read back or a part file.
 *
 * Only regular files are read: a device (/dev/zero, /dev/urandom), a FIFO,
 * a socket or a directory is refused before a byte is read. The file is
 * opened non-blocking, so a FIFO without a writer cannot hang the open, and
 * checked with fstat on the descriptor it was opened as. Every read has a
 * size limit: a file larger than it is refused with its size and the
 * limit, and a file that grows past the limit while it is read is refused
 * the same way. */
#ifndef LAM_FILE_H
#define LAM_FILE_H

#include <stddef.h>
#include <sys/stat.h>

#include "error.h"

/* Default largest model (or Unigrafix include) in bytes: 1 GiB, some 21
 * million triangles of binary STL. LAMINA_MAX_INPUT (bytes, or a number with
 * a K, M or G suffix) sets another. */
#define LAM_MAX_INPUT_DEFAULT ((size_t)1 << 30)

/* Largest machine profile in bytes: a profile is a page of text. */
#define LAM_MAX_PROFILE_BYTES ((size_t)4 << 20)

/* The model size limit: LAMINA_MAX_INPUT when it is set, else
 * LAM_MAX_INPUT_DEFAULT; 0 when LAMINA_MAX_INPUT is set to something that is
 * not a size (every read with that limit then fails and says so, rather
 * than quietly using the default). */
size_t lam_max_input(void);

/* What a limited read is for: names it in messages ("a model") and says how
 * to raise the limit (NULL when it cannot be raised). */
typedef struct lam_read_limit {
    size_t bytes;
    const char *what;
    const char *raise;
} lam_read_limit;

/* The limit for models and includes (lam_max_input, raised with
 * LAMINA_MAX_INPUT). */
lam_read_limit lam_model_limit(void);

/* Read a whole regular file into a NUL-terminated malloc'd buffer (caller
 * frees). Errors (naming the file, no position): LAM_EIO with the system's
 * reason, or "is a directory" / "is not a regular file"; LAM_EINVAL "too
 * large for <what>"; LAM_ENOMEM. */
int lam_read_file(const char *path, lam_read_limit limit, char **data, size_t *len, lam_error *err);

/* How messages name standard input. */
#define LAM_STDIN_NAME "<stdin>"

/* Read standard input to its end (a pipe, a terminal, a file: anything)
 * into a NUL-terminated malloc'd buffer (caller frees), with the same limit
 * and errors as lam_read_file, naming it LAM_STDIN_NAME. The file gate is
 * not asked: standard input is what the caller was handed, not a name. */
int lam_read_stdin(lam_read_limit limit, char **data, size_t *len, lam_error *err);

/* The same for a large input: maps the file read-only when the mapping is
 * NUL-terminated by the system (size not a multiple of the page size), else
 * reads it. *mapped says which; release with lam_unmap_file. The buffer
 * must not be written. */
int lam_map_file(const char *path, lam_read_limit limit, char **data, size_t *len, int *mapped, lam_error *err);

/* A gate every whole-file read passes before the file is opened: LAM_OK
 * lets `path` be read, anything else refuses it with the message set in
 * err. By default there is none. The Lua sandbox (lua/l_sandbox.c) sets
 * one while a sandboxed state lives, so that what a file names (a
 * Unigrafix include, a profile's `inherits`) is held to the sandbox's
 * directories as the file itself is. One gate per process; set it before
 * reading starts and put the old one back after (old_gate, old_ctx may be
 * NULL). Thread-safe: readers on any thread ask the gate at once, and
 * lam_file_set_gate waits for the calls of the old gate to return, so its
 * context may be freed after; a gate must not itself set the gate. */
typedef int (*lam_file_gate)(void *ctx, const char *path, lam_error *err);
void lam_file_set_gate(lam_file_gate gate, void *ctx, lam_file_gate *old_gate, void **old_ctx);

/* Open `path` for reading as every reader here does: the gate is asked,
 * the file is opened non-blocking (a FIFO without a writer cannot hang
 * the open) and close-on-exec, and refused unless fstat on that descriptor
 * says it is a regular file; it is then recorded as read (below). For a
 * reader that streams a file instead of reading it whole (part files).
 * *fd (regular-file reads ignore O_NONBLOCK) is the caller's to close; *st
 * is its fstat. Errors (naming the file): LAM_EIO "cannot open: REASON",
 * "cannot read: is a directory" / "is not a regular file"; LAM_ENOMEM. */
int lam_file_open(const char *path, int *fd, struct stat *st, lam_error *err);

/* The files a command read. While tracking is on, every file opened
 * through this module (the model, its Unigrafix includes, machine profiles
 * and the profiles they inherit, programs read back, part files) is
 * recorded by device and inode with the path it was opened as, and
 * lam_writer_file refuses to replace any of them (writer.h): an output may
 * not destroy an input, under any name or link. lam_file_track(1) starts
 * an empty record, lam_file_track(0) forgets it and stops. Off by default:
 * the CLI turns it on for a command's run; a Lua session (which may well
 * rewrite a file it read) is not held to it. Thread-safe. */
void lam_file_track(int on);

/* Record a file read by other means (a plugin, plugin.h) as read, when
 * tracking is on. Returns LAM_OK or LAM_ENOMEM (nothing recorded). */
int lam_file_note_read(const struct stat *st, const char *path);

/* Whether the file st names (st_dev, st_ino) was recorded as read; if so
 * and `as` is not NULL, the path it was read as goes into as (size bytes,
 * truncated, NUL-terminated). */
int lam_file_was_read(const struct stat *st, char *as, size_t size);

/* Releases what lam_map_file returned. */
void lam_unmap_file(char *data, size_t len, int mapped);

#endif
