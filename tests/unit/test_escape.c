/* escape.h: strings into XML and JSON. The cases are written out from the
 * rules (XML 1.0's Char production, RFC 8259's string, the HTML script
 * element); then every string of up to four bytes over a set of bytes that
 * matter (every byte up to two) is escaped and the result checked by the
 * test's own reading: Unicode's table of well-formed UTF-8 byte sequences
 * (Table 3-7, written here as ranges, not as lam_utf8_len's arithmetic),
 * XML's characters and entities, JSON's escapes. */
#include <stdlib.h>
#include <string.h>

#include "escape.h"
#include "tap.h"

#define FFFD "\xEF\xBF\xBD"

static char *esc(const char *t, lam_esc_mode mode)
{
    lam_writer *w;
    char *out = NULL;
    size_t len;
    if (lam_writer_memory(&w, NULL)) return NULL;
    if (lam_esc_write(w, t, mode)) {
        lam_writer_abort(w);
        return NULL;
    }
    return lam_writer_take(w, &out, &len, NULL) ? NULL : out;
}

static int check_str(const char *t, lam_esc_mode mode, const char *want, const char *what)
{
    char *got = esc(t, mode);
    int same = got && !strcmp(got, want);
    ok(same, "%s", what);
    if (!same) diag("got '%s', expected '%s'", got ? got : "(null)", want);
    free(got);
    return same;
}

/* Table 3-7: the length of the well-formed sequence at p, 0 if none. */
static size_t wellformed(const unsigned char *p, size_t n)
{
    static const struct { unsigned char lo[4], hi[4]; size_t k; } row[] = {
        { { 0x00 }, { 0x7F }, 1 },
        { { 0xC2, 0x80 }, { 0xDF, 0xBF }, 2 },
        { { 0xE0, 0xA0, 0x80 }, { 0xE0, 0xBF, 0xBF }, 3 },
        { { 0xE1, 0x80, 0x80 }, { 0xEC, 0xBF, 0xBF }, 3 },
        { { 0xED, 0x80, 0x80 }, { 0xED, 0x9F, 0xBF }, 3 },
        { { 0xEE, 0x80, 0x80 }, { 0xEF, 0xBF, 0xBF }, 3 },
        { { 0xF0, 0x90, 0x80, 0x80 }, { 0xF0, 0xBF, 0xBF, 0xBF }, 4 },
        { { 0xF1, 0x80, 0x80, 0x80 }, { 0xF3, 0xBF, 0xBF, 0xBF }, 4 },
        { { 0xF4, 0x80, 0x80, 0x80 }, { 0xF4, 0x8F, 0xBF, 0xBF }, 4 },
    };
    for (size_t r = 0; r < sizeof row / sizeof row[0]; r++) {
        size_t k = row[r].k, i = 0;
        while (i < k && i < n && p[i] >= row[r].lo[i] && p[i] <= row[r].hi[i]) i++;
        if (i == k) return k;
    }
    return 0;
}

/* Is `s` well-formed XML character data with nothing that opens markup:
 * UTF-8, only characters XML 1.0 takes (none of those escape.h also
 * leaves out), no < > " ', every & one of the five entities? */
static int good_xml(const char *s)
{
    static const char *ent[] = { "&lt;", "&gt;", "&amp;", "&quot;", "&#39;" };
    const unsigned char *p = (const unsigned char *)s;
    size_t n = strlen(s);
    while (n) {
        size_t k = wellformed(p, n);
        if (!k) return 0;
        if (k == 1 && (*p < 0x20 || *p == 0x7F || strchr("<>\"'", *p))) return 0;
        if (k == 2 && p[0] == 0xC2 && p[1] <= 0x9F) return 0;                        /* C1 */
        if (k == 3 && p[0] == 0xEF && p[1] == 0xBF && (p[2] == 0xBE || p[2] == 0xBF)) return 0; /* U+FFFE, U+FFFF */
        if (*p == '&') {
            size_t e = 0;
            while (e < 5 && strncmp((const char *)p, ent[e], strlen(ent[e]))) e++;
            if (e == 5) return 0;
            k = strlen(ent[e]);
        }
        p += k, n -= k;
    }
    return 1;
}

/* Is `s` the inside of a JSON string (script: with no '<')? */
static int good_json(const char *s, int script)
{
    const unsigned char *p = (const unsigned char *)s;
    size_t n = strlen(s);
    while (n) {
        size_t k = wellformed(p, n);
        if (!k || *p < 0x20 || *p == '"' || (script && *p == '<')) return 0;
        if (*p == '\\') {
            if (n >= 2 && (p[1] == '"' || p[1] == '\\')) k = 2;
            else if (n >= 6 && p[1] == 'u' && strspn((const char *)p + 2, "0123456789abcdef") >= 4) k = 6;
            else return 0;
        }
        p += k, n -= k;
    }
    return 1;
}

/* Is every character of s (all of it well-formed) one that goes into XML as
 * it is? Then the escaped text must be s itself. */
static int plain_xml(const char *s)
{
    return good_xml(s) && !strchr(s, '&');
}

static void exhaustive(void)
{
    static const unsigned char some[] = { 0x01, 0x09, 0x0A, 0x0D, 0x1F, 0x20, '"', '&', '\'', '<', '>', '\\', 'A', '/',
                                          0x7F, 0x80, 0x85, 0x8F, 0x90, 0x9F, 0xA0, 0xBD, 0xBE, 0xBF, 0xC0, 0xC1,
                                          0xC2, 0xDF, 0xE0, 0xE1, 0xED, 0xEE, 0xEF, 0xF0, 0xF1, 0xF4, 0xF5, 0xFF };
    /* four-byte strings start with a byte that begins a long sequence (or
     * one that does not): what follows a shorter one is a shorter string */
    static const unsigned char lead4[] = { '<', 'A', 0xC2, 0xE0, 0xED, 0xEF, 0xF0, 0xF1, 0xF4, 0xF5, 0xFF };
    size_t ns = sizeof some, tried = 0, bad[4] = { 0 }, changed = 0;
    char ex[4][96] = { "", "", "", "" };
    for (size_t len = 1; len <= 4; len++) {
        size_t base = len <= 2 ? 255 : ns, total = len == 4 ? sizeof lead4 : base;
        for (size_t i = 1; i < len; i++) total *= base;
        for (size_t c = 0; c < total; c++) {
            unsigned char s[5] = { 0 };
            size_t x = c;
            for (size_t i = len; i-- > 0;) {
                size_t b = i == 0 && len == 4 ? sizeof lead4 : base;
                s[i] = len <= 2 ? (unsigned char)(x % b + 1) : i == 0 && len == 4 ? lead4[x % b] : some[x % b];
                x /= b;
            }
            const char *t = (const char *)s;
            char *o[3] = { esc(t, LAM_ESC_XML), esc(t, LAM_ESC_JSON), esc(t, LAM_ESC_JSON_SCRIPT) };
            int fail[4] = { !o[0] || !good_xml(o[0]), !o[1] || !good_json(o[1], 0), !o[2] || !good_json(o[2], 1),
                            /* plain text stays as it is */
                            o[0] && plain_xml(t) && strcmp(o[0], t) };
            changed += o[0] && strcmp(o[0], t);
            for (int m = 0; m < 4; m++)
                if (fail[m] && !bad[m]++)
                    snprintf(ex[m], sizeof ex[m], "%02x %02x %02x %02x -> '%s'", s[0], s[1], s[2], s[3],
                             o[m < 3 ? m : 0] ? o[m < 3 ? m : 0] : "(null)");
            for (int m = 0; m < 3; m++) free(o[m]);
            tried++;
        }
    }
    diag("%zu strings of 1 to 4 bytes, %zu changed by XML escaping", tried, changed);
    ok(!bad[0], "XML: every escaped string is well-formed character data, nothing that opens markup (%zu bad) %s",
       bad[0], ex[0]);
    ok(!bad[1], "JSON: every escaped string is a valid JSON string's inside (%zu bad) %s", bad[1], ex[1]);
    ok(!bad[2], "JSON in a script: the same, and no '<' (%zu bad) %s", bad[2], ex[2]);
    ok(!bad[3], "XML: text of plain characters is written as it is (%zu bad) %s", bad[3], ex[3]);
}

int main(void)
{
    /* XML: markup and quotes */
    check_str("<>&\"'", LAM_ESC_XML, "&lt;&gt;&amp;&quot;&#39;", "XML: < > & \" ' become the five entities");
    check_str("<script>console.log(7)</script>", LAM_ESC_XML, "&lt;script&gt;console.log(7)&lt;/script&gt;",
              "XML: a script element is text");
    check_str("<svg onload=alert(1)>", LAM_ESC_XML, "&lt;svg onload=alert(1)&gt;", "XML: an element with a handler is text");
    check_str("mm", LAM_ESC_XML, "mm", "XML: a plain unit name as it is");
    check_str("\xC2\xB5m \xE2\x82\xAC \xF0\x9F\x98\x80 " FFFD, LAM_ESC_XML, "\xC2\xB5m \xE2\x82\xAC \xF0\x9F\x98\x80 " FFFD,
              "XML: characters of 2, 3 and 4 bytes (and U+FFFD itself) as they are");
    check_str(NULL, LAM_ESC_XML, "", "NULL: nothing");
    check_str("", LAM_ESC_XML, "", "the empty string: nothing");
    /* XML: bytes that are not UTF-8, one U+FFFD each */
    check_str("a\xFF" "b", LAM_ESC_XML, "a" FFFD "b", "XML: a byte that is never UTF-8");
    check_str("\x80", LAM_ESC_XML, FFFD, "XML: a stray continuation byte");
    check_str("\xC0\xAF", LAM_ESC_XML, FFFD FFFD, "XML: an overlong '/' (2 bytes)");
    check_str("\xE0\x80\xAF", LAM_ESC_XML, FFFD FFFD FFFD, "XML: an overlong '/' (3 bytes)");
    check_str("\xED\xA0\x80", LAM_ESC_XML, FFFD FFFD FFFD, "XML: a surrogate");
    check_str("\xF4\x90\x80\x80", LAM_ESC_XML, FFFD FFFD FFFD FFFD, "XML: past U+10FFFF");
    check_str("x\xE2\x82", LAM_ESC_XML, "x" FFFD FFFD, "XML: a sequence cut short by the end");
    check_str("\xE2\x82<", LAM_ESC_XML, FFFD FFFD "&lt;", "XML: a sequence cut short by a '<', which is escaped");
    /* XML: characters XML does not take, or a page shows as nothing */
    check_str("\x01\t\n\r\x1F", LAM_ESC_XML, FFFD FFFD FFFD FFFD FFFD, "XML: C0 controls, tab and newline too");
    check_str("\x7F", LAM_ESC_XML, FFFD, "XML: DEL");
    check_str("\xC2\x80\xC2\x85\xC2\x9F\xC2\xA0", LAM_ESC_XML, FFFD FFFD FFFD "\xC2\xA0",
              "XML: the C1 controls (one U+FFFD each), not U+00A0");
    check_str("\xEF\xBF\xBE\xEF\xBF\xBF", LAM_ESC_XML, FFFD FFFD, "XML: U+FFFE and U+FFFF");
    /* JSON */
    check_str("a\"b\\c\x01\x1F<>&'", LAM_ESC_JSON, "a\\\"b\\\\c\\u0001\\u001f<>&'",
              "JSON: quote and backslash escaped, C0 controls as \\u00XX, markup as it is");
    check_str("</script><!--", LAM_ESC_JSON_SCRIPT, "\\u003c/script>\\u003c!--",
              "JSON in a script: '<' as \\u003c, so no </script> or <!--");
    check_str("a\xFF" "b\xE2\x82", LAM_ESC_JSON, "a\\ufffdb\\ufffd\\ufffd", "JSON: bytes not UTF-8 as \\ufffd");
    check_str("\x7F\xC2\x85\xEF\xBF\xBF\xF0\x9F\x98\x80", LAM_ESC_JSON, "\x7F\xC2\x85\xEF\xBF\xBF\xF0\x9F\x98\x80",
              "JSON: DEL, C1, U+FFFF and a 4-byte character as they are (JSON holds them)");

    /* the parts */
    is_int(lam_esc_plain("ab<c", 4, LAM_ESC_XML), 2, "lam_esc_plain: up to the first '<'");
    is_int(lam_esc_plain("ab<c", 4, LAM_ESC_JSON), 4, "lam_esc_plain: JSON takes '<'");
    is_int(lam_esc_plain("\xC2\xB5\xE2\x82", 4, LAM_ESC_JSON), 2, "lam_esc_plain: stops at a sequence cut short");
    char e[LAM_ESC_MAX];
    is_int(lam_esc_one("\xC2\x85x", 3, LAM_ESC_XML, e), 2, "lam_esc_one: a C1 control stands for its 2 bytes");
    is_str(e, FFFD, "... and becomes U+FFFD");
    is_int(lam_esc_one("\xE2\x82\xACx", 2, LAM_ESC_XML, e), 1, "lam_esc_one: within n bytes only: a cut sequence, 1 byte");
    is_int(lam_utf8_len("\xF0\x9F\x98\x80", 4), 4, "lam_utf8_len: a 4-byte character");
    is_int(lam_utf8_len("\xF0\x9F\x98\x80", 3), 0, "lam_utf8_len: ... not within 3 bytes");

    exhaustive();
    return done_testing();
}
