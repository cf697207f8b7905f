/* Shortest round-trip decimals without printf; see shortest.h. */
#include "shortest.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "fmt.h"

/* lam_dialect_number's text (the programs' default rendering: the fewest
 * decimals up to 15 whose rounding reads back as x, else x's 17 digits
 * rounded to 15 or 16 or kept, the first that reads back, in plain
 * notation), made here without its printf and its read-back for what a
 * plan is made of: finite, 1e-4 <= |x| < 1e15, not a power of two. Those
 * two are done exactly in 128-bit integers: x = m 2^-E (m < 2^53), so
 * x 10^s rounds as m 10^s >> E does, and a decimal q 10^-s reads back as
 * x when it is nearer to x than half the gap to x's neighbours:
 * |q 2^(E+1) - 2 m 10^s| < 10^s. Every case where the two ways could part
 * (a tie at a rounding, a power of two's uneven gaps, the range) is left
 * to lam_dialect_number's slow way. Formatting was most of the writers'
 * time: this is about eight times faster than that way on hatch coordinates,
 * and gives the same bytes (the golden corpus; millions of numbers of
 * every kind compared one by one while it was written). */
typedef unsigned __int128 u128;

static const double p10d[] = { 1, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15 };
static const uint64_t p10u[] = { 1ull, 10ull, 100ull, 1000ull, 10000ull, 100000ull, 1000000ull, 10000000ull,
                                 100000000ull, 1000000000ull, 10000000000ull, 100000000000ull, 1000000000000ull,
                                 10000000000000ull, 100000000000000ull, 1000000000000000ull,
                                 10000000000000000ull, 100000000000000000ull, 1000000000000000000ull,
                                 10000000000000000000ull };

static u128 pow10_128(int s) /* 0 <= s <= 38 */
{
    return s <= 19 ? (u128)p10u[s] : (u128)p10u[19] * p10u[s - 19];
}

/* round(m 10^s / 2^E) into *q; 0 on an exact tie */
static int scaled128(uint64_t m, int s, int E, u128 *q)
{
    u128 n = (u128)m * pow10_128(s);
    u128 r = n >> E, rem = n - (r << E), half = (u128)1 << (E - 1);
    if (rem == half) return 0;
    *q = r + (rem > half);
    return 1;
}

/* Whether the decimal q 10^-s reads back as m 2^-E (not when a tie) */
static int reads_back(u128 q, int s, uint64_t m, int E)
{
    u128 a = q << (E + 1), b = ((u128)m * pow10_128(s)) << 1;
    return (a > b ? a - b : b - a) < pow10_128(s);
}

/* Step one: the fewest decimals d <= 15 (while x 10^d rounds exactly,
 * lam_fmt_scaled's bound) whose rounding reads back, or -1. If d does, so
 * does d + 1 (its rounding is at least as near), so the most decimals say
 * whether any does, and halving finds the fewest. */
static int fewest_decimals(double x, double ax, int ex)
{
    unsigned long long q;
    int d = 15 - ((ex * 78913 >> 18) - 1); /* about 15 - floor(log10 x): 78913 / 2^18 is log10 2 */
    if (d > 15) d = 15;
    while (d >= 0 && !(ax * p10d[d] < 4e15)) d--;
    while (d < 15 && ax * p10d[d + 1] < 4e15) d++;
    if (d < 0 || !lam_fmt_scaled(x, d, &q) || (double)q / p10d[d] != ax) return -1;
    int lo = 0;
    while (lo < d) {
        int mid = (lo + d) / 2;
        if (lam_fmt_scaled(x, mid, &q) && (double)q / p10d[mid] == ax) d = mid;
        else lo = mid + 1;
    }
    return d;
}

/* Step two: x's digits into d (the first *prec of them) and its decimal
 * exponent: 17 digits as printf's %.16e, rounded to 15 or 16 when those
 * read back. 0: leave it to lam_dialect_number's slow way. */
static int digits17(uint64_t m, int E, int ex, char d[17], int *prec, int *exp10)
{
    int t = (ex * 78913 >> 18) - 1;
    u128 q17 = 0;
    for (int tries = 0;; tries++) {
        if (tries == 4 || 16 - t < 0 || 16 - t > 22 || !scaled128(m, 16 - t, E, &q17)) return 0;
        if (q17 >= p10u[17]) t++;
        else if (q17 < p10u[16]) t--;
        else break;
    }
    *prec = 17;
    for (int k = 15; k <= 16; k++) {
        /* x rounded to k digits: what rounding its 17 gives when they are
         * not a tie, and what printf gives when they are */
        u128 q;
        int s = k - 1 - t;
        if (!scaled128(m, s, E, &q)) return 0;
        *exp10 = t;
        if (q == p10u[k]) q = p10u[k - 1], *exp10 = t + 1, s--; /* 9.99... rounded up */
        if (s < 0) return 0;
        if (!reads_back(q, s, m, E)) continue;
        *prec = k;
        for (uint64_t w = (uint64_t)q; k--; w /= 10) d[k] = (char)('0' + (int)(w % 10));
        return 1;
    }
    *exp10 = t;
    for (uint64_t w = (uint64_t)q17, k = 17; k--; w /= 10) d[k] = (char)('0' + (int)(w % 10));
    return 1;
}

size_t lam_shortest_plain(char *out, double x)
{
    double ax = fabs(x);
    if (!(ax >= 1e-4 && ax < 1e15)) return 0;
    int ex;
    double f = frexp(ax, &ex);
    int dec = fewest_decimals(x, ax, ex);
    if (dec >= 0) return lam_fmt_fixed(out, x, dec);
    uint64_t m = (uint64_t)ldexp(f, 53);
    int E = 53 - ex, prec, exp10;
    char d[17];
    if (m == (uint64_t)1 << 52 || E < 1 || E > 70 || !digits17(m, E, ex, d, &prec, &exp10))
        return 0;
    while (prec > 1 && d[prec - 1] == '0') prec--;
    if (exp10 < -4 || exp10 >= 15 || prec < exp10 + 1) return 0;
    return lam_shortest_layout(out, signbit(x) != 0, d, prec, exp10);
}

size_t lam_shortest_layout(char *out, int neg, const char *d, int prec, int exp10)
{
    size_t k = 0;
    if (neg) out[k++] = '-';
    if (exp10 < 0) {
        out[k++] = '0';
        out[k++] = '.';
        for (int i = 0; i < -exp10 - 1; i++) out[k++] = '0';
        memcpy(out + k, d, (size_t)prec);
        k += (size_t)prec;
    } else {
        memcpy(out + k, d, (size_t)exp10 + 1);
        k += (size_t)exp10 + 1;
        if (prec > exp10 + 1) {
            out[k++] = '.';
            memcpy(out + k, d + exp10 + 1, (size_t)(prec - exp10 - 1));
            k += (size_t)(prec - exp10 - 1);
        }
    }
    out[k] = '\0';
    return k;
}
