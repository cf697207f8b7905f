/* buf.h: the growing byte buffer (append, printf, take, the failure that
 * leaves it unchanged). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "buf.h"
#include "error.h"
#include "tap.h"

int main(void)
{
    lam_buf b;
    lam_buf_init(&b);
    ok(b.data == NULL && b.len == 0 && b.cap == 0, "init: empty, no memory");
    size_t n = 99;
    char *t = lam_buf_take(&b, &n);
    ok(t && t[0] == '\0' && n == 0, "take of an empty buffer: a new \"\"");
    free(t);

    is_int(lam_buf_append(&b, "ab", 2), LAM_OK, "append");
    is_int(lam_buf_append(&b, NULL, 0), LAM_OK, "append nothing (NULL, 0)");
    is_int(lam_buf_printf(&b, "-%d-%s", 42, "x"), LAM_OK, "printf");
    is_str(b.data, "ab-42-x", "bytes in order, NUL-terminated");
    is_int(b.len, 7, "length without the NUL");
    is_int(b.cap, 64, "first room: 64 bytes");

    /* a printf longer than the room left: measured, grown, written again */
    char big[300];
    memset(big, 'q', sizeof big - 1);
    big[sizeof big - 1] = '\0';
    is_int(lam_buf_printf(&b, "[%s]", big), LAM_OK, "printf past the room");
    ok(b.len == 7 + 301 && b.data[7] == '[' && b.data[b.len - 1] == ']' && b.data[b.len] == '\0',
       "long printf whole, NUL after it");
    is_int(b.cap, 512, "room doubled to 512");

    /* growing a byte at a time keeps every byte */
    lam_buf_clear(&b);
    ok(b.len == 0 && b.data[0] == '\0' && b.cap == 512, "clear keeps the memory");
    int good = 1;
    for (int i = 0; i < 5000 && good; i++) good = lam_buf_append(&b, &"0123456789"[i % 10], 1) == LAM_OK;
    for (size_t i = 0; good && i < 5000; i++) good = b.data[i] == (char)('0' + i % 10);
    ok(good && b.len == 5000 && b.cap == 8192, "5000 bytes one at a time: all there, room 8192");

    size_t len = b.len, cap = b.cap;
    is_int(lam_buf_reserve(&b, SIZE_MAX - 2), LAM_ENOMEM, "room past size_t: LAM_ENOMEM");
    /* (sizes that wrap, not sizes to try: a sanitizer refuses those loudly) */
    is_int(lam_buf_append(&b, "x", SIZE_MAX - len), LAM_ENOMEM, "an append that wraps with the NUL: LAM_ENOMEM");
    ok(b.len == len && b.cap == cap && b.data[len] == '\0', "... and the buffer unchanged");

    t = lam_buf_take(&b, &n);
    ok(t && n == 5000 && t[4999] == '9' && t[5000] == '\0', "take hands over the bytes");
    ok(b.data == NULL && b.len == 0 && b.cap == 0, "... and leaves the buffer empty");
    free(t);
    is_int(lam_buf_printf(&b, "%s", ""), LAM_OK, "printf of nothing");
    ok(b.len == 0, "... adds nothing");
    lam_buf_free(&b);
    lam_buf_free(NULL);
    ok(b.data == NULL, "free leaves it empty; NULL is fine");
    return done_testing();
}
