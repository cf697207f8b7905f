#include "svg.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "escape.h"
#include "grow.h"
#include "vstream.h"

#define PANEL 200.0   /* panel size in px */
#define PAD ((double)LAM_SVG_CELL_GAP)
#define LABEL LAM_SVG_CAPTION_BAND
#define FOOT 34.0     /* the scale bar and the axes, below the panels */
#define NOTE 16.0     /* the thinning note, below the footer, when a panel was thinned */
#define TOP 34.0      /* the title, above the panels */
#define CHAR_EM 0.6   /* estimated width of a character, in font sizes (svg.h) */
#define MIN_STEP 0.3  /* px: a point nearer than this to the last one drawn is not drawn */

/* Colours: solids are filled (strongly on a sheet of contours, with a tint
 * under scan paths), holes show the white background and a red outline;
 * scan paths run from dark blue through magenta to orange along the
 * layer's order; travels and jumps are grey dashes. */
#define FILL "#2f6db5"
#define TINT "#c9dbf0"
#define SOLID_LINE "#1b3f6b"
#define HOLE_LINE "#d62728"
#define TRAVEL "#8c8c8c"

typedef struct panel {
    size_t index;
    double cut;
    char *path;       /* SVG path data, owned */
    size_t ncontours;
    double *marks;    /* u, v pairs, owned */
    size_t nmarks;
    char *vec;        /* the scan paths' SVG elements, owned (NULL: none planned) */
    size_t nvec;
    size_t ndrawn;    /* of the layer's vectors, those drawn (< nvec: thinned) */
} panel;

/* A vector of the layer being planned, kept until the layer ends (its
 * colour depends on the layer's vector count). */
typedef struct rvec {
    double a[2], b[2];
    const char *kind;
    int exposed;
} rvec;

struct lam_svg {
    size_t nlayers, npanels, filled;
    size_t *wanted;   /* layer index of each panel, increasing */
    panel *panels;
    double box[4];
    char *title;
    char *units;      /* of the job (the sink's begin), owned; NULL unknown */
    char axis[2][8];  /* names of the layer frame's u and v axes */
    int vectors;      /* a sink feeds scan paths */
    int thinned;      /* some panel's vectors were thinned (LAM_SVG_CELL_VECTORS) */
    /* the sink's layer */
    long cur;         /* panel, -1: not drawn */
    rvec *rv;
    size_t nrv, caprv;
    lam_error *err;
};

int lam_svg_new(size_t nlayers, const double uvbox[4], const char *title, lam_svg **out, lam_error *err)
{
    *out = NULL;
    lam_svg *s = calloc(1, sizeof *s);
    size_t np = nlayers < LAM_SVG_MAX_PANELS ? nlayers : LAM_SVG_MAX_PANELS;
    if (s) {
        s->wanted = malloc((np + 1) * sizeof *s->wanted);
        s->panels = calloc(np + 1, sizeof *s->panels);
        s->title = strdup(title ? title : "lamina");
    }
    if (!s || !s->wanted || !s->panels || !s->title) {
        lam_svg_free(s);
        return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory");
    }
    s->nlayers = nlayers;
    s->npanels = np;
    for (size_t k = 0; k < np; k++)
        s->wanted[k] = np == nlayers ? k : (size_t)llround((double)k * (double)(nlayers - 1) / (double)(np - 1));
    memcpy(s->box, uvbox, sizeof s->box);
    strcpy(s->axis[0], "u");
    strcpy(s->axis[1], "v");
    s->cur = -1;
    *out = s;
    return LAM_OK;
}

int lam_svg_set_units(lam_svg *s, const char *units, lam_error *err)
{
    free(s->units);
    s->units = units && units[0] ? strdup(units) : NULL;
    return units && units[0] && !s->units ? lam_error_nomem(err, "naming the scale bar's units") : LAM_OK;
}

static long find_panel(const lam_svg *s, size_t index)
{
    size_t lo = 0, hi = s->npanels;
    while (lo < hi) {
        size_t mid = (lo + hi) / 2;
        if (s->wanted[mid] < index) lo = mid + 1;
        else hi = mid;
    }
    return lo < s->npanels && s->wanted[lo] == index ? (long)lo : -1;
}

int lam_svg_wants(const lam_svg *s, size_t index)
{
    return find_panel(s, index) >= 0;
}

static double scale_of(const lam_svg *s)
{
    double du = s->box[2] - s->box[0], dv = s->box[3] - s->box[1];
    double d = du > dv ? du : dv;
    return d > 0 ? (PANEL - 2 * PAD) / d : 1;
}

/* One contour as path data, relative to the panel's inner origin, v
 * flipped; a point nearer than MIN_STEP px to the last one written is left
 * out (a contact sheet cannot show it, and a finely tessellated section
 * would otherwise cost its every point). */
static void write_ring(lam_writer *w, const lam_svg *s, const lam_layer *L, const lam_contour *c, int first)
{
    double sc = scale_of(s), lx = 0, ly = 0;
    for (size_t j = 0; j < c->n; j++) {
        double x = (L->uv[2 * (c->first + j)] - s->box[0]) * sc, y = (s->box[3] - L->uv[2 * (c->first + j) + 1]) * sc;
        if (j && j + 1 < c->n && fabs(x - lx) < MIN_STEP && fabs(y - ly) < MIN_STEP) continue;
        lam_writer_printf(w, "%s%.2f %.2f", j ? " L" : (first ? "M" : " M"), x, y);
        lx = x, ly = y;
    }
    lam_writer_write(w, " Z", 2);
}

int lam_svg_add(lam_svg *s, const lam_layer *L, lam_error *err)
{
    long k = find_panel(s, L->index);
    if (k < 0) return LAM_OK;
    lam_writer *w;
    int rc = lam_writer_memory(&w, err);
    if (rc) return rc;
    /* the even-odd path of the section first, then "|" and the holes alone */
    for (size_t i = 0; i < L->ncontours; i++) write_ring(w, s, L, &L->contours[i], i == 0);
    lam_writer_write(w, "|", 1);
    int first = 1;
    for (size_t i = 0; i < L->ncontours; i++)
        if (L->contours[i].kind == LAM_HOLE) {
            write_ring(w, s, L, &L->contours[i], first);
            first = 0;
        }
    panel *p = &s->panels[k];
    free(p->path);
    p->index = L->index;
    p->cut = L->cut;
    p->ncontours = L->ncontours;
    size_t len;
    rc = lam_writer_take(w, &p->path, &len, err);
    if (!rc) s->filled++;
    return rc;
}

int lam_svg_mark(lam_svg *s, size_t index, double u, double v, lam_error *err)
{
    long k = find_panel(s, index);
    if (k < 0) return LAM_OK;
    panel *p = &s->panels[k];
    double *nm = realloc(p->marks, 2 * (p->nmarks + 1) * sizeof *nm);
    if (!nm) return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory");
    p->marks = nm;
    p->marks[2 * p->nmarks] = u;
    p->marks[2 * p->nmarks + 1] = v;
    p->nmarks++;
    return LAM_OK;
}

/* A round length for the scale bar: 1, 2 or 5 times a power of ten, the
 * largest not longer than `most`. */
static double nice_length(double most)
{
    double p = pow(10, floor(log10(most)));
    return most >= 5 * p ? 5 * p : most >= 2 * p ? 2 * p : p;
}

/* The font size, at most `most` px, at which n characters are estimated
 * (CHAR_EM) to fit `width` px; a tenth of a pixel, rounded down. */
static double fit_font(size_t n, double width, double most)
{
    double f = n ? width / (CHAR_EM * (double)n) : most;
    return f < most ? floor(f * 10) / 10 : most;
}

/* The footer's parts' places (px from the sheet's left): the scale bar's
 * start and its length, its label's start, the legend's start; and the
 * footer's estimated right end. */
typedef struct footer {
    double sc, len, bar, label, legend, right;
} footer;

static footer footer_of(const lam_svg *s)
{
    footer f;
    f.sc = scale_of(s);
    f.len = nice_length(60 / f.sc);
    f.bar = PAD + 60;
    f.label = f.bar + f.len * f.sc + 6;
    char num[32];
    int n = snprintf(num, sizeof num, "%g ", f.len);
    /* the label's estimated width (11 px), then a gap */
    f.legend = f.label + CHAR_EM * 11 * (double)(n + strlen(s->units ? s->units : "model units")) + 20;
    f.right = s->vectors ? f.legend + 230 : f.legend;
    return f;
}

static void write_footer(const lam_svg *s, lam_writer *w, double y, double width)
{
    footer f = footer_of(s);
    /* axes: u to the right, v up (the panels' orientation) */
    lam_writer_printf(w,
                      "<g class=\"axes\" font-family=\"sans-serif\" font-size=\"11\" fill=\"#222\" stroke=\"#222\">\n"
                      "<path d=\"M%.0f %.0f h24 m-5 -3 l5 3 l-5 3 M%.0f %.0f v-24 m-3 5 l3 -5 l3 5\" fill=\"none\"/>\n"
                      "<text x=\"%.0f\" y=\"%.0f\" stroke=\"none\">",
                      PAD, y + 26, PAD, y + 26, PAD + 28, y + 30);
    lam_esc_write(w, s->axis[0], LAM_ESC_XML);
    lam_writer_printf(w, "</text><text x=\"%.0f\" y=\"%.0f\" stroke=\"none\">", PAD - 3, y);
    lam_esc_write(w, s->axis[1], LAM_ESC_XML);
    lam_writer_printf(w, "</text>\n</g>\n");
    lam_writer_printf(w,
                      "<line class=\"scalebar\" x1=\"%.3f\" y1=\"%.0f\" x2=\"%.3f\" y2=\"%.0f\" stroke=\"#222\" "
                      "stroke-width=\"2\"/>\n"
                      "<text class=\"scalebar\" x=\"%.3f\" y=\"%.0f\" font-family=\"sans-serif\" font-size=\"11\" "
                      "fill=\"#222\">%g ",
                      f.bar, y + 26, f.bar + f.len * f.sc, y + 26, f.label, y + 30, f.len);
    lam_esc_write(w, s->units ? s->units : "model units", LAM_ESC_XML);
    lam_writer_printf(w, "</text>\n");
    if (s->vectors) {
        double x = f.legend;
        lam_writer_printf(w,
                          "<g class=\"legend\" font-family=\"sans-serif\" font-size=\"11\" fill=\"#222\">"
                          "<defs><linearGradient id=\"order\"><stop offset=\"0\" stop-color=\"#0d0887\"/>"
                          "<stop offset=\"0.5\" stop-color=\"#cc4778\"/><stop offset=\"1\" stop-color=\"#f89540\"/>"
                          "</linearGradient></defs>\n"
                          "<rect x=\"%.0f\" y=\"%.0f\" width=\"60\" height=\"6\" fill=\"url(#order)\"/>"
                          "<text x=\"%.0f\" y=\"%.0f\">first .. last</text>\n"
                          "<path d=\"M%.0f %.0f h30\" stroke=\"" TRAVEL "\" stroke-dasharray=\"3 2\"/>"
                          "<text x=\"%.0f\" y=\"%.0f\">travel</text></g>\n",
                          x, y + 21, x + 64, y + 30, x + 150, y + 26, x + 184, y + 30);
    }
    if (s->thinned) {
        char note[200];
        size_t n = (size_t)snprintf(note, sizeof note,
                                    "Thinned: a panel draws at most %d of its layer's vectors (see the captions)",
                                    LAM_SVG_CELL_VECTORS);
        lam_writer_printf(w, "<text class=\"note\" x=\"%.0f\" y=\"%.0f\" font-family=\"sans-serif\" "
                             "font-size=\"%.1f\" fill=\"#222\">%s</text>\n",
                          PAD, y + FOOT + 11, fit_font(n, width - 2 * PAD, 11), note);
    }
}

/* The title, sized to the sheet's width (the caption rule, svg.h). */
static void write_title(const lam_svg *s, lam_writer *w, double width)
{
    char tail[80];
    if (s->npanels < s->nlayers)
        snprintf(tail, sizeof tail, " (%zu of %zu layers shown, evenly chosen)", s->npanels, s->nlayers);
    else
        snprintf(tail, sizeof tail, " (%zu layer%s)", s->nlayers, s->nlayers == 1 ? "" : "s");
    /* bytes, not characters: a UTF-8 title is estimated wider than it is */
    double f = fit_font(strlen(s->title) + strlen(tail), width - 2 * PAD, 15);
    lam_writer_printf(w, "<text class=\"title\" x=\"%.0f\" y=\"22\" font-family=\"sans-serif\" font-size=\"%.1f\" "
                         "fill=\"#222\">",
                      PAD, f);
    lam_esc_write(w, s->title, LAM_ESC_XML);
    lam_writer_printf(w, "%s</text>\n", tail);
}

/* A panel's caption's two lines (svg.h); returns the longer's length. */
static size_t caption_lines(const lam_svg *s, size_t k, char l1[64], char l2[128])
{
    const panel *p = &s->panels[k];
    size_t n1 = (size_t)snprintf(l1, 64, "layer %zu  h=%.4g", s->wanted[k] + 1, p->cut);
    size_t n2 = (size_t)snprintf(l2, 128, "(%zu contour%s", p->ncontours, p->ncontours == 1 ? "" : "s");
    if (p->vec) n2 += (size_t)snprintf(l2 + n2, 128 - n2, ", %zu vector%s", p->nvec, p->nvec == 1 ? "" : "s");
    if (p->vec && p->ndrawn < p->nvec) n2 += (size_t)snprintf(l2 + n2, 128 - n2, ", %zu drawn", p->ndrawn);
    n2 += (size_t)snprintf(l2 + n2, 128 - n2, ")");
    return n1 > n2 ? n1 : n2;
}

/* The captions' font size: the largest at which every panel's longer line
 * fits its cell (one size for the sheet, so the captions read alike). */
static double caption_font(const lam_svg *s)
{
    size_t most = 0;
    for (size_t k = 0; k < s->npanels; k++) {
        char l1[64], l2[128];
        size_t n = caption_lines(s, k, l1, l2);
        if (n > most) most = n;
    }
    return fit_font(most, PANEL - 2 * LAM_SVG_CAPTION_MARGIN, LAM_SVG_CAPTION_FONT);
}

/* A panel's caption at font size f: two lines below its drawing. */
static void write_caption(const lam_svg *s, lam_writer *w, size_t k, double f)
{
    char l1[64], l2[128];
    caption_lines(s, k, l1, l2);
    double y1 = PANEL + LAM_SVG_CAPTION_MARGIN + f, y2 = y1 + 1.3 * f;
    lam_writer_printf(w,
                      "<g class=\"caption\" font-family=\"sans-serif\" font-size=\"%.1f\" fill=\"#222\">"
                      "<text x=\"%d\" y=\"%.2f\">%s</text><text x=\"%d\" y=\"%.2f\">%s</text></g>\n",
                      f, LAM_SVG_CAPTION_MARGIN, y1, l1, LAM_SVG_CAPTION_MARGIN, y2, l2);
}

/* A panel: its frame, the section, the holes' outlines, the scan paths and
 * the marks, clipped to the frame (the caption's band stays its own), then
 * the caption. */
static void write_panel(const lam_svg *s, lam_writer *w, size_t k, double x, double y, double font)
{
    const panel *p = &s->panels[k];
    lam_writer_printf(w,
                      "<g transform=\"translate(%.0f %.0f)\">\n"
                      "<rect width=\"%.0f\" height=\"%.0f\" fill=\"#ffffff\" stroke=\"#bbbbbb\"/>\n"
                      "<g class=\"drawing\" clip-path=\"url(#cell)\">\n",
                      x, y, PANEL, PANEL);
    const char *holes = p->path ? strchr(p->path, '|') : NULL;
    int nsec = p->path ? (int)(holes ? (size_t)(holes - p->path) : strlen(p->path)) : 0;
    if (nsec)
        lam_writer_printf(w,
                          "<path class=\"section\" transform=\"translate(%.0f %.0f)\" fill=\"%s\" "
                          "fill-rule=\"evenodd\" stroke=\"" SOLID_LINE "\" stroke-width=\"0.5\" d=\"%.*s\"/>\n",
                          PAD, PAD, s->vectors ? TINT : FILL, nsec, p->path);
    if (holes && holes[1])
        lam_writer_printf(w,
                          "<path class=\"hole\" transform=\"translate(%.0f %.0f)\" fill=\"none\" "
                          "stroke=\"" HOLE_LINE "\" stroke-width=\"0.8\" d=\"%s\"/>\n",
                          PAD, PAD, holes + 1);
    if (p->vec)
        lam_writer_printf(w,
                          "<g class=\"scan\" transform=\"translate(%.0f %.0f)\" fill=\"none\" stroke-width=\"0.8\" "
                          "stroke-linecap=\"round\">\n%s</g>\n",
                          PAD, PAD, p->vec);
    double sc = scale_of(s);
    for (size_t i = 0; i < p->nmarks; i++)
        lam_writer_printf(w, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"5\" fill=\"none\" stroke=\"#d62728\" "
                             "stroke-width=\"2\"/>\n",
                          PAD + (p->marks[2 * i] - s->box[0]) * sc, PAD + (s->box[3] - p->marks[2 * i + 1]) * sc);
    lam_writer_printf(w, "</g>\n");
    write_caption(s, w, k, font);
    lam_writer_printf(w, "</g>\n");
}

int lam_svg_write(const lam_svg *s, lam_writer *w)
{
    size_t np = s->npanels ? s->npanels : 1;
    size_t cols = (size_t)ceil(sqrt((double)np));
    size_t rows = (np + cols - 1) / cols;
    double cw = PANEL + PAD, ch = PANEL + LABEL + PAD;
    double width = PAD + (double)cols * cw, height = TOP + (double)rows * ch + FOOT + (s->thinned ? NOTE : 0);
    double fr = footer_of(s).right + PAD;
    if (width < fr) width = ceil(fr); /* room for the scale bar's label and the legend */
    lam_writer_printf(w,
                      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
                      "viewBox=\"0 0 %.0f %.0f\">\n"
                      "<defs><clipPath id=\"cell\"><rect width=\"%.0f\" height=\"%.0f\"/></clipPath></defs>\n"
                      "<rect width=\"100%%\" height=\"100%%\" fill=\"#ffffff\"/>\n",
                      width, height, width, height, PANEL, PANEL);
    write_title(s, w, width);
    double font = caption_font(s);
    for (size_t k = 0; k < s->npanels; k++)
        write_panel(s, w, k, PAD + (double)(k % cols) * cw, TOP + (double)(k / cols) * ch, font);
    write_footer(s, w, TOP + (double)rows * ch, width);
    return lam_writer_printf(w, "</svg>\n");
}

/* ---- the scan paths, from a planning run (vstream.h) ---------------------- */

/* Colour of position t (0 first .. 1 last) along a layer's order. */
static void order_colour(double t, char out[8])
{
    static const unsigned char stop[3][3] = { { 0x0d, 0x08, 0x87 }, { 0xcc, 0x47, 0x78 }, { 0xf8, 0x95, 0x40 } };
    int k = t < 0.5 ? 0 : 1;
    double f = t < 0.5 ? t * 2 : (t - 0.5) * 2;
    int c[3];
    for (int i = 0; i < 3; i++) c[i] = (int)lround(stop[k][i] + f * (stop[k + 1][i] - stop[k][i]));
    snprintf(out, 8, "#%02x%02x%02x", c[0], c[1], c[2]);
}

static int sv_begin(void *ctx, const lam_job_info *job)
{
    lam_svg *s = ctx;
    return lam_svg_set_units(s, job->units, s->err);
}

static int sv_layer(void *ctx, const lam_layer_info *li)
{
    lam_svg *s = ctx;
    s->cur = find_panel(s, li->index);
    s->nrv = 0;
    return LAM_OK;
}

static int sv_vector(void *ctx, const lam_vec *v)
{
    lam_svg *s = ctx;
    if (s->cur < 0) return LAM_OK;
    if (s->nrv == s->caprv) {
        rvec *n = lam_grow(s->rv, &s->caprv, s->nrv + 1, sizeof *n, 256);
        if (!n) return lam_error_nomem(s->err, "drawing the scan paths");
        s->rv = n;
    }
    rvec *r = &s->rv[s->nrv++];
    memcpy(r->a, v->fuv, sizeof r->a);
    memcpy(r->b, v->tuv, sizeof r->b);
    r->kind = lam_kind_name(v->kind);
    r->exposed = v->exposed;
    return LAM_OK;
}

/* Which of the layer's vectors its panel draws (svg.h): all of them up to
 * LAM_SVG_CELL_VECTORS; past it no travel or jump, every contour edge when
 * they are at most half of it (*contours set) else none, and every
 * `stride`-th other vector (the first, then one in `stride`), so that at
 * most LAM_SVG_CELL_VECTORS are drawn. */
static size_t thin_stride(const lam_svg *s, int *contours)
{
    size_t nc = 0, nother = 0;
    for (size_t i = 0; i < s->nrv; i++) {
        if (!s->rv[i].exposed) continue;
        if (!strcmp(s->rv[i].kind, "contour")) nc++;
        else nother++;
    }
    *contours = 2 * nc <= LAM_SVG_CELL_VECTORS;
    if (s->nrv <= LAM_SVG_CELL_VECTORS) return 1;
    size_t room = *contours ? LAM_SVG_CELL_VECTORS - nc : LAM_SVG_CELL_VECTORS;
    return nother > room ? (nother + room - 1) / room : 1;
}

/* Vector i (and the contour edges that continue it, joined into one path)
 * as an element; returns the last vector's index and adds the vectors
 * drawn to *drawn. */
static size_t write_vector(const lam_svg *s, lam_writer *w, size_t i, size_t *drawn)
{
    double sc = scale_of(s);
#define X(p) (((p)[0] - s->box[0]) * sc)
#define Y(p) ((s->box[3] - (p)[1]) * sc)
    const rvec *r = &s->rv[i];
    char col[8];
    order_colour(s->nrv > 1 ? (double)i / (double)(s->nrv - 1) : 0, col);
    lam_writer_write(w, "<path class=\"", 13);
    lam_esc_write(w, r->kind, LAM_ESC_XML);
    (*drawn)++;
    if (!r->exposed) {
        lam_writer_printf(w, "\" stroke=\"" TRAVEL "\" stroke-dasharray=\"2 1.5\" d=\"M%.2f %.2fL%.2f %.2f\"/>\n",
                          X(r->a), Y(r->a), X(r->b), Y(r->b));
        return i;
    }
    lam_writer_printf(w, "\" stroke=\"%s\" d=\"M%.2f %.2fL%.2f %.2f", col, X(r->a), Y(r->a), X(r->b), Y(r->b));
    double lx = X(r->b), ly = Y(r->b);
    while (!strcmp(r->kind, "contour") && i + 1 < s->nrv && !strcmp(s->rv[i + 1].kind, "contour") &&
           s->rv[i + 1].a[0] == r->b[0] && s->rv[i + 1].a[1] == r->b[1]) {
        r = &s->rv[++i];
        (*drawn)++;
        /* a point the panel cannot tell from the last one drawn is left out */
        if (fabs(X(r->b) - lx) < MIN_STEP && fabs(Y(r->b) - ly) < MIN_STEP) continue;
        lam_writer_printf(w, "L%.2f %.2f", X(r->b), Y(r->b));
        lx = X(r->b), ly = Y(r->b);
    }
#undef X
#undef Y
    lam_writer_printf(w, "\"/>\n");
    return i;
}

/* One element per vector drawn (class: its kind), in the layer's order;
 * the edges of a contour pass, one after the other, make one path. */
static int sv_layer_end(void *ctx, const lam_layer_info *li, const lam_vec_stats *st)
{
    (void)li;
    lam_svg *s = ctx;
    if (s->cur < 0) return LAM_OK;
    lam_writer *w;
    int rc = lam_writer_memory(&w, s->err);
    if (rc) return rc;
    int contours;
    size_t drawn = 0, other = 0, stride = thin_stride(s, &contours);
    int thin = s->nrv > LAM_SVG_CELL_VECTORS;
    for (size_t i = 0; i < s->nrv; i++) {
        const rvec *r = &s->rv[i];
        int contour = !strcmp(r->kind, "contour");
        if (thin && (!r->exposed || (contour && !contours))) continue;
        if (thin && !contour && other++ % stride) continue;
        i = write_vector(s, w, i, &drawn);
    }
    panel *p = &s->panels[s->cur];
    free(p->vec);
    p->vec = NULL;
    size_t len;
    rc = lam_writer_take(w, &p->vec, &len, s->err);
    p->nvec = st->vectors;
    p->ndrawn = thin ? drawn : p->nvec;
    if (thin) s->thinned = 1;
    return rc;
}

/* A world axis's name when v is one (x, -x, ...), else `other`. */
static void axis_name(const double v[3], const char *other, char out[8])
{
    static const char *names[3] = { "x", "y", "z" };
    snprintf(out, 8, "%s", other);
    for (int k = 0; k < 3; k++)
        if (fabs(v[k]) == 1 && v[(k + 1) % 3] == 0 && v[(k + 2) % 3] == 0)
            snprintf(out, 8, "%s%s", v[k] < 0 ? "-" : "", names[k]);
}

int lam_svg_consumer(lam_svg *s, const lam_frame *f, int frame_machine, lam_vec_consumer *out, lam_error *err)
{
    s->vectors = 1;
    s->err = err;
    if (!frame_machine) {
        axis_name(f->u, "u", s->axis[0]);
        axis_name(f->v, "v", s->axis[1]);
    }
    *out = (lam_vec_consumer){ .ctx = s, .begin = sv_begin, .layer = sv_layer, .vector = sv_vector,
                               .layer_end = sv_layer_end };
    return LAM_OK;
}

void lam_svg_free(lam_svg *s)
{
    if (!s) return;
    if (s->panels)
        for (size_t k = 0; k < s->npanels; k++) {
            free(s->panels[k].path);
            free(s->panels[k].marks);
            free(s->panels[k].vec);
        }
    free(s->panels);
    free(s->wanted);
    free(s->title);
    free(s->units);
    free(s->rv);
    free(s);
}

int lam_svg_save(const lam_svg *svg, const char *path, lam_error *err)
{
    lam_writer *w;
    int rc = lam_writer_file(path, &w, err);
    if (rc) return rc;
    lam_svg_write(svg, w);
    return lam_writer_commit(w, err);
}
