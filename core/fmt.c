#include "fmt.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

static const double pow10_tab[] = { 1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9,
                                    1e10, 1e11, 1e12, 1e13, 1e14, 1e15 };

size_t lam_fmt_fixed(char *buf, double x, int d)
{
    /* the fast path needs x * 10^d well inside the exact integer range */
    if (!isfinite(x) || d < 0 || d > 15 || fabs(x) * pow10_tab[d] >= 4e15) {
        int n = snprintf(buf, LAM_FMT_MAX, "%.*f", d < 0 ? 0 : d > 40 ? 40 : d, x);
        return n < 0 ? 0 : (size_t)n;
    }
    double s = pow10_tab[d];
    double ax = fabs(x);
    double p = ax * s;
    double e = fma(ax, s, -p);          /* ax * s == p + e exactly */
    double fl = floor(p);
    double t = (p - fl) - 0.5;          /* p - fl is exact */
    unsigned long long q = (unsigned long long)fl;
    double r = t + e;                   /* its sign is the exact sum's sign */
    if (r > 0 || (r == 0 && (q & 1))) q++;
    static const char pairs[] = "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
                                "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
                                "8081828384858687888990919293949596979899";
    char tmp[32];
    int n = 0;
    while (q >= 100000000) { /* 64-bit divisions only for the high part */
        unsigned lo2 = (unsigned)(q % 100);
        q /= 100;
        tmp[n++] = pairs[2 * lo2 + 1];
        tmp[n++] = pairs[2 * lo2];
    }
    uint32_t q32 = (uint32_t)q;
    while (q32 >= 10) {
        unsigned lo2 = q32 % 100;
        if (q32 < 100) {
            tmp[n++] = pairs[2 * lo2 + 1];
            tmp[n++] = pairs[2 * lo2];
            q32 = 0;
            break;
        }
        q32 /= 100;
        tmp[n++] = pairs[2 * lo2 + 1];
        tmp[n++] = pairs[2 * lo2];
    }
    if (q32 || n == 0) tmp[n++] = (char)('0' + q32);
    while (n <= d) tmp[n++] = '0';    /* at least one digit before the point */
    size_t len = 0;
    if (signbit(x)) buf[len++] = '-';
    for (int i = n - 1; i >= 0; i--) {
        buf[len++] = tmp[i];
        if (i == d && d > 0) buf[len++] = '.';
    }
    buf[len] = '\0';
    return len;
}
