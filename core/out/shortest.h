/* The fast way to lam_dialect_number's text (dialect_template.h: the
 * fewest decimals up to 15 whose rounding reads back, else x's 17 digits
 * rounded to 15 or 16 or kept, the first that reads back, in plain
 * notation) for what plans are made of, and the layout of digits as a
 * plain decimal both ways share. Formatting numbers is most of the time of
 * writing a program or the JSON: this is about eight times faster than
 * printf and a read-back on hatch coordinates, with the same bytes. */
#ifndef LAM_SHORTEST_H
#define LAM_SHORTEST_H

#include <stddef.h>

/* lam_dialect_number's text of x into out (LAM_FMT_MAX bytes) and its
 * length, for finite x with 1e-4 <= |x| < 1e15; 0 (nothing written that
 * counts) for any x it cannot decide exactly (a tie at a rounding, a power
 * of two's uneven gaps, the range): the caller then takes the slow way. */
size_t lam_shortest_plain(char *out, double x);

/* Lay out the significant digits d[0..prec) of a number whose first digit
 * is at the power exp10 (exp10 < 0, or exp10 + 1 <= prec) as a plain
 * decimal with no exponent, '-' first when neg: "0.00125", "12.5", "125".
 * out holds at least prec + |exp10| + 4 bytes; returns the length. */
size_t lam_shortest_layout(char *out, int neg, const char *d, int prec, int exp10);

#endif
