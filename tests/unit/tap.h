/* Minimal TAP producer for the C unit tests (read by prove). */
#ifndef LAM_TAP_H
#define LAM_TAP_H

#include <math.h>
#include <stdio.h>
#include <string.h>

static int tap_n, tap_failed;

#define ok(cond, ...) tap_ok(!!(cond), __FILE__, __LINE__, __VA_ARGS__)

static void tap_ok(int pass, const char *file, int line, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

#include <stdarg.h>
static void tap_ok(int pass, const char *file, int line, const char *fmt, ...)
{
    va_list ap;
    ++tap_n;
    if (!pass) ++tap_failed;
    printf("%s %d - ", pass ? "ok" : "not ok", tap_n);
    va_start(ap, fmt);
    vprintf(fmt, ap);
    va_end(ap);
    printf("\n");
    if (!pass) printf("#   failed at %s:%d\n", file, line);
    fflush(stdout);
}

/* |a - b| <= tol */
#define is_num(a, b, tol, ...) do { double a_ = (a), b_ = (b); \
    ok(fabs(a_ - b_) <= (tol), __VA_ARGS__); \
    if (!(fabs(a_ - b_) <= (tol))) printf("#   got %.17g, expected %.17g\n", a_, b_); } while (0)

#define is_int(a, b, ...) do { long long a_ = (long long)(a), b_ = (long long)(b); \
    ok(a_ == b_, __VA_ARGS__); \
    if (a_ != b_) printf("#   got %lld, expected %lld\n", a_, b_); } while (0)

#define is_str(a, b, ...) do { const char *a_ = (a), *b_ = (b); \
    int eq_ = a_ && b_ && strcmp(a_, b_) == 0; ok(eq_, __VA_ARGS__); \
    if (!eq_) printf("#   got '%s', expected '%s'\n", a_ ? a_ : "(null)", b_ ? b_ : "(null)"); } while (0)

#define diag(...) do { printf("# "); printf(__VA_ARGS__); printf("\n"); } while (0)

static int done_testing(void)
{
    printf("1..%d\n", tap_n);
    return tap_failed ? 1 : 0;
}

#endif
