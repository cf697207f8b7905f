/* lam_fmt_fixed must print exactly what printf("%.*f") prints. */
#include "fmt.h"
#include "tap.h"
#include "util.h"

#include <stdint.h>
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

int main(void)
{
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
    return done_testing();
}
