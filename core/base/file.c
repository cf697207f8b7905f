/* Whole-file input with a size limit; see file.h. */
#include "file.h"

#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "grow.h"

size_t lam_max_input(void)
{
    const char *s = getenv("LAMINA_MAX_INPUT");
    if (!s || !*s) return LAM_MAX_INPUT_DEFAULT;
    char *end;
    errno = 0;
    unsigned long long n = strtoull(s, &end, 10);
    unsigned shift = 0;
    if (*end == 'K' || *end == 'k') shift = 10, end++;
    else if (*end == 'M' || *end == 'm') shift = 20, end++;
    else if (*end == 'G' || *end == 'g') shift = 30, end++;
    if (end == s || *end || errno || s[0] == '-' || n == 0 || n > (SIZE_MAX / 2) >> shift) return 0;
    return (size_t)n << shift;
}

lam_read_limit lam_model_limit(void)
{
    lam_read_limit l = { lam_max_input(), "a model", "set LAMINA_MAX_INPUT to raise it" };
    return l;
}

static int too_large(const char *path, lam_read_limit limit, unsigned long long size, lam_error *err)
{
    return lam_error_set(err, LAM_EINVAL, path, 0, 0, "too large for %s: %s%llu bytes, the limit is %zu%s%s",
                         limit.what, size > limit.bytes ? "" : "over ", size > limit.bytes ? size : limit.bytes,
                         limit.bytes, limit.raise ? "; " : "", limit.raise ? limit.raise : "");
}

/* The gate and its context, set together: a read lock while a file is
 * asked about (any number of threads at once), the write lock to change
 * them, so a reader never pairs one gate with another's context, and once
 * lam_file_set_gate returns no thread still runs the old gate (its
 * context may be freed). */
static pthread_rwlock_t gate_mu = PTHREAD_RWLOCK_INITIALIZER;
static lam_file_gate gate;
static void *gate_ctx;

void lam_file_set_gate(lam_file_gate g, void *ctx, lam_file_gate *old_gate, void **old_ctx)
{
    pthread_rwlock_wrlock(&gate_mu);
    if (old_gate) *old_gate = gate;
    if (old_ctx) *old_ctx = gate_ctx;
    gate = g;
    gate_ctx = ctx;
    pthread_rwlock_unlock(&gate_mu);
}

/* What the gate says of path: LAM_OK without one. */
static int ask_gate(const char *path, lam_error *err)
{
    pthread_rwlock_rdlock(&gate_mu);
    int rc = gate ? gate(gate_ctx, path, err) : LAM_OK;
    pthread_rwlock_unlock(&gate_mu);
    return rc;
}

/* A limit from the environment that is not a size. */
static int bad_limit(const char *path, lam_error *err)
{
    return lam_error_set(err, LAM_EINVAL, path, 0, 0,
                         "cannot read: LAMINA_MAX_INPUT is not a size (bytes, or a number with K, M or G)");
}

/* ---- the files a command read ---------------------------------------------- */

typedef struct read_entry {
    dev_t dev;
    ino_t ino;
    char *path;
} read_entry;

/* Guarded by a mutex: a reader may run on a worker thread. */
static pthread_mutex_t reads_mu = PTHREAD_MUTEX_INITIALIZER;
static int tracking;
static read_entry *reads;
static size_t nreads, cap_reads;

void lam_file_track(int on)
{
    pthread_mutex_lock(&reads_mu);
    for (size_t i = 0; i < nreads; i++) free(reads[i].path);
    free(reads);
    reads = NULL;
    nreads = cap_reads = 0;
    tracking = on;
    pthread_mutex_unlock(&reads_mu);
}

static read_entry *find_read(const struct stat *st)
{
    for (size_t i = 0; i < nreads; i++)
        if (reads[i].dev == st->st_dev && reads[i].ino == st->st_ino) return &reads[i];
    return NULL;
}

int lam_file_note_read(const struct stat *st, const char *path)
{
    int rc = LAM_OK;
    pthread_mutex_lock(&reads_mu);
    if (tracking && !find_read(st)) {
        read_entry *nr = lam_grow(reads, &cap_reads, nreads + 1, sizeof *nr, 16);
        char *copy = strdup(path);
        if (nr) reads = nr;
        if (nr && copy) reads[nreads++] = (read_entry){ st->st_dev, st->st_ino, copy };
        else {
            free(copy);
            rc = LAM_ENOMEM;
        }
    }
    pthread_mutex_unlock(&reads_mu);
    return rc;
}

int lam_file_was_read(const struct stat *st, char *as, size_t size)
{
    pthread_mutex_lock(&reads_mu);
    const read_entry *e = find_read(st);
    if (e && as && size) snprintf(as, size, "%s", e->path);
    pthread_mutex_unlock(&reads_mu);
    return e != NULL;
}

/* ---- opening ------------------------------------------------------------------ */

int lam_file_open(const char *path, int *fd_out, struct stat *st, lam_error *err)
{
    *fd_out = -1;
    int rc = ask_gate(path, err);
    if (rc) return rc;
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) return lam_error_set(err, LAM_EIO, path, 0, 0, "cannot open: %s", strerror(errno));
    const char *bad = NULL;
    if (fstat(fd, st) != 0) bad = strerror(errno);
    else if (S_ISDIR(st->st_mode)) bad = "is a directory";
    else if (!S_ISREG(st->st_mode)) bad = "is not a regular file (a device, FIFO or socket)";
    if (bad) {
        close(fd);
        return lam_error_set(err, LAM_EIO, path, 0, 0, "cannot read: %s", bad);
    }
    /* recorded when opened: an output refuses it from here on, also when
     * the read fails half-way */
    if (lam_file_note_read(st, path)) {
        close(fd);
        return lam_error_set(err, LAM_ENOMEM, path, 0, 0, "out of memory");
    }
    *fd_out = fd;
    return LAM_OK;
}

/* Open a regular file within the limit for reading into *fd. */
static int open_regular(const char *path, lam_read_limit limit, struct stat *st, int *fd_out, lam_error *err)
{
    if (limit.bytes == 0) return bad_limit(path, err);
    int fd, rc = lam_file_open(path, &fd, st, err);
    if (rc) return rc;
    if ((unsigned long long)st->st_size > limit.bytes) {
        close(fd);
        return too_large(path, limit, (unsigned long long)st->st_size, err);
    }
    *fd_out = fd;
    return LAM_OK;
}

/* Read fd to its end into a NUL-terminated malloc'd buffer, at most
 * limit.bytes; cap is the first buffer's size (the file's size, a hint). */
static int read_fd(int fd, const char *path, lam_read_limit limit, size_t cap, char **data, size_t *len, lam_error *err)
{
    /* read up to one byte past the limit to see the input pass it */
    size_t n = 0;
    char *buf = malloc(cap);
    int rc = buf ? LAM_OK : lam_error_set(err, LAM_ENOMEM, path, 0, 0, "out of memory reading the file");
    while (rc == LAM_OK) {
        if (n + 1 >= cap) {
            size_t ncap = cap * 2 > limit.bytes + 2 ? limit.bytes + 2 : cap * 2;
            char *nb = ncap > cap ? realloc(buf, ncap) : NULL;
            if (!nb) {
                rc = ncap > cap ? lam_error_set(err, LAM_ENOMEM, path, 0, 0, "out of memory reading the file")
                                : too_large(path, limit, limit.bytes, err);
                break;
            }
            buf = nb;
            cap = ncap;
        }
        ssize_t got = read(fd, buf + n, cap - 1 - n);
        if (got < 0 && errno == EINTR) continue;
        if (got < 0) rc = lam_error_set(err, LAM_EIO, path, 0, 0, "read error: %s", strerror(errno));
        else if (got == 0) break;
        else n += (size_t)got;
        /* reading stops there: how much more would come is unknown */
        if (rc == LAM_OK && n > limit.bytes) rc = too_large(path, limit, limit.bytes, err);
    }
    if (rc) {
        free(buf);
        return rc;
    }
    buf[n] = '\0';
    *data = buf;
    *len = n;
    return LAM_OK;
}

int lam_read_file(const char *path, lam_read_limit limit, char **data, size_t *len, lam_error *err)
{
    *data = NULL;
    *len = 0;
    struct stat st;
    int fd = -1, rc = open_regular(path, limit, &st, &fd, err);
    if (rc) return rc;
    rc = read_fd(fd, path, limit, (size_t)st.st_size + 2, data, len, err);
    close(fd);
    return rc;
}

int lam_read_stdin(lam_read_limit limit, char **data, size_t *len, lam_error *err)
{
    *data = NULL;
    *len = 0;
    if (limit.bytes == 0) return bad_limit(LAM_STDIN_NAME, err);
    return read_fd(STDIN_FILENO, LAM_STDIN_NAME, limit, limit.bytes < 65536 ? limit.bytes + 2 : 65536, data, len, err);
}

int lam_map_file(const char *path, lam_read_limit limit, char **data, size_t *len, int *mapped, lam_error *err)
{
    *mapped = 0;
    struct stat st;
    int fd = -1, rc = open_regular(path, limit, &st, &fd, err);
    if (rc) return rc;
    long page = sysconf(_SC_PAGESIZE);
    /* Only when the size is not a whole number of pages: the system
     * zero-fills the rest of the last page, so the mapping ends in the NUL
     * the text readers rely on. Anything else is read. */
    if (page > 0 && st.st_size > 0 && st.st_size % page != 0) {
        void *p = mmap(NULL, (size_t)st.st_size, PROT_READ, MAP_PRIVATE, fd, 0);
        if (p != MAP_FAILED) {
            close(fd);
            *data = p;
            *len = (size_t)st.st_size;
            *mapped = 1;
            return LAM_OK;
        }
    }
    close(fd);
    return lam_read_file(path, limit, data, len, err);
}

void lam_unmap_file(char *data, size_t len, int mapped)
{
    if (mapped) munmap(data, len);
    else free(data);
}
