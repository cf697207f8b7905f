/* lam_fmt_fixed must print exactly what printf("%.*f") prints; lam_fmt_num
 * the fewest digits that read back (checked with strtod); the durations and
 * lengths for people are checked against values reasoned by hand. */
#include "fmt.h"
#include "tap.h"
#include "util.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <stdlib.h>

static uint64_t rng = 0x243f6a8885a308d3ull;
static uint64_t next(void) { return xorshift64(&rng); }

static int same(double x, int d)
{
    char a[LAM_FMT_MAX], b[LAM_FMT_MAX];
    lam_fmt_fixed(a, x, d);
    snprintf(b, sizeof b, "%.*f", d, x);
    if (strcmp(a, b) != 0) {
        diag("x=%.17g d=%d: got %s, printf %s", x, d, a, b);
        return 0;
    }
    return 1;
}

/* The number of significant digits in text t: neither leading nor
 * trailing zeros count ("-0.0012" has 2, "1200" 2). */
static int sig_digits(const char *t)
{
    int n = 0, lead = 1, zeros = 0;
    for (const char *p = t; *p && *p != 'e'; p++) {
        if (*p < '0' || *p > '9') continue;
        if (lead && *p == '0') continue;
        lead = 0;
        zeros = *p == '0' ? zeros + 1 : 0;
        n++;
    }
    return n - zeros ? n - zeros : 1;
}

/* lam_fmt_num(x, 17): reads back exactly, and no text of one digit less
 * does (printf's own %.*e rounding is the reference). Whole numbers from
 * 1e15 to 1e17 print all their digits, as %.17g does. */
static int shortest(double x)
{
    char t[LAM_FMT_NUM], fewer[64];
    lam_fmt_num(t, x, 17);
    int n = sig_digits(t);
    int good = strtod(t, NULL) == x;
    if (good && n > 1 && !(fabs(x) >= 1e15 && fabs(x) < 1e17)) {
        snprintf(fewer, sizeof fewer, "%.*e", n - 2, x);
        good = strtod(fewer, NULL) != x;
    }
    if (!good) diag("x=%.17g: got %s (%d digits)", x, t, n);
    return good;
}

static void num_is(double x, int digits, const char *want)
{
    char t[LAM_FMT_NUM];
    is_str(lam_fmt_num(t, x, digits), want, "lam_fmt_num(%.17g, %d) is %s", x, digits, want);
}

/* Durations for people (fmt.h), each value reasoned by hand: the range is
 * chosen by the value rounded to its resolution, then split. */
static void durations(void)
{
    static const struct { double t; const char *want, *why; } d[] = {
        { 0, "0 s", "nothing" },
        { 0.05, "0.050 s", "below 0.1 s: two significant digits, the zero shown" },
        { 0.0012, "0.0012 s", "two digits four places down" },
        { 0.09949, "0.099 s", "two digits by magnitude, not by the first rounding that reaches 10" },
        { 0.0996, "0.1 s", "two digits round to 0.100: tenths" },
        { 0.8, "0.8 s", "tenths below 10 s" },
        { 0.868351, "0.9 s", "the issue's jumps" },
        { 3.80372, "3.8 s", "the issue's exposure" },
        { 1, "1.0 s", "tenths keep their zero" },
        { 0.25, "0.2 s", "an exact tie rounds to even" },
        { 0.35, "0.3 s", "0.35 is 0.34999999999999997...: down, though 0.35 * 10 rounds to 3.5" },
        { 9.94, "9.9 s", "just below 10 s" },
        { 9.96, "10 s", "9.96 rounds to 10.0: whole seconds" },
        { 10.5, "10 s", "whole seconds: a tie to even" },
        { 11.5, "12 s", "whole seconds: a tie to even, up" },
        { 45, "45 s", "under a minute" },
        { 59.6, "1 min 0 s", "rounded once, then split: never 60 s" },
        { 723, "12 min 3 s", "12 x 60 + 3" },
        { 536, "8 min 56 s", "the issue's recoating: 8 x 60 + 56" },
        { 540.672, "9 min 1 s", "the issue's total: 541 s" },
        { 6105, "1 h 41 min 45 s", "3600 + 41 x 60 + 45" },
        { 3599.6, "1 h 0 min 0 s", "3600 s once rounded: every unit below the hour shown" },
        { 86399.4, "23 h 59 min 59 s", "the last second below a day" },
        { 86399.5, "1 d 0 h 0 min", "86399.5 rounds (to even) to 86400 s: a day, whole minutes" },
        { 183869, "2 d 3 h 4 min", "2 d 3 h 4 min 29 s: minutes round down" },
        { 183870, "2 d 3 h 4 min", "... 4 min 30 s, a tie: 3064 min is even" },
        { 183871, "2 d 3 h 5 min", "... 4 min 31 s: up" },
        { 183930, "2 d 3 h 6 min", "... 5 min 30 s, a tie: 3065 min is odd, up" },
        { 1e16, "1.16e+11 d", "past 4e15 s: days, three digits (1e16 / 86400 = 1.157e11)" },
        { -1, "unknown", "negative" },
        { NAN, "unknown", "not a number" },
        { INFINITY, "unknown", "infinite" },
    };
    char buf[64];
    for (size_t i = 0; i < sizeof d / sizeof *d; i++)
        is_str(lam_fmt_duration(d[i].t, buf, sizeof buf), d[i].want, "duration %.17g: %s (%s)", d[i].t, d[i].want,
               d[i].why);
    char small[5];
    is_str(lam_fmt_duration(723, small, sizeof small), "12 m", "a short buffer gets snprintf's truncation");
}

/* Lengths for people, by hand: three digits, the unit of the rounded value. */
static void lengths(void)
{
    static const struct { double len, mm; const char *unit, *want, *why; } l[] = {
        { 2926.01, 1, "mm", "2.93 m", "the issue's exposed length" },
        { 334.959, 1, "mm", "335 mm", "the issue's jumped length" },
        { 120000, 1, "mm", "120 m", "trailing zeros of the integer stay" },
        { 3.02e6, 1, "mm", "3.02 km", "kilometres from 1e6 mm" },
        { 1.234e11, 1, "mm", "123000 km", "no unit past km" },
        { 45.3, 1, "mm", "45.3 mm", "millimetres" },
        { 12, 1, "mm", "12 mm", "no fraction: no point" },
        { 0.8, 1, "mm", "0.8 mm", "the fraction's trailing zeros dropped" },
        { 0.1, 1, "mm", "0.1 mm", "millimetres down to 0.1 mm" },
        { 0.0999, 1, "mm", "99.9 \xc2\xb5m", "below 0.1 mm: micrometres" },
        { 0.09996, 1, "mm", "0.1 mm", "rounds to 0.100 mm: millimetres" },
        { 0.05, 1, "mm", "50 \xc2\xb5m", "micrometres" },
        { 1.5e-4, 1, "mm", "0.15 \xc2\xb5m", "a fraction of a micrometre" },
        { 999.4, 1, "mm", "999 mm", "below a metre" },
        { 999.6, 1, "mm", "1 m", "rounds to 1000 mm: metres" },
        { 2.5, 10, "cm", "25 mm", "centimetres in millimetres" },
        { 100, 25.4, "in", "2.54 m", "100 inches" },
        { 1.5, 1000, "m", "1.5 m", "metres" },
        { 800, 0.001, "um", "0.8 mm", "800 micrometres" },
        { -45.3, 1, "mm", "-45.3 mm", "a sign" },
        { 0, 1, "mm", "0 mm", "nothing" },
        { 1e30, 1, "mm", "1e+24 km", "too large for plain digits" },
        { 1e-9, 1, "mm", "1e-06 \xc2\xb5m", "too small for plain digits" },
        { 2926.01, 0, "furlong", "2930 furlong", "an unknown unit: the number in it" },
        { 0, 0, "furlong", "0 furlong", "nothing, in an unknown unit" },
        { 0.5, 0, NULL, "0.5", "no unit name: the number alone" },
        { NAN, 1, "mm", "unknown", "not a number" },
    };
    char buf[64];
    for (size_t i = 0; i < sizeof l / sizeof *l; i++)
        is_str(lam_fmt_length(l[i].len, l[i].mm, l[i].unit, buf, sizeof buf), l[i].want, "length %.17g x %g mm: %s (%s)",
               l[i].len, l[i].mm, l[i].want, l[i].why);
}

int main(void)
{
    /* what people read: the noise of arithmetic dropped at 15 digits, kept
     * at 17; decimals as typed; %g's notation; no "-0" */
    num_is(110.1 - 1.7, 15, "108.4");
    num_is(110.1 - 1.7, 17, "108.39999999999999");
    num_is(0.1 + 0.2, 15, "0.3");
    num_is(0.1 + 0.2, 17, "0.30000000000000004");
    num_is(1.0 / 3, 15, "0.333333333333333");
    num_is(2.0 / 3, 4, "0.6667");
    num_is(600, 15, "600");
    num_is(1e-5, 15, "1e-05");
    num_is(0.0001, 15, "0.0001");
    num_is(1e20, 15, "1e+20");
    num_is(1e16, 17, "10000000000000000");
    num_is(-0.0, 15, "0");
    num_is(-2.5, 15, "-2.5");
    num_is(123456.789, 15, "123456.789");
    num_is(-0.00012345678901234567, 17, "-0.00012345678901234567");
    num_is(-1.5e-300, 17, "-1.5e-300");
    num_is(1.2345678901234567e-300, 15, "1.23456789012346e-300");
    char m[64];
    snprintf(m, sizeof m, "h=%s, x=%s", LAM_NUM(110.1 - 1.7), LAM_NUM_EXACT(0.1 + 0.2));
    is_str(m, "h=108.4, x=0.30000000000000004", "LAM_NUM and LAM_NUM_EXACT as printf arguments");
    int fine = 1;
    for (int i = 0; i < 100000 && fine; i++) {
        uint64_t r = next();
        double x;
        memcpy(&x, &r, sizeof x);
        if (isfinite(x)) fine &= shortest(x);
        /* decimals as users write them */
        int64_t n = (int64_t)(next() % 2000000001) - 1000000000;
        fine &= shortest((double)n / 1e4) && shortest((double)n * 1e-9);
    }
    ok(fine, "random doubles: the shortest text that reads back exactly");

    static const double special[] = { 0.0, -0.0, 0.5, 1.5, 2.5, -2.5, 0.0000005, 0.0000015, -0.0000005,
                                      1.0000005, 0.125, 0.375, 1e-7, -1e-7, 1e15, 123456789.123456789,
                                      -1.00000049999999, 2.0000004999999999, 0.1, 0.7, 1e300, -1e-300 };
    int good = 1;
    for (size_t i = 0; i < sizeof special / sizeof *special; i++)
        for (int d = 0; d <= 9; d++) good &= same(special[i], d);
    ok(good, "special values match printf for 0..9 decimals");

    good = 1;
    for (int i = 0; i < 300000 && good; i++) {
        uint64_t r = next();
        double x = (double)(int64_t)(r >> 11) / (double)(1ull << (r % 50)) * ((r & 1) ? -1 : 1);
        good &= same(x, (int)(next() % 10));
    }
    ok(good, "300000 random values match printf");

    good = 1;
    /* exact ties at the last digit: k/2 * 10^-d for odd k */
    for (int k = 1; k < 20000 && good; k += 2) {
        good &= same(k / 2.0 / 1e0, 0);
        good &= same(k / 128.0, 6); /* binary fractions: exact decimal ties */
    }
    ok(good, "exact halfway cases round to even like printf");

    good = 1;
    for (int i = 0; i < 200000 && good; i++) {
        /* decimals as users write them: n / 10^k */
        int64_t n = (int64_t)(next() % 200000001) - 100000000;
        double x = (double)n / 1e6;
        good &= same(x, 6) && same(x, 5) && same(x, 3);
    }
    ok(good, "decimal inputs match printf");

    /* every precision of the fast path (0..15) and past it, at every
     * integer length: 1 digit up to the fast path's limit near 4e15 */
    good = 1;
    for (int i = 0; i < 200000 && good; i++) {
        uint64_t r = next();
        int d = (int)(r % 18);
        double mag = (double)(1ull << (r >> 8) % 52);
        double x = (double)(next() >> 11) / (double)(1ull << 53) * mag * ((r >> 7) & 1 ? -1 : 1);
        good &= same(x, d);
    }
    ok(good, "precisions 0 to 17 and integer parts of every length match printf");
    durations();
    lengths();
    return done_testing();
}
