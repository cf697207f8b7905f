/* grow.h: the doubling rule and its size checks; error.h's lam_error_nomem. */
#include <stdint.h>
#include <stdlib.h>

#include "error.h"
#include "grow.h"
#include "tap.h"

int main(void)
{
    is_int(lam_grow_cap(0, 1, 16, 8), 16, "from empty: the minimum");
    is_int(lam_grow_cap(0, 17, 16, 8), 32, "from empty: the minimum doubled until it holds need");
    is_int(lam_grow_cap(64, 65, 16, 8), 128, "one more than the capacity: doubled");
    is_int(lam_grow_cap(64, 1000, 16, 8), 1024, "doubled until it holds need");
    is_int(lam_grow_cap(0, 1, 0, 8), 1, "no minimum: at least one");
    is_int(lam_grow_cap(SIZE_MAX / 2 + 1, SIZE_MAX / 2 + 2, 16, 1), SIZE_MAX / 2 + 2,
           "near the top of size_t: need itself, not a wrapped doubling");
    is_int(lam_grow_cap(16, SIZE_MAX / 8 + 1, 16, 8), 0, "need * size past size_t: 0");
    ok(lam_realloc_n(NULL, SIZE_MAX / 4 + 1, 8) == NULL, "lam_realloc_n: a wrapping product fails");

    /* growing one element at a time keeps every value and doubles */
    int *a = NULL;
    size_t cap = 0, n = 0, reallocs = 0;
    int good = 1;
    for (int i = 0; i < 1000; i++) {
        if (n == cap) {
            int *na = lam_grow(a, &cap, n + 1, sizeof *a, 16);
            if (!na) {
                good = 0;
                break;
            }
            a = na;
            reallocs++;
        }
        a[n++] = i;
    }
    for (size_t i = 0; good && i < n; i++) good = a[i] == (int)i;
    ok(good, "1000 values survive the growth");
    is_int(cap, 1024, "capacity 16 doubled to 1024");
    is_int(reallocs, 7, "7 reallocations (16, 32, ..., 1024)");
    size_t before = cap;
    ok(lam_grow(a, &cap, SIZE_MAX / 2, sizeof *a, 16) == NULL && cap == before,
       "too large: NULL, capacity unchanged");
    free(a);

    lam_error err;
    lam_error_clear(&err);
    is_int(lam_error_nomem(&err, "while slicing"), LAM_ENOMEM, "lam_error_nomem returns LAM_ENOMEM");
    is_str(err.msg, "out of memory while slicing", "... with what was being done");
    lam_error_nomem(&err, NULL);
    is_str(err.msg, "out of memory", "... or the bare message");
    is_int(lam_error_nomem(NULL, "x"), LAM_ENOMEM, "err NULL: the code alone");
    return done_testing();
}
