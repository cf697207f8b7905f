/* Strings in the documents lamina writes (the SVG sheet, the HTML viewer,
 * the JSON): the one place that decides which bytes of a string may go
 * into a document as they are and how the others are written. Such a
 * string may hold any bytes: a model path (any bytes but NUL), a unit name
 * or a title from a profile, a -s option or a recipe. Internal to lamina
 * (not installed).
 *
 * A string is read as UTF-8. A byte that does not begin a valid sequence
 * (a stray continuation byte, a truncated sequence, an overlong form, a
 * surrogate, past U+10FFFF) stands for itself and becomes U+FFFD, one for
 * each such byte, so the document stays valid UTF-8 whatever the string.
 *
 *   LAM_ESC_XML   text or an attribute value (between " or ') of XML,
 *                 SVG or HTML: < > & " ' as &lt; &gt; &amp; &quot; &#39;,
 *                 so nothing in the string can open or close an element or
 *                 an attribute; the characters XML 1.0 does not allow (C0
 *                 controls, tab and newline included: a label is one line)
 *                 and those it discourages and a page would show as
 *                 nothing (DEL, the C1 controls U+0080..U+009F, U+FFFE,
 *                 U+FFFF) become U+FFFD, so the document is well-formed.
 *   LAM_ESC_JSON  a JSON string's contents: " and \ with a backslash, the
 *                 C0 controls as \u00XX, a byte not UTF-8 as \ufffd (the
 *                 rest, DEL and C1 included, as it is: JSON holds it).
 *   LAM_ESC_JSON_SCRIPT  the same, and '<' as \u003c: for JSON inside an
 *                 HTML <script> element, where neither "</script>" nor
 *                 "<!--" can then end or change the element (both need a
 *                 '<'); JSON.parse reads the string back as it was. */
#ifndef LAM_ESCAPE_H
#define LAM_ESCAPE_H

#include <stddef.h>

#include "writer.h"

typedef enum { LAM_ESC_XML, LAM_ESC_JSON, LAM_ESC_JSON_SCRIPT } lam_esc_mode;

/* Room for the longest replacement of one character, with its NUL. */
#define LAM_ESC_MAX 8

/* The length (1 to 4) of the valid UTF-8 sequence at p, which has n > 0
 * bytes; 0 when p[0] begins none. */
size_t lam_utf8_len(const char *p, size_t n);

/* How many of the n bytes at p, from the first, go into the document as
 * they are. */
size_t lam_esc_plain(const char *p, size_t n, lam_esc_mode mode);

/* The replacement of what begins at p (n > 0 bytes), where
 * lam_esc_plain(p, n, mode) is 0: its text in out (NUL-terminated);
 * returns the number of bytes of p it stands for (1 to 4). */
size_t lam_esc_one(const char *p, size_t n, lam_esc_mode mode, char out[LAM_ESC_MAX]);

/* Write the string t (NULL: nothing) to w, escaped for mode. Returns the
 * writer's code (LAM_OK, or its sticky error). */
int lam_esc_write(lam_writer *w, const char *t, lam_esc_mode mode);

#endif
