/* Fast number formatting for program writers: the same characters as
 * printf("%.*f"), without printf's arbitrary-precision path. */
#ifndef LAM_FMT_H
#define LAM_FMT_H

#include <stddef.h>

#define LAM_FMT_MAX 400 /* room for any double with up to 40 decimals */

/* Write x with `decimals` digits after the point into buf (LAM_FMT_MAX
 * bytes), exactly as snprintf("%.*f", decimals, x) would, including the
 * round-half-even rule on exact ties and "-0.000000" for tiny negatives.
 * Returns the length. */
size_t lam_fmt_fixed(char *buf, double x, int decimals);

/* |x| * 10^decimals rounded to a whole number, exactly as lam_fmt_fixed
 * rounds (half to even on exact ties), into *q: returns 1; 0 (q untouched)
 * when x is not finite, decimals is not 0..15 or |x| * 10^decimals >= 4e15
 * (where lam_fmt_fixed uses printf). */
int lam_fmt_scaled(double x, int decimals, unsigned long long *q);

#endif
