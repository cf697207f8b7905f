#include "svg.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PANEL 200.0   /* panel size in px */
#define PAD 10.0
#define LABEL 18.0

typedef struct panel {
    size_t index;
    double cut;
    char *path;       /* SVG path data, owned */
    size_t ncontours;
    double *marks;    /* u, v pairs, owned */
    size_t nmarks;
} panel;

struct lam_svg {
    size_t nlayers, npanels, filled;
    size_t *wanted;   /* layer index of each panel, increasing */
    panel *panels;
    double box[4];
    char *title;
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
    *out = s;
    return LAM_OK;
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

int lam_svg_add(lam_svg *s, const lam_layer *L, lam_error *err)
{
    long k = find_panel(s, L->index);
    if (k < 0) return LAM_OK;
    lam_writer *w;
    int rc = lam_writer_memory(&w, err);
    if (rc) return rc;
    double sc = scale_of(s);
    /* coordinates relative to the panel's inner origin; v flipped */
    for (size_t i = 0; i < L->ncontours; i++) {
        const lam_contour *c = &L->contours[i];
        for (size_t j = 0; j < c->n; j++) {
            double u = L->uv[2 * (c->first + j)], v = L->uv[2 * (c->first + j) + 1];
            lam_writer_printf(w, "%s%.2f %.2f", j ? " L" : (i ? " M" : "M"), (u - s->box[0]) * sc,
                              (s->box[3] - v) * sc);
        }
        lam_writer_write(w, " Z", 2);
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

static void xml_text(lam_writer *w, const char *t)
{
    for (; *t; t++) {
        switch (*t) {
        case '<': lam_writer_write(w, "&lt;", 4); break;
        case '>': lam_writer_write(w, "&gt;", 4); break;
        case '&': lam_writer_write(w, "&amp;", 5); break;
        case '"': lam_writer_write(w, "&quot;", 6); break;
        default: lam_writer_write(w, t, 1);
        }
    }
}

int lam_svg_write(const lam_svg *s, lam_writer *w)
{
    size_t np = s->npanels ? s->npanels : 1;
    size_t cols = (size_t)ceil(sqrt((double)np));
    size_t rows = (np + cols - 1) / cols;
    double cw = PANEL + PAD, ch = PANEL + LABEL + PAD, top = 34;
    double width = PAD + cols * cw, height = top + rows * ch;
    lam_writer_printf(w,
                      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
                      "viewBox=\"0 0 %.0f %.0f\">\n"
                      "<rect width=\"100%%\" height=\"100%%\" fill=\"#ffffff\"/>\n"
                      "<text x=\"%.0f\" y=\"22\" font-family=\"sans-serif\" font-size=\"15\" fill=\"#222\">",
                      width, height, width, height, PAD);
    xml_text(w, s->title);
    if (s->npanels < s->nlayers)
        lam_writer_printf(w, " (%zu of %zu layers shown, evenly chosen)", s->npanels, s->nlayers);
    else
        lam_writer_printf(w, " (%zu layer%s)", s->nlayers, s->nlayers == 1 ? "" : "s");
    lam_writer_printf(w, "</text>\n");
    for (size_t k = 0; k < s->npanels; k++) {
        const panel *p = &s->panels[k];
        double x = PAD + (double)(k % cols) * cw, y = top + (double)(k / cols) * ch;
        lam_writer_printf(w,
                          "<g transform=\"translate(%.0f %.0f)\">\n"
                          "<rect width=\"%.0f\" height=\"%.0f\" fill=\"#ffffff\" stroke=\"#bbbbbb\"/>\n",
                          x, y, PANEL, PANEL);
        if (p->path && p->path[0])
            lam_writer_printf(w,
                              "<path transform=\"translate(%.0f %.0f)\" fill=\"#2f6db5\" fill-rule=\"evenodd\" "
                              "stroke=\"#1b3f6b\" stroke-width=\"0.5\" d=\"%s\"/>\n",
                              PAD, PAD, p->path);
        double sc = scale_of(s);
        for (size_t i = 0; i < p->nmarks; i++)
            lam_writer_printf(w, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"5\" fill=\"none\" stroke=\"#d62728\" "
                                 "stroke-width=\"2\"/>\n",
                              PAD + (p->marks[2 * i] - s->box[0]) * sc, PAD + (s->box[3] - p->marks[2 * i + 1]) * sc);
        lam_writer_printf(w,
                          "<text x=\"2\" y=\"%.0f\" font-family=\"sans-serif\" font-size=\"12\" fill=\"#222\">"
                          "layer %zu  h=%.4g  (%zu contour%s)</text>\n</g>\n",
                          PANEL + 14, s->wanted[k] + 1, p->cut, p->ncontours, p->ncontours == 1 ? "" : "s");
    }
    return lam_writer_printf(w, "</svg>\n");
}

void lam_svg_free(lam_svg *s)
{
    if (!s) return;
    if (s->panels)
        for (size_t k = 0; k < s->npanels; k++) {
            free(s->panels[k].path);
            free(s->panels[k].marks);
        }
    free(s->panels);
    free(s->wanted);
    free(s->title);
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
