/* Plugins: loading and refusing (the test plugins in tests/plugins), the registry, the
 * sink adapter, and the cli-binary writer's bytes, read back by an
 * independent CLI decoder.
 *
 * Paths: $BUILD (default "build") is the build directory; the test plugins
 * are $BUILD/tests/plugins/NAME.so, the cli plugin $BUILD/plugins/cli-binary.so
 * when that exists (SAN=1 builds) else plugins/cli-binary.so (the test runs from
 * the repository root). This program lives in $BUILD/tests, so the
 * exe-relative plugin directory <exe dir>/plugins is $BUILD/tests/plugins. */
#include <dlfcn.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "plugin.h"
#include "tap.h"
#include "writer.h"

static char build_dir[1024];

static const char *test_plugin(const char *name)
{
    static char path[1200];
    snprintf(path, sizeof path, "%s/tests/plugins/%s.so", build_dir, name);
    return path;
}

static char cli_path[1300], cli_dir[1200];

static int has(const char *hay, const char *needle) { return hay && strstr(hay, needle) != NULL; }

/* ok() that hay contains needle, printing hay otherwise */
#define contains(hay, needle, ...) do { const char *h_ = (hay), *n_ = (needle); \
    ok(has(h_, n_), __VA_ARGS__); \
    if (!has(h_, n_)) diag("'%s' does not contain '%s'", h_ ? h_ : "(null)", n_); } while (0)

static int writer_listed(const char *name)
{
    const char *names[32];
    size_t n = lam_plugin_writers(names, 32);
    for (size_t i = 0; i < n && i < 32; i++)
        if (strcmp(names[i], name) == 0) return 1;
    return 0;
}

/* ---- an independent CLI (binary) reader ---- */

typedef struct cli_poly {
    int32_t id, dir, n;
    float xy[64];
} cli_poly;

typedef struct cli_layer {
    float z;
    int npoly;
    cli_poly poly[8];
} cli_layer;

typedef struct cli_file {
    char header[512];        /* the ASCII header, "$$HEADERSTART" .. "$$HEADEREND" */
    long layers_hdr;         /* $$LAYERS */
    int binary;              /* $$BINARY present */
    char units[64], version[64];
    int nlayer;
    cli_layer layer[8];
    char error[256];         /* "" when the file decoded cleanly to its end */
} cli_file;

static uint32_t rd_u32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static float rd_f32(const unsigned char *p)
{
    uint32_t bits = rd_u32(p);
    float f;
    memcpy(&f, &bits, sizeof f);
    return f;
}

static int32_t rd_i32(const unsigned char *p)
{
    uint32_t u = rd_u32(p);
    return u <= INT32_MAX ? (int32_t)u : -(int32_t)(UINT32_MAX - u) - 1;
}

/* Decode data[0..len): header lines up to "$$HEADEREND", then commands 127
 * and 130 (anything else, or a truncated command, is an error) until the
 * data ends. */
static void cli_decode(const unsigned char *data, size_t len, cli_file *f)
{
    memset(f, 0, sizeof *f);
    f->layers_hdr = -1;
    static const char end_mark[] = "$$HEADEREND";
    const unsigned char *hend = NULL;
    for (size_t i = 0; i + sizeof end_mark - 1 <= len; i++)
        if (memcmp(data + i, end_mark, sizeof end_mark - 1) == 0) {
            hend = data + i + sizeof end_mark - 1;
            break;
        }
    if (!hend || (size_t)(hend - data) >= sizeof f->header) {
        snprintf(f->error, sizeof f->error, "no $$HEADEREND");
        return;
    }
    memcpy(f->header, data, (size_t)(hend - data));
    /* header lines */
    char copy[512];
    memcpy(copy, f->header, sizeof copy);
    for (char *line = strtok(copy, "\n"); line; line = strtok(NULL, "\n")) {
        if (strcmp(line, "$$BINARY") == 0) f->binary = 1;
        else if (strncmp(line, "$$LAYERS/", 9) == 0) f->layers_hdr = strtol(line + 9, NULL, 10);
        else if (strncmp(line, "$$UNITS/", 8) == 0) snprintf(f->units, sizeof f->units, "%s", line + 8);
        else if (strncmp(line, "$$VERSION/", 10) == 0) snprintf(f->version, sizeof f->version, "%s", line + 10);
    }
    const unsigned char *p = hend, *e = data + len;
    while (p < e) {
        if (e - p < 2) {
            snprintf(f->error, sizeof f->error, "truncated command id at byte %td", p - data);
            return;
        }
        unsigned cmd = (unsigned)p[0] | (unsigned)p[1] << 8;
        p += 2;
        if (cmd == 127) {
            if (e - p < 4 || f->nlayer == 8) {
                snprintf(f->error, sizeof f->error, "bad layer command at byte %td", p - data);
                return;
            }
            f->layer[f->nlayer].z = rd_f32(p);
            f->layer[f->nlayer].npoly = 0;
            f->nlayer++;
            p += 4;
        } else if (cmd == 130) {
            if (f->nlayer == 0 || e - p < 12) {
                snprintf(f->error, sizeof f->error, "bad polyline at byte %td", p - data);
                return;
            }
            cli_layer *L = &f->layer[f->nlayer - 1];
            if (L->npoly == 8) {
                snprintf(f->error, sizeof f->error, "too many polylines");
                return;
            }
            cli_poly *q = &L->poly[L->npoly++];
            q->id = rd_i32(p);
            q->dir = rd_i32(p + 4);
            q->n = rd_i32(p + 8);
            p += 12;
            if (q->n < 0 || q->n > 32 || e - p < 8 * q->n) {
                snprintf(f->error, sizeof f->error, "bad polyline point count %d", q->n);
                return;
            }
            for (int32_t i = 0; i < 2 * q->n; i++, p += 4) q->xy[i] = rd_f32(p);
        } else {
            snprintf(f->error, sizeof f->error, "unknown command %u at byte %td", cmd, p - 2 - data);
            return;
        }
    }
}

/* ---- a synthetic job: per layer a CCW square of side 2, a CW square hole of side 1 ---- */

static const double solid_uv[8] = {0, 0, 2, 0, 2, 2, 0, 2};
static const double hole_uv[8] = {0.5, 0.5, 0.5, 1.5, 1.5, 1.5, 1.5, 0.5};

/* Drive sink through the whole job (layers at z = 0, 1.25 ...). xyz are
 * deliberately not uv (shifted) so the test sees which one the writer got.
 * Returns the first error code. */
static int drive(lam_sink *s, const char *machine, const char *units, size_t layers_announced,
                 size_t layers)
{
    lam_job_info job;
    memset(&job, 0, sizeof job);
    job.name = machine;
    job.process = "sls";
    job.units = units;
    job.layers = layers_announced;
    job.bead = 0.25;
    double bbox[6] = {10, 20, 0, 12, 22, 2};
    memcpy(job.bbox, bbox, sizeof bbox);
    int rc = s->begin(s->ctx, &job);
    if (rc) return rc;
    size_t id = 1;
    for (size_t l = 0; l < layers; l++) {
        lam_layer_info L = {.index = l, .z = 1.25 * (double)l, .width = 1.25, .floor = 1.25 * (double)l,
                            .ceiling = 1.25 * (double)(l + 1)};
        if ((rc = s->layer(s->ctx, &L))) return rc;
        for (int k = 0; k < 2; k++) {
            const double *uv = k == 0 ? solid_uv : hole_uv;
            double xyz[12];
            for (int i = 0; i < 4; i++) {
                xyz[3 * i] = uv[2 * i] + 10;
                xyz[3 * i + 1] = uv[2 * i + 1] + 20;
                xyz[3 * i + 2] = L.z;
            }
            lam_contour_info c = {.attrs.part = id++, .solid = k == 0, .depth = k, .z = L.z, .xyz = xyz, .uv = uv, .n = 4};
            if ((rc = s->contour(s->ctx, &c))) return rc;
        }
        if ((rc = s->layer_end(s->ctx, &L))) return rc;
    }
    return s->end(s->ctx);
}

/* Run a whole job into a memory writer; *data (caller frees) gets the bytes. */
static int run_job(const char *writer, const char *machine, const char *units, size_t announced, size_t layers,
                   lam_error *err, char **data, size_t *len)
{
    lam_writer *w;
    *data = NULL;
    *len = 0;
    if (lam_writer_memory(&w, err)) return err->code;
    lam_sink s;
    int rc = lam_plugin_writer_sink(writer, w, &s, err);
    if (rc) {
        lam_writer_abort(w);
        return rc;
    }
    rc = drive(&s, machine, units, announced, layers);
    s.destroy(s.ctx);
    lam_error e2;
    int trc = lam_writer_take(w, data, len, &e2);
    return rc ? rc : trc;
}

static void test_refusals(void)
{
    lam_error err;
    int rc;

    lam_error_clear(&err);
    rc = lam_plugin_load("/nonexistent/dir/nothing.so", &err);
    is_int(rc, LAM_EIO, "missing file: LAM_EIO");
    contains(err.msg, "/nonexistent/dir/nothing.so", "missing file: message names the file");
    contains(err.msg, "No such file", "missing file: message says why");

    /* in a directory of its own: /tmp is writable by all, so refused */
    char jdir[] = "/tmp/lamina-test-plugin-XXXXXX", junk[64] = "";
    int fd = -1;
    if (mkdtemp(jdir)) {
        snprintf(junk, sizeof junk, "%s/junk.so", jdir);
        fd = open(junk, O_WRONLY | O_CREAT | O_EXCL, 0644);
    }
    ok(fd >= 0, "made a junk file");
    if (fd >= 0) {
        ok(write(fd, "not an ELF file\n", 16) == 16, "wrote the junk file");
        close(fd);
        lam_error_clear(&err);
        rc = lam_plugin_load(junk, &err);
        is_int(rc, LAM_EFORMAT, "not a shared object: LAM_EFORMAT");
        contains(err.msg, "cannot load plugin", "not a shared object: message");
        contains(err.msg, junk, "not a shared object: message names the file");
        unlink(junk);
    }
    rmdir(jdir);

    lam_error_clear(&err);
    rc = lam_plugin_load(test_plugin("bad_abi"), &err);
    is_int(rc, LAM_EFORMAT, "bad ABI: LAM_EFORMAT");
    char want[1400];
    snprintf(want, sizeof want, "plugin %s was built for lamina plugin ABI 999, this lamina speaks %d",
             test_plugin("bad_abi"), 1);
    contains(err.msg, want, "bad ABI: message names the file and both ABIs");
    ok(!writer_listed("bad-abi"), "bad ABI: init never ran");

    lam_error_clear(&err);
    rc = lam_plugin_load(test_plugin("no_abi"), &err);
    is_int(rc, LAM_EFORMAT, "no lamina_plugin_abi: LAM_EFORMAT");
    contains(err.msg, "lamina_plugin_abi", "no lamina_plugin_abi: message names the symbol");
    contains(err.msg, test_plugin("no_abi"), "no lamina_plugin_abi: message names the file");
    ok(!has(err.msg, "must not run"), "no lamina_plugin_abi: init never ran");

    lam_error_clear(&err);
    rc = lam_plugin_load(test_plugin("no_init"), &err);
    is_int(rc, LAM_EFORMAT, "no lamina_plugin_init: LAM_EFORMAT");
    contains(err.msg, "lamina_plugin_init", "no lamina_plugin_init: message names the symbol");
    contains(err.msg, test_plugin("no_init"), "no lamina_plugin_init: message names the file");

    lam_error_clear(&err);
    rc = lam_plugin_load(test_plugin("init_fails"), &err);
    is_int(rc, LAM_EINVAL, "init fails: LAM_EINVAL");
    contains(err.msg, "the frobnicator is not calibrated (code 42)", "init fails: the plugin's message");
    contains(err.msg, test_plugin("init_fails"), "init fails: message names the file");
    ok(!writer_listed("init-fails"), "init fails: its writer was dropped");
    is_int(lam_plugin_writers(NULL, 0), 0, "no writers registered after the refusals");
}

static void test_registry(void)
{
    lam_error err;
    lam_error_clear(&err);

    /* lookup by name: NAME.so from $LAMINA_PLUGINS (the cli plugin's
     * directory) first, then <exe dir>/plugins = $BUILD/tests/plugins, and
     * no other file (ctor.so would leave its mark) */
    setenv("LAMINA_PLUGINS", cli_dir, 1);
    unsetenv("LAMINA_CTOR_RAN");
    lam_writer *w;
    lam_writer_memory(&w, &err);
    lam_sink s;
    int rc = lam_plugin_writer_sink("cli-binary", w, &s, &err);
    is_int(rc, LAM_OK, "cli-binary found as cli-binary.so in the plugin directories");
    if (rc) diag("%s", err.msg);
    ok(rc == LAM_OK && s.ctx && s.begin && s.destroy, "the sink is filled in");
    if (rc == LAM_OK) s.destroy(s.ctx);   /* before begin: nothing to abort */
    lam_writer_abort(w);
    ok(writer_listed("cli-binary"), "cli-binary is registered");
    ok(!writer_listed("old-writer"), "old-writer.so, in a later directory, was not loaded");
    ok(!getenv("LAMINA_CTOR_RAN"), "no other plugin file was opened (ctor.so's constructor did not run)");
    lam_writer_memory(&w, &err);
    rc = lam_plugin_writer_sink("old-writer", w, &s, &err);
    is_int(rc, LAM_OK, "old-writer found as old-writer.so in <exe dir>/plugins");
    if (rc == LAM_OK) s.destroy(s.ctx);
    lam_writer_abort(w);
    ok(!getenv("LAMINA_CTOR_RAN"), "... and still no other file opened");
    lam_writer_memory(&w, &err);
    rc = lam_plugin_writer_sink("no_abi", w, &s, &err);
    ok(rc == LAM_EFORMAT && has(err.msg, "lamina_plugin_abi"), "writer no_abi: no_abi.so refused (%s)", err.msg);
    lam_writer_abort(w);
    lam_writer_memory(&w, &err);
    rc = lam_plugin_writer_sink("ctor", w, &s, &err);
    ok(rc == LAM_EINVAL && has(err.msg, "does not provide writer 'ctor'"), "a plugin without the named writer (%s)",
       err.msg);
    lam_writer_abort(w);
    lam_writer_memory(&w, &err);
    rc = lam_plugin_writer_sink("../plugins/cli-binary", w, &s, &err);
    ok(rc == LAM_EINVAL && has(err.msg, "letters, digits"), "a writer name with '/' is no file name (%s)", err.msg);
    lam_writer_abort(w);
    size_t count = lam_plugin_writers(NULL, 0);

    rc = lam_plugin_load(cli_path, &err);
    is_int(rc, LAM_OK, "loading cli-binary.so again succeeds");
    char other[1400];
    snprintf(other, sizeof other, "%s/./cli-binary.so", cli_dir);
    rc = lam_plugin_load(other, &err);
    is_int(rc, LAM_OK, "loading cli-binary.so under another path succeeds");
    is_int(lam_plugin_writers(NULL, 0), count, "... and registers nothing twice");

    lam_error_clear(&err);
    rc = lam_plugin_load(test_plugin("dup_writer"), &err);
    is_int(rc, LAM_EINVAL, "duplicate writer name: LAM_EINVAL");
    contains(err.msg, "writer 'cli-binary' is already registered", "duplicate writer: message");
    contains(err.msg, cli_dir, "duplicate writer: message names the plugin that has it");
    ok(!writer_listed("dup-ok"), "duplicate writer: the plugin's other writer was dropped");
    is_int(lam_plugin_writers(NULL, 0), count, "duplicate writer: registry unchanged");

    const char *names[2] = {NULL, NULL};
    size_t n = lam_plugin_writers(names, 1);
    is_int(n, count, "lam_plugin_writers counts all even when max is smaller");
    is_str(names[0], "cli-binary", "lam_plugin_writers: sorted, cli-binary first");
    ok(names[1] == NULL, "lam_plugin_writers stores at most max");

    lam_error_clear(&err);
    lam_writer_memory(&w, &err);
    memset(&s, 0xff, sizeof s);
    rc = lam_plugin_writer_sink("no-such-writer", w, &s, &err);
    is_int(rc, LAM_EINVAL, "unknown writer: LAM_EINVAL");
    contains(err.msg, "unknown writer 'no-such-writer'", "unknown writer: message names it");
    contains(err.msg, "no no-such-writer.so in", "unknown writer: message says which file was looked for");
    contains(err.msg, cli_dir, "unknown writer: message lists the directories searched");
    ok(s.ctx == NULL && s.destroy == NULL, "unknown writer: sink left empty");
    lam_writer_abort(w);
}

static void test_cli_bytes(void)
{
    lam_error err;
    lam_error_clear(&err);
    char *data;
    size_t len;
    int rc = run_job("cli-binary", "test-machine", "mm", 2, 2, &err, &data, &len);
    is_int(rc, LAM_OK, "cli-binary: a 2-layer job runs");
    if (rc) diag("%s", err.msg);

    /* no label given: the part is called "part"; the box is the job's */
    const char *hdr = "$$HEADERSTART\n$$BINARY\n$$UNITS/00000001.000000\n$$VERSION/200\n"
                      "$$DIMENSION/10.00000,20.00000,0.00000,12.00000,22.00000,2.00000\n$$LAYERS/2\n$$LABEL/1,part\n"
                      "$$HEADEREND";
    ok(data && len > strlen(hdr) && memcmp(data, hdr, strlen(hdr)) == 0, "header is exactly the CLI header");
    /* layer commands: 2 x (2 + 4); polylines: 4 x (2 + 12 + 5 * 8) */
    is_int(len, strlen(hdr) + 2 * 6 + 4 * 54, "file size: header + 2 layers + 4 closed polylines");

    cli_file f;
    cli_decode((const unsigned char *)data, len, &f);
    is_str(f.error, "", "the binary part decodes to its end (nothing else follows)");
    ok(f.binary, "$$BINARY");
    is_str(f.units, "00000001.000000", "$$UNITS: 1 mm per unit");
    is_str(f.version, "200", "$$VERSION/200");
    is_int(f.layers_hdr, 2, "$$LAYERS/2");
    is_int(f.nlayer, 2, "two layer commands");
    ok(data && data[strlen(hdr)] == 127 && data[strlen(hdr) + 1] == 0,
       "binary data starts right after $$HEADEREND (no newline)");
    int32_t next_id = 1;
    for (int l = 0; l < f.nlayer && l < 2; l++) {
        cli_layer *L = &f.layer[l];
        is_num(L->z, 1.25 * l, 0, "layer %d: z = %g (float32)", l, 1.25 * l);
        is_int(L->npoly, 2, "layer %d: two polylines", l);
        for (int k = 0; k < L->npoly && k < 2; k++) {
            cli_poly *q = &L->poly[k];
            const double *uv = k == 0 ? solid_uv : hole_uv;
            is_int(q->id, next_id, "layer %d polyline %d: id %d", l, k, next_id);
            next_id++;
            is_int(q->dir, k == 0 ? 1 : 0, "layer %d polyline %d: dir %d (%s)", l, k, k == 0,
                   k == 0 ? "counter-clockwise solid" : "clockwise hole");
            is_int(q->n, 5, "layer %d polyline %d: n = 5 (closed)", l, k);
            int good = q->n == 5;
            for (int i = 0; i < 5 && good; i++)
                good = q->xy[2 * i] == (float)uv[2 * (i % 4)] && q->xy[2 * i + 1] == (float)uv[2 * (i % 4) + 1];
            ok(good, "layer %d polyline %d: the layer-plane (uv) points, first repeated last", l, k);
            if (!good)
                for (int i = 0; i < q->n && i < 32; i++) diag("  point %d: %g, %g", i, q->xy[2 * i], q->xy[2 * i + 1]);
            /* orientation, from the decoded points */
            double area = 0;
            for (int i = 0; i + 1 < q->n; i++)
                area += (double)q->xy[2 * i] * q->xy[2 * i + 3] - (double)q->xy[2 * i + 2] * q->xy[2 * i + 1];
            is_num(area / 2, k == 0 ? 4 : -1, 1e-12, "layer %d polyline %d: signed area %g", l, k, k == 0 ? 4.0 : -1.0);
        }
    }
    free(data);

    /* units */
    rc = run_job("cli-binary", "m", "in", 1, 1, &err, &data, &len);
    is_int(rc, LAM_OK, "cli-binary: inch job runs");
    cli_decode((const unsigned char *)data, len, &f);
    is_str(f.units, "00000025.400000", "$$UNITS for inches: 25.4 mm per unit");
    is_int(f.layers_hdr, 1, "$$LAYERS/1");
    free(data);

    lam_error_clear(&err);
    rc = run_job("cli-binary", "m", "furlong", 1, 1, &err, &data, &len);
    is_int(rc, LAM_EINVAL, "cli-binary: unknown units refused");
    is_str(err.msg, "cli-binary: CLI cannot express units 'furlong' (use mm, cm, m, um, in or inch)",
           "unknown units: the plugin's message, not prefixed twice");
    is_int(len, 0, "unknown units: nothing written");
    free(data);

    lam_error_clear(&err);
    rc = run_job("cli-binary", "m", "mm", 1, 2, &err, &data, &len);
    is_int(rc, LAM_EINVAL, "cli-binary: more layers than announced refused");
    contains(err.msg, "layer 1 is one more than the 1 the header announced", "more layers: message");
    free(data);

    lam_error_clear(&err);
    rc = run_job("cli-binary", "m", "mm", 3, 2, &err, &data, &len);
    is_int(rc, LAM_EINVAL, "cli-binary: fewer layers than announced refused at end");
    contains(err.msg, "the header announced 3 layers, 2 were written", "fewer layers: message");
    free(data);
}

static void test_sink_rules(void)
{
    lam_error err;
    lam_error_clear(&err);
    lam_writer *w;
    lam_writer_memory(&w, &err);
    lam_sink s;
    int rc = lam_plugin_writer_sink("cli-binary", w, &s, &err);
    is_int(rc, LAM_OK, "cli-binary sink");
    if (rc) return;

    lam_layer_info L = {.index = 0, .z = 0};
    rc = s.layer(s.ctx, &L);
    is_int(rc, LAM_EUSAGE, "layer before begin: LAM_EUSAGE");
    contains(err.msg, "before begin", "layer before begin: message");

    lam_job_info job = {.name = "m", .process = "sls", .units = "mm", .layers = 1};
    is_int(s.begin(s.ctx, &job), LAM_OK, "begin");
    double c[3] = {0, 0, 0};
    lam_error_clear(&err);
    is_int(s.feed(s.ctx, 100), LAM_EUSAGE, "feed: LAM_EUSAGE");
    is_str(err.msg, "writer cli-binary handles contour programs (SLS) only", "feed: message");
    lam_error_clear(&err);
    is_int(s.laser(s.ctx, 1), LAM_EUSAGE, "laser: LAM_EUSAGE");
    is_str(err.msg, "writer cli-binary handles contour programs (SLS) only", "laser: message");
    lam_error_clear(&err);
    lam_move_info mv = { .deposit = 1, .xyz = { c[0], c[1], c[2] } };
    is_int(s.move(s.ctx, &mv), LAM_EUSAGE, "move: LAM_EUSAGE");
    is_str(err.msg, "writer cli-binary handles contour programs (SLS) only", "move: message");

    lam_error_clear(&err);
    lam_contour_info ci = {.attrs.part = 1, .solid = 1, .uv = solid_uv, .n = 4};
    is_int(s.contour(s.ctx, &ci), LAM_EINVAL, "contour before the first layer: refused by the writer");
    contains(err.msg, "contour 1 before the first layer", "contour before layer: message");

    is_int(s.layer(s.ctx, &L), LAM_OK, "layer");
    /* destroy without end: the writer's abort frees its state (a leak
     * otherwise, which the sanitizer build would report) */
    s.destroy(s.ctx);
    char *data;
    size_t len;
    lam_writer_take(w, &data, &len, &err);
    ok(len > 0, "aborted job: the memory writer kept what was written (the caller discards it)");
    free(data);

    /* the size rule: old-writer's declared size ends before abort */
    lam_writer_memory(&w, &err);
    rc = lam_plugin_writer_sink("old-writer", w, &s, &err);
    is_int(rc, LAM_OK, "old-writer sink");
    if (rc == LAM_OK) {
        job.name = "old";
        is_int(s.begin(s.ctx, &job), LAM_OK, "old-writer: begin");
        lam_contour_info h = {.attrs.part = 2, .solid = 0, .uv = hole_uv, .n = 4};
        is_int(s.layer(s.ctx, &L), LAM_OK, "old-writer: layer");
        is_int(s.contour(s.ctx, &h), LAM_OK, "old-writer: contour");
        s.destroy(s.ctx);
    }
    lam_writer_take(w, &data, &len, &err);
    is_str(data, "begin old 1\nlayer 0 0\npoly 2 0 4 0.5,0.5 0.5,1.5 1.5,1.5 1.5,0.5\n",
           "old-writer: output, and its abort (beyond its declared size) never called");
    free(data);

    /* a writer's refusal, with its message */
    lam_error_clear(&err);
    rc = run_job("old-writer", "fail-begin", "mm", 1, 1, &err, &data, &len);
    is_int(rc, LAM_EINVAL, "old-writer: begin refused");
    is_str(err.msg, "old-writer: refusing machine 'fail-begin'",
           "old-writer: begin's message (already naming the writer: no second prefix)");
    free(data);
    lam_error_clear(&err);
    rc = run_job("old-writer", "fail-hole", "mm", 1, 1, &err, &data, &len);
    is_int(rc, LAM_EINVAL, "old-writer: polyline refused");
    is_str(err.msg, "old-writer: contour 2 is a hole", "old-writer: polyline's message");
    free(data);

    /* output that cannot be written: an unbuffered stream on /dev/full */
    FILE *full = fopen("/dev/full", "wb");
    if (full) {
        setvbuf(full, NULL, _IONBF, 0);
        lam_writer_stream(full, "/dev/full", &w, &err);
        rc = lam_plugin_writer_sink("cli-binary", w, &s, &err);
        lam_error_clear(&err);
        int brc = s.begin(s.ctx, &job);
        is_int(brc, LAM_EIO, "write failure: LAM_EIO");
        is_str(err.msg, "writer cli-binary: cannot write output", "write failure: message");
        s.destroy(s.ctx);
        lam_writer_abort(w);
        fclose(full);
    } else {
        ok(1, "# SKIP no /dev/full");
        ok(1, "# SKIP no /dev/full");
    }
}

/* A plugin file or directory others than its owner may write is refused
 * before it is opened. */
static void test_permissions(void)
{
    char dir[] = "/tmp/lamina-plugin-XXXXXX";
    if (!mkdtemp(dir)) {
        ok(0, "mkdtemp");
        return;
    }
    char path[64];
    snprintf(path, sizeof path, "%s/ctor.so", dir);
    FILE *in = fopen(test_plugin("ctor"), "rb"), *out = fopen(path, "wb");
    char buf[4096];
    size_t n;
    while (in && out && (n = fread(buf, 1, sizeof buf, in)) > 0) fwrite(buf, 1, n, out);
    if (in) fclose(in);
    if (out) fclose(out);
    lam_error err;
    lam_error_clear(&err);
    unsetenv("LAMINA_CTOR_RAN");
    chmod(dir, 0777);
    chmod(path, 0755);
    int rc = lam_plugin_load(path, &err);
    ok(rc == LAM_EIO && has(err.msg, "directory") && has(err.msg, "writable by others than its owner"),
       "a world-writable plugin directory is refused (%s)", err.msg);
    chmod(dir, 0700);
    chmod(path, 0664);
    rc = lam_plugin_load(path, &err);
    ok(rc == LAM_EIO && has(err.msg, "file") && has(err.msg, "writable by others than its owner"),
       "a group-writable plugin file is refused (%s)", err.msg);
    ok(!getenv("LAMINA_CTOR_RAN"), "neither was opened (its constructor did not run)");
    chmod(path, 0755);
    lam_error_clear(&err);
    rc = lam_plugin_load(path, &err);
    ok(rc == LAM_OK && getenv("LAMINA_CTOR_RAN"), "mode 755 in a 700 directory loads (%s)", err.msg);
    remove(path);
    rmdir(dir);
}

static void test_unload(void)
{
    lam_plugins_unload();
    is_int(lam_plugin_writers(NULL, 0), 0, "unload: registry empty");
    lam_error err;
    lam_error_clear(&err);
    is_int(lam_plugin_load(cli_path, &err), LAM_OK, "cli-binary.so loads again after unload");
    is_int(lam_plugin_writers(NULL, 0), 1, "... registering cli-binary only");
    char *data;
    size_t len;
    int rc = run_job("cli-binary", "m", "mm", 2, 2, &err, &data, &len);
    is_int(rc, LAM_OK, "and runs a job");
    free(data);
    lam_plugins_unload();
}

/* A plugin is loaded through /proc/self/fd/N of the descriptor checked;
 * glibc hands back an object already loaded under that name. An object
 * left loaded (RTLD_NODELETE, as C++ unique symbols make one) under the
 * name of a descriptor since closed must not be taken for the next plugin,
 * whose descriptor gets that same number. */
static void test_stale_name(void)
{
    int fd = open(test_plugin("no_init"), O_RDONLY | O_CLOEXEC);
    char name[64];
    snprintf(name, sizeof name, "/proc/self/fd/%d", fd);
    void *stale = fd >= 0 ? dlopen(name, RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE) : NULL;
    ok(stale != NULL, "no_init.so held loaded as %s", name);
    if (fd >= 0) close(fd);
    /* the next open gets the lowest free number: fd's */
    int probe = open(cli_path, O_RDONLY | O_CLOEXEC);
    is_int(probe, fd, "(the next descriptor has that number again)");
    if (probe >= 0) close(probe);
    lam_error err;
    lam_error_clear(&err);
    int rc = lam_plugin_load(cli_path, &err);
    ok(rc == LAM_OK && writer_listed("cli-binary"), "cli-binary.so loads as itself, not as the stale object (%s)",
       err.msg);
    if (stale) dlclose(stale);
    lam_plugins_unload();
}

int main(void)
{
    const char *b = getenv("BUILD");
    snprintf(build_dir, sizeof build_dir, "%s", b && *b ? b : "build");
    struct stat st;
    snprintf(cli_dir, sizeof cli_dir, "%s/plugins", build_dir);
    snprintf(cli_path, sizeof cli_path, "%s/cli-binary.so", cli_dir);
    if (stat(cli_path, &st) != 0) {
        snprintf(cli_dir, sizeof cli_dir, "plugins");
        snprintf(cli_path, sizeof cli_path, "plugins/cli-binary.so");
    }
    diag("cli plugin: %s; test plugins: %s/tests/plugins", cli_path, build_dir);

    test_refusals();
    test_registry();
    test_cli_bytes();
    test_sink_rules();
    test_permissions();
    test_unload();
    test_stale_name();
    return done_testing();
}
