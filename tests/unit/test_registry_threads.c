/* The process-wide registries under threads (issue 23): the plugin registry
 * (plugin.h: loading, listing, unloading from several threads at once) and
 * the file gate (file.h: a reader on one thread while another sets the
 * gate never sees one gate with another's context).
 *
 * Paths as test_plugin.c: the cli plugin is $BUILD/plugins/cli-binary.so
 * when that exists (SAN=1 builds), else plugins/cli-binary.so. */
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "error.h"
#include "file.h"
#include "plugin.h"
#include "tap.h"

#define THREADS 8
#define ROUNDS 200

static char cli_path[1300];

/* ---- plugins ---- */

typedef struct load_job {
    int failures; /* loads that did not return LAM_OK */
    int missing;  /* listings without the writer after a load */
} load_job;

static void *loader(void *arg)
{
    load_job *j = arg;
    for (int r = 0; r < ROUNDS; r++) {
        lam_error err;
        lam_error_clear(&err);
        if (lam_plugin_load(cli_path, &err) != LAM_OK) j->failures++;
        const char *names[16];
        size_t n = lam_plugin_writers(names, 16), found = 0;
        for (size_t i = 0; i < n && i < 16; i++) found += strcmp(names[i], "cli-binary") == 0;
        if (found != 1) j->missing++;
    }
    return NULL;
}

static void test_plugins(void)
{
    for (int pass = 0; pass < 3; pass++) {
        pthread_t t[THREADS];
        load_job jobs[THREADS];
        memset(jobs, 0, sizeof jobs);
        for (int i = 0; i < THREADS; i++) pthread_create(&t[i], NULL, loader, &jobs[i]);
        int failures = 0, missing = 0;
        for (int i = 0; i < THREADS; i++) {
            pthread_join(t[i], NULL);
            failures += jobs[i].failures;
            missing += jobs[i].missing;
        }
        is_int(failures, 0, "pass %d: %d threads load the same plugin at once, every load succeeds", pass, THREADS);
        is_int(missing, 0, "pass %d: every listing after a load shows its writer once", pass);
        is_int(lam_plugin_writers(NULL, 0), 1, "pass %d: the writer is registered once", pass);
        lam_plugins_unload();
        is_int(lam_plugin_writers(NULL, 0), 0, "pass %d: unloaded, nothing is registered", pass);
    }
}

/* ---- the file gate ---- */

static int ctx_a, ctx_b;

/* Each gate lets a file through only with its own context. */
static int gate_a(void *ctx, const char *path, lam_error *err)
{
    return ctx == &ctx_a ? LAM_OK : lam_error_set(err, LAM_EINVAL, path, 0, 0, "gate a with another context");
}

static int gate_b(void *ctx, const char *path, lam_error *err)
{
    return ctx == &ctx_b ? LAM_OK : lam_error_set(err, LAM_EINVAL, path, 0, 0, "gate b with another context");
}

static const char *gate_file;
static volatile int gate_stop;

static void *opener(void *arg)
{
    int *torn = arg;
    while (!gate_stop) {
        int fd;
        struct stat st;
        lam_error err;
        lam_error_clear(&err);
        if (lam_file_open(gate_file, &fd, &st, &err) == LAM_OK) close(fd);
        else (*torn)++;
    }
    return NULL;
}

static void test_gate(void)
{
    char path[] = "/tmp/lamina-gate-XXXXXX";
    int fd = mkstemp(path);
    ok(fd >= 0, "a file to read");
    if (fd < 0) return;
    if (write(fd, "x\n", 2) != 2) diag("short write");
    close(fd);
    gate_file = path;
    gate_stop = 0;
    pthread_t t[THREADS];
    int torn[THREADS] = { 0 };
    for (int i = 0; i < THREADS; i++) pthread_create(&t[i], NULL, opener, &torn[i]);
    for (int r = 0; r < 20000; r++) {
        if (r % 3 == 0) lam_file_set_gate(gate_a, &ctx_a, NULL, NULL);
        else if (r % 3 == 1) lam_file_set_gate(gate_b, &ctx_b, NULL, NULL);
        else lam_file_set_gate(NULL, NULL, NULL, NULL);
    }
    gate_stop = 1;
    int all = 0;
    for (int i = 0; i < THREADS; i++) {
        pthread_join(t[i], NULL);
        all += torn[i];
    }
    lam_file_set_gate(NULL, NULL, NULL, NULL);
    is_int(all, 0, "readers on %d threads never see a gate with the other gate's context", THREADS);
    lam_file_gate old;
    void *old_ctx;
    lam_file_set_gate(gate_a, &ctx_a, NULL, NULL);
    lam_file_set_gate(NULL, NULL, &old, &old_ctx);
    ok(old == gate_a && old_ctx == &ctx_a, "set_gate hands back the gate and context it replaced");
    unlink(path);
}

int main(void)
{
    const char *b = getenv("BUILD");
    struct stat st;
    snprintf(cli_path, sizeof cli_path, "%s/plugins/cli-binary.so", b && *b ? b : "build");
    if (stat(cli_path, &st) != 0) snprintf(cli_path, sizeof cli_path, "plugins/cli-binary.so");
    diag("cli plugin: %s", cli_path);
    test_plugins();
    test_gate();
    return done_testing();
}
