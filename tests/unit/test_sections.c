/* Sections at degenerate planes (issue 10), as a property over many
 * generated meshes: solids of revolution (spheres, tori, a stepped tube)
 * cut at planes through their vertex rings and flat faces, about the z axis
 * and about an oblique one; the same meshes unwelded with every corner
 * jittered; a box with a doubled fin (spikes) and a zero-volume plate
 * (doubled outlines); boxes that touch along an edge or a face
 * (non-manifold unions); each with floor, middle and ceiling cuts.
 *
 * On every layer:
 *   - the net area (the signed areas of the written points, computed here)
 *     equals the exact section of the test's own triangles: each triangle
 *     crossing the plane gives a directed segment (material on its left)
 *     and Green's theorem sums them, with the vertices on the plane put on
 *     the side SPEC 3.2 says; within the area the printed precision (six
 *     decimals) can move: half a unit of the last digit along the perimeter;
 *   - every solid is counter-clockwise and every hole clockwise by that
 *     signed area;
 *   - no contour is its own ancestor (parents followed up end at a root).
 *
 * Then the pieces one at a time on hand-made loops (spikes, near-repeated
 * points, coincident loops, slivers), and the gap default: the same open
 * scan in metres and in millimetres gives the same sections. */
#include "contour.h"
#include "meshes.h"
#include "profile.h"
#include "slice.h"

#include <float.h>

/* ---- triangle soups (the test's own geometry) ------------------------------- */

typedef struct soup {
    double *t; /* 9 per triangle, wound outward */
    size_t n, cap;
} soup;

static void soup_add(soup *s, const double *a, const double *b, const double *c)
{
    if (s->n == s->cap) {
        s->cap = s->cap ? 2 * s->cap : 256;
        s->t = realloc(s->t, 9 * s->cap * sizeof *s->t);
        if (!s->t) abort();
    }
    memcpy(s->t + 9 * s->n, a, 3 * sizeof *a);
    memcpy(s->t + 9 * s->n + 3, b, 3 * sizeof *b);
    memcpy(s->t + 9 * s->n + 6, c, 3 * sizeof *c);
    s->n++;
}

static void soup_quad(soup *s, const double *a, const double *b, const double *c, const double *d)
{
    soup_add(s, a, b, c);
    soup_add(s, a, c, d);
}

/* Six times the signed volume. */
static double soup_volume6(const soup *s)
{
    double v = 0;
    for (size_t i = 0; i < s->n; i++) {
        const double *a = s->t + 9 * i, *b = a + 3, *c = a + 6;
        v += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
             a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    return v;
}

static void soup_flip(soup *s)
{
    for (size_t i = 0; i < s->n; i++) {
        double tmp[3];
        memcpy(tmp, s->t + 9 * i + 3, sizeof tmp);
        memcpy(s->t + 9 * i + 3, s->t + 9 * i + 6, sizeof tmp);
        memcpy(s->t + 9 * i + 6, tmp, sizeof tmp);
    }
}

/* x -> M x + d for every corner. */
static void soup_move(soup *s, const double M[9], const double d[3])
{
    for (size_t i = 0; i < 3 * s->n; i++) {
        double *p = s->t + 3 * i, q[3];
        for (int k = 0; k < 3; k++) q[k] = M[3 * k] * p[0] + M[3 * k + 1] * p[1] + M[3 * k + 2] * p[2] + d[k];
        memcpy(p, q, sizeof q);
    }
}

/* Every corner moved by up to amp in each coordinate, independently, so no
 * two triangles share a vertex any more. */
static void soup_jitter(soup *s, double amp, uint32_t seed)
{
    for (size_t i = 0; i < 9 * s->n; i++) s->t[i] += amp * ((double)lcg(&seed) / 32768.0 - 1);
}

/* The model lamina builds from the soup (it welds equal corners itself). */
static lam_model *soup_model(const soup *s, const char *name)
{
    lam_mesh m;
    lam_mesh_init(&m);
    for (size_t i = 0; i < s->n; i++) {
        const double *p = s->t + 9 * i;
        uint32_t a = vtx(&m, p[0], p[1], p[2]), b = vtx(&m, p[3], p[4], p[5]), c = vtx(&m, p[6], p[7], p[8]);
        tri(&m, a, b, c);
    }
    return build_model_quiet(&m, name);
}

/* A closed profile of k points (r, z), r >= 0, turned about the z axis in
 * nseg steps; points on the axis become one vertex. Wound outward. */
static void revolve(soup *s, const double *prof, size_t k, int nseg)
{
    const double pi = acos(-1.0);
    for (size_t i = 0; i < k; i++) {
        const double *p = prof + 2 * i, *q = prof + 2 * ((i + 1) % k);
        if (p[0] == 0 && q[0] == 0) continue; /* along the axis: no surface */
        for (int j = 0; j < nseg; j++) {
            double c0 = cos(2 * pi * j / nseg), s0 = sin(2 * pi * j / nseg);
            int j1 = (j + 1) % nseg; /* the seam closes on the same points */
            double c1 = cos(2 * pi * j1 / nseg), s1 = sin(2 * pi * j1 / nseg);
            double a[3] = { p[0] * c0, p[0] * s0, p[1] }, b[3] = { p[0] * c1, p[0] * s1, p[1] };
            double c[3] = { q[0] * c1, q[0] * s1, q[1] }, d[3] = { q[0] * c0, q[0] * s0, q[1] };
            if (p[0] != 0) soup_add(s, a, b, c);
            if (q[0] != 0) soup_add(s, a, c, d);
        }
    }
    if (soup_volume6(s) < 0) soup_flip(s);
}

/* Profiles with their rings at whole heights (h = 1): a sphere of radius
 * r (poles on the axis), a torus of tube radius r around radius R (its
 * bottom and top single points are rings of vertices at its extremes). */
static size_t sphere_profile(double r, double *prof)
{
    size_t k = 0;
    for (int i = 0; i <= (int)(2 * r); i++) {
        double z = -r + i;
        prof[2 * k] = sqrt(r * r - z * z);
        prof[2 * k + 1] = z;
        k++;
    }
    return k;
}

static size_t torus_profile(double R, double r, double *prof)
{
    size_t k = 0;
    for (int i = 0; i <= (int)(2 * r); i++) { /* outer side, bottom to top */
        double z = -r + i;
        prof[2 * k] = R + sqrt(r * r - z * z);
        prof[2 * k + 1] = z;
        k++;
    }
    for (int i = (int)(2 * r) - 1; i >= 1; i--) { /* inner side, top to bottom */
        double z = -r + i;
        prof[2 * k] = R - sqrt(r * r - z * z);
        prof[2 * k + 1] = z;
        k++;
    }
    return k;
}

/* ---- the reference section ---------------------------------------------------- */

/* Height along w as the slicer computes it (zero terms skipped), so that
 * both agree which side of a plane a vertex is on. */
static double along(const double *p, const double *w)
{
    double s = 0;
    for (int k = 0; k < 3; k++)
        if (w[k] != 0) s += p[k] * w[k];
    return s;
}

/* The exact area of the section of soup s at height c along frame f, with
 * vertices at c counted below (floor and middle cuts) or above (ceiling),
 * its perimeter and its diameter (of its box). Each crossing triangle gives
 * a segment from its edge leaving the lone vertex forward to its edge
 * entering it (lone vertex above; reversed when it is below), material on
 * the left for outward winding; Green's theorem sums u dv - v du over them,
 * measured from the first point met (an unwelded soup's outlines do not
 * quite close: measured from nearby, that costs no more than its gaps). */
static double section_area(const soup *s, const lam_frame *f, double c, int ceiling, double *perimeter,
                           double *diameter)
{
    long double a2 = 0;
    double per = 0, o[2] = { 0, 0 }, box[4] = { INFINITY, INFINITY, -INFINITY, -INFINITY };
    int first = 1;
    for (size_t i = 0; i < s->n; i++) {
        const double *p[3] = { s->t + 9 * i, s->t + 9 * i + 3, s->t + 9 * i + 6 };
        double h[3];
        int up[3];
        for (int k = 0; k < 3; k++) {
            h[k] = along(p[k], f->w);
            up[k] = ceiling ? h[k] >= c : h[k] > c;
        }
        if (up[0] == up[1] && up[1] == up[2]) continue;
        int lone = up[0] == up[1] ? 2 : up[0] == up[2] ? 1 : 0;
        int nx = (lone + 1) % 3, pv = (lone + 2) % 3;
        double P[2][2];
        int ends[2][2] = { { lone, nx }, { pv, lone } };
        for (int e = 0; e < 2; e++) {
            int x = ends[e][0], y = ends[e][1];
            double t = (c - h[x]) / (h[y] - h[x]);
            double ux = along(p[x], f->u), vx = along(p[x], f->v), uy = along(p[y], f->u), vy = along(p[y], f->v);
            P[e][0] = ux + t * (uy - ux);
            P[e][1] = vx + t * (vy - vx);
            if (first) {
                o[0] = P[e][0];
                o[1] = P[e][1];
                first = 0;
            }
            if (P[e][0] < box[0]) box[0] = P[e][0];
            if (P[e][1] < box[1]) box[1] = P[e][1];
            if (P[e][0] > box[2]) box[2] = P[e][0];
            if (P[e][1] > box[3]) box[3] = P[e][1];
            P[e][0] -= o[0];
            P[e][1] -= o[1];
        }
        if (!up[lone]) { /* lone vertex below: the other way round */
            double tmp[2] = { P[0][0], P[0][1] };
            P[0][0] = P[1][0];
            P[0][1] = P[1][1];
            P[1][0] = tmp[0];
            P[1][1] = tmp[1];
        }
        a2 += (long double)P[0][0] * P[1][1] - (long double)P[1][0] * P[0][1];
        per += hypot(P[1][0] - P[0][0], P[1][1] - P[0][1]);
    }
    *perimeter = per;
    *diameter = first ? 0 : hypot(box[2] - box[0], box[3] - box[1]);
    return (double)(a2 / 2);
}

/* Signed area of n points (> 0 counter-clockwise), in long double. */
static double shoelace(const double *uv, size_t n)
{
    long double a = 0;
    for (size_t i = 0; i < n; i++) {
        size_t j = (i + 1) % n;
        a += ((long double)uv[2 * i] - uv[0]) * ((long double)uv[2 * j + 1] - uv[1]) -
             ((long double)uv[2 * j] - uv[0]) * ((long double)uv[2 * i + 1] - uv[1]);
    }
    return (double)(a / 2);
}

/* ---- the property -------------------------------------------------------------- */

static const char *const cut_name[3] = { "floor", "middle", "ceiling" };

typedef struct tally {
    size_t runs, layers, contours, twins, slivers, open_layers;
    int unwelded; /* the model at hand is a jittered soup */
    int bad;
} tally;

#define BAD(...) do { if (t->bad++ < 8) diag(__VA_ARGS__); } while (0)

/* Slice m with o and hold every layer against the soup's exact section. */
static void check_run(const lam_model *m, const soup *s, const lam_slice_opts *o, const char *what, tally *t)
{
    lam_error err;
    lam_error_clear(&err);
    lam_slicer *sl = NULL;
    if (lam_slicer_new(m, o, &sl, &err)) {
        BAD("%s: %s", what, err.msg);
        return;
    }
    t->runs++;
    const lam_frame *f = lam_slicer_frame(sl);
    for (;;) {
        lam_layer *L = NULL;
        if (lam_slicer_next(sl, &L, &err)) {
            BAD("%s: %s", what, err.msg);
            break;
        }
        if (!L) break;
        t->layers++;
        t->twins += L->twins;
        t->slivers += L->slivers;
        t->contours += L->ncontours;
        double per, diam, want = section_area(s, f, L->cut, o->cut == LAM_CUT_CEILING, &per, &diam);
        double net = 0;
        for (size_t k = 0; k < L->ncontours; k++) {
            const lam_contour *c = &L->contours[k];
            double a = shoelace(L->uv + 2 * c->first, c->n);
            net += a;
            if (!((c->kind == LAM_SOLID && a > 0) || (c->kind == LAM_HOLE && a < 0)))
                BAD("%s layer %zu (%s cut at %.17g): contour %zu is a %s with signed area %.17g", what, L->index,
                    cut_name[o->cut], L->cut, k, c->kind == LAM_SOLID ? "solid" : "hole", a);
            /* follow the parents: at most ncontours steps to a root */
            long at = c->parent;
            size_t steps = 0;
            while (at >= 0 && at != (long)k && (size_t)at < L->ncontours && steps++ < L->ncontours)
                at = L->contours[at].parent;
            if (at != -1)
                BAD("%s layer %zu: contour %zu is its own ancestor or has a parent out of range (%ld)", what,
                    L->index, k, at);
        }
        /* A jittered soup cut exactly at one of its vertices' heights can
         * be open for real: the two copies of a nearly level edge are cut
         * far apart. Such outlines are reported (a run fails without
         * --allow-open), never dropped silently; a welded mesh has none. */
        if (L->nopen) {
            if (!t->unwelded) BAD("%s layer %zu: %zu outlines left open", what, L->index, L->nopen);
            t->open_layers++;
            lam_layer_free(L);
            continue;
        }
        /* Six printed decimals move each point by up to 5e-7 in u and v.
         * Where gaps were bridged (unwelded soups), each bridge may add or
         * take up to its length times the section's diameter, and the
         * exact section of outlines that do not close is uncertain by as
         * much. */
        double tol = 0.5e-6 * sqrt(2.0) * per + 1.5 * (double)L->gaps_closed * L->max_gap * diam + 1e-12;
        /* and each sliver dropped had at most the sliver area (slice.h) */
        const double *bb = m->stats.bbox;
        double size = LAM_SLIVER_REL * sqrt((bb[3] - bb[0]) * (bb[3] - bb[0]) + (bb[4] - bb[1]) * (bb[4] - bb[1]) +
                                            (bb[5] - bb[2]) * (bb[5] - bb[2]));
        tol += (double)L->slivers * size * size;
        if (!(fabs(net - want) <= tol))
            BAD("%s layer %zu (%s cut at %.17g): net area %.17g, exact section %.17g (tolerance %.3g; %zu "
                "contours, %zu twins, %zu slivers, %zu open)",
                what, L->index, cut_name[o->cut], L->cut, net, want, tol, L->ncontours, L->twins, L->slivers,
                L->nopen);
        lam_layer_free(L);
    }
    lam_slicer_free(sl);
}

/* The run for each cut: planes through heights[0 .. n) (floor and ceiling
 * cuts on them; middle cuts on them too, from planes half way between) and
 * a plain uniform width that meets none of them. */
static void check_cuts(const lam_model *m, const soup *s, const lam_frame *f, const double *heights, size_t n,
                       const char *what, tally *t)
{
    double *mid = malloc((n + 1) * sizeof *mid);
    mid[0] = heights[0] - (heights[1] - heights[0]) / 2;
    for (size_t i = 0; i + 1 < n; i++) mid[i + 1] = heights[i] + (heights[i + 1] - heights[i]) / 2;
    mid[n] = heights[n - 1] + (heights[n - 1] - heights[n - 2]) / 2;
    for (int cut = 0; cut < 3; cut++) {
        lam_slice_opts o;
        lam_slice_opts_init(&o);
        o.frame = *f;
        o.cut = (lam_cut)cut;
        if (cut == LAM_CUT_MIDDLE) {
            o.planes = mid;
            o.nplanes = n + 1;
        } else {
            o.planes = heights;
            o.nplanes = n;
        }
        char w[160];
        snprintf(w, sizeof w, "%s, planes on the rings", what);
        check_run(m, s, &o, w, t);
        o.planes = NULL;
        o.nplanes = 0;
        o.width = 0.37;
        snprintf(w, sizeof w, "%s, width 0.37", what);
        check_run(m, s, &o, w, t);
    }
    free(mid);
}

/* Distinct heights of the soup's corners along f (to within 1e-6: a ring
 * turned about an oblique axis is level only up to rounding; the first
 * corner met stands for it), at most max. */
static size_t ring_heights(const soup *s, const lam_frame *f, double *out, size_t max)
{
    size_t n = 0;
    for (size_t i = 0; i < 3 * s->n; i++) {
        double h = along(s->t + 3 * i, f->w);
        size_t j = 0;
        while (j < n && fabs(out[j] - h) > 1e-6) j++;
        if (j == n && n < max) out[n++] = h;
    }
    for (size_t i = 1; i < n; i++) /* insertion sort: a few dozen heights */
        for (size_t j = i; j > 0 && out[j - 1] > out[j]; j--) {
            double x = out[j];
            out[j] = out[j - 1];
            out[j - 1] = x;
        }
    return n;
}

/* One generated model: as built, and (jitter > 0) unwelded with its
 * corners jittered; sliced along z and along `axis` (the model turned so
 * that its own z axis lies along it). */
static void check_model(soup *s, const char *name, double jitter, tally *t)
{
    static const double axis[3] = { 1, 2, 2 }; /* unit after /3 */
    /* a rotation taking z to axis/3: columns u, v, w */
    static const double M[9] = { 2.0 / 3, -1.0 / 3, 1.0 / 3, -1.0 / 3, 2.0 / 3, 2.0 / 3, -2.0 / 3, -2.0 / 3, 2.0 / 3 };
    static const double shift[3] = { 3.25, -1.5, 0.75 };
    for (int turned = 0; turned < 2; turned++) {
        for (int jit = 0; jit < (jitter > 0 ? 2 : 1); jit++) {
            soup c = { 0 };
            c.t = malloc(9 * s->n * sizeof *c.t);
            memcpy(c.t, s->t, 9 * s->n * sizeof *c.t);
            c.n = c.cap = s->n;
            lam_frame f;
            lam_frame_axis('z', &f, NULL);
            if (turned) {
                soup_move(&c, M, shift);
                lam_frame_direction(axis, &f, NULL);
            }
            if (jit) soup_jitter(&c, jitter, 12345);
            char what[128];
            snprintf(what, sizeof what, "%s%s%s", name, turned ? " about (1,2,2)" : "", jit ? " jittered" : "");
            lam_model *m = soup_model(&c, what);
            t->unwelded = jit;
            if (!m) {
                BAD("%s: could not build", what);
            } else {
                double h[64];
                size_t n = ring_heights(&c, &f, h, 64);
                if (n >= 2) check_cuts(m, &c, &f, h, n, what, t);
                lam_model_free(m);
            }
            free(c.t);
        }
    }
}

static void box_soup(soup *s, double x0, double y0, double z0, double x1, double y1, double z1)
{
    double p[8][3];
    for (int i = 0; i < 8; i++) {
        p[i][0] = i & 1 ? x1 : x0;
        p[i][1] = i & 2 ? y1 : y0;
        p[i][2] = i & 4 ? z1 : z0;
    }
    for (int f = 0; f < 6; f++)
        soup_quad(s, p[BOX_QUADS[f][0]], p[BOX_QUADS[f][1]], p[BOX_QUADS[f][2]], p[BOX_QUADS[f][3]]);
}

static void test_property(void)
{
    tally t = { 0 };
    double prof[128];
    soup s = { 0 };

    revolve(&s, prof, sphere_profile(6, prof), 24);
    check_model(&s, "sphere r=6", 1e-9, &t);
    s.n = 0;
    revolve(&s, prof, torus_profile(12, 4, prof), 32);
    check_model(&s, "torus 12/4", 1e-9, &t);
    s.n = 0;
    /* a tube with steps: flat rings (faces) at whole heights */
    static const double tube[] = { 2, 0, 6, 0, 6, 2, 4, 2, 4, 5, 7, 5, 7, 6, 2, 6 };
    revolve(&s, tube, 8, 20);
    check_model(&s, "stepped tube", 1e-9, &t);
    s.n = 0;

    /* a box with a fin: a doubled quad on the split side x = 2, sharing its
     * edge (2,1,z) with the box (non-manifold), so sections go out along
     * the fin and back (a spike) */
    {
        double a[3] = { 2, 0, 0 }, b[3] = { 2, 1, 0 }, c[3] = { 2, 2, 0 };
        double A[3] = { 2, 0, 2 }, B[3] = { 2, 1, 2 }, C[3] = { 2, 2, 2 };
        double F0[3] = { 4, 1, 0 }, F1[3] = { 4, 1, 2 };
        double p[8][3];
        for (int i = 0; i < 8; i++) {
            p[i][0] = i & 1 ? 2 : 0;
            p[i][1] = i & 2 ? 2 : 0;
            p[i][2] = i & 4 ? 2 : 0;
        }
        for (int f = 0; f < 5; f++) /* all but +x */
            soup_quad(&s, p[BOX_QUADS[f][0]], p[BOX_QUADS[f][1]], p[BOX_QUADS[f][2]], p[BOX_QUADS[f][3]]);
        soup_quad(&s, a, b, B, A); /* +x, in two halves */
        soup_quad(&s, b, c, C, B);
        soup_quad(&s, b, F0, F1, B); /* the fin, both sides */
        soup_quad(&s, b, B, F1, F0);
        check_model(&s, "box with a fin", 0, &t);
        s.n = 0;
    }
    /* a plate of no thickness: its two sides through the same points */
    {
        double a[3] = { 0, 0, 0 }, b[3] = { 3, 0, 1 }, c[3] = { 3, 2, 3 }, d[3] = { 0, 2, 2 };
        soup_quad(&s, a, b, c, d);
        soup_quad(&s, a, d, c, b);
        /* and a cube beside it, so the model has a size and a section */
        box_soup(&s, 4, 0, 0, 6, 2, 3);
        check_model(&s, "doubled plate and a box", 0, &t);
        s.n = 0;
    }
    /* two boxes touching along an edge, two stacked touching on a face */
    box_soup(&s, 0, 0, 0, 2, 2, 2);
    box_soup(&s, 2, 2, 0, 4, 4, 2);
    check_model(&s, "boxes sharing an edge", 1e-9, &t);
    s.n = 0;
    box_soup(&s, 0, 0, 0, 4, 4, 2);
    box_soup(&s, 1, 1, 2, 3, 3, 4);
    box_soup(&s, 0, 0, 4, 4, 4, 5);
    check_model(&s, "stacked boxes", 1e-9, &t);
    s.n = 0;
    free(s.t);

    diag("%zu runs, %zu layers, %zu contours, %zu loops cancelled as coincident, %zu slivers dropped, %zu "
         "layers of jittered soups reported open",
         t.runs, t.layers, t.contours, t.twins, t.slivers, t.open_layers);
    ok(t.runs >= 100 && t.layers >= 2000, "many runs and layers were checked (%zu, %zu)", t.runs, t.layers);
    ok(t.twins > 0 && t.slivers > 0, "coincident loops and slivers did occur");
    ok(t.bad == 0, "every layer: net area = exact section, solids CCW, holes CW, no contour its own ancestor");
}

/* ---- the pieces on hand-made loops -------------------------------------------- */

/* lam_loop_simplify + lam_loops_tidy + lam_contours_assign on loops given as
 * (count, points...) runs. */
static int assign(lam_layer *L, const double *pts, const size_t *len, size_t nl, size_t *slivers, size_t *twins)
{
    size_t np = 0;
    for (size_t l = 0; l < nl; l++) np += len[l];
    lam_loops loops = { malloc(2 * np * sizeof(double) + 1), malloc(nl * sizeof(size_t) + 1), 0, 0 };
    for (size_t l = 0, off = 0; l < nl; off += len[l], l++) {
        memcpy(loops.uv + 2 * loops.npoints, pts + 2 * off, 2 * len[l] * sizeof(double));
        size_t n = lam_loop_simplify(loops.uv + 2 * loops.npoints, len[l]);
        loops.len[loops.nloops++] = n;
        loops.npoints += n;
    }
    lam_error err;
    lam_error_clear(&err);
    *slivers = *twins = 0;
    int rc = lam_loops_tidy(&loops, 1e-12, 1, slivers, twins, &err);
    if (!rc) rc = lam_contours_assign(L, &loops, &err);
    if (rc) diag("%s", err.msg);
    free(loops.uv);
    free(loops.len);
    return rc;
}

static void test_loops(void)
{
    lam_layer L;
    memset(&L, 0, sizeof L);
    size_t sl, tw;

    /* the loop: out to (20,10) and back (a spike), then a triangle
     * of area -50; the turn at (10,10) between (20,20) and (20,10) says
     * counter-clockwise, the area says clockwise */
    static const double spike[] = { 10, 10, 20, 10, 10, 10, 10, 20, 20, 20 };
    size_t n5 = 5;
    ok(assign(&L, spike, &n5, 1, &sl, &tw) == 0 && L.ncontours == 1, "spike loop: one contour");
    if (L.ncontours == 1) {
        static const double want[] = { 10, 10, 20, 20, 10, 20 };
        ok(L.contours[0].n == 3 && !memcmp(L.uv, want, sizeof want),
           "spike loop: the spike is gone; the solid runs (10,10) (20,20) (10,20), counter-clockwise");
        is_num(shoelace(L.uv, L.contours[0].n), 50, 0, "spike loop: written area +50");
    }
    /* a near-repeated point beside the lowest vertex: the loop crosses
     * itself by 1e-9 there, and the turn at (10,10) is counter-clockwise
     * while the loop is clockwise */
    static const double near[] = { 10, 10, 20, 10, 10 + 1e-9, 10, 10, 20, 20, 20 };
    ok(assign(&L, near, &n5, 1, &sl, &tw) == 0 && L.ncontours == 1, "near-repeated point: one contour");
    if (L.ncontours == 1) {
        ok(L.contours[0].kind == LAM_SOLID && shoelace(L.uv + 2 * L.contours[0].first, L.contours[0].n) > 0,
           "near-repeated point: the solid is counter-clockwise by its area");
        is_num(L.contours[0].area, 50, 1e-6, "near-repeated point: area 50");
    }
    /* collinear points on straight runs and a zero-length edge */
    static const double runs[] = { 0, 0, 1, 0, 2, 0, 2, 0, 2, 1, 2, 2, 1, 2, 0, 2, 0, 1 };
    size_t n9 = 9;
    ok(assign(&L, runs, &n9, 1, &sl, &tw) == 0 && L.ncontours == 1 && L.contours[0].n == 4,
       "straight runs and a repeated point: a square of 4 points");

    /* coincident loops: a square and the same points backwards from
     * another start cancel; a third copy stays; inside an outer square */
    static const double twin[] = { 0, 0, 4, 0, 4, 4, 0, 4,   /* outer */
                                   1, 1, 2, 1, 2, 2, 1, 2,   /* a */
                                   2, 2, 2, 1, 1, 1, 1, 2 }; /* a backwards */
    size_t len3[3] = { 4, 4, 4 };
    int rc = assign(&L, twin, len3, 3, &sl, &tw);
    ok(rc == 0 && L.ncontours == 1 && tw == 2 && L.contours[0].area == 16,
       "a loop and its reverse cancel; the outer square stays (twins %zu)", tw);
    static const double three[] = { 1, 1, 2, 1, 2, 2, 1, 2, 2, 1, 2, 2, 1, 2, 1, 1, 1, 1, 2, 1, 2, 2, 1, 2 };
    ok(assign(&L, three, len3, 3, &sl, &tw) == 0 && L.ncontours == 1 && tw == 2 && L.contours[0].kind == LAM_SOLID &&
           L.contours[0].area == 1,
       "three coincident loops: a pair cancels, one solid stays");
    /* the same points in another order are not coincident: a bow tie of the
     * square's corners stays */
    static const double bow[] = { 1, 1, 2, 1, 2, 2, 1, 2, 1, 1, 2, 2, 2, 1, 1, 2 };
    size_t len2[2] = { 4, 4 };
    ok(assign(&L, bow, len2, 2, &sl, &tw) == 0 && tw == 0, "same points in another order: not coincident");

    /* a sliver of area 1e-15 is dropped and counted; a loop of 1e-9 stays */
    static const double thin[] = { 0, 0, 1, 0, 1, 2e-15, 5, 5, 5 + 1e-4, 5, 5 + 1e-4, 5 + 2e-5 };
    size_t l33[2] = { 3, 3 };
    ok(assign(&L, thin, l33, 2, &sl, &tw) == 0 && L.ncontours == 1 && sl == 1 && L.contours[0].area > 0,
       "a sliver of 1e-15 is dropped and counted, a triangle of 1e-9 stays");
    free(L.uv);
    free(L.contours);
}

/* ---- nesting never loops -------------------------------------------------------- */

static void test_equal_areas(void)
{
    /* two squares of the same area that overlap: each holds the other's
     * inner point; they must nest one way only */
    lam_layer L;
    memset(&L, 0, sizeof L);
    static const double two[] = { 0, 0, 2, 0, 2, 2, 0, 2, 0.5, 0.5, 2.5, 0.5, 2.5, 2.5, 0.5, 2.5 };
    size_t len2[2] = { 4, 4 }, sl, tw;
    int rc = assign(&L, two, len2, 2, &sl, &tw);
    ok(rc == 0 && L.ncontours == 2 && ((L.contours[0].parent == -1) != (L.contours[1].parent == -1)),
       "overlapping squares of equal area: one is the root, the other inside it, not each inside the other");
    free(L.uv);
    free(L.contours);
}

/* ---- gap closing scales with the model ------------------------------------------ */

/* A sphere of radius r cut open along the meridian y = 0 by a crack of
 * r / 1000 (the half y > 0 moved by it) and with a hole of about r / 2
 * across (the triangles near +x at the equator removed). */
static lam_model *open_scan(double r, const char *name)
{
    soup s = { 0 }, c = { 0 };
    double prof[64];
    revolve(&s, prof, sphere_profile(6, prof), 24);
    for (size_t i = 0; i < s.n; i++) {
        const double *p = s.t + 9 * i;
        double cx = (p[0] + p[3] + p[6]) / 3, cy = (p[1] + p[4] + p[7]) / 3, cz = (p[2] + p[5] + p[8]) / 3;
        if (cx > 5 && fabs(cy) < 1.5 && fabs(cz) < 2.5) continue; /* the hole */
        double q[9];
        for (int k = 0; k < 9; k++) q[k] = p[k] * (r / 6);
        if (cy > 0)
            for (int k = 1; k < 9; k += 3) q[k] += r / 1000;
        soup_add(&c, q, q + 3, q + 6);
    }
    lam_model *m = soup_model(&c, name);
    free(s.t);
    free(c.t);
    return m;
}

typedef struct sweep {
    size_t layers, contours, open, gaps;
    double area[64];
    double gap;
} sweep;

static sweep sweep_run(const lam_model *m, double gap)
{
    sweep w = { 0 };
    lam_slice_opts o;
    lam_slice_opts_init(&o);
    o.gap = gap;
    o.width = 0; /* the default: 1/100 of the extent, scales too */
    lam_error err;
    lam_slicer *s = NULL;
    if (!m || lam_slicer_new(m, &o, &s, &err)) return w;
    w.gap = lam_slicer_gap(s);
    for (lam_layer *L; !lam_slicer_next(s, &L, &err) && L; lam_layer_free(L)) {
        if (w.layers < 64) {
            double a = 0;
            for (size_t k = 0; k < L->ncontours; k++) a += L->contours[k].area;
            w.area[w.layers] = a;
        }
        w.layers++;
        w.contours += L->ncontours;
        w.open += L->nopen;
        w.gaps += L->gaps_closed;
    }
    lam_slicer_free(s);
    return w;
}

static void test_gap_scale(void)
{
    lam_model *mm = open_scan(60, "scan in mm"), *me = open_scan(0.06, "scan in m");
    sweep a = sweep_run(mm, LAM_GAP_AUTO), b = sweep_run(me, LAM_GAP_AUTO);
    const double *bb = mm->stats.bbox;
    double diag_mm = sqrt((bb[3] - bb[0]) * (bb[3] - bb[0]) + (bb[4] - bb[1]) * (bb[4] - bb[1]) +
                          (bb[5] - bb[2]) * (bb[5] - bb[2]));
    is_num(a.gap, 5e-4 * diag_mm, 1e-12, "mm: automatic gap 5e-4 of the diagonal (%g)", diag_mm);
    is_num(b.gap, a.gap / 1000, 1e-15, "m: the same gap, in metres");
    ok(a.layers > 50 && a.layers == b.layers, "as many layers each (%zu, %zu)", a.layers, b.layers);
    ok(a.gaps > 0 && a.gaps == b.gaps && a.open > 0 && a.open == b.open && a.contours == b.contours,
       "same sections: %zu/%zu gaps closed (the crack), %zu/%zu outlines open (the hole), %zu/%zu contours", a.gaps,
       b.gaps, a.open, b.open, a.contours, b.contours);
    int same = 1;
    for (size_t i = 0; i < 64 && i < a.layers; i++)
        if (fabs(a.area[i] - 1e6 * b.area[i]) > 1e-9 * (1 + fabs(a.area[i]))) same = 0;
    ok(same, "every layer's area in mm^2 is its area in m^2 times 10^6");
    /* the old absolute default (0.05 units) bridges the hole in metres only */
    sweep c = sweep_run(mm, 0.05), d = sweep_run(me, 0.05);
    ok(c.open > 0 && d.open == 0, "a fixed gap of 0.05 would close the hole in metres (%zu open) but not in mm (%zu)",
       d.open, c.open);
    lam_model_free(mm);
    lam_model_free(me);

    /* the limit a machine's units set */
    is_num(lam_default_gap(1000, 0), 0.5, 1e-15, "no limit: 5e-4 of the size");
    is_num(lam_default_gap(1000, 0.05), 0.05, 0, "limit 0.05 caps it");
    is_num(lam_default_gap(10, 0.05), 0.005, 1e-15, "below the limit: the relative gap");
    lam_profile p;
    memset(&p, 0, sizeof p);
    const char *units[] = { "mm", "cm", "m", "in", "furlong" };
    double want[] = { 0.05, 0.005, 5e-5, 0.05 / 25.4, 0 };
    for (int i = 0; i < 5; i++) {
        p.units = (char *)units[i];
        is_num(lam_profile_gap_limit(&p), want[i], 1e-18, "gap limit in %s", units[i]);
    }
}

int main(void)
{
    test_loops();
    test_equal_areas();
    test_gap_scale();
    test_property();
    return done_testing();
}
