/* The template language of a machine dialect (dialect.h documents the
 * templates, their fields and the rendering rules): commands, parsing
 * (once, when the profile loads, dialect_template.c) and rendering (per
 * command). The rendering section is what the dialect sink (dialect.c)
 * builds on; a library user needs only the parser. */
#ifndef LAM_DIALECT_TEMPLATE_H
#define LAM_DIALECT_TEMPLATE_H

#include <stddef.h>
#include <string.h>

#include "error.h"

typedef enum lam_cmd {
    LAM_CMD_PREAMBLE, LAM_CMD_POSTAMBLE, LAM_CMD_LAYER, LAM_CMD_LAYER_END,
    LAM_CMD_FEED, LAM_CMD_LASER_ON, LAM_CMD_LASER_OFF, LAM_CMD_TRAVEL, LAM_CMD_DEPOSIT,
    LAM_CMD_CONTOUR_BEGIN, LAM_CMD_CONTOUR_END, LAM_CMD_LOOP_BEGIN, LAM_CMD_LOOP_END,
    LAM_CMD_VERTEX, LAM_CMD_POLYLINE, LAM_CMD_SEPARATOR,
    LAM_CMD_HATCHES_BEGIN, LAM_CMD_HATCH, LAM_CMD_HATCHES_END, LAM_CMD_HATCHES,
    LAM_CMD_COUNT
} lam_cmd;

/* The YAML key of a command ("preamble", "laser_on", ...). */
const char *lam_cmd_name(lam_cmd c);

/* The fields a command's template may use, separated by spaces (static;
 * "" for none). */
const char *lam_cmd_fields(lam_cmd c);

typedef struct lam_tseg lam_tseg; /* below */

typedef struct lam_template {
    int present;             /* 0: the command emits nothing */
    char *source;            /* the template text as written (owned) */
    lam_tseg *segs;          /* parsed form (owned) */
    size_t nsegs;
} lam_template;

typedef struct lam_dialect {
    lam_template cmd[LAM_CMD_COUNT];
    int close_polylines;     /* `points` repeats the first point */
} lam_dialect;

/* Parse `text` as the template of command c into *t. On error returns
 * LAM_EINVAL with err->msg saying what is wrong and *offset the byte offset
 * in text where it is (the profile loader turns that into line:column). */
int lam_template_parse(lam_cmd c, const char *text, lam_template *t, size_t *offset, lam_error *err);

void lam_template_free(lam_template *t);
void lam_dialect_free(lam_dialect *d);

/* The default rendering of a number field: lam_fmt_num(buf, x, 17), the
 * fewest significant digits that read back as exactly x (fmt.h): 600,
 * 0.08, 0.1, 1e-05, 1e+20; never "-0". buf holds LAM_FMT_MAX bytes.
 * Returns the length. */
size_t lam_dialect_number(char *buf, double x);


/* ---- rendering (for the dialect sink) ---------------------------------- */

/* The fields of all commands (dialect.h lists which command has which). */
enum lam_tfield {
    LAM_TF_NAME, LAM_TF_PROCESS, LAM_TF_UNITS, LAM_TF_LAYERS, LAM_TF_DIMENSION, LAM_TF_BEAD, LAM_TF_RATE,
    LAM_TF_TRAVEL_RATE,
    LAM_TF_XMIN, LAM_TF_YMIN, LAM_TF_ZMIN, LAM_TF_XMAX, LAM_TF_YMAX, LAM_TF_ZMAX,
    LAM_TF_INDEX, LAM_TF_NUMBER, LAM_TF_Z, LAM_TF_WIDTH, LAM_TF_FLOOR, LAM_TF_CEILING,
    LAM_TF_DX, LAM_TF_DY, LAM_TF_DZ, LAM_TF_X, LAM_TF_Y, LAM_TF_I,
    LAM_TF_ID, LAM_TF_DIR, LAM_TF_KIND, LAM_TF_DEPTH, LAM_TF_N, LAM_TF_POINTS,
    LAM_TF_LABEL, LAM_TF_POWER, LAM_TF_SPEED, LAM_TF_POINT_DISTANCE, LAM_TF_EXPOSURE_TIME, LAM_TF_ANGLE,
    LAM_TF_X0, LAM_TF_Y0, LAM_TF_Z0, LAM_TF_X1, LAM_TF_Y1, LAM_TF_Z1,
    LAM_TF_COUNT
};

/* One segment of a parsed template: literal text or a field with its
 * conversion. */
struct lam_tseg {
    int field;      /* -1: literal text */
    char *lit;      /* literal (owned) */
    size_t len;
    char conv;      /* 0 default, else d i f F e E g G s */
    int prec;       /* -1 when not given */
    int fast;       /* exactly %.Nf (or %f): lam_fmt_fixed with prec */
    char spec[32];  /* the conversion for snprintf (d/i with "ll") */
};

/* The text of the fixed-point number a segment printed last: a layer's
 * points repeat its height, so the SLS point command writes the digits of
 * z once per layer instead of once per point (a third of its numbers).
 * The text depends only on the segment and the rounded value. */
typedef struct lam_tnumo {
    const void *seg;
    unsigned long long q;
    int neg;
    size_t len;
    char txt[32];
} lam_tnumo;

typedef struct lam_tbuf {
    char *s;
    size_t len, cap;
    int oom;
    lam_tnumo memo[LAM_TF_COUNT];      /* by the segment's field */
} lam_tbuf;

/* Grow b for n more bytes and a NUL (the slow half of lam_tbuf_room);
 * NULL, b->oom set, when out of memory. */
char *lam_tbuf_grow(lam_tbuf *b, size_t n);

/* Room for n more bytes and a NUL at the end of b; NULL when out of memory.
 * The test inline (once per number written), the growth out of line. */
static inline char *lam_tbuf_room(lam_tbuf *b, size_t n)
{
    return !b->oom && b->len + n + 1 <= b->cap ? b->s + b->len : lam_tbuf_grow(b, n);
}

/* Append s[0..n) to b (nothing when out of memory: b->oom says so). */
static inline void lam_tbuf_put(lam_tbuf *b, const char *s, size_t n)
{
    if (!n) return; /* s may be NULL: an empty layer's text */
    char *at = lam_tbuf_room(b, n);
    if (!at) return;
    memcpy(at, s, n);
    b->len += n;
    b->s[b->len] = '\0';
}

/* The values a command can use. */
typedef struct lam_tvals {
    double num[LAM_TF_COUNT];
    const char *text[LAM_TF_COUNT];
    const double *uv;        /* points: 2 per point, or xyz with stride 3 */
    size_t uv_stride, npts;
    int close;
    /* preamble, postamble: the job's labels (nlabels >= 1), labels[k] the
     * text of id k + 1; NULL: the template renders once as it is */
    const char *const *labels;
    size_t nlabels;
} lam_tvals;

/* Render t into b; for travel/deposit also the text of dx dy dz
 * (rel[k] set to the value the machine reads, has_rel[k] to 1). Numbers
 * are formatted straight into b. With v->labels (a preamble or
 * postamble), each line of t that uses {id} is rendered once per label,
 * with that label's id and text as {id} and {label}, the copies one a
 * line; the other lines once, {label} there v->text's. */
void lam_template_render(const lam_template *t, const lam_tvals *v, lam_tbuf *b, double rel[3], int has_rel[3]);

#endif
