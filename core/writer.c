/* realpath (XSI) */
#define _XOPEN_SOURCE 700
#include "writer.h"

#include <errno.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

enum kind { W_FILE, W_DEVICE, W_STREAM, W_MEMORY };

struct lam_writer {
    enum kind kind;
    FILE *f;
    char *path, *tmp;      /* W_FILE */
    char *buf;             /* W_MEMORY */
    size_t len, cap;
    int failed;            /* errno of the first failure, 0 if none */
};

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

int lam_writer_file(const char *path, lam_writer **out, lam_error *err)
{
    *out = NULL;
    struct stat st;
    if (stat(path, &st) == 0) {
        if (S_ISDIR(st.st_mode)) return lam_error_set(err, LAM_EIO, path, 0, 0, "cannot write output: is a directory");
        if (!S_ISREG(st.st_mode)) return open_device(path, out, err);
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
        w->tmp = malloc(n + 32);
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
    /* same directory as the target, so the final rename is atomic */
    snprintf(w->tmp, n + 32, "%s.tmp-XXXXXX", w->path);
    int fd = mkstemp(w->tmp);
    if (fd >= 0) {
        /* mkstemp makes the file private; the output gets the usual mode */
        mode_t mask = umask(0);
        umask(mask);
        fchmod(fd, 0666 & ~mask);
    }
    if (fd < 0 || !(w->f = fdopen(fd, "wb"))) {
        int e = errno;
        if (fd >= 0) {
            close(fd);
            unlink(w->tmp);
        }
        free(w->path);
        free(w->tmp);
        free(w);
        return lam_error_set(err, LAM_EIO, path, 0, 0, "cannot create output: %s", strerror(e));
    }
    *out = w;
    return LAM_OK;
}

int lam_writer_stream(FILE *f, const char *name, lam_writer **out, lam_error *err)
{
    *out = NULL;
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

int lam_writer_write(lam_writer *w, const void *data, size_t len)
{
    if (w->failed) return LAM_EIO;
    if (w->kind == W_MEMORY) {
        if (w->len + len + 1 > w->cap) {
            size_t cap = w->cap ? w->cap : 4096;
            while (cap < w->len + len + 1) cap *= 2;
            char *nb = realloc(w->buf, cap);
            if (!nb) {
                w->failed = ENOMEM;
                return LAM_ENOMEM;
            }
            w->buf = nb;
            w->cap = cap;
        }
        memcpy(w->buf + w->len, data, len);
        w->len += len;
        w->buf[w->len] = '\0';
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
    free(w->path);
    free(w->tmp);
    free(w->buf);
    free(w);
}

int lam_writer_commit(lam_writer *w, lam_error *err)
{
    int rc = LAM_OK;
    if (w->kind == W_FILE) {
        int bad = w->failed;
        if (fflush(w->f) != 0 && !bad) bad = errno ? errno : EIO;
        if (fclose(w->f) != 0 && !bad) bad = errno ? errno : EIO;
        w->f = NULL;
        if (!bad && rename(w->tmp, w->path) != 0) bad = errno;
        if (bad) {
            unlink(w->tmp);
            rc = lam_error_set(err, LAM_EIO, w->path, 0, 0, "cannot write output: %s", strerror(bad));
        }
    } else if (w->kind == W_STREAM || w->kind == W_DEVICE) {
        int bad = w->failed;
        if (fflush(w->f) != 0 && !bad) bad = errno ? errno : EIO;
        if (w->kind == W_DEVICE && fclose(w->f) != 0 && !bad) bad = errno ? errno : EIO;
        if (bad) rc = lam_error_set(err, LAM_EIO, w->path, 0, 0, "cannot write output: %s", strerror(bad));
    } else if (w->failed) {
        rc = lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory writing output");
    }
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
        release(w);
        return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory writing output");
    }
    *data = w->buf ? w->buf : calloc(1, 1);
    *len = w->len;
    w->buf = NULL;
    release(w);
    return *data ? LAM_OK : lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory");
}
