/* The template language of a machine dialect: commands, fields, parsing
 * (once, when the profile loads) and rendering (per command). See
 * dialect.h; the sink that writes a plan through templates is dialect.c. */
#include "dialect_template.h"

#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmt.h"
#include "lexnum.h"
#include "shortest.h"

/* ---- commands and fields ---------------------------------------------- */

static const char *const cmd_names[LAM_CMD_COUNT] = {
    "preamble", "postamble", "layer", "layer_end", "feed", "laser_on", "laser_off", "travel", "deposit",
    "contour_begin", "contour_end", "loop_begin", "loop_end", "vertex", "polyline", "separator",
    "hatches_begin", "hatch", "hatches_end", "hatches",
};

const char *lam_cmd_name(lam_cmd c)
{
    return (unsigned)c < LAM_CMD_COUNT ? cmd_names[c] : "?";
}

static const char *const field_names[LAM_TF_COUNT] = {
    "name", "process", "units", "layers", "dimension", "bead", "rate", "travel_rate",
    "xmin", "ymin", "zmin", "xmax", "ymax", "zmax",
    "index", "number", "z", "width", "floor", "ceiling",
    "dx", "dy", "dz", "x", "y", "i",
    "id", "dir", "kind", "depth", "n", "points",
    "label", "power", "speed", "point_distance", "exposure_time", "angle", "x0", "y0", "z0", "x1", "y1", "z1",
};

enum ftype { T_INT, T_NUM, T_TEXT, T_POINTS };

static enum ftype field_type(int f)
{
    switch (f) {
    case LAM_TF_INDEX: case LAM_TF_NUMBER: case LAM_TF_LAYERS: case LAM_TF_DIMENSION: case LAM_TF_N: case LAM_TF_ID: case LAM_TF_DIR:
    case LAM_TF_DEPTH: case LAM_TF_I:
        return T_INT;
    case LAM_TF_NAME: case LAM_TF_PROCESS: case LAM_TF_UNITS: case LAM_TF_KIND: case LAM_TF_LABEL:
        return T_TEXT;
    case LAM_TF_POINTS:
        return T_POINTS;
    default:
        return T_NUM;
    }
}

#define B(f) ((uint64_t)1 << (f))

#define EXPOSURE " power speed point_distance exposure_time"

/* The fields of each command, in the order dialect.h lists them. */
static const char *const cmd_field_text[LAM_CMD_COUNT] = {
    [LAM_CMD_PREAMBLE] = "name process units layers dimension bead rate travel_rate xmin ymin zmin xmax ymax zmax "
                         "label id",
    [LAM_CMD_POSTAMBLE] = "name process units layers dimension bead rate travel_rate xmin ymin zmin xmax ymax zmax "
                          "label id",
    [LAM_CMD_LAYER] = "index number z width floor ceiling",
    [LAM_CMD_LAYER_END] = "index number z width floor ceiling",
    [LAM_CMD_FEED] = "rate",
    [LAM_CMD_LASER_ON] = "rate",
    [LAM_CMD_LASER_OFF] = "rate",
    [LAM_CMD_TRAVEL] = "dx dy dz x y z rate",
    [LAM_CMD_DEPOSIT] = "dx dy dz x y z rate",
    [LAM_CMD_CONTOUR_BEGIN] = "index id dir kind depth n z points" EXPOSURE,
    [LAM_CMD_CONTOUR_END] = "index id dir kind depth n z points" EXPOSURE,
    [LAM_CMD_LOOP_BEGIN] = "n z",
    [LAM_CMD_LOOP_END] = "n z",
    [LAM_CMD_VERTEX] = "x y z i",
    [LAM_CMD_POLYLINE] = "index id dir kind depth n z points" EXPOSURE,
    [LAM_CMD_SEPARATOR] = "",
    [LAM_CMD_HATCHES_BEGIN] = "index id kind n z angle points" EXPOSURE,
    [LAM_CMD_HATCH] = "x0 y0 z0 x1 y1 z1 i power speed",
    [LAM_CMD_HATCHES_END] = "index id kind n z angle points" EXPOSURE,
    [LAM_CMD_HATCHES] = "index id kind n z angle points" EXPOSURE,
};

const char *lam_cmd_fields(lam_cmd c)
{
    return (unsigned)c < LAM_CMD_COUNT ? cmd_field_text[c] : "";
}

static int field_id(const char *name, size_t len)
{
    for (int f = 0; f < LAM_TF_COUNT; f++)
        if (strlen(field_names[f]) == len && memcmp(field_names[f], name, len) == 0) return f;
    return -1;
}

static uint64_t cmd_fields(lam_cmd c)
{
    uint64_t set = 0;
    for (const char *p = cmd_field_text[c]; *p;) {
        size_t len = strcspn(p, " ");
        set |= B(field_id(p, len));
        p += len;
        p += strspn(p, " ");
    }
    return set;
}

/* ---- templates ---------------------------------------------------------- */

#define MAX_WIDTH 40
#define MAX_PREC 40

void lam_template_free(lam_template *t)
{
    if (!t) return;
    for (size_t i = 0; i < t->nsegs; i++) free(t->segs[i].lit);
    free(t->segs);
    free(t->source);
    memset(t, 0, sizeof *t);
}

void lam_dialect_free(lam_dialect *d)
{
    if (!d) return;
    for (int c = 0; c < LAM_CMD_COUNT; c++) lam_template_free(&d->cmd[c]);
}

static int push_seg(lam_template *t, size_t *cap, const lam_tseg *s)
{
    if (t->nsegs == *cap) {
        size_t nc = *cap ? 2 * *cap : 8;
        lam_tseg *ns = realloc(t->segs, nc * sizeof *ns);
        if (!ns) return 0;
        t->segs = ns;
        *cap = nc;
    }
    t->segs[t->nsegs++] = *s;
    return 1;
}

/* Whether command c's lines that use {id} are written once per label
 * (lam_tvals.labels): its literal segments then end at line breaks, so
 * that a line is a run of whole segments. */
static int by_lines(lam_cmd c)
{
    return c == LAM_CMD_PREAMBLE || c == LAM_CMD_POSTAMBLE;
}

/* Append text[0..n) to the literal segment at the end of t (a new one if
 * the last segment is a field, or, with lines, ends a line). */
static int push_lit(lam_template *t, size_t *cap, const char *text, size_t n, int lines)
{
    lam_tseg *last = t->nsegs ? &t->segs[t->nsegs - 1] : NULL;
    if (!last || last->field >= 0 || (lines && last->len && last->lit[last->len - 1] == '\n')) {
        lam_tseg s;
        memset(&s, 0, sizeof s);
        s.field = -1;
        if (!push_seg(t, cap, &s)) return 0;
        last = &t->segs[t->nsegs - 1];
    }
    char *nl = realloc(last->lit, last->len + n + 1);
    if (!nl) return 0;
    memcpy(nl + last->len, text, n);
    last->len += n;
    nl[last->len] = '\0';
    last->lit = nl;
    return 1;
}

static int perr(lam_error *err, size_t *offset, size_t at, const char *fmt, ...) __attribute__((format(printf, 4, 5)));
static int perr(lam_error *err, size_t *offset, size_t at, const char *fmt, ...)
{
    if (offset) *offset = at;
    va_list ap;
    va_start(ap, fmt);
    int rc = lam_error_vset(err, LAM_EINVAL, NULL, 0, 0, -1, fmt, ap);
    va_end(ap);
    return rc;
}

/* Check conversion letter text[p] of field f's format (at: its '%%';
 * flags[0..nflags) given): allowed, and fit for the field's type. */
static int check_conv(int f, const char *text, size_t at, size_t p, const char *flags, size_t nflags,
                      size_t *offset, lam_error *err)
{
    enum ftype ty = field_type(f);
    char conv = text[p];
    if (conv == '*') return perr(err, offset, p, "'*' is not allowed in a format: give the width");
    if (conv == 'n') return perr(err, offset, p, "%%n is not allowed: a template only formats values");
    if (conv && strchr("hlLqjzt", conv))
        return perr(err, offset, p,
                    "length modifier '%c' is not allowed: write just the conversion (d i f F e E g G, s for text)",
                    conv);
    if (conv == '}' || conv == '\0')
        return perr(err, offset, p, "the format of '%s' has no conversion letter (d i f F e E g G, s for text)",
                    field_names[f]);
    if (!strchr("difFeEgGs", conv))
        return perr(err, offset, p, "unsupported conversion '%%%c' (allowed: d i f F e E g G, s for text fields)",
                    conv);
    if (conv == 's' && ty != T_TEXT)
        return perr(err, offset, p, "%%s is for text fields; '%s' is a number (use d i f F e E g G)", field_names[f]);
    if (conv != 's' && ty == T_TEXT)
        return perr(err, offset, p, "'%s' is text: format it with %%s", field_names[f]);
    if (conv == 'd' || conv == 'i') {
        if (ty == T_POINTS) return perr(err, offset, p, "'points' are coordinates: use f F e E g G");
        if (memchr(flags, '#', nflags))
            return perr(err, offset, at + 1 + (size_t)((char *)memchr(flags, '#', nflags) - flags),
                        "flag '#' does not apply to %%%c", conv);
    }
    if (conv == 's') {
        for (size_t k = 0; k < nflags; k++)
            if (flags[k] != '-')
                return perr(err, offset, at + 1 + k, "flag '%c' does not apply to %%s (only '-')", flags[k]);
    }
    return LAM_OK;
}

/* The snprintf spec of a parsed format into seg (d and i as long long). */
static void write_spec(lam_tseg *seg, const char *flags, size_t nflags, int width, int prec, char conv)
{
    char *s = seg->spec;
    size_t k = 0;
    s[k++] = '%';
    memcpy(s + k, flags, nflags);
    k += nflags;
    if (width >= 0) k += (size_t)snprintf(s + k, sizeof seg->spec - k, "%d", width);
    if (prec >= 0) k += (size_t)snprintf(s + k, sizeof seg->spec - k, ".%d", prec);
    if (conv == 'd' || conv == 'i') {
        s[k++] = 'l';
        s[k++] = 'l';
    }
    s[k++] = conv;
    s[k] = '\0';
    seg->conv = conv;
    seg->prec = prec;
    seg->fast = conv == 'f' && nflags == 0 && width < 0;
    if (seg->fast && prec < 0) seg->prec = 6;
}

/* Parse the conversion spec text[at..] (starting at '%') for field f up to the
 * closing '}'. On success fills seg and sets *endp to the '}' offset. */
static int parse_spec(lam_cmd c, int f, const char *text, size_t at, lam_tseg *seg, size_t *endp,
                      size_t *offset, lam_error *err)
{
    (void)c;
    size_t p = at;
    if (text[p] != '%')
        return perr(err, offset, p, "a format starts with '%%' (as in {%s:%%.3f}), got '%c'", field_names[f],
                    text[p] ? text[p] : ' ');
    p++;
    char flags[8];
    size_t nflags = 0;
    while (text[p] && strchr("-+ 0#", text[p])) {
        if (memchr(flags, text[p], nflags))
            return perr(err, offset, p, "flag '%c' given twice in the format of '%s'", text[p], field_names[f]);
        flags[nflags++] = text[p++];
    }
    int width = -1;
    size_t wat = p;
    if (text[p] >= '0' && text[p] <= '9') {
        width = 0;
        while (text[p] >= '0' && text[p] <= '9') {
            if (width <= MAX_WIDTH) width = width * 10 + (text[p] - '0');
            p++;
        }
        if (width > MAX_WIDTH)
            return perr(err, offset, wat, "width of '%s' is more than %d", field_names[f], MAX_WIDTH);
    }
    int prec = -1;
    if (text[p] == '.') {
        p++;
        size_t pat = p;
        if (!(text[p] >= '0' && text[p] <= '9')) {
            if (text[p] == '*') return perr(err, offset, p, "'*' is not allowed in a format: give the precision");
            return perr(err, offset, p, "precision of '%s' needs digits after '.'", field_names[f]);
        }
        prec = 0;
        while (text[p] >= '0' && text[p] <= '9') {
            if (prec <= MAX_PREC) prec = prec * 10 + (text[p] - '0');
            p++;
        }
        if (prec > MAX_PREC)
            return perr(err, offset, pat, "precision of '%s' is more than %d", field_names[f], MAX_PREC);
    }
    char conv = text[p];
    int rc = check_conv(f, text, at, p, flags, nflags, offset, err);
    if (rc) return rc;
    p++;
    if (text[p] != '}') {
        if (text[p] == '\0') return perr(err, offset, p, "unterminated field '%s': expected '}'", field_names[f]);
        return perr(err, offset, p, "unexpected '%c' after the conversion of '%s', expected '}'", text[p],
                    field_names[f]);
    }
    write_spec(seg, flags, nflags, width, prec, conv);
    *endp = p;
    return LAM_OK;
}

/* The field at text[open] ('{'): {name} or {name:%spec}, one of
 * `allowed` of command c, into seg; *close is its '}'. */
static int parse_field(lam_cmd c, uint64_t allowed, const char *text, size_t open, lam_tseg *seg, size_t *close,
                       size_t *offset, lam_error *err)
{
    size_t ns = open + 1, ne = ns;
    while (text[ne] && text[ne] != '}' && text[ne] != ':' && text[ne] != '{' && text[ne] != '\n') ne++;
    if (text[ne] != '}' && text[ne] != ':')
        return perr(err, offset, open, "unterminated '{': a field ends with '}' (write '{{' for a literal brace)");
    if (ne == ns) return perr(err, offset, open, "empty field name in '{}' (write '{{' for a literal brace)");
    int f = field_id(text + ns, ne - ns);
    if (f < 0 || !(allowed & B(f))) {
        char shown[64];
        lam_quote_bytes(shown, sizeof shown, (const unsigned char *)text + ns, ne - ns);
        if (!allowed)
            return perr(err, offset, ns, "unknown field %s: the %s command has no fields", shown, cmd_names[c]);
        return perr(err, offset, ns, "unknown field %s for the %s command (fields: %s)", shown, cmd_names[c],
                    cmd_field_text[c]);
    }
    memset(seg, 0, sizeof *seg);
    seg->field = f;
    seg->prec = -1;
    *close = ne;
    if (text[ne] == ':') {
        /* the spec must end with '}' before any newline */
        size_t e = ne + 1;
        while (text[e] && text[e] != '}' && text[e] != '\n') e++;
        if (text[e] != '}')
            return perr(err, offset, open, "unterminated '{': a field ends with '}' (write '{{' for a literal brace)");
        return parse_spec(c, f, text, ne + 1, seg, close, offset, err);
    }
    if (field_type(f) == T_POINTS) {
        seg->conv = 'f';
        seg->prec = 6;
        seg->fast = 1;
        strcpy(seg->spec, "%.6f");
    }
    return LAM_OK;
}

int lam_template_parse(lam_cmd c, const char *text, lam_template *t, size_t *offset, lam_error *err)
{
    memset(t, 0, sizeof *t);
    if (offset) *offset = 0;
    if ((unsigned)c >= LAM_CMD_COUNT) return perr(err, offset, 0, "no such command");
    size_t cap = 0;
    uint64_t allowed = cmd_fields(c);
    int lines = by_lines(c);
    int rc = LAM_OK;
    size_t i = 0;
    while (text[i] && !rc) {
        char ch = text[i];
        if (ch == '{' && text[i + 1] == '{') {
            if (!push_lit(t, &cap, "{", 1, lines)) goto nomem;
            i += 2;
            continue;
        }
        if (ch == '}') {
            if (text[i + 1] == '}') {
                if (!push_lit(t, &cap, "}", 1, lines)) goto nomem;
                i += 2;
                continue;
            }
            rc = perr(err, offset, i, "single '}' (write '}}' for a literal brace)");
            break;
        }
        if (ch != '{') {
            size_t run = strcspn(text + i, lines ? "{}\n" : "{}");
            if (lines && text[i + run] == '\n') run++; /* the break ends its line's segment */
            if (!push_lit(t, &cap, text + i, run, lines)) goto nomem;
            i += run;
            continue;
        }
        lam_tseg seg;
        size_t close = i;
        if ((rc = parse_field(c, allowed, text, i, &seg, &close, offset, err))) break;
        if (!push_seg(t, &cap, &seg)) goto nomem;
        i = close + 1;
    }
    if (!rc && !(t->source = strdup(text))) goto nomem;
    if (rc) {
        lam_template_free(t);
        return rc;
    }
    t->present = 1;
    return LAM_OK;
nomem:
    lam_template_free(t);
    return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory");
}

/* ---- rendering ---------------------------------------------------------- */

char *lam_tbuf_grow(lam_tbuf *b, size_t n)
{
    if (b->oom) return NULL;
    if (b->len + n + 1 > b->cap) {
        size_t nc = b->cap ? b->cap : 256;
        while (nc < b->len + n + 1) nc *= 2;
        char *ns = realloc(b->s, nc);
        if (!ns) {
            b->oom = 1;
            return NULL;
        }
        b->s = ns;
        b->cap = nc;
    }
    return b->s + b->len;
}

/* The shortest digits by trying 1, 2, ... 17 of them, and %g's notation:
 * slow (a printf per try), for the cases the fast way leaves. */
static size_t number_slow(char *out, double x)
{
    return strlen(lam_fmt_num(out, x, 17));
}

/* d[0..17) rounded to k digits (k < 17) in place, half up; the exponent
 * grows on a carry out of the first digit. 0 when the digits cut off are
 * exactly half (x's own rounding to k digits may go either way: only
 * printf knows). */
static int round_digits(char *d, int k, int *exp10)
{
    int tie = d[k] == '5';
    for (int i = k + 1; i < 17 && tie; i++) tie = d[i] == '0';
    if (tie) return 0;
    if (d[k] >= '5') {
        int i = k - 1;
        while (i >= 0 && d[i] == '9') d[i--] = '0';
        if (i >= 0) {
            d[i]++;
        } else {
            memmove(d + 1, d, (size_t)k - 1);
            d[0] = '1';
            (*exp10)++;
        }
    }
    return 1;
}

/* d[0..n) times 10^exp10 as "D.DDDe+XX" into b; returns the length. */
static size_t sci(char *b, int neg, const char *d, int n, int exp10)
{
    size_t k = 0;
    if (neg) b[k++] = '-';
    b[k++] = d[0];
    if (n > 1) {
        b[k++] = '.';
        memcpy(b + k, d + 1, (size_t)n - 1);
        k += (size_t)n - 1;
    }
    int e = exp10 < 0 ? -exp10 : exp10;
    b[k++] = 'e';
    b[k++] = exp10 < 0 ? '-' : '+';
    if (e >= 100) b[k++] = (char)('0' + e / 100);
    b[k++] = (char)('0' + e / 10 % 10);
    b[k++] = (char)('0' + e % 10);
    b[k] = '\0';
    return k;
}

size_t lam_dialect_number(char *out, double x)
{
    if (x == 0) x = 0; /* no "-0" */
    if (!isfinite(x)) return (size_t)snprintf(out, LAM_FMT_MAX, "%g", x);
    /* subnormals have fewer digits than 15: the slow way */
    if (x == 0 || fabs(x) < DBL_MIN) return number_slow(out, x);
    /* Plain notation (1e-4 <= |x| < 1e15): the fewest decimals d whose
     * exact rounding q = round(|x| * 10^d) reads back, q / 10^d == |x| (q
     * and 10^d are exact, so the division rounds as reading the text does),
     * are the fewest digits, and that rounding is the one %e would give:
     * lam_fmt_fixed prints it without printf. Up to 16 digits, while q
     * stays exact; beyond, the general way below. */
    size_t fast = lam_shortest_plain(out, x); /* this, and the rest, without printf */
    if (fast) return fast;
    static const double p10[] = { 1, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15 };
    if (fabs(x) >= 1e-4 && fabs(x) < 1e15) {
        unsigned long long q;
        for (int d = 0; d <= 15 && lam_fmt_scaled(x, d, &q); d++)
            if ((double)q / p10[d] == fabs(x)) return lam_fmt_fixed(out, x, d);
    }
    /* One printf gives x to 17 digits, D17. Its roundings to 15 and 16
     * digits are x's own, unless D17 sits on a midpoint (then printf
     * decides). When any k <= 15 digits read back as x, so do x's 15 with
     * the zeros after them taken off: a 15-digit step (>= 1e-15 of x) is
     * far wider than x's half-ulp (<= 1.2e-16 of x). So: 15 digits less
     * their zeros, else 16, else 17. */
    char e17[40];
    snprintf(e17, sizeof e17, "%.16e", x);
    int neg = e17[0] == '-';
    const char *m = e17 + neg;
    char d17[17];
    d17[0] = m[0];
    memcpy(d17 + 1, m + 2, 16);
    int exp17 = atoi(strchr(m, 'e') + 1);
    char d[17];
    int exp10 = exp17, prec = 17;
    for (int k = 15; k <= 16; k++) {
        memcpy(d, d17, 17);
        exp10 = exp17;
        if (!round_digits(d, k, &exp10)) return number_slow(out, x);
        char b[40];
        size_t n = sci(b, neg, d, k, exp10);
        double back;
        if (lam_parse_number((const unsigned char *)b, n, &back) == LAM_OK && back == x) {
            prec = k;
            break;
        }
    }
    if (prec == 17) {
        memcpy(d, d17, 17);
        exp10 = exp17;
    }
    while (prec > 1 && d[prec - 1] == '0') prec--;
    /* plain decimals for 1e-4 <= |x| < 1e17, as %.17g; a number whose
     * shortest digits stop before the point (1e10, 2^55) prints every
     * digit of x there, %g's way: below 2^53 x is that whole number */
    if (exp10 >= -4 && exp10 < 17 && prec < exp10 + 1) {
        if (fabs(x) >= 9007199254740992.0) return number_slow(out, x);
        memset(d + prec, '0', (size_t)(exp10 + 1 - prec));
        prec = exp10 + 1;
    }
    if (exp10 < -4 || exp10 >= 17) return sci(out, neg, d, prec, exp10);
    return lam_shortest_layout(out, neg, d, prec, exp10);
}

/* 1 when the fixed rendering s (from lam_fmt_fixed) is "-0", "-0.000...". */
static int negative_zero(const char *s)
{
    if (s[0] != '-') return 0;
    for (const char *p = s + 1; *p; p++)
        if (*p != '0' && *p != '.') return 0;
    return 1;
}

/* Render number x with seg's conversion (or the default for ftype ty). */
static size_t fmt_number(char *out, const lam_tseg *seg, double x, enum ftype ty, lam_tnumo *m)
{
    if (seg->conv == 0) {
        if (ty == T_INT && fabs(x) < 9e18) return (size_t)snprintf(out, LAM_FMT_MAX, "%lld", (long long)x);
        return lam_dialect_number(out, x);
    }
    if (x == 0) x = 0; /* never "-0" */
    if ((seg->conv == 'f' || seg->conv == 'F') && seg->fast) {
        /* one formatting; a negative that rounds to zero loses its sign */
        unsigned long long q;
        if (m && lam_fmt_scaled(x, seg->prec, &q)) {
            int neg = signbit(x) && q;
            if (m->seg == seg && m->q == q && m->neg == neg) {
                memcpy(out, m->txt, m->len + 1);
                return m->len;
            }
            size_t n = lam_fmt_scaled_text(out, q, seg->prec, neg);
            if (n < sizeof m->txt) {
                m->seg = seg;
                m->q = q;
                m->neg = neg;
                m->len = n;
                memcpy(m->txt, out, n + 1);
            }
            return n;
        }
        size_t n = lam_fmt_fixed(out, x, seg->prec);
        if (out[0] == '-' && negative_zero(out)) memmove(out, out + 1, n--);
        return n;
    }
    if (seg->conv == 'f' || seg->conv == 'F') {
        if (isfinite(x) && signbit(x)) {
            char tmp[LAM_FMT_MAX];
            lam_fmt_fixed(tmp, x, seg->prec < 0 ? 6 : seg->prec);
            if (negative_zero(tmp)) x = 0;
        }
    }
    int n;
    if (seg->conv == 'd' || seg->conv == 'i') {
        if (fabs(x) < 9e18) n = snprintf(out, LAM_FMT_MAX, seg->spec, (long long)llround(x));
        else return lam_dialect_number(out, x);
    } else {
        n = snprintf(out, LAM_FMT_MAX, seg->spec, x);
    }
    /* width and precision <= 40 keep any double under 360 characters */
    return n < 0 ? 0 : n >= LAM_FMT_MAX ? LAM_FMT_MAX - 1 : (size_t)n;
}

/* Render segments [from, to) of t into b (lam_template_render). */
static void render_segs(const lam_template *t, size_t from, size_t to, const lam_tvals *v, lam_tbuf *b,
                        double rel[3], int has_rel[3])
{
    for (size_t i = from; i < to; i++) {
        const lam_tseg *s = &t->segs[i];
        if (s->field < 0) {
            lam_tbuf_put(b, s->lit, s->len);
            continue;
        }
        enum ftype ty = field_type(s->field);
        if (ty == T_TEXT) {
            const char *txt = v->text[s->field] ? v->text[s->field] : "";
            if (!s->conv) {
                lam_tbuf_put(b, txt, strlen(txt));
            } else {
                int n = snprintf(NULL, 0, s->spec, txt);
                char *tmp = n >= 0 ? malloc((size_t)n + 1) : NULL;
                if (!tmp) {
                    b->oom = 1;
                    return;
                }
                snprintf(tmp, (size_t)n + 1, s->spec, txt);
                lam_tbuf_put(b, tmp, (size_t)n);
                free(tmp);
            }
        } else if (ty == T_POINTS) {
            size_t total = v->npts + (v->close && v->npts ? 1 : 0);
            for (size_t k = 0; k < total; k++) {
                const double *p = v->uv + (k % v->npts) * v->uv_stride;
                for (int j = 0; j < 2; j++) {
                    if (k || j) lam_tbuf_put(b, ",", 1);
                    char *at = lam_tbuf_room(b, LAM_FMT_MAX);
                    if (!at) return;
                    b->len += fmt_number(at, s, p[j], T_NUM, NULL);
                }
            }
        } else {
            char *at = lam_tbuf_room(b, LAM_FMT_MAX);
            if (!at) return;
            size_t n = fmt_number(at, s, v->num[s->field], ty, &b->memo[s->field]);
            b->len += n;
            int k = s->field == LAM_TF_DX ? 0 : s->field == LAM_TF_DY ? 1 : s->field == LAM_TF_DZ ? 2 : -1;
            if (rel && k >= 0 && !has_rel[k]) {
                double back;
                has_rel[k] = 1;
                rel[k] = lam_parse_number((const unsigned char *)at, n, &back) == LAM_OK && isfinite(back)
                             ? back
                             : v->num[s->field];
            }
        }
    }
}

/* Render t line by line, a line that uses {id} once per label of v
 * (by_lines parsed its literals to end at line breaks). */
static void render_labels(const lam_template *t, const lam_tvals *v, lam_tbuf *b)
{
    lam_tvals lv = *v;
    for (size_t from = 0, to; from < t->nsegs; from = to) {
        int id = 0, broken = 0;
        for (to = from; to < t->nsegs && !broken; to++) {
            const lam_tseg *s = &t->segs[to];
            id |= s->field == LAM_TF_ID;
            broken = s->field < 0 && s->len && s->lit[s->len - 1] == '\n';
        }
        if (!id) {
            render_segs(t, from, to, v, b, NULL, NULL);
            continue;
        }
        for (size_t k = 0; k < v->nlabels; k++) {
            /* the template's last line has no break of its own: the
             * labels' lines are still one a line */
            if (k && !broken) lam_tbuf_put(b, "\n", 1);
            lv.num[LAM_TF_ID] = (double)(k + 1);
            lv.text[LAM_TF_LABEL] = v->labels[k];
            render_segs(t, from, to, &lv, b, NULL, NULL);
        }
    }
}

void lam_template_render(const lam_template *t, const lam_tvals *v, lam_tbuf *b, double rel[3], int has_rel[3])
{
    if (v->labels && v->nlabels) render_labels(t, v, b);
    else render_segs(t, 0, t->nsegs, v, b, rel, has_rel);
}
