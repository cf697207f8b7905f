/* The viewer's layer blocks (vblock.h, docs/viewer.md) and base64
 * (buf.h): base64 against RFC 4648's own test vectors and against the
 * test's decoder on random bytes; a block's bytes against the ones worked
 * out by hand from docs/viewer.md's grammar. */
#include "buf.h"
#include "tap.h"
#include "util.h"
#include "vblock.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static uint64_t rng = 0x9e3779b97f4a7c15ull;

static void base64_vectors(void)
{
    /* RFC 4648, section 10 */
    static const char *const in[] = { "", "f", "fo", "foo", "foob", "fooba", "foobar" };
    static const char *const out[] = { "", "Zg==", "Zm8=", "Zm9v", "Zm9vYg==", "Zm9vYmE=", "Zm9vYmFy" };
    for (int i = 0; i < 7; i++) {
        lam_buf b = { 0 };
        ok(lam_buf_base64(&b, in[i], strlen(in[i])) == LAM_OK, "base64 of \"%s\": ok", in[i]);
        ok(!strcmp(b.len ? b.data : "", out[i]), "base64 of vector %d is %s", i, out[i]);
        lam_buf_free(&b);
    }
}

static int val(char c)
{
    const char *A = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const char *p = strchr(A, c);
    return p && c ? (int)(p - A) : -1;
}

/* the test's own decoder: 4 characters to 3 bytes, '=' ends */
static size_t unbase64(const char *s, size_t n, unsigned char *out)
{
    size_t k = 0;
    for (size_t i = 0; i + 4 <= n; i += 4) {
        int a = val(s[i]), b = val(s[i + 1]), c = s[i + 2] == '=' ? 0 : val(s[i + 2]), d = s[i + 3] == '=' ? 0 : val(s[i + 3]);
        if (a < 0 || b < 0 || c < 0 || d < 0) return (size_t)-1;
        unsigned long t = (unsigned long)a << 18 | (unsigned long)b << 12 | (unsigned long)c << 6 | (unsigned long)d;
        out[k++] = (unsigned char)(t >> 16);
        if (s[i + 2] != '=') out[k++] = (unsigned char)(t >> 8);
        if (s[i + 3] != '=') out[k++] = (unsigned char)t;
    }
    return k;
}

static void base64_random(void)
{
    int good = 1;
    for (int round = 0; round < 200 && good; round++) {
        size_t n = (size_t)(xorshift64(&rng) % 300);
        unsigned char in[300], back[300];
        for (size_t i = 0; i < n; i++) in[i] = (unsigned char)xorshift64(&rng);
        lam_buf b = { 0 };
        lam_buf_append(&b, "x", 1); /* appends after what is there */
        good = lam_buf_base64(&b, in, n) == LAM_OK && b.len == 1 + (n + 2) / 3 * 4 &&
               unbase64(b.data + 1, b.len - 1, back) == n && !memcmp(in, back, n);
        if (!good) diag("round %d, %zu bytes", round, n);
        lam_buf_free(&b);
    }
    ok(good, "200 random byte strings: 4 characters per 3 bytes, read back by the test's decoder");
}

static lam_vec vec(int kind, double fu, double fv, double tu, double tv)
{
    lam_vec v = { .kind = kind, .attrs = lam_attrs_default() };
    v.fuv[0] = fu, v.fuv[1] = fv, v.tuv[0] = tu, v.tuv[1] = tv;
    return v;
}

static void block_by_hand(void)
{
    lam_vblock b;
    lam_vblock_init(&b, 0.5);
    /* quanta: (0,0) (2,0) (2,2); a core vector (2,2)->(0,2); a jump; a core
     * vector (0,0)->(4,0); a contour edge (4,0)->(4,2) */
    lam_vblock_contour(&b, (const double[]){ 0, 0, 1, 0, 1, 1 }, 3, 1, 0);
    lam_vec v[4] = { vec(LAM_KIND_CORE, 1, 1, 0, 1), vec(LAM_KIND_JUMP, 0, 1, 0, 0), vec(LAM_KIND_CORE, 0, 0, 2, 0),
                     vec(LAM_KIND_CONTOUR, 2, 0, 2, 1) };
    for (int i = 0; i < 4; i++) lam_vblock_vector(&b, &v[i]);
    lam_buf out = { 0 };
    ok(lam_vblock_finish(&b, &out) == LAM_OK, "a block: ok");
    static const unsigned char want[] = {
        1, 2, 0, 0, 0,                /* one attribute row: part 1 (zigzag 2), style, laser, label 0 */
        1, 3, 1, 0, 0, 4, 0, 0, 4,    /* one contour, 3 points, solid depth 0: (0,0) +(2,0) +(0,2) */
        2,                            /* two runs */
        2, 1, 0, 0, 0, 3, 0, 1, 3, 8, 0, /* 2 core: from +0 to -2,0; jump to +(0,-2), to +(4,0) */
        1, 0, 0, 0, 0, 0, 4           /* 1 contour edge: from +0, to +(0,2) */
    };
    is_int(out.len, sizeof want, "the block has the bytes worked out by hand: its length");
    ok(out.len == sizeof want && !memcmp(out.data, want, sizeof want), "... and each byte");
    /* the next layer starts from a clean cursor and table */
    lam_vblock_reset(&b);
    lam_buf_clear(&out);
    lam_vec far = vec(LAM_KIND_CORE, 500000, 0, 500000, 0);
    lam_vblock_vector(&b, &far);
    lam_vblock_finish(&b, &out);
    /* 500000 / 0.5 = 1e6 quanta; zigzag 2e6 = 0x1e8480, <<1 for the flag:
     * 4e6 = 0x3d0900 -> 0x80 0x92 0xf4 0x01 */
    static const unsigned char far_want[] = { 1, 2, 0, 0, 0, 0, 1, 1, 1, 0, 0x80, 0x92, 0xf4, 0x01, 0, 0, 0 };
    ok(out.len == sizeof far_want && !memcmp(out.data, far_want, sizeof far_want),
       "after a reset: a far point as a 4-byte varint, the cursor from (0, 0)");
    lam_buf_free(&out);
    lam_vblock_free(&b);
}

static void quantum(void)
{
    const double small[4] = { -10, -10, 250, 250 }, tiny[4] = { -1, -1, 1, 1 }, huge[4] = { 0, 0, 1e9, 1e9 };
    is_num(lam_vblock_quantum("mm", small), 1e-4, 1e-18, "mm: 0.1 um");
    is_num(lam_vblock_quantum("inch", tiny), 1e-4 / 25.4, 1e-18, "inch: 0.1 um in inches");
    is_num(lam_vblock_quantum("m", tiny), 1e-7, 1e-20, "m: 0.1 um in metres");
    double q = lam_vblock_quantum("mm", huge);
    ok(4e9 / q <= (double)(LAM_VBLOCK_MAX_Q / 4) * 1.000001, "an extent of 1e9 mm: four times it fits the block's range");
    lam_vblock b;
    lam_vblock_init(&b, 1);
    lam_vec inf = vec(LAM_KIND_CORE, 1e30, NAN, 0, 0);
    lam_vblock_vector(&b, &inf);
    lam_buf out = { 0 };
    lam_vblock_finish(&b, &out);
    /* 2^29 clamped: zigzag 2^30, <<1 = 2^31 -> 0x80 0x80 0x80 0x80 0x08; NaN
     * -> 0; back to 0: -2^29 -> zigzag 2^30-1 -> 0xff 0xff 0xff 0xff 0x03 */
    static const unsigned char want[] = { 1, 2, 0, 0, 0, 0, 1, 1, 1, 0, 0x80, 0x80, 0x80, 0x80, 0x08, 0,
                                          0xff, 0xff, 0xff, 0xff, 0x03, 0 };
    ok(out.len == sizeof want && !memcmp(out.data, want, sizeof want),
       "a point beyond the range is put at its bound, not a NaN or an overflow");
    lam_buf_free(&out);
    lam_vblock_free(&b);
}

int main(void)
{
    base64_vectors();
    base64_random();
    block_by_hand();
    quantum();
    return done_testing();
}
