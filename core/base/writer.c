/* realpath (XSI); flock (BSD) */
#define _XOPEN_SOURCE 700
#define _DEFAULT_SOURCE
#include "writer.h"

#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include "buf.h"
#include "file.h"

enum kind { W_FILE, W_DEVICE, W_STREAM, W_MEMORY };

struct lam_writer {
    enum kind kind;
    FILE *f;
    char *path, *tmp;      /* W_FILE */
    lam_buf mem;           /* W_MEMORY */
    int failed;            /* errno of the first failure, 0 if none */
    int lockfd;            /* W_FILE: holds the temporary's flock until commit/abort */
    unsigned long long written, limit;
};

/* EFBIG stands for "over lam_writer_set_limit" in `failed`. */
#define OVER_LIMIT EFBIG

/* ---- the registry of live temporaries ------------------------------------ */

/* Read by lam_writer_unlink_temps in a signal handler: a slot holds a path
 * only while that string is allocated and complete, and is cleared before
 * the string is freed. Writers live in one thread (the CLI's and the Lua
 * binding's), so plain volatile pointers do. */
#define MAX_LIVE 64
static char *volatile live[MAX_LIVE];

static void live_add(char *path)
{
    for (size_t i = 0; i < MAX_LIVE; i++)
        if (!live[i]) {
            live[i] = path;
            return;
        }
}

static void live_remove(const char *path)
{
    for (size_t i = 0; i < MAX_LIVE; i++)
        if (live[i] == path) live[i] = NULL;
}

void lam_writer_unlink_temps(void)
{
    for (size_t i = 0; i < MAX_LIVE; i++) {
        char *p = live[i];
        if (p) unlink(p);
    }
}

/* ---- stale temporaries ------------------------------------------------------ */

/* name is BASE ".tmp-" DIGITS "-" six characters (what create_temp makes). */
static int is_temp_name(const char *name, const char *base, size_t nbase)
{
    if (strncmp(name, base, nbase) != 0 || strncmp(name + nbase, ".tmp-", 5) != 0) return 0;
    const char *p = name + nbase + 5;
    if (!isdigit((unsigned char)*p)) return 0;
    while (isdigit((unsigned char)*p)) p++;
    return *p == '-' && strlen(p + 1) == 6;
}

/* Remove the temporaries of `target` that no live writer holds (writer.h). */
static void remove_stale(const char *target)
{
    const char *slash = strrchr(target, '/');
    const char *base = slash ? slash + 1 : target;
    size_t nbase = strlen(base), ndir = slash ? (size_t)(slash - target) + 1 : 0;
    char *dirpath = malloc(ndir + 2), *full = malloc(ndir + nbase + 64);
    DIR *dir = NULL;
    if (dirpath && full) {
        if (ndir) memcpy(dirpath, target, ndir);
        else dirpath[ndir++] = '.';
        dirpath[ndir] = '\0';
        dir = opendir(dirpath);
    }
    struct dirent *de;
    uid_t me = geteuid();
    while (dir && (de = readdir(dir))) {
        if (!is_temp_name(de->d_name, base, nbase) || strlen(de->d_name) > nbase + 40) continue;
        snprintf(full, ndir + nbase + 64, "%.*s%s", (int)(slash ? ndir : 0), target, de->d_name);
        struct stat ls, fs;
        if (lstat(full, &ls) != 0 || !S_ISREG(ls.st_mode) || ls.st_uid != me) continue;
        int fd = open(full, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
        if (fd < 0) continue;
        /* a lock nobody holds: its writer is gone; the same file still at
         * that name (not replaced in between) */
        if (flock(fd, LOCK_EX | LOCK_NB) == 0 && fstat(fd, &fs) == 0 && fs.st_ino == ls.st_ino &&
            fs.st_dev == ls.st_dev)
            unlink(full);
        close(fd);
    }
    if (dir) closedir(dir);
    free(dirpath);
    free(full);
}

/* ---- outputs that would replace inputs ---------------------------------------- */

/* LAM_EUSAGE when st (a regular file) is one the command read (file.h):
 * writing it would destroy an input. `shown` is the output as its caller
 * named it. */
static int refuse_input(const struct stat *st, const char *shown, lam_error *err)
{
    char as[512];
    if (!S_ISREG(st->st_mode) || !lam_file_was_read(st, as, sizeof as)) return LAM_OK;
    return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "%s is an input of this command (read as %s): refusing to overwrite it",
                         shown, as);
}

int lam_writer_check(const char *path, lam_error *err)
{
    struct stat st;
    return stat(path, &st) == 0 ? refuse_input(&st, path, err) : LAM_OK;
}

int lam_writer_check_stream(FILE *f, const char *shown, lam_error *err)
{
    struct stat st;
    int fd = f ? fileno(f) : -1;
    return fd >= 0 && fstat(fd, &st) == 0 ? refuse_input(&st, shown, err) : LAM_OK;
}

/* An existing target that is not a regular file (a terminal, /dev/null, a
 * pipe): written to directly, since renaming over it would replace the
 * device or pipe with a plain file. */
static int open_device(const char *path, lam_writer **out, lam_error *err)
{
    lam_writer *w = calloc(1, sizeof *w);
    if (!w || !(w->path = strdup(path))) {
        free(w);
        return lam_error_set(err, LAM_ENOMEM, path, 0, 0, "out of memory");
    }
    w->kind = W_DEVICE;
    if (!(w->f = fopen(path, "wb"))) {
        int e = errno;
        free(w->path);
        free(w);
        return lam_error_set(err, LAM_EIO, path, 0, 0, "cannot open output: %s", strerror(e));
    }
    *out = w;
    return LAM_OK;
}

/* The mode of the file at path it replaces, else the usual one. */
static mode_t target_mode(const char *path)
{
    struct stat old;
    if (stat(path, &old) == 0 && S_ISREG(old.st_mode)) return old.st_mode & 07777;
    mode_t mask = umask(0);
    umask(mask);
    return 0666 & ~mask;
}

/* A new temporary beside w->path, named into w->tmp (room bytes),
 * registered as live and locked: its descriptor, or -1 with *e the errno. */
static int create_temp(lam_writer *w, size_t room, int *e)
{
    /* Signals are held from mkstemp until the temporary is registered, so
     * a handler never misses it. Same directory as the target, so the final
     * rename is atomic. */
    sigset_t all, was;
    sigfillset(&all);
    int fd = -1;
    for (int attempt = 0; attempt < 8 && fd < 0; attempt++) {
        snprintf(w->tmp, room, "%s.tmp-%ld-XXXXXX", w->path, (long)getpid());
        sigprocmask(SIG_BLOCK, &all, &was);
        fd = mkstemp(w->tmp);
        if (fd >= 0) live_add(w->tmp);
        sigprocmask(SIG_SETMASK, &was, NULL);
        if (fd < 0) {
            *e = errno;
            break;
        }
        /* the lock marks it live (remove_stale); a cleaner that locked it
         * first (between mkstemp and here) has unlinked it: make another */
        struct stat ts;
        if (flock(fd, LOCK_EX) != 0 || fstat(fd, &ts) != 0 || ts.st_nlink == 0) {
            live_remove(w->tmp);
            close(fd);
            fd = -1;
            *e = EAGAIN;
        }
    }
    return fd;
}

int lam_writer_file(const char *path, lam_writer **out, lam_error *err)
{
    *out = NULL;
    struct stat st;
    if (stat(path, &st) == 0) {
        if (S_ISDIR(st.st_mode)) return lam_error_set(err, LAM_EIO, path, 0, 0, "cannot write output: is a directory");
        if (!S_ISREG(st.st_mode)) return open_device(path, out, err);
        int rc = refuse_input(&st, path, err);
        if (rc) return rc;
    }
    /* through a symbolic link to the file it names, so the link stays a
     * link (a dangling link is replaced); messages name the path given */
    char *real = NULL;
    struct stat lst;
    if (lstat(path, &lst) == 0 && S_ISLNK(lst.st_mode)) real = realpath(path, NULL);
    const char *target = real ? real : path;
    size_t n = strlen(target);
    lam_writer *w = calloc(1, sizeof *w);
    if (w) {
        w->path = strdup(target);
        w->tmp = malloc(n + 48);
    }
    free(real);
    if (!w || !w->path || !w->tmp) {
        if (w) {
            free(w->path);
            free(w->tmp);
        }
        free(w);
        return lam_error_set(err, LAM_ENOMEM, path, 0, 0, "out of memory");
    }
    w->kind = W_FILE;
    w->lockfd = -1;
    remove_stale(w->path);
    mode_t mode = target_mode(w->path);
    int e = 0, fd = create_temp(w, n + 48, &e);
    if (fd >= 0) {
        fchmod(fd, mode);
        w->lockfd = dup(fd);
        if (w->lockfd < 0 || !(w->f = fdopen(fd, "wb"))) e = errno;
    }
    if (fd < 0 || !w->f) {
        if (fd >= 0) {
            close(fd);
            unlink(w->tmp);
            live_remove(w->tmp);
        }
        if (w->lockfd >= 0) close(w->lockfd);
        free(w->path);
        free(w->tmp);
        free(w);
        return lam_error_set(err, LAM_EIO, path, 0, 0, "cannot create output: %s", strerror(e ? e : EIO));
    }
    *out = w;
    return LAM_OK;
}

int lam_writer_stream(FILE *f, const char *name, lam_writer **out, lam_error *err)
{
    *out = NULL;
    int rc = lam_writer_check_stream(f, name ? name : "(stream)", err);
    if (rc) return rc;
    lam_writer *w = calloc(1, sizeof *w);
    if (!w || !(w->path = strdup(name ? name : "(stream)"))) {
        free(w);
        return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory");
    }
    w->kind = W_STREAM;
    w->f = f;
    *out = w;
    return LAM_OK;
}

int lam_writer_memory(lam_writer **out, lam_error *err)
{
    *out = NULL;
    lam_writer *w = calloc(1, sizeof *w);
    if (!w) return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory");
    w->kind = W_MEMORY;
    *out = w;
    return LAM_OK;
}

void lam_writer_set_limit(lam_writer *w, unsigned long long max_bytes) { w->limit = max_bytes; }

int lam_writer_over_limit(const lam_writer *w) { return w->failed == OVER_LIMIT; }

unsigned long long lam_writer_bytes(const lam_writer *w) { return w->written; }

static const char *reason(int e, char *buf, size_t size, unsigned long long limit)
{
    if (e == OVER_LIMIT) {
        snprintf(buf, size, "output exceeds the limit of %llu bytes", limit);
        return buf;
    }
    return strerror(e ? e : EIO);
}

int lam_writer_error(const lam_writer *w, lam_error *err)
{
    if (!w->failed) return LAM_OK;
    char buf[96];
    if (w->kind == W_MEMORY && w->failed != OVER_LIMIT)
        return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory writing output");
    int code = w->failed == OVER_LIMIT ? LAM_ELIMIT : LAM_EIO;
    return lam_error_set(err, code, w->kind == W_MEMORY ? NULL : w->path, 0, 0, "cannot write output: %s",
                         reason(w->failed, buf, sizeof buf, w->limit));
}

int lam_writer_write(lam_writer *w, const void *data, size_t len)
{
    if (w->failed) return w->failed == ENOMEM ? LAM_ENOMEM : LAM_EIO;
    if (w->limit && len > w->limit - w->written) {
        w->failed = OVER_LIMIT;
        return LAM_EIO;
    }
    w->written += len;
    if (w->kind == W_MEMORY) {
        if (lam_buf_append(&w->mem, data, len)) {
            w->failed = ENOMEM;
            return LAM_ENOMEM;
        }
        return LAM_OK;
    }
    if (len && fwrite(data, 1, len, w->f) != len) {
        w->failed = errno ? errno : EIO;
        return LAM_EIO;
    }
    return LAM_OK;
}

int lam_writer_printf(lam_writer *w, const char *fmt, ...)
{
    char small[512];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(small, sizeof small, fmt, ap);
    va_end(ap);
    if (n < 0) return LAM_EINVAL;
    if ((size_t)n < sizeof small) return lam_writer_write(w, small, (size_t)n);
    char *big = malloc((size_t)n + 1);
    if (!big) {
        w->failed = ENOMEM;
        return LAM_ENOMEM;
    }
    va_start(ap, fmt);
    vsnprintf(big, (size_t)n + 1, fmt, ap);
    va_end(ap);
    int rc = lam_writer_write(w, big, (size_t)n);
    free(big);
    return rc;
}

static void release(lam_writer *w)
{
    if (w->tmp) live_remove(w->tmp);
    if (w->kind == W_FILE && w->lockfd >= 0) close(w->lockfd);
    free(w->path);
    free(w->tmp);
    lam_buf_free(&w->mem);
    free(w);
}

int lam_writer_commit(lam_writer *w, lam_error *err)
{
    /* again: a file read after the output was opened (a plugin loaded for
     * it) may be the target; the original stays as it was */
    int refused = w->kind == W_FILE     ? lam_writer_check(w->path, err)
                  : w->kind == W_STREAM ? lam_writer_check_stream(w->f, w->path, err)
                                        : LAM_OK;
    if (refused) {
        lam_writer_abort(w);
        return refused;
    }
    int bad = w->failed;
    FILE *stream = w->kind == W_STREAM ? w->f : NULL;
    if (w->kind != W_MEMORY) {
        if (fflush(w->f) != 0 && !bad) bad = errno ? errno : EIO;
        if (w->kind != W_STREAM && fclose(w->f) != 0 && !bad) bad = errno ? errno : EIO;
        w->f = NULL;
    }
    /* the temporary is renamed while its lock is still held (lockfd) */
    if (w->kind == W_FILE && !bad && rename(w->tmp, w->path) != 0) bad = errno;
    if (w->kind == W_FILE && bad) unlink(w->tmp);
    w->failed = bad;
    int rc = lam_writer_error(w, err);
    /* reported here: the stream's owner need not report it again */
    if (rc && stream) clearerr(stream);
    release(w);
    return rc;
}

void lam_writer_abort(lam_writer *w)
{
    if (!w) return;
    if (w->kind == W_FILE) {
        if (w->f) fclose(w->f);
        unlink(w->tmp);
    } else if (w->kind == W_STREAM) {
        fflush(w->f);
    } else if (w->kind == W_DEVICE) {
        fclose(w->f); /* what went out is out: a device cannot be unwritten */
    }
    release(w);
}

int lam_writer_take(lam_writer *w, char **data, size_t *len, lam_error *err)
{
    *data = NULL;
    *len = 0;
    if (w->kind != W_MEMORY) {
        lam_writer_abort(w);
        return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "not a memory writer");
    }
    if (w->failed) {
        int rc = lam_writer_error(w, err);
        release(w);
        return rc;
    }
    *data = lam_buf_take(&w->mem, len);
    release(w);
    return *data ? LAM_OK : lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory");
}
