/* Helpers shared by the unit tests (the importers' above all; meshes.h has
 * the model builders). All static inline, so a test program that includes
 * this pays nothing for the helpers it does not use (and -Wunused-function
 * stays quiet). It includes tap.h itself. */
#ifndef LAM_TEST_UTIL_H
#define LAM_TEST_UTIL_H

#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"
#include "mesh.h"
#include "plan.h"
#include "tap.h"

/* A stage move of sink s to p (output frame; the dialects read no other). */
static inline int move_to(const lam_sink *s, int deposit, const double p[3])
{
    lam_move_info m = { .attrs = lam_attrs_default(), .deposit = deposit, .xyz = { p[0], p[1], p[2] } };
    return s->move(s->ctx, &m);
}

/* A growable NUL-terminated string: start from (sbuf){ 0 }, free b.s. */
typedef struct sbuf {
    char *s;
    size_t n, cap;
} sbuf;

/* Append printf-style text to b (aborts the test program when out of
 * memory: a test has nothing better to do). */
static inline void sb_add(sbuf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static inline void sb_add(sbuf *b, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int k = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    if (b->n + (size_t)k + 1 > b->cap) {
        b->cap = (b->n + (size_t)k + 1) * 2;
        b->s = realloc(b->s, b->cap);
        if (!b->s) abort();
    }
    va_start(ap, fmt);
    vsnprintf(b->s + b->n, (size_t)k + 1, fmt, ap);
    va_end(ap);
    b->n += (size_t)k;
}

/* A malloc'd copy of src[0..len) of exactly len bytes (1 when len is 0), so
 * that AddressSanitizer catches any read past len. The caller frees it. */
static inline void *heap_copy(const void *src, size_t len)
{
    void *copy = malloc(len ? len : 1);
    if (!copy) abort();
    if (len) memcpy(copy, src, len);
    return copy;
}

/* The three corners of triangle t of m (pointers into m->xyz). */
static inline void tri_corners(const lam_mesh *m, size_t t, const double **a, const double **b, const double **c)
{
    *a = m->xyz + 3 * (size_t)m->tris[3 * t];
    *b = m->xyz + 3 * (size_t)m->tris[3 * t + 1];
    *c = m->xyz + 3 * (size_t)m->tris[3 * t + 2];
}

/* Volume enclosed by m's triangles, positive when they wind outward. */
static inline double signed_volume(const lam_mesh *m)
{
    double vol = 0;
    for (size_t t = 0; t < m->ntris; t++) {
        const double *a, *b, *c;
        tri_corners(m, t, &a, &b, &c);
        vol += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
               a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    return vol / 6;
}

/* hay (may be NULL) contains needle. */
static inline int has(const char *hay, const char *needle) { return hay && strstr(hay, needle) != NULL; }

/* xorshift64: the next pseudo-random number of the sequence *state holds
 * (state must not be 0). Fixed seeds keep the random tests repeatable. */
static inline uint64_t xorshift64(uint64_t *state)
{
    *state ^= *state << 13;
    *state ^= *state >> 7;
    *state ^= *state << 17;
    return *state;
}

/* One TAP check, `what`: the import returned LAM_OK; err's message otherwise. */
static inline void load_ok(int rc, const lam_error *err, const char *what)
{
    is_int(rc, LAM_OK, "%s", what);
    if (rc) diag("%s", err->msg);
}

/* One TAP check, `what`: the import returned rc == code, err holds code at
 * line:col and a message containing msg. Prints what it got otherwise. */
static inline void error_is(int rc, const lam_error *err, int code, long line, long col, const char *msg,
                            const char *what)
{
    int good = rc == code && err->code == code && err->line == line && err->column == col && has(err->msg, msg);
    ok(good, "%s", what);
    if (!good)
        diag("got rc %d at %ld:%ld '%s'; expected %d at %ld:%ld '%s'", rc, err->line, err->column, err->msg,
             code, line, col, msg);
}

#endif
