#include "fmt.h"

#include "error.h"
#include "lexnum.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char pairs[] = "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
                            "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
                            "8081828384858687888990919293949596979899";

static const double pow10_tab[] = { 1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9,
                                    1e10, 1e11, 1e12, 1e13, 1e14, 1e15 };

int lam_fmt_scaled(double x, int d, unsigned long long *out)
{
    /* x * 10^d well inside the exact integer range */
    if (!isfinite(x) || d < 0 || d > 15 || fabs(x) * pow10_tab[d] >= 4e15) return 0;
    double s = pow10_tab[d];
    double ax = fabs(x);
    double p = ax * s;
    unsigned long long q = (unsigned long long)p; /* floor: 0 <= p < 2^52 */
    double t = (p - (double)q) - 0.5;            /* p - q is exact */
    /* p is ax * s rounded, off by at most half an ulp of p (<= p * 2^-53):
     * unless p lies that close to a midpoint, t's sign decides. Only then
     * the exact error of the product (a fused multiply-add, a library call
     * on a baseline x86-64 build) */
    if (fabs(t) > p * 0x1p-52) {
        *out = q + (t > 0);
        return 1;
    }
    double e = fma(ax, s, -p);                   /* ax * s == p + e exactly */
    double r = t + e;                            /* its sign is the exact sum's sign */
    if (r > 0 || (r == 0 && (q & 1))) q++;
    *out = q;
    return 1;
}

size_t lam_fmt_fixed(char *buf, double x, int d)
{
    unsigned long long q;
    if (!lam_fmt_scaled(x, d, &q)) {
        int n = snprintf(buf, LAM_FMT_MAX, "%.*f", d < 0 ? 0 : d > 40 ? 40 : d, x);
        return n < 0 ? 0 : (size_t)n;
    }
    return lam_fmt_scaled_text(buf, q, d, signbit(x) != 0);
}

size_t lam_fmt_scaled_text(char *buf, unsigned long long q, int d, int neg)
{
    double s = pow10_tab[d];
    /* Digits from the right into the end of tmp: the d decimals, the point,
     * then the integer part. The split divides by a constant per case, so
     * the compiler turns it into a multiplication. */
    uint64_t ip, fp;
    switch (d) {
    case 0: ip = q; fp = 0; break;
    case 1: ip = q / 10u; fp = q % 10u; break;
    case 2: ip = q / 100u; fp = q % 100u; break;
    case 3: ip = q / 1000u; fp = q % 1000u; break;
    case 4: ip = q / 10000u; fp = q % 10000u; break;
    case 5: ip = q / 100000u; fp = q % 100000u; break;
    case 6: ip = q / 1000000u; fp = q % 1000000u; break;
    case 7: ip = q / 10000000u; fp = q % 10000000u; break;
    case 8: ip = q / 100000000u; fp = q % 100000000u; break;
    case 9: ip = q / 1000000000u; fp = q % 1000000000u; break;
    default: {
        uint64_t p10 = (uint64_t)s;
        ip = q / p10;
        fp = q % p10;
    }
    }
    /* The length is known before the first digit, so the digits go
     * straight to their places, right to left. */
    int nint = 1;
    for (uint64_t v = ip; v >= 10u; v /= 10u) nint++;
    size_t len = (size_t)(neg ? 1 : 0) + (size_t)nint + (d > 0 ? 1 + (size_t)d : 0);
    char *w = buf + len;
    if (neg) buf[0] = '-';
    int k = d;
    for (; k >= 2; k -= 2) {
        unsigned two = (unsigned)(fp % 100u);
        fp /= 100u;
        w -= 2;
        memcpy(w, pairs + 2 * two, 2);
    }
    if (k) *--w = (char)('0' + fp);
    if (d > 0) *--w = '.';
    while (ip >= 100u) {
        unsigned two = (unsigned)(ip % 100u);
        ip /= 100u;
        w -= 2;
        memcpy(w, pairs + 2 * two, 2);
    }
    if (ip >= 10u) {
        w -= 2;
        memcpy(w, pairs + 2 * ip, 2);
    } else {
        *--w = (char)('0' + ip);
    }
    buf[len] = '\0';
    return len;
}

const char *lam_fmt_num(char *buf, double x, int digits)
{
    if (digits < 1) digits = 1;
    if (digits > 17) digits = 17; /* 17 digits read back as any double */
    if (x == 0) x = 0;            /* no "-0" */
    if (!isfinite(x)) {
        snprintf(buf, LAM_FMT_NUM, "%g", x);
        return buf;
    }
    char e[LAM_FMT_NUM];
    int prec = 1;
    for (;; prec++) {
        int n = snprintf(e, sizeof e, "%.*e", prec - 1, x);
        double back;
        if (prec == digits ||
            (lam_parse_number((const unsigned char *)e, (size_t)n, &back) == LAM_OK && back == x))
            break;
    }
    /* the decimal exponent of those digits decides the notation, as %.17g
     * decides it: plain decimals for 1e-4 <= |x| < 1e17 */
    int exp10 = atoi(strchr(e, 'e') + 1);
    if (exp10 >= -4 && exp10 < 17 && prec < exp10 + 1) prec = exp10 + 1;
    snprintf(buf, LAM_FMT_NUM, "%.*g", prec, x);
    return buf;
}

const char *lam_fmt_bytes(char *buf, size_t size, double n)
{
    static const char *const unit[] = { "bytes", "kB", "MB", "GB", "TB", "PB", "EB" };
    int u = 0;
    while (n >= 1024 && u < 6) n /= 1024, u++;
    snprintf(buf, size, u ? "%.3g %s" : "%.0f %s", n, unit[u]);
    return buf;
}

void lam_fmt_pair(char *a, char *b, double x, double y)
{
    lam_fmt_num(a, x, 15);
    lam_fmt_num(b, y, 15);
    if (x != y && !strcmp(a, b)) lam_fmt_num(a, x, 17), lam_fmt_num(b, y, 17);
}

/* ---- for people: durations and lengths ------------------------------------ */

/* Whole minutes of seconds t (86400 <= t < 4e15), rounded half to even
 * exactly: t = 60 m + r with r computed without rounding (r < 64 and t's
 * fraction needs at most 36 bits below the point from t >= 2^16, 42 bits in
 * all), so only the comparison with 30 decides. */
static unsigned long long whole_minutes(double t)
{
    unsigned long long s = (unsigned long long)t; /* floor: t < 2^52 */
    double r = (double)(s % 60u) + (t - (double)s);
    unsigned long long m = s / 60u;
    return m + (r > 30 || (r == 30 && (m & 1u)));
}

const char *lam_fmt_duration(double t, char *buf, size_t size)
{
    unsigned long long q;
    if (!(t >= 0) || !isfinite(t)) {
        snprintf(buf, size, "unknown");
        return buf;
    }
    if (t == 0) {
        snprintf(buf, size, "0 s");
        return buf;
    }
    if (!lam_fmt_scaled(t, 0, &q)) { /* from 4e15 s: 46 billion days */
        snprintf(buf, size, "%.3g d", t / 86400);
        return buf;
    }
    char num[LAM_FMT_MAX];
    if (t < 0.1) {
        /* the decimals that show two significant digits: the first d with
         * t 10^d >= 10 (a product rounded up to 10 is t within an ulp of
         * 10^-(d-1), whose two digits at d + 1 round to the same value) */
        int d = 2;
        while (d < 15 && t * pow10_tab[d] < 10) d++;
        lam_fmt_scaled(t, d, &q);
        if (q < 10u) {
            snprintf(buf, size, "%.2g s", t);
            return buf;
        }
        if (q < (unsigned long long)pow10_tab[d - 1]) { /* still below 0.1 once rounded */
            lam_fmt_scaled_text(num, q, d, 0);
            snprintf(buf, size, "%s s", num);
            return buf;
        }
    }
    if (lam_fmt_scaled(t, 1, &q) && q < 100u) {
        snprintf(buf, size, "%llu.%llu s", q / 10u, q % 10u);
        return buf;
    }
    lam_fmt_scaled(t, 0, &q);
    if (q < 86400u) {
        unsigned long long h = q / 3600u, m = q / 60u % 60u, s = q % 60u;
        if (h) snprintf(buf, size, "%llu h %llu min %llu s", h, m, s);
        else if (m) snprintf(buf, size, "%llu min %llu s", m, s);
        else snprintf(buf, size, "%llu s", s);
        return buf;
    }
    unsigned long long m = whole_minutes(t);
    snprintf(buf, size, "%llu d %llu h %llu min", m / 1440u, m / 60u % 24u, m % 60u);
    return buf;
}

/* The three digits dig (a nonzero first) times 10^(e - 2) as plain
 * decimals into out (room for 24), the fraction's trailing zeros dropped;
 * -4 <= e <= 17. */
static void plain3(char *out, const char dig[3], int e)
{
    char *w = out;
    if (e < 0) {
        *w++ = '0';
        *w++ = '.';
        for (int k = -1; k > e; k--) *w++ = '0';
        for (int k = 0; k < 3; k++) *w++ = dig[k];
    } else {
        for (int k = 0; k <= e; k++) *w++ = k < 3 ? dig[k] : '0';
        if (e < 2) {
            *w++ = '.';
            for (int k = e + 1; k < 3; k++) *w++ = dig[k];
        }
    }
    *w = '\0';
    if (strchr(out, '.')) { /* trailing zeros of the fraction, then a bare point */
        while (w[-1] == '0') *--w = '\0';
        if (w[-1] == '.') *--w = '\0';
    }
}

const char *lam_fmt_length(double length, double mm_per_unit, const char *unit, char *buf, size_t size)
{
    if (!isfinite(length) || !isfinite(mm_per_unit) || !(mm_per_unit >= 0)) {
        snprintf(buf, size, "unknown");
        return buf;
    }
    const char *sign = length < 0 ? "-" : "", *name = unit && *unit ? unit : "";
    int known = mm_per_unit > 0;
    double v = fabs(length) * (known ? mm_per_unit : 1);
    if (!isfinite(v)) {
        snprintf(buf, size, "unknown");
        return buf;
    }
    if (known) name = "mm";
    char num[32] = "0";
    if (v > 0) {
        char e[LAM_FMT_NUM];
        snprintf(e, sizeof e, "%.2e", v); /* d.dde+XX, exactly rounded */
        char dig[3] = { e[0], e[2], e[3] };
        int ex = atoi(e + 5);
        static const struct { int from, shift; double scale; const char *name; } units[] = {
            { 6, 6, 1e-6, "km" }, { 3, 3, 1e-3, "m" }, { -1, 0, 1, "mm" }, { INT32_MIN, -3, 1e3, "\xc2\xb5m" }
        };
        if (known) {
            size_t i = 0;
            while (ex < units[i].from) i++;
            ex -= units[i].shift;
            v *= units[i].scale;
            name = units[i].name;
        }
        if (ex < -4 || ex > 17) snprintf(num, sizeof num, "%.3g", v);
        else plain3(num, dig, ex);
    } else {
        sign = "";
    }
    snprintf(buf, size, "%s%s%s%s", sign, num, *name ? " " : "", name);
    return buf;
}
