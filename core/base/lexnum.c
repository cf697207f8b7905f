/* lexnum: see lexnum.h. */
#include "lexnum.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

static int is_digit(unsigned char c) { return c >= '0' && c <= '9'; }
static int is_alnum(unsigned char c)
{
    return is_digit(c) || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
}
static unsigned char lower(unsigned char c) { return c >= 'A' && c <= 'Z' ? (unsigned char)(c + 32) : c; }

static const double pow10_exact[23] = {
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11,
    1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
};

/* The value so far: mant * 10^e10, mant holding nd significant digits. */
typedef struct num_acc {
    uint64_t mant;
    int nd;
    long long e10;
} num_acc;

/* Read the run of digits at s[i..n) into a; returns the index after it. The
 * first 19 significant digits (leading zeros are not) go into the mantissa;
 * a digit past them counts in the exponent only in the integer part, and a
 * kept fraction digit lowers the exponent by one. */
static inline size_t read_digits(const unsigned char *s, size_t i, size_t n, int fraction, num_acc *a)
{
    for (; i < n && is_digit(s[i]); i++) {
        unsigned d = (unsigned)(s[i] - '0');
        if (a->nd < 19) {
            if (a->mant || d) {
                a->mant = a->mant * 10 + d;
                a->nd++;
            }
            a->e10 -= fraction;
        } else {
            a->e10 += !fraction;
        }
    }
    return i;
}

/* The slow path, for strtod: the sign, every digit of s[0..n) (digits and
 * at most one '.') without the point, and the exponent ev adjusted for the
 * fraction digits. Kept out of line: its buffer would weigh on every call. */
static __attribute__((noinline)) int exact_slow(const unsigned char *s, size_t n, int neg, long long ev,
                                                double *out)
{
    char small[320], *buf = small;
    size_t need = n + 32;
    if (need > sizeof small && !(buf = malloc(need))) return LAM_ENOMEM;
    size_t k = 0;
    long long frac = 0;
    int in_frac = 0;
    if (neg) buf[k++] = '-';
    for (size_t j = 0; j < n; j++) {
        if (s[j] == '.') {
            in_frac = 1;
            continue;
        }
        buf[k++] = (char)s[j];
        frac += in_frac;
    }
    snprintf(buf + k, need - k, "e%lld", ev - frac);
    *out = strtod(buf, NULL);
    if (buf != small) free(buf);
    return LAM_OK;
}

int lam_parse_number(const unsigned char *s, size_t n, double *out)
{
    size_t i = 0;
    int neg = 0;
    if (i < n && (s[i] == '+' || s[i] == '-')) neg = s[i++] == '-';
    if (i < n && !is_digit(s[i]) && s[i] != '.') {
        if (lam_word_eq_nocase(s + i, n - i, "nan")) {
            *out = NAN;
            return LAM_OK;
        }
        if (lam_word_eq_nocase(s + i, n - i, "inf") || lam_word_eq_nocase(s + i, n - i, "infinity")) {
            *out = neg ? -INFINITY : INFINITY;
            return LAM_OK;
        }
        return LAM_ESYNTAX;
    }
    size_t digits_from = i;
    num_acc a = { 0, 0, 0 };
    size_t j = read_digits(s, i, n, 0, &a);
    int digits = j > i;
    i = j;
    if (i < n && s[i] == '.') {
        j = read_digits(s, i + 1, n, 1, &a);
        digits |= j > i + 1;
        i = j;
        if (i < n && s[i] == '#' && digits) { /* MSVC: 1.#QNAN0, -1.#IND00, 1.#INF00 */
            j = i + 1;
            while (j < n && is_alnum(s[j])) j++;
            if (j != n || j == i + 1) return LAM_ESYNTAX;
            if (n - i > 3 && lower(s[i + 1]) == 'i' && lower(s[i + 2]) == 'n' && lower(s[i + 3]) == 'f')
                *out = neg ? -INFINITY : INFINITY;
            else
                *out = NAN;
            return LAM_OK;
        }
    }
    if (!digits) return LAM_ESYNTAX;
    size_t digits_to = i;
    long long ev = 0;
    if (i < n && (s[i] == 'e' || s[i] == 'E')) {
        i++;
        int eneg = 0;
        if (i < n && (s[i] == '+' || s[i] == '-')) eneg = s[i++] == '-';
        if (i >= n || !is_digit(s[i])) return LAM_ESYNTAX;
        for (; i < n && is_digit(s[i]); i++)
            if (ev < 1000000000) ev = ev * 10 + (s[i] - '0');
        if (eneg) ev = -ev;
    }
    if (i != n) return LAM_ESYNTAX;
    if (a.mant == 0) {
        *out = neg ? -0.0 : 0.0;
        return LAM_OK;
    }
    long long e10 = a.e10 + ev;
#if FLT_EVAL_METHOD == 0
    if (a.mant <= (UINT64_C(1) << 53) && e10 >= -22 && e10 <= 22) {
        double d = (double)a.mant;
        d = e10 < 0 ? d / pow10_exact[-e10] : d * pow10_exact[e10];
        *out = neg ? -d : d;
        return LAM_OK;
    }
#endif
    return exact_slow(s + digits_from, digits_to - digits_from, neg, ev, out);
}

const char *lam_quote_bytes(char *buf, size_t size, const unsigned char *s, size_t n)
{
    size_t k = 0, i;
    buf[k++] = '\'';
    for (i = 0; i < n && i < LAM_QUOTE_MAX && k + 10 < size; i++) {
        if (s[i] >= 0x20 && s[i] < 0x7f) {
            buf[k++] = (char)s[i];
        } else {
            snprintf(buf + k, size - k, "\\x%02x", s[i]);
            k += 4;
        }
    }
    if (i < n && k + 5 < size) {
        memcpy(buf + k, "...", 3);
        k += 3;
    }
    buf[k++] = '\'';
    buf[k] = '\0';
    return buf;
}
