/* arrange.h: parts on the plate (lam_arrange), a footprint's hull and box,
 * and the layout drawing. The geometry is checked by the test's own code:
 * spacing between every pair of placed boxes, every box inside the plate
 * less its margin, fixed parts where they were asked to be; the counts
 * expected are the test's own (a grid of the boxes). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "arrange.h"
#include "error.h"
#include "tap.h"
#include "writer.h"

#define MAXN 400

/* The plate's size times 1e-9: the slack a box may take (arrange.h). */
static double slack(const lam_plate *p)
{
    return 1e-9 * (p->round ? p->diameter : fmax(p->width, p->depth));
}

/* Item it's box on the plate (box + shift). */
static void placed(const lam_arrange_item *it, double b[4])
{
    b[0] = it->box[0] + it->shift[0];
    b[1] = it->box[1] + it->shift[1];
    b[2] = it->box[2] + it->shift[0];
    b[3] = it->box[3] + it->shift[1];
}

static int inside_plate(const lam_plate *p, const double b[4])
{
    double t = slack(p), m = p->margin;
    if (!p->round) return b[0] >= m - t && b[1] >= m - t && b[2] <= p->width - m + t && b[3] <= p->depth - m + t;
    double R = p->diameter / 2 - m;
    for (int cx = 0; cx < 4; cx += 2)
        for (int cy = 1; cy < 4; cy += 2)
            if (sqrt(b[cx] * b[cx] + b[cy] * b[cy]) > R + t) return 0;
    return 1;
}

/* The invariants of a successful call: NULL, or what is wrong. in: the
 * items as passed. */
static const char *violation(const lam_plate *p, double s, const lam_arrange_item *in, const lam_arrange_item *out,
                             size_t n, char *buf, size_t size)
{
    double t = slack(p);
    for (size_t i = 0; i < n; i++) {
        double b[4], cx = (out[i].box[0] + out[i].box[2]) / 2, cy = (out[i].box[1] + out[i].box[3]) / 2;
        placed(&out[i], b);
        if (memcmp(in[i].box, out[i].box, sizeof in[i].box) || in[i].fixed != out[i].fixed)
            return snprintf(buf, size, "item %zu's box or fixed changed", i), buf;
        if (in[i].fixed && (in[i].at[0] != out[i].at[0] || in[i].at[1] != out[i].at[1]))
            return snprintf(buf, size, "fixed item %zu moved", i), buf;
        if (fabs(out[i].at[0] - cx - out[i].shift[0]) > t || fabs(out[i].at[1] - cy - out[i].shift[1]) > t)
            return snprintf(buf, size, "item %zu: shift is not at - box centre", i), buf;
        if (!inside_plate(p, b))
            return snprintf(buf, size, "item %zu (%g %g %g %g) is off the plate", i, b[0], b[1], b[2], b[3]), buf;
        for (size_t j = 0; j < i; j++) {
            double c[4];
            placed(&out[j], c);
            double gx = fmax(c[0] - b[2], b[0] - c[2]), gy = fmax(c[1] - b[3], b[1] - c[3]);
            /* the spacing to rounding (arrange.h allows the slack, which
             * only a box that passes the edge by less than it takes) */
            if (fmax(gx, gy) < s - 1e-9)
                return snprintf(buf, size, "items %zu and %zu are %g apart (spacing %g)", j, i, fmax(gx, gy), s), buf;
        }
    }
    return NULL;
}

static void box_item(lam_arrange_item *it, double x0, double y0, double w, double h, const char *name)
{
    memset(it, 0, sizeof *it);
    it->box[0] = x0;
    it->box[1] = y0;
    it->box[2] = x0 + w;
    it->box[3] = y0 + h;
    it->name = name;
}

/* Arrange n copies of one box; rc, and the invariants checked. */
static int arrange_copies(const lam_plate *p, double s, double w, double h, size_t n, lam_error *err,
                          const char **why)
{
    static lam_arrange_item in[MAXN], out[MAXN];
    static char buf[256];
    for (size_t i = 0; i < n; i++) box_item(&in[i], -7.5 + (double)i, 3, w, h, NULL); /* any part coordinates */
    memcpy(out, in, n * sizeof *in);
    int rc = lam_arrange(p, s, out, n, "mm", err);
    *why = rc ? (memcmp(in, out, n * sizeof *in) ? "changed on failure" : NULL)
              : violation(p, s, in, out, n, buf, sizeof buf);
    return rc;
}

/* How many boxes w x h a rectangle's grid holds, from its corner. */
static size_t rect_grid(const lam_plate *p, double s, double w, double h)
{
    double cols = floor((p->width - 2 * p->margin + s) / (w + s)), rows = floor((p->depth - 2 * p->margin + s) / (h + s));
    return cols > 0 && rows > 0 ? (size_t)(cols * rows) : 0;
}

/* How many boxes w x h a round plate's centred grid holds: the best of
 * the four centrings (a row or a gap on the centre line, a column or a gap). */
static size_t round_grid(const lam_plate *p, double s, double w, double h)
{
    double R = p->diameter / 2 - p->margin, px = w + s, py = h + s;
    size_t best = 0;
    for (int ox = 0; ox < 2; ox++)
        for (int oy = 0; oy < 2; oy++) {
            size_t c = 0;
            /* cell (i, j): lower-left corner at offset + i * pitch, the
             * offsets putting a cell's centre (o = 0) or a gap's (o = 1) on 0 */
            double x0 = ox ? s / 2 : -w / 2, y0 = oy ? s / 2 : -h / 2;
            int k = (int)(R / fmin(px, py)) + 2;
            for (int i = -k; i <= k; i++)
                for (int j = -k; j <= k; j++) {
                    double b[4] = { x0 + i * px, y0 + j * py, x0 + i * px + w, y0 + j * py + h };
                    double xm = fmax(fabs(b[0]), fabs(b[2])), ym = fmax(fabs(b[1]), fabs(b[3]));
                    if (sqrt(xm * xm + ym * ym) <= R) c++;
                }
            if (c > best) best = c;
        }
    return best;
}

static void test_grids(void)
{
    lam_error err;
    const char *why;
    lam_plate sq = { .width = 250, .depth = 250, .margin = 5 };
    is_int(rect_grid(&sq, 5, 40, 40), 25, "a 5 x 5 grid of 40 x 40 boxes on 250 x 250 (margin 5, spacing 5)");
    int rc = arrange_copies(&sq, 5, 40, 40, 25, &err, &why);
    ok(rc == LAM_OK && !why, "25 cylinders of 40 x 40 fit on 250 x 250%s%s", why ? ": " : "", why ? why : "");
    if (rc) diag("%s", err.msg);
    /* 5 * 44 + 4 * 5 = 240: each row exactly fills the room */
    rc = arrange_copies(&sq, 5, 44, 44, 25, &err, &why);
    ok(rc == LAM_OK && !why, "25 boxes of 44 that exactly fill the rows fit");
    /* the same in numbers that are not exact in binary: 4 * 0.1 + 3 * 0.05 = 0.55 */
    lam_plate tiny = { .width = 0.65, .depth = 0.65, .margin = 0.05 };
    rc = arrange_copies(&tiny, 0.05, 0.1, 0.1, 16, &err, &why);
    ok(rc == LAM_OK && !why, "16 boxes of 0.1 that exactly fill 0.55 (inexact decimals) fit");
    if (rc) diag("%s", err.msg);
    /* round plate: at least the centred grid */
    lam_plate disc = { .round = 1, .diameter = 300, .margin = 5 };
    size_t g = round_grid(&disc, 5, 40, 40);
    ok(g >= 24, "the centred grid of 40 x 40 on a disc of 300 holds %zu", g);
    rc = arrange_copies(&disc, 5, 40, 40, g, &err, &why);
    ok(rc == LAM_OK && !why, "a round plate takes the centred grid's %zu boxes%s%s", g, why ? ": " : "",
       why ? why : "");
    if (rc) diag("%s", err.msg);
    rc = arrange_copies(&disc, 5, 30, 55, round_grid(&disc, 5, 30, 55), &err, &why);
    ok(rc == LAM_OK && !why, "... and of 30 x 55 boxes (%zu)", round_grid(&disc, 5, 30, 55));
    /* not all fit: 2 x 2 of 100 x 100 */
    size_t k = rect_grid(&sq, 5, 100, 100);
    is_int(k, 4, "100 x 100 on 250 x 250: a 2 x 2 grid");
    rc = arrange_copies(&sq, 5, 100, 100, 10, &err, &why);
    char want[128];
    snprintf(want, sizeof want, "only %zu of 10 parts fit on the plate (250 x 250 mm, margin 5, spacing 5)", k);
    ok(rc == LAM_EINVAL && strstr(err.msg, want) && !why, "10 of 100 x 100: '%s'", err.msg);
    ok(strstr(err.msg, "not placed: #5 and 5 more") != NULL, "... naming the first left out");
}

static void test_errors(void)
{
    lam_error err;
    lam_plate sq = { .width = 250, .depth = 250, .margin = 5 };
    lam_arrange_item it[3], keep[3];
    box_item(&it[0], 0, 0, 245, 10, "long");
    memcpy(keep, it, sizeof it);
    int rc = lam_arrange(&sq, 5, it, 1, "mm", &err);
    ok(rc == LAM_EINVAL && strstr(err.msg, "part long (245 x 10 mm) is larger than the plate (250 x 250 mm, margin 5)"),
       "oversize: '%s'", err.msg);
    ok(!memcmp(it, keep, sizeof it[0]), "... the item untouched");
    box_item(&it[0], 0, 0, 240, 240, "exact");
    ok(lam_arrange(&sq, 5, it, 1, "mm", &err) == LAM_OK && it[0].shift[0] == 5 && it[0].shift[1] == 5,
       "a part as large as the room fits, at the margin");
    lam_plate disc = { .round = 1, .diameter = 100, .margin = 0 };
    box_item(&it[0], 0, 0, 80, 61, "wide"); /* half-diagonal 50.3 > 50 */
    ok(lam_arrange(&disc, 0, it, 1, NULL, &err) == LAM_EINVAL && strstr(err.msg, "part wide (80 x 61) is larger"),
       "round: a box whose corners cannot all be inside: '%s'", err.msg);
    box_item(&it[0], 0, 0, 80, 59, "fits");
    ok(lam_arrange(&disc, 0, it, 1, NULL, &err) == LAM_OK, "... one whose corners can be");
    /* fixed parts */
    box_item(&it[0], 0, 0, 20, 20, "A<1>");
    box_item(&it[1], 100, 100, 20, 20, "B");
    box_item(&it[2], 0, 0, 20, 20, "free");
    it[0].fixed = it[1].fixed = 1;
    it[0].at[0] = 50, it[0].at[1] = 50, it[1].at[0] = 60, it[1].at[1] = 55;
    memcpy(keep, it, sizeof it);
    rc = lam_arrange(&sq, 5, it, 3, "mm", &err);
    ok(rc == LAM_EINVAL && strstr(err.msg, "fixed parts A<1> and B overlap"), "overlapping fixed parts: '%s'", err.msg);
    ok(!memcmp(it, keep, sizeof it), "... nothing changed");
    it[1].at[0] = 50 + 20 + 4; /* 4 apart in x, overlapping in y */
    rc = lam_arrange(&sq, 5, it, 3, "mm", &err);
    ok(rc == LAM_EINVAL && strstr(err.msg, "fixed parts A<1> and B are closer than the spacing (5 mm)"),
       "fixed parts 4 apart, spacing 5: '%s'", err.msg);
    it[1].at[0] = 50 + 20 + 5;
    rc = lam_arrange(&sq, 5, it, 3, "mm", &err);
    ok(rc == LAM_OK, "... 5 apart: fine");
    it[1].at[0] = 250 - 5 - 10 + 0.5;
    rc = lam_arrange(&sq, 5, it, 3, "mm", &err);
    ok(rc == LAM_EINVAL && strstr(err.msg, "fixed part B at (235.5, 55) is off the plate (250 x 250 mm, margin 5)"),
       "a fixed part past the margin: '%s'", err.msg);
    /* round: a fixed part's corners within the radius less the margin */
    lam_plate disc2 = { .round = 1, .diameter = 110, .margin = 5 };
    box_item(&it[0], 0, 0, 20, 20, "corner");
    it[0].fixed = 1;
    it[0].at[0] = 0, it[0].at[1] = 39; /* corner (10, 49): 50.01 from the centre */
    ok(lam_arrange(&disc2, 5, it, 1, "mm", &err) == LAM_EINVAL &&
           strstr(err.msg, "fixed part corner at (0, 39) is off the plate (diameter 110 mm, margin 5)"),
       "round: a fixed part with a corner past the margin: '%s'", err.msg);
    it[0].at[1] = 38; /* corner (10, 48): 49.03 */
    ok(lam_arrange(&disc2, 5, it, 1, "mm", &err) == LAM_OK && it[0].shift[0] == -10 && it[0].shift[1] == 28,
       "... its corners inside: placed where asked");
    box_item(&it[1], 100, 100, 20, 20, "B");
    box_item(&it[2], 0, 0, 20, 20, "free");
    ok(lam_arrange(&sq, -1, it, 3, "mm", &err) == LAM_EINVAL && strstr(err.msg, "spacing"), "negative spacing");
    lam_plate none = { .width = 10, .depth = 10, .margin = 5 };
    ok(lam_arrange(&none, 0, it, 3, "mm", &err) == LAM_EINVAL && strstr(err.msg, "no room"), "a margin leaving no room");
    ok(lam_arrange(&sq, 5, NULL, 0, "mm", &err) == LAM_OK, "no parts: nothing to do");
}

/* A fixed part in the middle: the others go around it. */
static void test_fixed_middle(void)
{
    lam_error err;
    char buf[256];
    lam_plate sq = { .width = 250, .depth = 250, .margin = 5 };
    lam_arrange_item in[21], out[21];
    box_item(&in[0], -30, -30, 60, 60, "middle");
    in[0].fixed = 1;
    in[0].at[0] = in[0].at[1] = 125;
    for (size_t i = 1; i < 21; i++) box_item(&in[i], 0, 0, 40, 40, NULL);
    memcpy(out, in, sizeof in);
    int rc = lam_arrange(&sq, 5, out, 21, "mm", &err);
    const char *why = rc ? err.msg : violation(&sq, 5, in, out, 21, buf, sizeof buf);
    ok(!rc && !why, "20 boxes around a fixed 60 x 60 in the middle%s%s", why ? ": " : "", why ? why : "");
    is_num(out[0].shift[0], 125, 0, "the fixed part's shift: at - box centre (x)");
    is_num(out[0].shift[1], 125, 0, "... (y)");
    is_num(out[1].at[0], 25, 1e-12, "the first free box at the front-left corner (x)");
    is_num(out[1].at[1], 25, 1e-12, "... (y)");
    /* the same job gives the same placement */
    lam_arrange_item again[21];
    memcpy(again, in, sizeof in);
    lam_arrange(&sq, 5, again, 21, "mm", &err);
    ok(!memcmp(again, out, sizeof out), "deterministic");
}

/* Deepest first, ties by index: a shallow box given first comes after. */
static void test_order(void)
{
    lam_error err;
    lam_plate sq = { .width = 250, .depth = 250, .margin = 5 };
    lam_arrange_item it[3];
    box_item(&it[0], 0, 0, 50, 10, "shallow");
    box_item(&it[1], 0, 0, 50, 80, "deep");
    box_item(&it[2], 0, 0, 50, 80, "deep2");
    ok(lam_arrange(&sq, 5, it, 3, NULL, &err) == LAM_OK, "three boxes");
    ok(it[1].at[0] == 30 && it[2].at[0] == 85 && it[0].at[0] == 140, "one row, deep ones first, by index (%g %g %g)",
       it[1].at[0], it[2].at[0], it[0].at[0]);
    ok(it[0].at[1] == 10 && it[1].at[1] == 45, "all at the row's front edge");
}

static uint64_t rng_state = 0x9e3779b97f4a7c15u;

static double rnd(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (double)(rng_state >> 11) / 9007199254740992.0;
}

static void random_plate(lam_plate *p)
{
    memset(p, 0, sizeof *p);
    p->round = rnd() < 0.3;
    p->width = 100 + 300 * rnd();
    p->depth = 100 + 300 * rnd();
    p->diameter = 100 + 300 * rnd();
    p->margin = rnd() < 0.2 ? 0 : 10 * rnd();
}

/* One random mix: sizes, some fixed parts; whatever the outcome, the
 * invariants hold, a failure changes nothing, and again gives the same. */
static int random_trial(int t, char *why, size_t size)
{
    static lam_arrange_item in[MAXN], out[MAXN], again[MAXN];
    lam_plate p;
    random_plate(&p);
    double s = rnd() < 0.2 ? 0 : 8 * rnd(), room = p.round ? p.diameter / 2 - p.margin : fmin(p.width, p.depth) / 2;
    size_t n = 1 + (size_t)(rnd() * (t % 10 == 0 ? 300 : 60));
    double big = 5 + rnd() * room;
    for (size_t i = 0; i < n; i++) {
        box_item(&in[i], 200 * rnd() - 100, 200 * rnd() - 100, 1 + rnd() * big, 1 + rnd() * big, NULL);
        if (rnd() < 0.08) {
            double w = in[i].box[2] - in[i].box[0], h = in[i].box[3] - in[i].box[1];
            in[i].fixed = 1;
            in[i].at[0] = p.round ? (rnd() - 0.5) * room : p.margin + w / 2 + rnd() * (p.width - 2 * p.margin - w);
            in[i].at[1] = p.round ? (rnd() - 0.5) * room : p.margin + h / 2 + rnd() * (p.depth - 2 * p.margin - h);
        }
    }
    lam_error err;
    memcpy(out, in, n * sizeof *in);
    memcpy(again, in, n * sizeof *in);
    int rc = lam_arrange(&p, s, out, n, "mm", &err), rc2 = lam_arrange(&p, s, again, n, "mm", NULL);
    if (rc != rc2 || memcmp(out, again, n * sizeof *in))
        return snprintf(why, size, "trial %d: not deterministic", t), 0;
    if (rc && (memcmp(in, out, n * sizeof *in) || !err.msg[0]))
        return snprintf(why, size, "trial %d: failed (%s) but changed the items", t, err.msg), 0;
    if (!rc) {
        const char *v = violation(&p, s, in, out, n, why, size);
        if (v) return 0;
    }
    size_t k, N;
    if (rc && sscanf(err.msg, "only %zu of %zu", &k, &N) == 2 && !(k < N && N == n))
        return snprintf(why, size, "trial %d: '%s' with %zu parts", t, err.msg, n), 0;
    return rc ? 1 : 2;
}

/* Copies of one random box: at least the grid's count fits. */
static int random_grid(int t, char *why, size_t size)
{
    lam_plate p;
    random_plate(&p);
    double s = rnd() < 0.2 ? 0 : 8 * rnd(), w = 3 + 60 * rnd(), h = 3 + 60 * rnd();
    size_t g = p.round ? round_grid(&p, s, w, h) : rect_grid(&p, s, w, h);
    if (g == 0 || g > MAXN) return 1;
    lam_error err;
    const char *v;
    int rc = arrange_copies(&p, s, w, h, g, &err, &v);
    if (rc) return snprintf(why, size, "trial %d: the grid's %zu do not fit: %s", t, g, err.msg), 0;
    if (v) return snprintf(why, size, "trial %d: %s", t, v), 0;
    return 1;
}

static void test_random(void)
{
    char why[1500] = "";
    int good = 1, okc = 0, failc = 0;
    for (int t = 0; t < 200 && good; t++) {
        int r = random_trial(t, why, sizeof why);
        good = r != 0;
        okc += r == 2;
        failc += r == 1;
    }
    ok(good, "200 random mixes keep the invariants%s%s", good ? "" : ": ", why);
    ok(okc > 20 && failc > 20, "... both outcomes are exercised (%d placed, %d refused)", okc, failc);
    good = 1;
    for (int t = 0; t < 200 && good; t++) good = random_grid(t, why, sizeof why);
    ok(good, "200 random boxes: at least the grid's count fits%s%s", good ? "" : ": ", why);
}

static void test_hull(void)
{
    /* a square, with a point inside, one on an edge, a repeated corner */
    double xyz[] = { 4, 4, 1, 2, 2, 0, 0, 0, 5, 2, 0, 0, 4, 0, 3, 0, 4, 0, 1, 3, 9, 4, 4, 2, -0, 0, 1 };
    size_t nv = sizeof xyz / sizeof *xyz / 3, nh;
    double *h;
    lam_error err;
    ok(lam_footprint_hull(xyz, nv, &h, &nh, &err) == LAM_OK, "hull of %zu points", nv);
    double want[] = { 0, 0, 4, 0, 4, 4, 0, 4 };
    ok(nh == 4 && !memcmp(h, want, sizeof want), "... the square's 4 corners, counter-clockwise from (0, 0)");
    free(h);
    double box[4];
    ok(lam_footprint_box(xyz, nv, box, &err) == LAM_OK && box[0] == 0 && box[1] == 0 && box[2] == 4 && box[3] == 4,
       "its box: 0 0 4 4");
    double tri[] = { 0, 0, 0, 10, 0, 0, 5, 5, 0, 5, -1, 0, 1, 0, 0 }; /* (1, 0) is inside */
    lam_footprint_hull(tri, 5, &h, &nh, &err);
    double wt[] = { 0, 0, 5, -1, 10, 0, 5, 5 };
    ok(nh == 4 && !memcmp(h, wt, sizeof wt), "a kite: 4 points, the inner ones dropped");
    free(h);
    double line[] = { 3, 3, 0, 1, 1, 0, 2, 2, 7, 1, 1, 0 };
    lam_footprint_hull(line, 4, &h, &nh, &err);
    double wl[] = { 1, 1, 3, 3 };
    ok(nh == 2 && !memcmp(h, wl, sizeof wl), "collinear points: the segment's two ends");
    free(h);
    double one[] = { 2, 3, 0, 2, 3, 1 };
    lam_footprint_hull(one, 2, &h, &nh, &err);
    ok(nh == 1 && h[0] == 2 && h[1] == 3, "one point twice: one point");
    free(h);
    ok(lam_footprint_hull(xyz, 0, &h, &nh, &err) == LAM_EINVAL && !h && nh == 0, "no vertices: LAM_EINVAL");
    double bad[] = { 0, 0, 0, NAN, 1, 0 };
    ok(lam_footprint_hull(bad, 2, &h, &nh, &err) == LAM_EINVAL && strstr(err.msg, "vertex 2"), "a NaN: '%s'",
       err.msg);
}

static size_t count(const char *s, const char *what)
{
    size_t c = 0;
    for (const char *p = s; (p = strstr(p, what)); p += strlen(what)) c++;
    return c;
}

/* The y of the text element after the n-th (0-based) occurrence of what. */
static double text_y(const char *s, const char *what, size_t n)
{
    const char *p = s;
    for (size_t k = 0; p && k <= n; k++) p = strstr(k ? p + 1 : p, what);
    const char *y = p ? strstr(p, " y=\"") : NULL;
    return y ? atof(y + 4) : NAN;
}

static void test_layout(void)
{
    lam_error err;
    lam_plate sq = { .width = 250, .depth = 200, .margin = 5 };
    lam_arrange_item it[3];
    box_item(&it[0], 0, 0, 40, 40, "a<&>b");
    box_item(&it[1], 0, 0, 40, 30, "front");
    box_item(&it[2], 0, 0, 30, 30, NULL);
    it[0].fixed = 1;
    it[0].at[0] = 125, it[0].at[1] = 150;
    ok(lam_arrange(&sq, 5, it, 3, "mm", &err) == LAM_OK, "three parts arranged");
    double tri[] = { 10, 10, 40, 10, 25, 35 };
    const double *outline[3] = { NULL, tri, NULL };
    size_t npts[3] = { 0, 3, 0 };
    double fields[2][4] = { { 0, 0, 150, 200 }, { 100, 0, 250, 200 } };
    lam_writer *w;
    char *svg = NULL;
    size_t len;
    if (lam_writer_memory(&w, &err)) abort();
    ok(lam_layout_svg(w, &sq, it, 3, outline, npts, (const double(*)[4])fields, 2, "mm") == LAM_OK, "layout");
    if (lam_writer_take(w, &svg, &len, &err)) abort();
    ok(strncmp(svg, "<?xml", 5) == 0 && strstr(svg, "</svg>\n"), "an SVG document");
    is_int(count(svg, "class=\"part\""), 3, "one outline per part");
    is_int(count(svg, "<polygon class=\"part\""), 1, "... the given outline as a polygon");
    is_int(count(svg, "class=\"name\""), 3, "one name per part");
    is_int(count(svg, "class=\"field\""), 2, "one rectangle per field");
    ok(strstr(svg, ">laser 1</text>") && strstr(svg, ">laser 2</text>"), "the fields labelled laser 1, laser 2");
    is_int(count(svg, "class=\"plate\""), 1, "the plate");
    is_int(count(svg, "class=\"margin\""), 1, "its margin");
    ok(strstr(svg, "stroke-dasharray") != NULL, "... dashed");
    ok(strstr(svg, ">a&lt;&amp;&gt;b</text>") && !strstr(svg, "a<&>b"), "the name escaped");
    ok(strstr(svg, ">#3</text>") != NULL, "an unnamed part by its number");
    ok(strstr(svg, " mm</text>") != NULL, "a scale bar in mm");
    /* y up: the part at the back (y 150) is drawn above the front one */
    double yback = text_y(svg, "class=\"name\"", 0), yfront = text_y(svg, "class=\"name\"", 1);
    ok(yback < yfront, "y up: the back part above the front one (%g < %g)", yback, yfront);
    free(svg);
    lam_plate disc = { .round = 1, .diameter = 300, .margin = 0 };
    if (lam_writer_memory(&w, &err)) abort();
    lam_layout_svg(w, &disc, it, 0, NULL, NULL, NULL, 0, NULL);
    if (lam_writer_take(w, &svg, &len, &err)) abort();
    ok(count(svg, "<circle class=\"plate\"") == 1 && !count(svg, "class=\"margin\"") && !count(svg, "class=\"part\""),
       "a round plate without margin or parts: its circle");
    free(svg);
}

int main(void)
{
    test_grids();
    test_errors();
    test_fixed_middle();
    test_order();
    test_random();
    test_hull();
    test_layout();
    return done_testing();
}
