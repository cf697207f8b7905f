/* Strings in documents: see escape.h. */
#include "escape.h"

#include <string.h>

#define FFFD "\xEF\xBF\xBD" /* U+FFFD REPLACEMENT CHARACTER, in UTF-8 */

static unsigned code_point(const unsigned char *p, size_t k)
{
    return k == 1   ? p[0]
           : k == 2 ? (p[0] & 0x1Fu) << 6 | (p[1] & 0x3Fu)
           : k == 3 ? (p[0] & 0x0Fu) << 12 | (p[1] & 0x3Fu) << 6 | (p[2] & 0x3Fu)
                    : (p[0] & 0x07u) << 18 | (p[1] & 0x3Fu) << 12 | (p[2] & 0x3Fu) << 6 | (p[3] & 0x3Fu);
}

size_t lam_utf8_len(const char *s, size_t n)
{
    const unsigned char *p = (const unsigned char *)s;
    size_t k = p[0] < 0x80 ? 1 : (p[0] & 0xE0) == 0xC0 ? 2 : (p[0] & 0xF0) == 0xE0 ? 3 : (p[0] & 0xF8) == 0xF0 ? 4 : 0;
    if (!k || k > n || (k == 2 && p[0] < 0xC2)) return 0;
    for (size_t i = 1; i < k; i++)
        if ((p[i] & 0xC0) != 0x80) return 0;
    unsigned cp = code_point(p, k);
    /* overlong forms, surrogates and past U+10FFFF are not UTF-8 */
    if ((k == 3 && cp < 0x800) || (k == 4 && (cp < 0x10000 || cp > 0x10FFFF)) || (cp >= 0xD800 && cp <= 0xDFFF))
        return 0;
    return k;
}

/* Does the valid k-byte character at p go in as it is? */
static int plain(const unsigned char *p, size_t k, lam_esc_mode mode)
{
    if (mode != LAM_ESC_XML)
        return k > 1 || (p[0] >= 0x20 && p[0] != '"' && p[0] != '\\' && !(p[0] == '<' && mode == LAM_ESC_JSON_SCRIPT));
    if (k == 1) return p[0] >= 0x20 && p[0] != 0x7F && !strchr("<>&\"'", p[0]);
    unsigned c = code_point(p, k);
    return !(c >= 0x80 && c <= 0x9F) && c != 0xFFFE && c != 0xFFFF;
}

size_t lam_esc_plain(const char *s, size_t n, lam_esc_mode mode)
{
    size_t i = 0, k;
    while (i < n && (k = lam_utf8_len(s + i, n - i)) && plain((const unsigned char *)s + i, k, mode)) i += k;
    return i;
}

static const char *xml_entity(unsigned char c)
{
    switch (c) {
    case '<': return "&lt;";
    case '>': return "&gt;";
    case '&': return "&amp;";
    case '"': return "&quot;";
    case '\'': return "&#39;";
    default: return FFFD; /* a character XML does not take */
    }
}

size_t lam_esc_one(const char *s, size_t n, lam_esc_mode mode, char out[LAM_ESC_MAX])
{
    const unsigned char *p = (const unsigned char *)s;
    size_t k = lam_utf8_len(s, n);
    if (!k) {
        strcpy(out, mode == LAM_ESC_XML ? FFFD : "\\ufffd");
        return 1;
    }
    if (plain(p, k, mode)) { /* not asked for, but harmless: itself */
        memcpy(out, s, k);
        out[k] = '\0';
    } else if (mode == LAM_ESC_XML) {
        strcpy(out, xml_entity(p[0]));
    } else if (p[0] == '"' || p[0] == '\\') {
        out[0] = '\\', out[1] = (char)p[0], out[2] = '\0';
    } else { /* a C0 control, or '<' in a script */
        static const char hex[] = "0123456789abcdef";
        memcpy(out, "\\u00", 4);
        out[4] = hex[p[0] >> 4], out[5] = hex[p[0] & 15], out[6] = '\0';
    }
    return k;
}

int lam_esc_write(lam_writer *w, const char *t, lam_esc_mode mode)
{
    size_t n = t ? strlen(t) : 0;
    while (n) {
        size_t k = lam_esc_plain(t, n, mode);
        if (k) {
            lam_writer_write(w, t, k);
        } else {
            char e[LAM_ESC_MAX];
            k = lam_esc_one(t, n, mode, e);
            lam_writer_write(w, e, strlen(e));
        }
        t += k, n -= k;
    }
    return lam_writer_write(w, "", 0);
}
