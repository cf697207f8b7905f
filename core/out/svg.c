#include "svg.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "escape.h"
#include "grow.h"
#include "vstream.h"

#define PANEL 200.0   /* panel size in px */
#define PAD 10.0
#define LABEL 18.0
#define FOOT 34.0     /* the scale bar and the axes, below the panels */

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
    /* the even-odd path of the section first, then "|" and the holes alone */
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
    lam_writer_write(w, "|", 1);
    int first = 1;
    for (size_t i = 0; i < L->ncontours; i++) {
        const lam_contour *c = &L->contours[i];
        if (c->kind != LAM_HOLE) continue;
        for (size_t j = 0; j < c->n; j++) {
            double u = L->uv[2 * (c->first + j)], v = L->uv[2 * (c->first + j) + 1];
            lam_writer_printf(w, "%s%.2f %.2f", j ? " L" : (first ? "M" : " M"), (u - s->box[0]) * sc,
                              (s->box[3] - v) * sc);
            first = 0;
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

/* A round length for the scale bar: 1, 2 or 5 times a power of ten, the
 * largest not longer than `most`. */
static double nice_length(double most)
{
    double p = pow(10, floor(log10(most)));
    return most >= 5 * p ? 5 * p : most >= 2 * p ? 2 * p : p;
}

static void write_footer(const lam_svg *s, lam_writer *w, double y)
{
    double sc = scale_of(s);
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
    double len = nice_length(60 / sc);
    double x = PAD + 60;
    lam_writer_printf(w,
                      "<line class=\"scalebar\" x1=\"%.3f\" y1=\"%.0f\" x2=\"%.3f\" y2=\"%.0f\" stroke=\"#222\" "
                      "stroke-width=\"2\"/>\n"
                      "<text class=\"scalebar\" x=\"%.3f\" y=\"%.0f\" font-family=\"sans-serif\" font-size=\"11\" "
                      "fill=\"#222\">%g ",
                      x, y + 26, x + len * sc, y + 26, x + len * sc + 6, y + 30, len);
    lam_esc_write(w, s->units ? s->units : "model units", LAM_ESC_XML);
    lam_writer_printf(w, "</text>\n");
    if (s->vectors) {
        x += len * sc + 80;
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
}

int lam_svg_write(const lam_svg *s, lam_writer *w)
{
    size_t np = s->npanels ? s->npanels : 1;
    size_t cols = (size_t)ceil(sqrt((double)np));
    if (s->vectors && cols < 2) cols = 2; /* room for the legend */
    size_t rows = (np + cols - 1) / cols;
    double cw = PANEL + PAD, ch = PANEL + LABEL + PAD, top = 34;
    double width = PAD + cols * cw, height = top + rows * ch + FOOT;
    lam_writer_printf(w,
                      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
                      "viewBox=\"0 0 %.0f %.0f\">\n"
                      "<rect width=\"100%%\" height=\"100%%\" fill=\"#ffffff\"/>\n"
                      "<text x=\"%.0f\" y=\"22\" font-family=\"sans-serif\" font-size=\"15\" fill=\"#222\">",
                      width, height, width, height, PAD);
    lam_esc_write(w, s->title, LAM_ESC_XML);
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
        lam_writer_printf(w,
                          "<text x=\"2\" y=\"%.0f\" font-family=\"sans-serif\" font-size=\"12\" fill=\"#222\">"
                          "layer %zu  h=%.4g  (%zu contour%s",
                          PANEL + 14, s->wanted[k] + 1, p->cut, p->ncontours, p->ncontours == 1 ? "" : "s");
        if (p->vec) lam_writer_printf(w, ", %zu vector%s", p->nvec, p->nvec == 1 ? "" : "s");
        lam_writer_printf(w, ")</text>\n</g>\n");
    }
    write_footer(s, w, top + rows * ch);
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
    free(s->units);
    s->units = job->units && job->units[0] ? strdup(job->units) : NULL;
    return job->units && job->units[0] && !s->units ? lam_error_nomem(s->err, "drawing the scale bar") : LAM_OK;
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

/* One element per vector (class: its kind), in the layer's order; the
 * edges of a contour pass, one after the other, make one path. */
static int sv_layer_end(void *ctx, const lam_layer_info *li, const lam_vec_stats *st)
{
    (void)li;
    lam_svg *s = ctx;
    if (s->cur < 0) return LAM_OK;
    lam_writer *w;
    int rc = lam_writer_memory(&w, s->err);
    if (rc) return rc;
    double sc = scale_of(s);
#define X(p) (((p)[0] - s->box[0]) * sc)
#define Y(p) ((s->box[3] - (p)[1]) * sc)
    for (size_t i = 0; i < s->nrv; i++) {
        const rvec *r = &s->rv[i];
        char col[8];
        order_colour(s->nrv > 1 ? (double)i / (double)(s->nrv - 1) : 0, col);
        lam_writer_write(w, "<path class=\"", 13);
        lam_esc_write(w, r->kind, LAM_ESC_XML);
        if (!r->exposed)
            lam_writer_printf(w, "\" stroke=\"" TRAVEL "\" stroke-dasharray=\"2 1.5\" d=\"M%.2f %.2fL%.2f %.2f\"/>\n",
                              X(r->a), Y(r->a), X(r->b), Y(r->b));
        else {
            lam_writer_printf(w, "\" stroke=\"%s\" d=\"M%.2f %.2fL%.2f %.2f", col, X(r->a), Y(r->a), X(r->b), Y(r->b));
            while (!strcmp(r->kind, "contour") && i + 1 < s->nrv && !strcmp(s->rv[i + 1].kind, "contour") &&
                   s->rv[i + 1].a[0] == r->b[0] && s->rv[i + 1].a[1] == r->b[1]) {
                r = &s->rv[++i];
                lam_writer_printf(w, "L%.2f %.2f", X(r->b), Y(r->b));
            }
            lam_writer_printf(w, "\"/>\n");
        }
    }
#undef X
#undef Y
    panel *p = &s->panels[s->cur];
    free(p->vec);
    p->vec = NULL;
    size_t len;
    rc = lam_writer_take(w, &p->vec, &len, s->err);
    p->nvec = st->vectors;
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
