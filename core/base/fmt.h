/* Number formatting: for program writers, the same characters as
 * printf("%.*f") without printf's arbitrary-precision path; for programs
 * and people, the shortest text that reads back as the same double. */
#ifndef LAM_FMT_H
#define LAM_FMT_H

#include <stddef.h>

#define LAM_FMT_MAX 400 /* room for any double with up to 40 decimals */

/* Write x with `decimals` digits after the point into buf (LAM_FMT_MAX
 * bytes), exactly as snprintf("%.*f", decimals, x) would, including the
 * round-half-even rule on exact ties and "-0.000000" for tiny negatives.
 * Returns the length. */
size_t lam_fmt_fixed(char *buf, double x, int decimals);

/* The fewest significant digits, at most `digits` (1..17), that read back
 * as exactly x, in the notation %g would choose for them: plain decimals
 * for 1e-4 <= |x| < 1e17, else an exponent (600, 0.08, 1e-05, 1e+20);
 * never "-0". When no text of at most `digits` digits reads back as x, x
 * rounded to `digits` digits. digits 17 is always exact; 15 (LAM_NUM) drops
 * the last-bit noise of arithmetic (110.1 - 1.7 prints 108.4, not
 * 108.39999999999999) and prints any decimal of up to 15 digits as typed.
 * buf holds LAM_FMT_NUM bytes. Returns buf. */
#define LAM_FMT_NUM 32
const char *lam_fmt_num(char *buf, double x, int digits);

/* For messages: a number for people as a printf %s argument, in a buffer
 * that lives to the end of the enclosing block:
 *   printf("layer %zu (h=%s)", i + 1, LAM_NUM(h));
 * LAM_NUM drops arithmetic noise (15 digits), LAM_NUM_EXACT never does
 * (17: for numbers whose last bits are the point, such as two heights
 * that differ by an ulp). */
#define LAM_NUM(x) lam_fmt_num((char[LAM_FMT_NUM]){ 0 }, (x), 15)
#define LAM_NUM_EXACT(x) lam_fmt_num((char[LAM_FMT_NUM]){ 0 }, (x), 17)

/* Two numbers for people that are told apart: each at 15 digits as
 * LAM_NUM, or at 17 (exact) when those texts would be the same but x != y
 * ("the widths add up to 1.9999999999999998 but the model spans 2").
 * a and b hold LAM_FMT_NUM bytes. */
void lam_fmt_pair(char *a, char *b, double x, double y);

/* A byte count for people, in powers of 1024 as the size limits:
 * "512 bytes", "1.5 kB", "16 GB" (three significant digits). Returns buf. */
const char *lam_fmt_bytes(char *buf, size_t size, double n);

/* |x| * 10^decimals rounded to a whole number, exactly as lam_fmt_fixed
 * rounds (half to even on exact ties), into *q: returns 1; 0 (q untouched)
 * when x is not finite, decimals is not 0..15 or |x| * 10^decimals >= 4e15
 * (where lam_fmt_fixed uses printf). */
int lam_fmt_scaled(double x, int decimals, unsigned long long *q);

/* The text of lam_fmt_fixed for a value lam_fmt_scaled turned into q
 * (decimals 0..15), with a '-' when neg. Returns the length. Lets a caller
 * that meets the same rounded value again reuse its text. */
size_t lam_fmt_scaled_text(char *buf, unsigned long long q, int decimals, int neg);

/* A duration for people, rounded once to the resolution shown and then
 * split into units (so 59.96 s is "1 min 0 s", never "60 s"):
 *   below 0.1 s   two significant digits: "0.050 s", "0.0012 s" ("0 s" for 0;
 *                 "%.2g s" when 15 decimals show fewer: "3e-16 s")
 *   below 10 s    tenths: "0.8 s", "3.8 s", "1.0 s"
 *   below 1 day   whole seconds, every unit below the largest shown:
 *                 "45 s", "12 min 3 s", "1 h 0 min 0 s" (3599.6 s)
 *   from 1 day    whole minutes: "2 d 3 h 4 min"; from 4e15 s "%.3g d"
 * Each range is chosen by the rounded value (9.96 s is "10 s"); rounding is
 * exact, half to even on exact ties (lam_fmt_scaled). A negative or not
 * finite seconds is "unknown". Writes at most size bytes (snprintf's
 * truncation); returns buf. */
const char *lam_fmt_duration(double seconds, char *buf, size_t size);

/* A length for people: three significant digits with the trailing zeros
 * of the fraction dropped, in the metric unit the rounded value reads best
 * in: km from 1 km, m from 1 m, mm from 0.1 mm, else µm ("3.02 km",
 * "120 m", "45.3 mm", "0.8 mm", "50 µm"; 0 is "0 mm"). length is in model
 * units, mm_per_unit how many millimetres one is (lam_key_unit_mm,
 * profile_keys.h); when that is 0 (a unit lamina does not know) the
 * number is written in model units followed by ` unit` ("2930 furlong",
 * or the number alone when unit is NULL or ""). The digits are %.2e's
 * (exactly rounded); numbers too large or small to write plainly (a
 * decimal exponent past 17 or below -4 in the unit) are written as %.3g. A
 * negative length gets a "-"; a not finite one is "unknown". Writes at most
 * size bytes; returns buf. */
const char *lam_fmt_length(double length, double mm_per_unit, const char *unit, char *buf, size_t size);

#endif
