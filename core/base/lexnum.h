/* lexnum: the number reader and small lexical helpers shared by the text
 * importers that read counted buffers (STL, OBJ).
 *
 * Everything works on a byte range s[0..n): nothing past s + n is read and
 * no NUL terminator is needed. Nothing here keeps state, so every function
 * may be called from several threads at once.
 *
 * Numbers: [+-]digits[.digits][(e|E)[+-]digits] (".5" and "5." too). The
 * words nan, inf and infinity (any case, with a sign) and MSVC's 1.#QNAN /
 * -1.#IND / 1.#INF (any digits before the '#', any letters and digits after
 * it) are read as non-finite values, so that an importer can say "not a
 * finite number" rather than "malformed". Conversion is exact (correctly
 * rounded): Clinger's fast path (mantissa <= 2^53, |exponent| <= 22) and
 * otherwise strtod on the digits rewritten without a decimal point, which
 * keeps the result independent of the C locale's decimal separator. */
#ifndef LAM_LEXNUM_H
#define LAM_LEXNUM_H

#include <stddef.h>
#include <string.h>

#include "error.h"

/* Read the whole of s[0..n) as a number into *out (NaN or infinite for the
 * words above; a value too large for a double becomes an infinity, too small
 * a zero, as strtod does). Returns LAM_OK; LAM_ESYNTAX when s[0..n) is not a
 * number (empty, trailing bytes, no digits, exponent without digits), *out
 * then untouched; LAM_ENOMEM when a number of more than 288 digits could
 * not be copied for strtod. No message is recorded: the caller knows where
 * the number stood and reports it. */
int lam_parse_number(const unsigned char *s, size_t n, double *out);

/* 1 when s[0..n) spells the word kw (lower-case, NUL-terminated) in any
 * ASCII case, else 0. Reads no more than n bytes of s. Inline: lexers call
 * it for every keyword they try. */
static inline int lam_word_eq_nocase(const unsigned char *s, size_t n, const char *kw)
{
    if (n != strlen(kw)) return 0;
    for (size_t i = 0; i < n; i++) {
        unsigned char c = s[i] >= 'A' && s[i] <= 'Z' ? (unsigned char)(s[i] + 32) : s[i];
        if (c != (unsigned char)kw[i]) return 0;
    }
    return 1;
}

/* Write s[0..n) into the caller's buf (size >= 3 bytes) as 'text' for a
 * message: at most LAM_QUOTE_MAX bytes shown, so that a message never
 * carries a line of a file (the one quoting rule of every reader), bytes
 * outside printable ASCII as \xNN,
 * "..." when cut (a short buf shows fewer bytes). Always NUL-terminated.
 * Returns buf; cannot fail. */
#define LAM_QUOTE_MAX 20
const char *lam_quote_bytes(char *buf, size_t size, const unsigned char *s, size_t n);

#endif
