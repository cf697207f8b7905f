/* The layout drawing of a build's plate (arrange.h, lam_layout_svg). */
#include <math.h>
#include <stdio.h>

#include "arrange.h"
#include "escape.h"
#include "fmt.h"

#define SIZE 720.0 /* the drawing's longer side in px */
#define PAD 24.0
#define FOOT 36.0  /* the scale bar, below the plate */

/* Fields cycle through these (a field's fill is translucent). */
static const char *const FIELD_COLOUR[] = { "#d62728", "#2ca02c", "#ff7f0e", "#9467bd",
                                            "#17becf", "#8c564b", "#e377c2", "#bcbd22" };

/* Plate coordinates to the picture's px, y flipped (the plate's front at
 * the bottom). */
typedef struct view {
    double x0, y1, sc;
} view;

static double X(const view *v, double x)
{
    return PAD + (x - v->x0) * v->sc;
}

static double Y(const view *v, double y)
{
    return PAD + (v->y1 - y) * v->sc;
}

static void grow_ext(double e[4], double x0, double y0, double x1, double y1)
{
    if (!isfinite(x0) || !isfinite(y0) || !isfinite(x1) || !isfinite(y1)) return;
    e[0] = fmin(e[0], x0);
    e[1] = fmin(e[1], y0);
    e[2] = fmax(e[2], x1);
    e[3] = fmax(e[3], y1);
}

/* The drawing's extent: the plate, and the fields that reach past it. */
static void extent(const lam_plate *p, const double (*fields)[4], size_t nf, double e[4])
{
    double r = p->diameter / 2;
    if (p->round) {
        e[0] = e[1] = -r;
        e[2] = e[3] = r;
    } else {
        e[0] = e[1] = 0;
        e[2] = p->width;
        e[3] = p->depth;
    }
    if (!(e[2] > e[0]) || !(e[3] > e[1]) || !isfinite(e[2] - e[0]) || !isfinite(e[3] - e[1])) {
        e[0] = e[1] = 0;
        e[2] = e[3] = 1;
    }
    for (size_t k = 0; k < nf; k++) grow_ext(e, fields[k][0], fields[k][1], fields[k][2], fields[k][3]);
}

/* The plate's outline (solid) or the room inside its margin (dashed). */
static void write_outline(lam_writer *w, const view *v, const lam_plate *p, double inset, const char *cls)
{
    const char *look = inset > 0 ? "fill=\"none\" stroke=\"#888888\" stroke-dasharray=\"6 4\""
                                 : "fill=\"#f2f2f2\" stroke=\"#444444\" stroke-width=\"1.5\"";
    if (p->round) {
        double r = fmax(0, p->diameter / 2 - inset);
        lam_writer_printf(w, "<circle class=\"%s\" cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" %s/>\n", cls, X(v, 0), Y(v, 0),
                          r * v->sc, look);
    } else {
        double wd = fmax(0, p->width - 2 * inset), dp = fmax(0, p->depth - 2 * inset);
        lam_writer_printf(w, "<rect class=\"%s\" x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" %s/>\n", cls,
                          X(v, inset), Y(v, inset + dp), wd * v->sc, dp * v->sc, look);
    }
}

static void write_fields(lam_writer *w, const view *v, const double (*fields)[4], size_t nf)
{
    for (size_t k = 0; k < nf; k++) {
        const double *f = fields[k];
        const char *c = FIELD_COLOUR[k % (sizeof FIELD_COLOUR / sizeof *FIELD_COLOUR)];
        lam_writer_printf(w,
                          "<rect class=\"field\" x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" fill=\"%s\" "
                          "fill-opacity=\"0.12\" stroke=\"%s\" stroke-opacity=\"0.8\"/>\n"
                          "<text class=\"field-label\" x=\"%.2f\" y=\"%.2f\" font-family=\"sans-serif\" "
                          "font-size=\"12\" fill=\"%s\">laser %zu</text>\n",
                          X(v, f[0]), Y(v, f[3]), fabs(f[2] - f[0]) * v->sc, fabs(f[3] - f[1]) * v->sc, c, c,
                          X(v, f[0]) + 4, Y(v, f[3]) + 14, c, k + 1);
    }
}

/* Item i's outline (given, else its box where the arrangement put it) and
 * its name at the box's centre. */
static void write_part(lam_writer *w, const view *v, const lam_arrange_item *it, size_t i, const double *pts,
                       size_t np)
{
    const char *look = "fill=\"#2f6db5\" fill-opacity=\"0.35\" stroke=\"#1b3f6b\"";
    if (pts && np) {
        lam_writer_printf(w, "<polygon class=\"part\" points=\"");
        for (size_t k = 0; k < np; k++)
            lam_writer_printf(w, "%s%.2f,%.2f", k ? " " : "", X(v, pts[2 * k]), Y(v, pts[2 * k + 1]));
        lam_writer_printf(w, "\" %s/>\n", look);
    } else {
        const double *b = it->box, *s = it->shift;
        lam_writer_printf(w, "<rect class=\"part\" x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" %s/>\n",
                          X(v, b[0] + s[0]), Y(v, b[3] + s[1]), (b[2] - b[0]) * v->sc, (b[3] - b[1]) * v->sc, look);
    }
    lam_writer_printf(w,
                      "<text class=\"name\" x=\"%.2f\" y=\"%.2f\" text-anchor=\"middle\" dominant-baseline=\"central\" "
                      "font-family=\"sans-serif\" font-size=\"11\" fill=\"#111111\">",
                      X(v, it->at[0]), Y(v, it->at[1]));
    if (it->name)
        lam_esc_write(w, it->name, LAM_ESC_XML);
    else
        lam_writer_printf(w, "#%zu", i + 1);
    lam_writer_printf(w, "</text>\n");
}

/* A round length for the scale bar: 1, 2 or 5 times a power of ten, the
 * largest not longer than `most`. */
static double nice_length(double most)
{
    double p = pow(10, floor(log10(most)));
    return most >= 5 * p ? 5 * p : most >= 2 * p ? 2 * p : p;
}

static void write_scale(lam_writer *w, const view *v, double y, double span, const char *units)
{
    double len = nice_length(span / 5);
    char nb[LAM_FMT_NUM];
    lam_writer_printf(w,
                      "<line class=\"scalebar\" x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"#222222\" "
                      "stroke-width=\"2\"/>\n"
                      "<text class=\"scalebar\" x=\"%.2f\" y=\"%.2f\" font-family=\"sans-serif\" font-size=\"12\" "
                      "fill=\"#222222\">%s",
                      PAD, y, PAD + len * v->sc, y, PAD + len * v->sc + 6, y + 4, lam_fmt_num(nb, len, 15));
    if (units && *units) {
        lam_writer_printf(w, " ");
        lam_esc_write(w, units, LAM_ESC_XML);
    }
    lam_writer_printf(w, "</text>\n");
}

int lam_layout_svg(lam_writer *w, const lam_plate *p, const lam_arrange_item *items, size_t n,
                   const double *const *outline, const size_t *npts, const double (*fields)[4], size_t nf,
                   const char *units)
{
    double e[4];
    extent(p, fields, nf, e);
    double span = fmax(e[2] - e[0], e[3] - e[1]);
    view v = { e[0], e[3], SIZE / span };
    double width = 2 * PAD + (e[2] - e[0]) * v.sc, height = 2 * PAD + (e[3] - e[1]) * v.sc + FOOT;
    lam_writer_printf(w,
                      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
                      "viewBox=\"0 0 %.0f %.0f\">\n"
                      "<rect width=\"100%%\" height=\"100%%\" fill=\"#ffffff\"/>\n",
                      ceil(width), ceil(height), ceil(width), ceil(height));
    write_outline(w, &v, p, 0, "plate");
    if (p->margin > 0) write_outline(w, &v, p, p->margin, "margin");
    write_fields(w, &v, fields, nf);
    for (size_t i = 0; i < n; i++)
        write_part(w, &v, &items[i], i, outline ? outline[i] : NULL, outline && npts ? npts[i] : 0);
    write_scale(w, &v, height - FOOT / 2 - PAD / 2, span, units);
    return lam_writer_printf(w, "</svg>\n");
}
