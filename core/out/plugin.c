/* realpath, S_ISVTX (XSI) */
#define _XOPEN_SOURCE 700
#include "plugin.h"

#include "dialect.h"
#include "grow.h"

#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "file.h"
#include "lamina_plugin.h"
#include "paths.h"

#include "version.h"

#define MSG_MAX 1024
#define MAX_DIRS 16

/* One loaded plugin. The host struct handed to the plugin is the first
 * member, so set_error and register_writer find their plugin from it; each
 * plugin has its own (heap-allocated, stable) copy, which it may keep. */
typedef struct plugin {
    struct lamina_host host;
    char *path;
    dev_t dev;
    ino_t ino;
    int fd;                  /* the file checked and loaded, open while loaded */
    void *handle;
    char reg_msg[MSG_MAX];   /* why a register_writer call was refused */
    int reg_failed;
} plugin;

/* A registered writer: a host-side copy of the plugin's struct holding the
 * members up to the size the plugin declared (the rest stay NULL). */
typedef struct writer_entry {
    struct lamina_writer w;
    plugin *owner;
} writer_entry;

static plugin **plugins;
static size_t nplugins, cap_plugins;
static writer_entry **writers;
static size_t nwriters, cap_writers;

/* The registry above is guarded by one mutex, so any thread may load
 * plugins and make sinks. Recursive: lam_plugin_load holds it while the
 * plugin's init calls register_writer, and lam_plugin_writer_sink while it
 * loads the plugin that provides a writer (also no other thread sees the
 * writers of a plugin whose init then fails). */
static pthread_mutex_t registry_mu;
static pthread_once_t registry_once = PTHREAD_ONCE_INIT;

static void registry_init(void)
{
    pthread_mutexattr_t a;
    pthread_mutexattr_init(&a);
    pthread_mutexattr_settype(&a, PTHREAD_MUTEX_RECURSIVE);
    pthread_mutex_init(&registry_mu, &a);
    pthread_mutexattr_destroy(&a);
}

static void registry_lock(void)
{
    pthread_once(&registry_once, registry_init);
    pthread_mutex_lock(&registry_mu);
}

static void registry_unlock(void) { pthread_mutex_unlock(&registry_mu); }

/* the smallest declared size that still holds member m */
#define HOLDS(size, type, m) ((size) >= offsetof(type, m) + sizeof(((type *)0)->m))

/* ---- the host functions a plugin calls ---- */

/* The last host->set_error message of this thread, "" if none: per thread,
 * as worker threads format layers through writers at the same time
 * (lamina_writer.layer_written); read right after the call that failed. */
static _Thread_local char last_msg[MSG_MAX];

static void host_set_error(const struct lamina_host *host, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

static void host_set_error(const struct lamina_host *host, const char *fmt, ...)
{
    if (!host || !fmt) return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(last_msg, sizeof last_msg, fmt, ap);
    va_end(ap);
}

static writer_entry *find_writer(const char *name)
{
    for (size_t i = 0; i < nwriters; i++)
        if (strcmp(writers[i]->w.name, name) == 0) return writers[i];
    return NULL;
}

static int refuse(plugin *p, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

static int refuse(plugin *p, const char *fmt, ...)
{
    if (!p->reg_failed) {   /* keep the first reason */
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(p->reg_msg, sizeof p->reg_msg, fmt, ap);
        va_end(ap);
    }
    p->reg_failed = 1;
    return 1;
}

static int register_writer(const struct lamina_host *host, const struct lamina_writer *w)
{
    if (!host) return 1;
    plugin *p = (plugin *)(uintptr_t)host;
    if (!w) return refuse(p, "plugin %s registered a NULL writer", p->path);
    size_t size = w->size;
    /* name, begin, layer, polyline and end are required; description and
     * abort are optional */
    if (!HOLDS(size, struct lamina_writer, end))
        return refuse(p, "plugin %s registered a writer whose struct is too small (%zu bytes; "
                      "at least %zu needed)", p->path, size,
                      offsetof(struct lamina_writer, end) + sizeof w->end);
    struct lamina_writer copy;
    memset(&copy, 0, sizeof copy);
    memcpy(&copy, w, size < sizeof copy ? size : sizeof copy);
    copy.size = sizeof copy;
    if (!copy.name || !copy.name[0])
        return refuse(p, "plugin %s registered a writer without a name", p->path);
    if (!copy.begin || !copy.layer || !copy.polyline || !copy.end)
        return refuse(p, "plugin %s: writer '%s' lacks one of begin, layer, polyline, end",
                      p->path, copy.name);
    writer_entry *dup = find_writer(copy.name);
    if (dup)
        return refuse(p, "plugin %s: writer '%s' is already registered (by plugin %s)", p->path,
                      copy.name, dup->owner->path);
    if (nwriters == cap_writers) {
        size_t cap = cap_writers ? 2 * cap_writers : 8;
        writer_entry **nw = realloc(writers, cap * sizeof *nw);
        if (!nw) return refuse(p, "out of memory registering writer '%s'", copy.name);
        writers = nw;
        cap_writers = cap;
    }
    writer_entry *e = malloc(sizeof *e);
    if (!e) return refuse(p, "out of memory registering writer '%s'", copy.name);
    e->w = copy;
    e->owner = p;
    writers[nwriters++] = e;
    return 0;
}

/* A plugin's register_writer: during its init (the lock is held already)
 * or, should it keep the host, at any time. */
static int host_register_writer(const struct lamina_host *host, const struct lamina_writer *w)
{
    registry_lock();
    int rc = register_writer(host, w);
    registry_unlock();
    return rc;
}

static int host_write(struct lamina_out *out, const void *data, size_t len);

/* ---- loading ---- */

/* Remove every writer p registered (after its init failed). */
static void drop_writers_of(const plugin *p)
{
    size_t k = 0;
    for (size_t i = 0; i < nwriters; i++) {
        if (writers[i]->owner == p)
            free(writers[i]);
        else
            writers[k++] = writers[i];
    }
    nwriters = k;
}

static void free_plugin(plugin *p)
{
    if (!p) return;
    if (p->handle) dlclose(p->handle);
    if (p->fd >= 0) close(p->fd); /* after: the loaded object goes by its number */
    free(p->path);
    free(p);
}

/* ---- trusting a plugin's file ----
 *
 * A plugin is code lamina runs, so it must be code nobody but root and the
 * user could have put there (OpenSSH's StrictModes rule for its key files):
 * the file opened, and every directory from where it really is up to /,
 * and from the directory it was named in up to /, owned by root or the
 * user and not writable by group or others. One difference from OpenSSH: a
 * sticky directory (/tmp, mode 1777) passes when root or the user owns it,
 * since in it nobody may rename or remove an entry but the entry's owner
 * (checked at the next step down), the directory's owner and root; staging
 * installs and test trees live under /tmp. What is checked is the open
 * descriptor, and that descriptor is what is loaded (/proc/self/fd/N, so
 * Linux with /proc mounted): nothing can be swapped in between. */

/* Owned by root or by the user lamina runs as. */
static int trusted_owner(const struct stat *st) { return st->st_uid == 0 || st->st_uid == geteuid(); }

/* The file opened as fd, named path: a regular file, trusted (above). */
static int trusted_file(int fd, const char *path, struct stat *st, lam_error *err)
{
    if (fstat(fd, st) != 0)
        return lam_error_set(err, LAM_EIO, NULL, 0, 0, "cannot load plugin %s: %s", path, strerror(errno));
    if (!S_ISREG(st->st_mode))
        return lam_error_set(err, LAM_EIO, NULL, 0, 0, "refusing plugin %s: not a regular file", path);
    if (!trusted_owner(st))
        return lam_error_set(err, LAM_EIO, NULL, 0, 0,
                             "refusing plugin %s: the file belongs to uid %u, neither root nor you (uid %u)", path,
                             (unsigned)st->st_uid, (unsigned)geteuid());
    if (st->st_mode & (S_IWGRP | S_IWOTH))
        return lam_error_set(err, LAM_EIO, NULL, 0, 0,
                             "refusing plugin %s: the file is writable by others than its owner (mode %03o)", path,
                             (unsigned)(st->st_mode & 0777));
    return LAM_OK;
}

/* dir (a realpath: absolute, no links) and every directory above it,
 * trusted; dir is cut down as it goes. */
static int trusted_dirs(char *dir, const char *path, lam_error *err)
{
    for (;;) {
        struct stat st;
        if (lstat(dir, &st) != 0)
            return lam_error_set(err, LAM_EIO, NULL, 0, 0, "cannot load plugin %s: %s: %s", path, dir, strerror(errno));
        if (!S_ISDIR(st.st_mode))
            return lam_error_set(err, LAM_EIO, NULL, 0, 0, "refusing plugin %s: %s changed while it was checked", path,
                                 dir);
        if (!trusted_owner(&st))
            return lam_error_set(err, LAM_EIO, NULL, 0, 0,
                                 "refusing plugin %s: directory %s belongs to uid %u, neither root nor you (uid %u)",
                                 path, dir, (unsigned)st.st_uid, (unsigned)geteuid());
        if ((st.st_mode & (S_IWGRP | S_IWOTH)) && !(st.st_mode & S_ISVTX))
            return lam_error_set(err, LAM_EIO, NULL, 0, 0,
                                 "refusing plugin %s: directory %s is writable by others than its owner (mode %03o)",
                                 path, dir, (unsigned)(st.st_mode & 0777));
        char *slash = strrchr(dir, '/');
        if (!slash || slash[1] == '\0') return LAM_OK; /* "/" done */
        slash[slash == dir ? 1 : 0] = '\0';
    }
}

/* The directory part of path ("." when none), malloc'd. */
static char *dir_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    if (!slash) return strdup(".");
    size_t n = slash == path ? 1 : (size_t)(slash - path);
    char *d = malloc(n + 1);
    if (d) {
        memcpy(d, path, n);
        d[n] = '\0';
    }
    return d;
}

/* The directories of the file opened (st), named path: where it really is
 * and where it was named (a link's directory), each up to /. The file must
 * still be at its real path when they are found trusted: from then on
 * nobody else can move it. */
static int trusted_place(const char *path, const struct stat *st, lam_error *err)
{
    char *real = realpath(path, NULL), *named = dir_of(path), *named_real = named ? realpath(named, NULL) : NULL;
    char *real_dir = real ? dir_of(real) : NULL;
    int rc = LAM_OK;
    if (!named || (real && !real_dir)) rc = lam_error_nomem(err, NULL);
    else if (!real || !named_real)
        rc = lam_error_set(err, LAM_EIO, NULL, 0, 0, "cannot load plugin %s: %s", path, strerror(errno));
    /* "DIR/x.so, which is /elsewhere/x.so": where a link led */
    char shown[2 * PATH_MAX + 16];
    const char *base = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
    if (!rc) {
        size_t k = strlen(named_real);
        int same = strncmp(real, named_real, k) == 0 && real[k] == '/' && strcmp(real + k + 1, base) == 0;
        if (!strcmp(named_real, "/")) same = real[0] == '/' && strcmp(real + 1, base) == 0;
        if (same) snprintf(shown, sizeof shown, "%s", path);
        else snprintf(shown, sizeof shown, "%s, which is %s", path, real);
    }
    if (!rc) rc = trusted_dirs(named_real, shown, err);
    if (!rc) rc = trusted_dirs(real_dir, shown, err);
    struct stat now;
    if (!rc && (stat(real, &now) != 0 || now.st_dev != st->st_dev || now.st_ino != st->st_ino))
        rc = lam_error_set(err, LAM_EIO, NULL, 0, 0, "refusing plugin %s: the file changed while it was checked", path);
    free(real);
    free(real_dir);
    free(named);
    free(named_real);
    return rc;
}

/* Open the plugin at path and check what was opened (above): *fd, with its
 * fstat in *st. Non-blocking: a FIFO cannot hang the open. */
static int open_trusted(const char *path, int *fd_out, struct stat *st, lam_error *err)
{
    int fd = open(path, O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY);
    if (fd < 0) return lam_error_set(err, LAM_EIO, NULL, 0, 0, "cannot load plugin %s: %s", path, strerror(errno));
    int rc = trusted_file(fd, path, st, err);
    if (!rc) rc = trusted_place(path, st, err);
    if (rc) close(fd);
    else *fd_out = fd;
    return rc;
}

/* dlopen the file open as *fd (the one checked) through /proc/self/fd.
 * glibc takes a name an object was loaded by for that object: a plugin that
 * could not be unloaded (C++'s unique symbols make one) keeps the name of a
 * descriptor since closed, so a number no object goes by is found first
 * (*fd may change; the plugin keeps it open while loaded, so its own name
 * stays its). name gets the name used. */
static void *dlopen_fd(int *fd, char *name, size_t size)
{
    for (int tries = 0;; tries++) {
        snprintf(name, size, "/proc/self/fd/%d", *fd);
        void *old = tries < 16 ? dlopen(name, RTLD_NOW | RTLD_LOCAL | RTLD_NOLOAD) : NULL;
        if (!old) break;
        dlclose(old);
        int nfd = fcntl(*fd, F_DUPFD_CLOEXEC, *fd + 1);
        if (nfd < 0) break;
        close(*fd);
        *fd = nfd;
    }
    dlerror();
    return dlopen(name, RTLD_NOW | RTLD_LOCAL);
}

/* dlerror's message, without the /proc name it gives for the file. */
static const char *load_error(const char *name)
{
    const char *why = dlerror();
    size_t k = strlen(name);
    if (!why) return "unknown dlopen error";
    if (access("/proc/self/fd", F_OK) != 0)
        return "/proc is not mounted (lamina loads the plugin it checked through /proc/self/fd)";
    return strncmp(why, name, k) == 0 && why[k] == ':' ? why + k + (why[k + 1] == ' ' ? 2 : 1) : why;
}

typedef int (*init_fn)(const struct lamina_host *);

/* A plugin for the file open as fd (st), with room for it in the list; it
 * is recorded as read (file.h: no output may replace it). NULL when out of
 * memory (fd is then the caller's). */
static plugin *new_plugin(const char *path, int fd, const struct stat *st)
{
    if (nplugins == cap_plugins) {
        plugin **np = lam_grow(plugins, &cap_plugins, nplugins + 1, sizeof *np, 8);
        if (!np) return NULL;
        plugins = np;
    }
    plugin *p = calloc(1, sizeof *p);
    if (!p || !(p->path = strdup(path)) || lam_file_note_read(st, path)) {
        if (p) free(p->path);
        free(p);
        return NULL;
    }
    p->fd = fd;
    p->dev = st->st_dev;
    p->ino = st->st_ino;
    return p;
}

static int load(const char *path, lam_error *err)
{
    if (!path || !*path) return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "no plugin path given");
    struct stat st;
    int fd = -1, unsafe = open_trusted(path, &fd, &st, err);
    if (unsafe) return unsafe;
    for (size_t i = 0; i < nplugins; i++)
        if (plugins[i]->dev == st.st_dev && plugins[i]->ino == st.st_ino) {
            close(fd);
            return LAM_OK;
        }

    plugin *p = new_plugin(path, fd, &st);
    if (!p) {
        close(fd);
        return lam_error_nomem(err, NULL);
    }
    char name[64];
    p->handle = dlopen_fd(&p->fd, name, sizeof name);
    if (!p->handle) {
        lam_error_set(err, LAM_EFORMAT, NULL, 0, 0, "cannot load plugin %s: %s", path, load_error(name));
        free_plugin(p);
        return LAM_EFORMAT;
    }

    const uint32_t *abi = dlsym(p->handle, "lamina_plugin_abi");
    if (!abi) {
        lam_error_set(err, LAM_EFORMAT, NULL, 0, 0,
                      "plugin %s does not export lamina_plugin_abi "
                      "(not a lamina plugin? a plugin declares LAMINA_PLUGIN_DECLARE;)", path);
        free_plugin(p);
        return LAM_EFORMAT;
    }
    if (*abi != LAMINA_PLUGIN_ABI) {
        lam_error_set(err, LAM_EFORMAT, NULL, 0, 0,
                      "plugin %s was built for lamina plugin ABI %u, this lamina speaks %u "
                      "(rebuild the plugin against this lamina's lamina_plugin.h)",
                      path, (unsigned)*abi, (unsigned)LAMINA_PLUGIN_ABI);
        free_plugin(p);
        return LAM_EFORMAT;
    }
    void *sym = dlsym(p->handle, "lamina_plugin_init");
    if (!sym) {
        lam_error_set(err, LAM_EFORMAT, NULL, 0, 0,
                      "plugin %s does not export lamina_plugin_init "
                      "(int lamina_plugin_init(const struct lamina_host *host))", path);
        free_plugin(p);
        return LAM_EFORMAT;
    }
    init_fn init = (init_fn)sym;   /* POSIX: dlsym results convert to function pointers */

    p->host.size = sizeof p->host;
    p->host.abi = LAMINA_PLUGIN_ABI;
    p->host.version = LAMINA_VERSION;
    p->host.register_writer = host_register_writer;
    p->host.write = host_write;
    p->host.set_error = host_set_error;

    last_msg[0] = '\0';
    int rc = init(&p->host);
    if (rc != 0 || p->reg_failed) {
        if (p->reg_failed)
            lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "%s", p->reg_msg);
        else if (last_msg[0])
            lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "plugin %s failed to initialise: %s", path, last_msg);
        else
            lam_error_set(err, LAM_EINVAL, NULL, 0, 0,
                          "plugin %s failed to initialise (lamina_plugin_init returned %d)", path, rc);
        drop_writers_of(p);
        free_plugin(p);
        return LAM_EINVAL;
    }
    last_msg[0] = '\0';
    plugins[nplugins++] = p;
    return LAM_OK;
}

int lam_plugin_load(const char *path, lam_error *err)
{
    registry_lock();
    int rc = load(path, err);
    registry_unlock();
    return rc;
}

void lam_plugins_unload(void)
{
    registry_lock();
    for (size_t i = 0; i < nwriters; i++) free(writers[i]);
    free(writers);
    writers = NULL;
    nwriters = cap_writers = 0;
    /* last loaded first, in case one plugin's code refers to another's */
    while (nplugins > 0) free_plugin(plugins[--nplugins]);
    free(plugins);
    plugins = NULL;
    cap_plugins = 0;
    registry_unlock();
}

static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(const char *const *)a, *(const char *const *)b);
}

static size_t writer_names(const char **names, size_t max)
{
    if (!names) return nwriters;
    size_t n = nwriters < max ? nwriters : max;
    if (n == nwriters) {
        for (size_t i = 0; i < n; i++) names[i] = writers[i]->w.name;
        qsort(names, n, sizeof *names, cmp_str);
        return nwriters;
    }
    /* only the first max of the sorted list: sort a full copy */
    const char **all = malloc(nwriters * sizeof *all);
    if (!all) {
        for (size_t i = 0; i < n; i++) names[i] = writers[i]->w.name;
        return nwriters;
    }
    for (size_t i = 0; i < nwriters; i++) all[i] = writers[i]->w.name;
    qsort(all, nwriters, sizeof *all, cmp_str);
    memcpy(names, all, n * sizeof *names);
    free(all);
    return nwriters;
}

size_t lam_plugin_writers(const char **names, size_t max)
{
    registry_lock();
    size_t n = writer_names(names, max);
    registry_unlock();
    return n;
}

/* ---- scanning the plugin directories ---- */

/* A growable text, for messages that list things. */
typedef struct text {
    char buf[MSG_MAX];
    size_t len;
} text;

static void text_add(text *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

static void text_add(text *t, const char *fmt, ...)
{
    if (t->len >= sizeof t->buf - 1) return;
    va_list ap;
    va_start(ap, fmt);
    int k = vsnprintf(t->buf + t->len, sizeof t->buf - t->len, fmt, ap);
    va_end(ap);
    if (k > 0) t->len += (size_t)k;
    if (t->len > sizeof t->buf - 1) t->len = sizeof t->buf - 1;
}

/* A writer name that can name a file: letters, digits, '-', '_', '.', not
 * starting with '.'. */
static int file_name_ok(const char *name)
{
    size_t n = strlen(name);
    if (n == 0 || n > 64 || name[0] == '.') return 0;
    for (size_t i = 0; i < n; i++) {
        unsigned char c = (unsigned char)name[i];
        if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
              c == '_' || c == '.'))
            return 0;
    }
    return 1;
}

/* Load NAME.so from the first plugin directory that has it (see plugin.h);
 * only that file is opened, so no other plugin's code runs. */
static int load_named(const char *name, char **dirs, size_t ndirs, lam_error *err)
{
    if (!file_name_ok(name))
        return lam_error_set(err, LAM_EINVAL, NULL, 0, 0,
                             "unknown writer: a writer name is letters, digits, '-', '_' and '.' (a plugin file "
                             "NAME.so)");
    for (size_t d = 0; d < ndirs; d++) {
        size_t need = strlen(dirs[d]) + strlen(name) + 5;
        char *full = malloc(need);
        if (!full) return lam_error_nomem(err, NULL);
        snprintf(full, need, "%s/%s.so", dirs[d], name);
        struct stat st;
        if (stat(full, &st) != 0) {
            free(full);
            continue;
        }
        int rc = lam_plugin_load(full, err);
        if (rc == LAM_OK && !find_writer(name))
            rc = lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "plugin %s does not provide writer '%s'", full, name);
        free(full);
        return rc;
    }
    text t = {.len = 0};
    text_add(&t, "unknown writer '%s' (no %s.so in", name, name);
    for (size_t i = 0; i < ndirs; i++) text_add(&t, "%s %s", i ? "," : "", dirs[i]);
    if (!ndirs) text_add(&t, " any plugin directory: set LAMINA_PLUGINS");
    text_add(&t, ")");
    return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "%s", t.buf);
}

/* ---- the sink adapter ---- */

/* Where a writer's bytes go: the output, or (w NULL: a worker's state,
 * the fork member) a buffer holding the layer being formatted. */
struct lamina_out {
    lam_writer *w;
    int failed;              /* a write failed (the lam_writer's error is sticky) */
    char *buf;
    size_t len, cap;
};

static int host_write(struct lamina_out *out, const void *data, size_t len)
{
    if (!out || (!data && len)) return 1;
    if (!out->w) {
        if (len > out->cap - out->len) {
            size_t cap = out->cap ? out->cap : 4096;
            while (cap - out->len < len) {
                if (cap > SIZE_MAX / 2) return out->failed = 1;
                cap *= 2;
            }
            char *nb = realloc(out->buf, cap);
            if (!nb) return out->failed = 1;
            out->buf = nb;
            out->cap = cap;
        }
        if (len) memcpy(out->buf + out->len, data, len);
        out->len += len;
        return 0;
    }
    if (lam_writer_write(out->w, data, len) != LAM_OK) {
        out->failed = 1;
        return 1;
    }
    return 0;
}

typedef struct plugin_sink {
    const writer_entry *we;
    struct lamina_out out;
    lam_error *err;
    void *state;             /* the writer's, between begin and end */
    int begun, ended;
    struct lamina_job job;   /* as begin had it, for the workers' states */
    const char **labels;     /* job.labels (owned; the texts are the caller's job's) */
    size_t layer;            /* the layer last begun (a worker's) */
} plugin_sink;

/* Turn a writer's failure (rc != 0) or a failed write into an error. */
static int writer_result(plugin_sink *s, int rc, const char *what)
{
    const char *name = s->we->w.name;
    const char *msg = last_msg;
    if (s->out.failed && !s->out.w) return lam_error_nomem(s->err, "formatting a layer");
    if (s->out.failed)
        return lam_error_set(s->err, LAM_EIO, NULL, 0, 0, "writer %s: cannot write output", name);
    if (rc == 0) return LAM_OK;
    if (msg[0]) {
        /* "cli-binary: ..." from the plugin already says which writer */
        size_t k = strlen(name);
        int named = strncmp(msg, name, k) == 0 && msg[k] == ':';
        if (named) return lam_error_set(s->err, LAM_EINVAL, NULL, 0, 0, "%s", msg);
        return lam_error_set(s->err, LAM_EINVAL, NULL, 0, 0, "writer %s: %s", name, msg);
    }
    return lam_error_set(s->err, LAM_EINVAL, NULL, 0, 0, "writer %s: %s failed", name, what);
}

static int not_running(plugin_sink *s, const char *what)
{
    return lam_error_set(s->err, LAM_EUSAGE, NULL, 0, 0, "writer %s: %s %s", s->we->w.name, what,
                         s->ended ? "after end" : "before begin");
}

static int ps_begin(void *ctx, const lam_job_info *job)
{
    plugin_sink *s = ctx;
    if (s->begun)
        return lam_error_set(s->err, LAM_EUSAGE, NULL, 0, 0, "writer %s: begin called twice", s->we->w.name);
    struct lamina_job j;
    memset(&j, 0, sizeof j);
    j.size = sizeof j;
    j.machine = job->name;
    j.process = job->process;
    j.units = job->units;
    j.layers = job->layers;
    memcpy(j.bbox, job->bbox, sizeof j.bbox);
    j.bead = job->bead;
    j.label = job->label ? job->label : "part";
    /* the writer's table: the job's (a label NULL: "part"), or the one label */
    int table = job->labels && job->nlabels;
    j.nlabels = table ? job->nlabels : 1;
    free(s->labels);
    if (!(s->labels = malloc(j.nlabels * sizeof *s->labels))) return lam_error_nomem(s->err, NULL);
    for (size_t k = 0; k < j.nlabels; k++) s->labels[k] = !table ? j.label : job->labels[k] ? job->labels[k] : "part";
    j.labels = s->labels;
    s->job = j;
    last_msg[0] = '\0';
    s->state = s->we->w.begin(&s->out, &j);
    if (!s->state) return writer_result(s, 1, "begin");
    s->begun = 1;
    return writer_result(s, 0, "begin");
}

static int ps_layer(void *ctx, const lam_layer_info *layer)
{
    plugin_sink *s = ctx;
    if (!s->state) return not_running(s, "layer");
    s->layer = layer->index;
    last_msg[0] = '\0';
    return writer_result(s, s->we->w.layer(s->state, layer->index, layer->z), "layer");
}

static int ps_layer_end(void *ctx, const lam_layer_info *layer)
{
    plugin_sink *s = ctx;
    (void)layer;
    return s->state ? LAM_OK : not_running(s, "layer_end");
}

static int ps_contour(void *ctx, const lam_contour_info *c)
{
    plugin_sink *s = ctx;
    if (!s->state) return not_running(s, "contour");
    last_msg[0] = '\0';
    return writer_result(s, s->we->w.polyline(s->state, (size_t)lam_attrs_id(&c->attrs), c->solid, c->uv, c->n), "polyline");
}

static int ps_hatches(void *ctx, const lam_hatch_info *h)
{
    plugin_sink *s = ctx;
    if (!s->state) return not_running(s, "hatches");
    if (!s->we->w.hatches)
        return lam_error_set(s->err, LAM_EUSAGE, NULL, 0, 0, "writer %s cannot write hatches (set hatch_strategy: none)",
                             s->we->w.name);
    last_msg[0] = '\0';
    return writer_result(s, s->we->w.hatches(s->state, (size_t)lam_attrs_id(&h->attrs), h->uv, h->n), "hatches");
}

static int ps_end(void *ctx)
{
    plugin_sink *s = ctx;
    if (!s->state) return not_running(s, "end");
    last_msg[0] = '\0';
    void *state = s->state;
    s->state = NULL;          /* end frees the state, whatever it returns */
    s->ended = 1;
    return writer_result(s, s->we->w.end(state), "end");
}

static int contour_only(plugin_sink *s)
{
    return lam_error_set(s->err, LAM_EUSAGE, NULL, 0, 0,
                         "writer %s handles contour programs (SLS) only", s->we->w.name);
}

static int ps_feed(void *ctx, double rate)
{
    (void)rate;
    return contour_only(ctx);
}

static int ps_laser(void *ctx, int on)
{
    (void)on;
    return contour_only(ctx);
}

static int ps_move(void *ctx, const lam_move_info *m)
{
    (void)m;
    return contour_only(ctx);
}

static void ps_destroy(void *ctx)
{
    plugin_sink *s = ctx;
    if (!s) return;
    if (s->state && s->we->w.abort) s->we->w.abort(s->state);
    free(s->out.buf);
    free(s->labels);
    free(s);
}

/* A sink on s with the calls of a layer (a worker's sink has no more). */
static void layer_calls(lam_sink *out, plugin_sink *s)
{
    *out = (lam_sink){ .ctx = s, .layer = ps_layer, .layer_end = ps_layer_end, .feed = ps_feed, .laser = ps_laser,
                       .move = ps_move, .contour = ps_contour, .hatches = ps_hatches, .destroy = ps_destroy };
}

/* A worker's sink for the plugin sink m (ps_fork, the sink's fork member). */
static int fork_of(const plugin_sink *m, lam_sink *out, lam_error *err)
{
    memset(out, 0, sizeof *out);
    if (!m->state || !m->we->w.layer_written || !m->we->w.abort) return LAM_EUSAGE;
    plugin_sink *s = calloc(1, sizeof *s);
    if (!s) return lam_error_nomem(err, "starting threads");
    s->we = m->we;
    s->err = err;
    s->job = m->job;
    last_msg[0] = '\0';
    s->state = s->we->w.begin(&s->out, &s->job);
    if (!s->state || s->out.failed) {
        ps_destroy(s); /* the caller formats on its own thread instead */
        return LAM_EUSAGE;
    }
    s->begun = 1;
    s->out.len = 0; /* the header: the file has it from main's begin */
    layer_calls(out, s);
    return LAM_OK;
}

static void fork_start(void *ctx, lam_error *err)
{
    plugin_sink *s = ctx;
    s->err = err;
    s->out.len = 0;
    s->out.failed = 0;
}

static void fork_take(void *ctx, lam_layer_text *t)
{
    plugin_sink *s = ctx;
    char *keep = t->s;
    size_t keep_cap = t->cap;
    memset(t, 0, sizeof *t);
    t->s = s->out.buf;
    t->len = s->out.len;
    t->cap = s->out.cap;
    t->complete = 1;
    t->layer = s->layer;
    s->out.buf = keep; /* the buffer the writer is done with, for the next layer */
    s->out.cap = keep_cap;
    s->out.len = 0;
}

static int fork_put(void *ctx, const lam_layer_text *t)
{
    plugin_sink *s = ctx;
    if (!s->state) return not_running(s, "layer");
    if (t->len && lam_writer_write(s->out.w, t->s, t->len) != LAM_OK) s->out.failed = 1;
    last_msg[0] = '\0';
    return writer_result(s, s->out.failed ? 1 : s->we->w.layer_written(s->state, t->layer), "layer");
}

/* The sink's fork member (plan.h): writers take contours only, no moves. */
static int ps_fork(void *ctx, int moves, lam_sink_fork *out, lam_error *err)
{
    memset(out, 0, sizeof *out);
    if (moves) return LAM_EUSAGE;
    int rc = fork_of(ctx, &out->sink, err);
    if (rc) return rc;
    out->start = fork_start;
    out->take = fork_take;
    out->put = fork_put;
    out->main = ctx;
    return LAM_OK;
}

int lam_plugin_writer_sink(const char *name, lam_writer *w, lam_sink *out, lam_error *err)
{
    memset(out, 0, sizeof *out);
    if (!name || !*name) return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "no writer name given");
    if (!w) return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "writer %s: no output given", name);
    registry_lock();
    int rc = LAM_OK;
    const writer_entry *we = find_writer(name);
    if (!we) {
        /* a sanitizer build's own plugins/ first, the build tree, an installed
         * tree (lib/lamina/plugins from bin/ and from lib/lua/5.4/), a LuaRocks
         * tree (lib/lua/5.4/lamina/plugins, deployed with the C module) */
        static const char *const exe[] = { "plugins", "../plugins", "../lib/lamina/plugins", NULL };
        static const char *const module[] = { "plugins", "../plugins", "../../lamina/plugins", "lamina/plugins", NULL };
        static const lam_rel_dirs rel = { exe, module };
        char *dirs[MAX_DIRS];
        size_t ndirs = lam_search_dirs("LAMINA_PLUGINS", &rel, dirs, MAX_DIRS);
        lam_error_clear(err);
        rc = load_named(name, dirs, ndirs, err);
        for (size_t i = 0; i < ndirs; i++) free(dirs[i]);
        we = rc ? NULL : find_writer(name);
    }
    registry_unlock();
    if (rc) return rc;
    plugin_sink *s = calloc(1, sizeof *s);
    if (!s) return lam_error_nomem(err, NULL);
    s->we = we;
    s->out.w = w;
    s->err = err;
    layer_calls(out, s);
    out->begin = ps_begin;
    out->end = ps_end;
    out->fork = ps_fork;
    return LAM_OK;
}

int lam_program_text(const char *writer)
{
    return !writer || !strcmp(writer, "text");
}

int lam_program_sink(const char *writer, const lam_dialect *d, lam_writer *w, lam_sink *out, lam_error *err)
{
    return lam_program_text(writer) ? lam_dialect_sink(d, w, out, err) : lam_plugin_writer_sink(writer, w, out, err);
}
