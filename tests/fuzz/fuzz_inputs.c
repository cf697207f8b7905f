/* Fuzz target for everything lamina reads: models (Unigrafix, STL, OBJ),
 * machine profiles (YAML) and programs read back (SLS, CLI). Built two ways:
 *  - with clang -fsanitize=fuzzer (make fuzz): a libFuzzer target;
 *  - in the test suite: a deterministic mutation driver that replays every
 *    seed file given on the command line and a few thousand mutants of
 *    each (bit flips, byte changes, insertions, deletions, truncations,
 *    duplicated spans), under ASan/UBSan with `make SAN=1 test`.
 * Every input must either load or fail with a message; nothing may crash,
 * leak or read out of bounds. TAP output: one test per seed. */
#include "error.h"
#include "import.h"
#include "model.h"
#include "profile.h"
#include "program_read.h"
#include "slice.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The first byte picks the reader, the rest is the input. */
static int one(const uint8_t *data, size_t size)
{
    if (size < 1) return 0;
    int kind = data[0] % 5;
    const char *buf = (const char *)data + 1;
    size_t len = size - 1;
    lam_error err;
    lam_error_clear(&err);
    lam_mesh m;
    lam_mesh_init(&m);
    int rc = LAM_OK, bin = 0;
    switch (kind) {
    case 0: rc = lam_import_ug_buf("fuzz.ug", buf, len, &m, &err); break;
    case 1: rc = lam_import_stl_buf("fuzz.stl", (const unsigned char *)buf, len, &m, &bin, &err); break;
    case 2: rc = lam_import_obj_buf("fuzz.obj", buf, len, &m, &err); break;
    case 4: {
        /* a program read back, and its layers made along z and x */
        lam_program *p = NULL;
        rc = lam_program_read_buf("fuzz.sls", (const unsigned char *)buf, len, &p, &err);
        for (size_t i = 0; p && i < p->nlayers; i++)
            for (int ax = 0; ax < 2; ax++) {
                lam_frame f;
                lam_frame_axis(ax ? 'x' : 'z', &f, NULL);
                lam_layer L;
                lam_error lerr;
                if (lam_program_layer_make(p, i, &f, 0, "fuzz.sls", &L, &lerr) == LAM_OK) lam_layer_clear(&L);
                else if (lerr.msg[0] == '\0') rc = -1;
            }
        lam_program_free(p);
        return rc != LAM_OK && err.msg[0] == '\0' ? -1 : 0;
    }
    default: {
        lam_profile *p = NULL;
        rc = lam_profile_load_buf("fuzz.yaml", buf, len, &p, &err);
        lam_profile_free(p);
        return rc != LAM_OK && err.msg[0] == '\0' ? -1 : 0;
    }
    }
    if (rc == LAM_OK && m.ntris) {
        /* what loads must also build: weld, edges, shells, orientation */
        lam_model *md = NULL;
        rc = lam_model_from_mesh(&m, "fuzz", "fuzz", &md, &err);
        /* ... and slice, straight and oblique, whatever shape it has */
        for (int axis = 0; md && axis < 2; axis++) {
            lam_slice_opts o;
            lam_slice_opts_init(&o);
            const double oblique[3] = { 0.3, -0.2, 0.9 };
            if (axis) lam_frame_direction(oblique, &o.frame, &err);
            o.fill_nonzero = (int)(size & 1);
            double ext = 0;
            for (int k = 0; k < 3; k++)
                if (md->stats.bbox[k + 3] - md->stats.bbox[k] > ext) ext = md->stats.bbox[k + 3] - md->stats.bbox[k];
            o.width = ext > 0 && ext < 1e300 ? ext / 7 : 1;
            lam_slicer *s = NULL;
            lam_error serr;
            if (lam_slicer_new(md, &o, &s, &serr) == LAM_OK) {
                lam_layer *L;
                while (lam_slicer_next(s, &L, &serr) == LAM_OK && L) lam_layer_free(L);
            }
            lam_slicer_free(s);
        }
        lam_model_free(md);
    }
    lam_mesh_free(&m);
    /* a failure always says what went wrong */
    return rc != LAM_OK && err.msg[0] == '\0' ? -1 : 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    (void)one(data, size);
    return 0;
}

#ifndef LAMINA_LIBFUZZER
static uint64_t rng = 0x9e3779b97f4a7c15ull;
static uint64_t next(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return rng;
}

static size_t mutate(uint8_t *b, size_t n, size_t cap)
{
    int ops = 1 + (int)(next() % 4);
    for (int k = 0; k < ops; k++) {
        size_t body = n > 1 ? n - 1 : 1; /* keep byte 0: the reader */
        size_t at = 1 + (size_t)(next() % body);
        switch (next() % 7) {
        case 0: if (at < n) b[at] ^= (uint8_t)(1u << (next() % 8)); break;
        case 1: if (at < n) b[at] = (uint8_t)next(); break;
        case 2: /* insert a byte from a small alphabet of troublemakers */
            if (n < cap && at <= n) {
                static const char alpha[] = " ;(){}/*\n-.0123456789eEnaif:#\"'[]";
                memmove(b + at + 1, b + at, n - at);
                b[at] = (uint8_t)alpha[next() % (sizeof alpha - 1)];
                n++;
            }
            break;
        case 3: /* delete a span */
            if (at < n) {
                size_t len = 1 + (size_t)(next() % 16);
                if (at + len > n) len = n - at;
                memmove(b + at, b + at + len, n - at - len);
                n -= len;
            }
            break;
        case 4: if (at < n) n = at; break; /* truncate */
        case 5: /* duplicate a span */
            if (at < n) {
                size_t len = 1 + (size_t)(next() % 64);
                if (at + len > n) len = n - at;
                if (n + len <= cap) {
                    memmove(b + at + len, b + at, n - at);
                    n += len;
                }
            }
            break;
        default: /* overwrite 4 bytes: counts in binary STL, huge numbers in text */
            for (int i = 0; i < 4 && at + i < n; i++) b[at + i] = (uint8_t)next();
        }
    }
    return n;
}

int main(int argc, char **argv)
{
    int mutants = 2000, failed = 0, t = 0;
    const char *env = getenv("LAMINA_FUZZ_MUTANTS");
    if (env) mutants = atoi(env);
    for (int i = 1; i < argc; i++) {
        FILE *f = fopen(argv[i], "rb");
        if (!f) {
            printf("not ok %d - cannot open %s\n", ++t, argv[i]);
            failed++;
            continue;
        }
        uint8_t *seed = malloc(1 << 20);
        size_t n = fread(seed + 1, 1, (1 << 20) - 1, f) + 1;
        fclose(f);
        const char *dot = strrchr(argv[i], '.');
        seed[0] = !dot                    ? 0
                  : !strcmp(dot, ".stl")  ? 1
                  : !strcmp(dot, ".obj")  ? 2
                  : !strcmp(dot, ".yaml") ? 3
                  : !strcmp(dot, ".sls") || !strcmp(dot, ".cli") ? 4
                                          : 0;
        size_t cap = n + 4096;
        uint8_t *b = malloc(cap);
        int bad = one(seed, n) != 0;
        for (int k = 0; k < mutants && !bad; k++) {
            memcpy(b, seed, n);
            size_t m = mutate(b, n, cap);
            /* exact-size heap copy: ASan sees any read past the end */
            uint8_t *exact = malloc(m ? m : 1);
            memcpy(exact, b, m);
            bad = one(exact, m) != 0;
            free(exact);
        }
        printf("%s %d - %s and %d mutants: loaded or refused with a message\n", bad ? "not ok" : "ok", ++t, argv[i],
               mutants);
        failed += bad;
        free(seed);
        free(b);
    }
    printf("1..%d\n", t);
    return failed ? 1 : 0;
}
#endif
