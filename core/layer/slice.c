/* The plane sweep; see slice.h for the rules it keeps. */
#include "slice.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "contour.h"
#include "winding.h"
#include "fmt.h"
#include "grow.h"
#include "hugemem.h"
#include "prefetch.h"

#define NONE UINT32_MAX


static int nomem(lam_error *err) { return lam_error_nomem(err, "while slicing"); }

static double dot_exact(const double *p, const double *a)
{
    double s = 0;
    for (int k = 0; k < 3; k++)
        if (a[k] != 0) s += p[k] * a[k];
    return s;
}

void lam_slice_opts_init(lam_slice_opts *o)
{
    memset(o, 0, sizeof *o);
    lam_frame_axis('z', &o->frame, NULL);
    o->cut = LAM_CUT_MIDDLE;
    o->gap = LAM_GAP_AUTO;
}

double lam_default_gap(double size, double limit)
{
    if (!(size > 0) || !isfinite(size)) return 0;
    double g = LAM_GAP_REL * size;
    return limit > 0 && limit < g ? limit : g;
}

/* The diagonal of the model's bounding box (0 for an empty model). */
static double model_size(const lam_model *m)
{
    const double *b = m->stats.bbox;
    double dx = b[3] - b[0], dy = b[4] - b[1], dz = b[5] - b[2];
    double d = sqrt(dx * dx + dy * dy + dz * dz);
    return isfinite(d) ? d : 0;
}

double lam_default_width(double extent)
{
    if (!(extent > 0) || !isfinite(extent)) return 1;
    double target = extent / 100;
    double p = pow(10, floor(log10(target)));
    static const double steps[] = { 5, 2.5, 2, 1 };
    for (int i = 0; i < 4; i++)
        if (steps[i] * p <= target * (1 + 1e-12)) return steps[i] * p;
    return p;
}

/* ---- the slicer ------------------------------------------------------------- */

struct lam_slicer {
    const lam_model *m;
    lam_slice_opts o;
    double *planes;        /* S + 1 boundaries */
    size_t nlayers, next;
    /* per vertex v: height W(v) and layer-frame coordinates U(v), V(v), all
     * with stride 3. For the axis frames they point into the mesh's own
     * xyz (the exact same numbers, one cache line per vertex, no copy);
     * for any other direction into wuv, computed once. */
    const double *pw, *pu, *pv;
    double *wuv;
    double *cuts;          /* cut height of each layer, nondecreasing */
    double min_area;       /* loops of no more area are slivers */
    double crossings;      /* edge crossings over all cuts */
    int up;                /* vertices on a plane count as below it */
    uint32_t *order;       /* edges that cross some cut, by first layer crossed */
    size_t *layer_first;   /* order[layer_first[i] ..] enter at layer i */
    size_t norder, ins;
    uint32_t *active;
    size_t nactive;
    /* edge id -> slot in active, for this layer's edges only: a small
     * open-addressing table (2 to 4 cells per active edge) stays in cache,
     * where an array over all edges would be read and written at random */
    uint32_t *slot_edge, *slot_at;
    size_t slot_cap;
    /* per-layer scratch, grown as needed */
    double *pts;           /* point of each active edge */
    uint32_t *seg_in, *seg_out, *in_first, *in_seg, *indeg;
    unsigned char *used;
    size_t cap_active, cap_seg;
    int borrowed;          /* a fork: planes, wuv, cuts and the schedule are its parent's */
};

#define W(s, v) ((s)->pw[3 * (size_t)(v)])
#define U(s, v) ((s)->pu[3 * (size_t)(v)])
#define V(s, v) ((s)->pv[3 * (size_t)(v)])

/* k when a is exactly the unit vector along axis k, else -1. */
static int unit_axis(const double a[3])
{
    for (int k = 0; k < 3; k++)
        if (a[k] == 1 && a[(k + 1) % 3] == 0 && a[(k + 2) % 3] == 0) return k;
    return -1;
}

static int too_many(double layers, size_t max, const char *what, lam_error *err)
{
    return lam_error_set(err, LAM_ELIMIT, NULL, 0, 0, "%s makes %.0f layers, more than the limit of %zu", what, layers,
                         max);
}

static int make_planes(lam_slicer *s, double wmin, double wmax, lam_error *err)
{
    const lam_slice_opts *o = &s->o;
    size_t n, max = o->max_layers ? o->max_layers : LAM_DEFAULT_MAX_LAYERS;
    if (o->planes && o->nplanes > max + 1) return too_many((double)o->nplanes - 1, max, "the list of planes", err);
    if (!o->planes && o->widths && o->nwidths > max) return too_many((double)o->nwidths, max, "the list of widths", err);
    if (o->planes) {
        if (o->nplanes < 2)
            return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "at least two planes are needed (they bound the layers)");
        for (size_t i = 0; i < o->nplanes; i++) {
            if (!isfinite(o->planes[i]))
                return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "plane %zu is not a finite number", i + 1);
            if (i && !(o->planes[i] > o->planes[i - 1])) {
                char a[LAM_FMT_NUM], b[LAM_FMT_NUM];
                lam_fmt_pair(a, b, o->planes[i], o->planes[i - 1]);
                return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "planes must increase strictly (plane %zu is %s after %s)",
                                     i + 1, a, b);
            }
        }
        n = o->nplanes;
        s->planes = malloc(n * sizeof *s->planes);
        if (!s->planes) return nomem(err);
        memcpy(s->planes, o->planes, n * sizeof *s->planes);
    } else if (o->widths) {
        if (o->nwidths == 0) return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "empty list of widths");
        n = o->nwidths + 1;
        s->planes = malloc(n * sizeof *s->planes);
        if (!s->planes) return nomem(err);
        s->planes[0] = wmin;
        for (size_t i = 0; i < o->nwidths; i++) {
            if (!(o->widths[i] > 0) || !isfinite(o->widths[i]))
                return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "width %zu must be a positive number (got %s)",
                                     i + 1, LAM_NUM(o->widths[i]));
            s->planes[i + 1] = s->planes[i] + o->widths[i];
        }
        if (s->planes[n - 1] < wmax) {
            char a[LAM_FMT_NUM], b[LAM_FMT_NUM], c[LAM_FMT_NUM], d[LAM_FMT_NUM];
            lam_fmt_pair(a, b, s->planes[n - 1] - wmin, wmax - wmin);
            /* the sums may round to one number while the ends differ */
            lam_fmt_pair(c, d, s->planes[n - 1], wmax);
            int same = !strcmp(a, b);
            return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0,
                                 "the widths add up to %s but the model spans %s along the axis%s%s%s%s%s", a, b,
                                 same ? " (they end at " : "", same ? c : "", same ? ", the model at " : "",
                                 same ? d : "", same ? ")" : "");
        }
    } else {
        if (o->width < 0 || isnan(o->width) || isinf(o->width))
            return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "layer width must be a positive number (got %s)",
                                 LAM_NUM(o->width));
        double w = o->width > 0 ? o->width : lam_default_width(wmax - wmin);
        if (!(w > 0) || !isfinite(w))
            return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "layer width must be a positive number (got %s)",
                                 LAM_NUM(o->width));
        double q = (wmax - wmin) / w;
        if (q > (double)max) {
            char what[64];
            snprintf(what, sizeof what, "width %s", LAM_NUM(w));
            return too_many(ceil(q), max, what, err);
        }
        /* an extent that is a whole number of layers up to rounding gets
         * exactly that many, not one more nearly empty layer */
        double layers = floor(q);
        if (q - layers > 1e-9) layers += 1;
        if (layers < 1) layers = 1;
        n = (size_t)layers + 1;
        s->planes = malloc(n * sizeof *s->planes);
        if (!s->planes) return nomem(err);
        for (size_t i = 0; i < n; i++) s->planes[i] = wmin + (double)i * w; /* never accumulated */
    }
    s->nlayers = n - 1;
    return LAM_OK;
}

static double edge_lo(const lam_slicer *s, uint32_t e)
{
    const uint32_t *v = s->m->edges.v + 2 * (size_t)e;
    double a = W(s, v[0]), b = W(s, v[1]);
    return a < b ? a : b;
}

static double edge_hi(const lam_slicer *s, uint32_t e)
{
    const uint32_t *v = s->m->edges.v + 2 * (size_t)e;
    double a = W(s, v[0]), b = W(s, v[1]);
    return a < b ? b : a;
}

/* The first layer whose cut is at or above h (strictly above when
 * strict), S when none. Uniform layers (c0 the first cut, step the mean
 * spacing) let it be guessed from the height; the guess is checked against
 * the cuts themselves, and binary search takes over where it is off
 * (adaptive widths). */
static size_t first_cut(const lam_slicer *s, double c0, double step, double h, int strict)
{
    size_t S = s->nlayers;
#define AT_OR_ABOVE(i) (strict ? s->cuts[i] > h : s->cuts[i] >= h)
    double g = step > 0 ? ceil((h - c0) / step) : 0;
    size_t guess = g <= 0 ? 0 : g >= (double)S ? S : (size_t)g;
    if (guess < S && AT_OR_ABOVE(guess) && (guess == 0 || !AT_OR_ABOVE(guess - 1))) return guess;
    if (guess + 1 < S && AT_OR_ABOVE(guess + 1) && !AT_OR_ABOVE(guess)) return guess + 1;
    if (guess == S && !AT_OR_ABOVE(S - 1)) return S;
    size_t a = 0, z = S;
    while (a < z) {
        size_t mid = (a + z) / 2;
        if (AT_OR_ABOVE(mid)) z = mid;
        else a = mid + 1;
    }
#undef AT_OR_ABOVE
    return a;
}

/* Mean spacing of the cuts, for first_cut's guess. */
static double cut_step(const lam_slicer *s)
{
    size_t S = s->nlayers;
    return S > 1 ? (s->cuts[S - 1] - s->cuts[0]) / (double)(S - 1) : 0;
}

/* A cut meant to lie on a vertex height but missing it by rounding (a plane
 * wmin + i * width computed an ulp off a flat face) is put on it, so that
 * the symbolic perturbation decides the section there, as it does for a
 * cut that hits the face exactly, and not the last bit of a product. "By
 * rounding": within 8 DBL_EPSILON of the magnitudes the cut came from. A
 * cut that some vertex lies on exactly stays. Non-zero when out of memory. */
static int snap_cuts(lam_slicer *s, size_t nv)
{
    size_t S = s->nlayers;
    double *best = malloc(S * sizeof *best + 1);
    unsigned char *exact = calloc(S + 1, 1);
    if (!best || !exact) {
        free(best);
        free(exact);
        return 1;
    }
    for (size_t j = 0; j < S; j++) best[j] = NAN;
    double base = fabs(s->planes[0]), c0 = s->cuts[0], step = cut_step(s);
    for (size_t v = 0; v < nv; v++) {
        double h = W(s, v);
        /* the cuts either side of h */
        size_t a = first_cut(s, c0, step, h, 0);
        for (size_t j = a ? a - 1 : 0; j <= a && j < S; j++) {
            double c = s->cuts[j], d = fabs(c - h);
            if (d == 0) {
                exact[j] = 1;
                continue;
            }
            if (d > 8 * DBL_EPSILON * (base + fabs(c))) continue;
            if (isnan(best[j]) || d < fabs(c - best[j]) || (d == fabs(c - best[j]) && h < best[j])) best[j] = h;
        }
    }
    /* a floor or ceiling cut is a plane: the plane moves with it, so the
     * slab bounds stay the cut and shared, bit for bit, with the slab next
     * to it */
    int on_plane = s->o.cut != LAM_CUT_MIDDLE;
    for (size_t j = 0; j < S; j++) {
        if (exact[j] || isnan(best[j])) continue;
        double b = best[j];
        size_t pl = s->o.cut == LAM_CUT_FLOOR ? j : j + 1; /* planes 0 .. S */
        /* an ulp never passes a neighbour, unless layers are an ulp thin */
        if (on_plane && ((pl > 0 && !(b > s->planes[pl - 1])) || (pl < S && !(b < s->planes[pl + 1])))) continue;
        if ((j > 0 && b < s->cuts[j - 1]) || (j + 1 < S && b > s->cuts[j + 1])) continue;
        s->cuts[j] = b;
        if (on_plane) s->planes[pl] = b;
    }
    free(best);
    free(exact);
    return 0;
}

/* The vertices' (u, v, w) in the frame: straight from the mesh when the
 * frame's axes are coordinate axes, else computed once. 0, or -1 when out
 * of memory. */
static int frame_coords(lam_slicer *s, const lam_model *m, const lam_frame *f)
{
    size_t nv = m->mesh.nverts;
    int ku = unit_axis(f->u), kv = unit_axis(f->v), kw = unit_axis(f->w);
    if (ku >= 0 && kv >= 0 && kw >= 0) {
        s->pu = m->mesh.xyz + ku;
        s->pv = m->mesh.xyz + kv;
        s->pw = m->mesh.xyz + kw;
        return 0;
    }
    if (!(s->wuv = lam_big_malloc(3 * nv * sizeof *s->wuv + 1))) return -1;
    s->pw = s->wuv;
    s->pu = s->wuv + 1;
    s->pv = s->wuv + 2;
    for (size_t v = 0; v < nv; v++) {
        const double *p = m->mesh.xyz + 3 * v;
        s->wuv[3 * v] = dot_exact(p, f->w);
        s->wuv[3 * v + 1] = dot_exact(p, f->u);
        s->wuv[3 * v + 2] = dot_exact(p, f->v);
    }
    return 0;
}

/* The schedule (Minetto et al.): each edge goes into the bucket of the
 * first layer whose cut it crosses, found by binary search over the cut
 * heights, so the run costs O(E log S) instead of a sort of all edges.
 * Edges that cross no cut (horizontal ones, and short ones between two
 * cuts) are left out entirely. */
static int schedule(lam_slicer *s, lam_cut cut, lam_error *err)
{
    size_t S = s->nlayers, nv = s->m->mesh.nverts, ne = s->m->edges.n;
    s->cuts = malloc(S * sizeof *s->cuts + 1);
    s->layer_first = calloc(S + 2, sizeof *s->layer_first);
    uint32_t *bucket = lam_big_malloc(ne * sizeof *bucket + 1);
    if (!s->cuts || !s->layer_first || !bucket) goto oom;
    s->up = cut != LAM_CUT_CEILING;
    for (size_t i = 0; i < S; i++) {
        double lo = s->planes[i], hi = s->planes[i + 1];
        s->cuts[i] = cut == LAM_CUT_FLOOR ? lo : cut == LAM_CUT_CEILING ? hi : lo + (hi - lo) / 2;
    }
    if (snap_cuts(s, nv)) goto oom;
    double c0 = s->cuts[0], step = cut_step(s);
    for (size_t e = 0; e < ne; e++) {
        double lo = edge_lo(s, (uint32_t)e), hi = edge_hi(s, (uint32_t)e);
        /* first layer with lo below its cut: cut >= lo (up) or cut > lo */
        size_t a = first_cut(s, c0, step, lo, !s->up);
        int crosses = a < S && (s->up ? hi > s->cuts[a] : hi >= s->cuts[a]);
        /* cuts crossed: those from a up to the first one at or above hi */
        if (crosses) s->crossings += (double)(first_cut(s, c0, step, hi, !s->up) - a);
        bucket[e] = crosses ? (uint32_t)a : NONE;
        if (crosses) s->layer_first[a + 1]++;
    }
    for (size_t i = 0; i < S; i++) s->layer_first[i + 1] += s->layer_first[i];
    s->norder = s->layer_first[S];
    s->order = lam_big_malloc(s->norder * sizeof *s->order + 1);
    if (!s->order) goto oom;
    for (size_t e = 0; e < ne; e++)
        if (bucket[e] != NONE) s->order[s->layer_first[bucket[e]]++] = (uint32_t)e;
    for (size_t i = S; i > 0; i--) s->layer_first[i] = s->layer_first[i - 1];
    s->layer_first[0] = 0;
    free(bucket);
    return LAM_OK;
oom:
    free(bucket);
    return nomem(err);
}

int lam_slicer_new(const lam_model *m, const lam_slice_opts *opts, lam_slicer **out, lam_error *err)
{
    *out = NULL;
    lam_slicer *s = calloc(1, sizeof *s);
    if (!s) return nomem(err);
    s->m = m;
    s->o = *opts;
    s->o.planes = NULL; /* the copy must not point at the caller's arrays */
    s->o.widths = NULL;
    double size = model_size(m);
    if (!(s->o.gap >= 0)) s->o.gap = lam_default_gap(size, s->o.gap_limit);
    s->min_area = (LAM_SLIVER_REL * size) * (LAM_SLIVER_REL * size);
    int rc = LAM_OK;
    if (frame_coords(s, m, &opts->frame)) {
        rc = nomem(err);
        goto fail;
    }
    double wmin = INFINITY, wmax = -INFINITY;
    for (size_t v = 0; v < m->mesh.nverts; v++) {
        double h = W(s, v);
        if (h < wmin) wmin = h;
        if (h > wmax) wmax = h;
    }
    s->o.planes = opts->planes;
    s->o.widths = opts->widths;
    rc = make_planes(s, wmin, wmax, err);
    s->o.planes = NULL;
    s->o.widths = NULL;
    if (rc || (rc = schedule(s, opts->cut, err))) goto fail;
    *out = s;
    return LAM_OK;
fail:
    lam_slicer_free(s);
    return rc;
}

size_t lam_slicer_count(const lam_slicer *s) { return s->nlayers; }
double lam_slicer_crossings(const lam_slicer *s) { return s->crossings; }
const lam_model *lam_slicer_model(const lam_slicer *s) { return s->m; }
const double *lam_slicer_planes(const lam_slicer *s) { return s->planes; }
double lam_slicer_cut(const lam_slicer *s, size_t i)
{
    return i < s->nlayers ? s->cuts[i] : NAN;
}

void lam_slicer_uv_bounds(const lam_slicer *s, double box[4])
{
    box[0] = box[1] = INFINITY;
    box[2] = box[3] = -INFINITY;
    for (size_t v = 0; v < s->m->mesh.nverts; v++) {
        double u = U(s, v), w = V(s, v);
        if (u < box[0]) box[0] = u;
        if (u > box[2]) box[2] = u;
        if (w < box[1]) box[1] = w;
        if (w > box[3]) box[3] = w;
    }
}

const lam_frame *lam_slicer_frame(const lam_slicer *s) { return &s->o.frame; }

double lam_slicer_gap(const lam_slicer *s) { return s->o.gap; }

void lam_slicer_free(lam_slicer *s)
{
    if (!s) return;
    if (!s->borrowed) {
        free(s->planes);
        free(s->wuv);
        free(s->order);
        free(s->cuts);
        free(s->layer_first);
    }
    free(s->active);
    free(s->slot_edge);
    free(s->slot_at);
    free(s->pts);
    free(s->seg_in);
    free(s->seg_out);
    free(s->in_first);
    free(s->in_seg);
    free(s->indeg);
    free(s->used);
    free(s);
}

size_t lam_slicer_bytes(const lam_slicer *s)
{
    size_t b = sizeof *s, S = s->nlayers;
    if (!s->borrowed)
        b += (S + 1) * sizeof *s->planes + (s->wuv ? 3 * s->m->mesh.nverts * sizeof *s->wuv : 0) +
             s->norder * sizeof *s->order + S * sizeof *s->cuts + (S + 2) * sizeof *s->layer_first;
    /* active, in_first, indeg, pts; seg_in, seg_out, in_seg, used; the slots */
    b += s->cap_active * (3 * sizeof *s->active + 2 * sizeof *s->pts) + s->cap_seg * (3 * sizeof *s->seg_in + 1) +
         s->slot_cap * (sizeof *s->slot_edge + sizeof *s->slot_at);
    return b;
}

static int reserve_active(lam_slicer *s, size_t n, lam_error *err);

int lam_slicer_fork(const lam_slicer *s, lam_slicer **out, lam_error *err)
{
    lam_slicer *f = calloc(1, sizeof *f);
    *out = f;
    if (!f) return nomem(err);
    f->m = s->m;
    f->o = s->o;
    f->planes = s->planes;
    f->nlayers = s->nlayers;
    f->pw = s->pw;
    f->pu = s->pu;
    f->pv = s->pv;
    f->wuv = s->wuv;
    f->cuts = s->cuts;
    f->min_area = s->min_area;
    f->crossings = s->crossings;
    f->up = s->up;
    f->order = s->order;
    f->layer_first = s->layer_first;
    f->norder = s->norder;
    f->borrowed = 1;
    return LAM_OK;
}

/* The active set at layer i is the edges scheduled before it that have not
 * passed below its cut, in schedule order (the sweep only ever appends and
 * drops keeping order): so dropping the passed ones from the active set and
 * appending the edges scheduled in between that have not passed gives the
 * very set, and the very order, a sweep from layer 0 would have. */
int lam_slicer_all(lam_slicer *s, lam_layer ***out, size_t *n, lam_error *err)
{
    *out = NULL;
    *n = 0;
    size_t want = lam_slicer_count(s), got = 0;
    lam_layer **L = calloc(want + 1, sizeof *L);
    if (!L) return lam_error_nomem(err, "slicing the run");
    int rc = LAM_OK;
    lam_slicer_seek(s, 0);
    while (got < want && !(rc = lam_slicer_next(s, &L[got], err)) && L[got]) got++;
    lam_slicer_seek(s, 0);
    if (rc) {
        lam_layers_free(L, got);
        return rc;
    }
    *out = L;
    *n = got;
    return LAM_OK;
}

void lam_layers_free(lam_layer **layers, size_t n)
{
    for (size_t i = 0; layers && i < n; i++) lam_layer_free(layers[i]);
    free(layers);
}

void lam_slicer_seek(lam_slicer *s, size_t i)
{
    if (i > s->nlayers) i = s->nlayers;
    if (i < s->next) {
        s->nactive = 0;
        s->ins = 0;
    }
    s->next = i;
    size_t to = s->layer_first[i];
    if (s->ins >= to) return;
    if (i >= s->nlayers) {
        s->nactive = 0;
        s->ins = to;
        return;
    }
    /* keep only what layer i's section would keep, as section() drops: a
     * jump over many layers must not hold all their edges at once */
    double c = s->cuts[i];
    int up = s->up;
#define PASSED(e) (up ? edge_hi(s, e) <= c : edge_hi(s, e) < c)
    size_t na = 0;
    for (size_t k = 0; k < s->nactive; k++)
        if (!PASSED(s->active[k])) s->active[na++] = s->active[k];
    s->nactive = na;
    for (; s->ins < to; s->ins++) {
        uint32_t e = s->order[s->ins];
        if (PASSED(e)) continue;
        if (s->nactive == s->cap_active && reserve_active(s, s->nactive + 1, NULL)) {
            /* no room: start over at layer i, the active set rebuilt by section() */
            s->nactive = 0;
            s->ins = 0;
            return;
        }
        s->active[s->nactive++] = e;
    }
#undef PASSED
}

static int grow_u32(uint32_t **p, size_t n, lam_error *err)
{
    uint32_t *np = lam_realloc_n(*p, n + 1, sizeof **p);
    if (!np) return nomem(err);
    *p = np;
    return LAM_OK;
}

static int reserve_active(lam_slicer *s, size_t n, lam_error *err)
{
    if (n <= s->cap_active) return LAM_OK;
    size_t cap = lam_grow_cap(s->cap_active, n, 64, 2 * sizeof *s->pts);
    if (!cap) return nomem(err);
    if (grow_u32(&s->active, cap, err) || grow_u32(&s->in_first, cap + 1, err) ||
        grow_u32(&s->indeg, cap, err))
        return LAM_ENOMEM;
    double *np = lam_realloc_n(s->pts, cap, 2 * sizeof *np);
    if (!np) return nomem(err);
    s->pts = np;
    s->cap_active = cap;
    return LAM_OK;
}

static int reserve_segs(lam_slicer *s, size_t n, lam_error *err)
{
    if (n <= s->cap_seg) return LAM_OK;
    size_t cap = lam_grow_cap(s->cap_seg, n, 64, sizeof *s->seg_in);
    if (!cap) return nomem(err);
    if (grow_u32(&s->seg_in, cap, err) || grow_u32(&s->seg_out, cap, err) || grow_u32(&s->in_seg, cap, err))
        return LAM_ENOMEM;
    unsigned char *nu = realloc(s->used, cap);
    if (!nu) return nomem(err);
    s->used = nu;
    s->cap_seg = cap;
    return LAM_OK;
}

/* Growing list of polylines for one layer. */
typedef struct chains {
    double *uv;
    size_t *len;
    unsigned char *closed;
    size_t n, npts, cap_pts, cap_n;
} chains;

static int chains_point(chains *c, double u, double v, lam_error *err)
{
    if (c->npts == c->cap_pts) {
        double *np = lam_grow(c->uv, &c->cap_pts, c->npts + 1, 2 * sizeof *np, 256);
        if (!np) return nomem(err);
        c->uv = np;
    }
    /* consecutive equal points are one point: no zero-length segment */
    size_t start = c->npts - c->len[c->n - 1];
    if (c->len[c->n - 1] > 0 && c->npts > start && c->uv[2 * c->npts - 2] == u && c->uv[2 * c->npts - 1] == v)
        return LAM_OK;
    c->uv[2 * c->npts] = u;
    c->uv[2 * c->npts + 1] = v;
    c->npts++;
    c->len[c->n - 1]++;
    return LAM_OK;
}

static int chains_begin(chains *c, lam_error *err)
{
    if (c->n == c->cap_n) {
        size_t cap = lam_grow_cap(c->cap_n, c->n + 1, 16, sizeof *c->len);
        size_t *nl = cap ? lam_realloc_n(c->len, cap, sizeof *nl) : NULL;
        if (!nl) return nomem(err);
        c->len = nl;
        unsigned char *nc = realloc(c->closed, cap);
        if (!nc) return nomem(err);
        c->closed = nc;
        c->cap_n = cap;
    }
    c->len[c->n] = 0;
    c->closed[c->n] = 0;
    c->n++;
    return LAM_OK;
}

static void chains_free(chains *c)
{
    free(c->uv);
    free(c->len);
    free(c->closed);
}

/* Walk one chain starting with segment s0; closed when it returns to the
 * segment's own entry edge. */
static int walk(lam_slicer *s, chains *c, uint32_t s0, lam_error *err)
{
    int rc = chains_begin(c, err);
    if (rc) return rc;
    uint32_t seg = s0, start_edge = s->seg_in[s0];
    for (;;) {
        s->used[seg] = 1;
        uint32_t k = s->seg_in[seg];
        if ((rc = chains_point(c, s->pts[2 * k], s->pts[2 * k + 1], err))) return rc;
        uint32_t next_edge = s->seg_out[seg], nxt = NONE;
        for (uint32_t i = s->in_first[next_edge]; i < s->in_first[next_edge + 1]; i++)
            if (!s->used[s->in_seg[i]]) {
                nxt = s->in_seg[i];
                break;
            }
        if (nxt == NONE) {
            if (next_edge == start_edge) {
                c->closed[c->n - 1] = 1;
            } else {
                rc = chains_point(c, s->pts[2 * next_edge], s->pts[2 * next_edge + 1], err);
                if (rc) return rc;
            }
            /* drop a repeated closing point */
            size_t len = c->len[c->n - 1], first = c->npts - len;
            if (c->closed[c->n - 1] && len > 1 && c->uv[2 * first] == c->uv[2 * c->npts - 2] &&
                c->uv[2 * first + 1] == c->uv[2 * c->npts - 1]) {
                c->npts--;
                c->len[c->n - 1]--;
            }
            return LAM_OK;
        }
        seg = nxt;
    }
}

/* (1-t)*a + t*b: exact at t = 0 and t = 1, and exactly a when a == b (an
 * edge along which this coordinate does not change keeps it exactly). */
static double lerp(double a, double b, double t)
{
    return a == b ? a : (1 - t) * a + t * b;
}

static uint32_t slot_hash(const lam_slicer *s, uint32_t e)
{
    return (uint32_t)((e * 0x9e3779b1u) & (s->slot_cap - 1));
}

/* Fill the edge -> slot table for the active edges of this layer. */
static int index_slots(lam_slicer *s, lam_error *err)
{
    size_t need = 16;
    while (need < 2 * s->nactive) need *= 2;
    if (need > s->slot_cap) {
        uint32_t *ne = realloc(s->slot_edge, need * sizeof *ne);
        if (ne) s->slot_edge = ne;
        uint32_t *na = ne ? realloc(s->slot_at, need * sizeof *na) : NULL;
        if (na) s->slot_at = na;
        if (!ne || !na) return nomem(err);
        s->slot_cap = need;
    }
    memset(s->slot_edge, 0xff, s->slot_cap * sizeof *s->slot_edge);
    for (size_t k = 0; k < s->nactive; k++) {
        uint32_t e = s->active[k], h = slot_hash(s, e);
        while (s->slot_edge[h] != NONE) h = (h + 1) & (uint32_t)(s->slot_cap - 1);
        s->slot_edge[h] = e;
        s->slot_at[h] = (uint32_t)k;
    }
    return LAM_OK;
}

/* The slot of active edge e, NONE if it is not active. (Every edge a
 * crossing triangle leaves by crosses the plane too, so it is active;
 * NONE would only drop a segment, never index out of bounds.) */
static uint32_t slot_of(const lam_slicer *s, uint32_t e)
{
    for (uint32_t h = slot_hash(s, e);; h = (h + 1) & (uint32_t)(s->slot_cap - 1)) {
        if (s->slot_edge[h] == e) return s->slot_at[h];
        if (s->slot_edge[h] == NONE) return NONE;
    }
}

/* The section's segments s->seg_in/seg_out[0..nseg) between its na active
 * edges, grouped by entry edge and walked into chains. */
static int chain_segments(lam_slicer *s, size_t na, size_t nseg, chains *ch, lam_error *err)
{
    /* segments grouped by entry edge (counting sort keeps triangle order) */
    memset(s->in_first, 0, (na + 1) * sizeof *s->in_first);
    memset(s->indeg, 0, na * sizeof *s->indeg);
    for (size_t g = 0; g < nseg; g++) {
        s->in_first[s->seg_in[g] + 1]++;
        s->indeg[s->seg_out[g]]++;
        s->used[g] = 0;
    }
    for (size_t k = 0; k < na; k++) s->in_first[k + 1] += s->in_first[k];
    size_t *fill = malloc((na + 1) * sizeof *fill);
    if (!fill) return nomem(err);
    for (size_t k = 0; k <= na; k++) fill[k] = s->in_first[k];
    for (size_t g = 0; g < nseg; g++) s->in_seg[fill[s->seg_in[g]]++] = (uint32_t)g;
    free(fill);

    /* Open chains first, from edges more segments leave than enter (open
     * surfaces), then the closed loops. */
    for (size_t g = 0; g < nseg; g++) {
        uint32_t k = s->seg_in[g];
        if (!s->used[g] && s->indeg[k] < s->in_first[k + 1] - s->in_first[k]) {
            int rc = walk(s, ch, (uint32_t)g, err);
            if (rc) return rc;
        }
    }
    for (size_t g = 0; g < nseg; g++)
        if (!s->used[g]) {
            int rc = walk(s, ch, (uint32_t)g, err);
            if (rc) return rc;
        }
    return LAM_OK;
}

/* Cut at height c: the active edges' points and the directed segments of
 * the triangles crossing the plane, chained into polylines by edge. */
static int section(lam_slicer *s, size_t layer, chains *ch, lam_error *err)
{
    double c = s->cuts[layer];
    int up = s->up;
    const lam_model *m = s->m;
    const lam_edges *E = &m->edges;
#define BELOW(h) (up ? (h) <= c : (h) < c)
    if (reserve_active(s, s->nactive + (s->layer_first[layer + 1] - s->ins) + 1, err)) return LAM_ENOMEM;
    while (s->ins < s->layer_first[layer + 1]) s->active[s->nactive++] = s->order[s->ins++];
    size_t na = 0;
    for (size_t i = 0; i < s->nactive; i++) {
        uint32_t e = s->active[i];
        if (i + 8 < s->nactive) LAM_PREFETCH(E->v + 2 * (size_t)s->active[i + 8]);
        if (BELOW(edge_hi(s, e))) continue; /* passed for good: heights only rise */
        s->active[na] = e;
        /* the point, from the lower end to the upper end, exact at both */
        const uint32_t *ev = E->v + 2 * (size_t)e;
        uint32_t lo = ev[0], hi = ev[1];
        if (W(s, lo) > W(s, hi)) { uint32_t t = lo; lo = hi; hi = t; }
        double t = (c - W(s, lo)) / (W(s, hi) - W(s, lo));
        s->pts[2 * na] = lerp(U(s, lo), U(s, hi), t);
        s->pts[2 * na + 1] = lerp(V(s, lo), V(s, hi), t);
        LAM_PREFETCH(E->first + e);
        na++;
    }
    s->nactive = na;
    if (index_slots(s, err)) return LAM_ENOMEM;

    /* Directed segments: with outward triangles (a, b, c) and a lone vertex
     * above the plane, the section runs from edge (lone, next) to edge
     * (prev, lone) with the material on its left; a lone vertex below
     * reverses that. Each crossing triangle is emitted once, from its entry
     * edge. */
    size_t nseg = 0;
    for (size_t k = 0; k < na; k++) {
        uint32_t e = s->active[k];
        /* The crossing triangles lie all over the mesh: fetch what the
         * edges a little ahead will read while this one is worked on. */
        if (k + 16 < na) LAM_PREFETCH(E->tris + E->first[s->active[k + 16]]);
        if (k + 8 < na) {
            uint32_t ahead = s->active[k + 8];
            for (uint32_t i = E->first[ahead]; i < E->first[ahead + 1] && i < E->first[ahead] + 2; i++) {
                LAM_PREFETCH(m->mesh.tris + 3 * (size_t)E->tris[i]);
                LAM_PREFETCH(E->tri_edge + 3 * (size_t)E->tris[i]);
            }
        }
        for (uint32_t i = E->first[e]; i < E->first[e + 1]; i++) {
            uint32_t t = E->tris[i];
            const uint32_t *tv = m->mesh.tris + 3 * (size_t)t;
            int above[3];
            for (int j = 0; j < 3; j++) above[j] = !BELOW(W(s, tv[j]));
            int lone = above[0] == above[1] ? 2 : above[0] == above[2] ? 1 : 0;
            int entry = above[lone] ? lone : (lone + 2) % 3;
            int exit = above[lone] ? (lone + 2) % 3 : lone;
            if (E->tri_edge[3 * (size_t)t + entry] != e) continue;
            uint32_t out = slot_of(s, E->tri_edge[3 * (size_t)t + exit]);
            if (out == NONE) continue;
            if (reserve_segs(s, nseg + 1, err)) return LAM_ENOMEM;
            s->seg_in[nseg] = (uint32_t)k;
            s->seg_out[nseg] = out;
            nseg++;
        }
    }
#undef BELOW
    return chain_segments(s, na, nseg, ch, err);
}

/* ---- gap closing ------------------------------------------------------------ */

typedef struct gpair {
    double d;
    uint32_t from, to; /* end of chain `from` joins start of chain `to` */
} gpair;

static int cmp_gpair(const void *a, const void *b)
{
    const gpair *p = a, *q = b;
    if (p->d != q->d) return p->d < q->d ? -1 : 1;
    if (p->from != q->from) return p->from < q->from ? -1 : 1;
    return p->to < q->to ? -1 : p->to > q->to;
}

typedef struct skey {
    double u;
    uint32_t chain;
} skey;

static int cmp_skey(const void *a, const void *b)
{
    const skey *p = a, *q = b;
    if (p->u != q->u) return p->u < q->u ? -1 : 1;
    return p->chain < q->chain ? -1 : p->chain > q->chain;
}

static const double *chain_first(const chains *c, const size_t *off, size_t i) { return c->uv + 2 * off[i]; }
static const double *chain_last(const chains *c, const size_t *off, size_t i)
{
    return c->uv + 2 * (off[i] + c->len[i] - 1);
}

/* The candidate joins: every open chain's end with every open chain's
 * start (starts sorted by u) at most gap away, into *pairs. */
static int find_pairs(const chains *c, const size_t *off, const skey *starts, size_t nstarts, double gap,
                      gpair **pairs, size_t *npairs, lam_error *err)
{
    size_t cap_pairs = 0;
    for (size_t i = 0; i < c->n; i++) {
        if (c->closed[i] || c->len[i] == 0) continue;
        const double *e = chain_last(c, off, i);
        /* starts within gap along u, by binary search */
        size_t lo = 0, hi = nstarts;
        while (lo < hi) {
            size_t mid = (lo + hi) / 2;
            if (starts[mid].u < e[0] - gap) lo = mid + 1;
            else hi = mid;
        }
        for (size_t k = lo; k < nstarts && starts[k].u <= e[0] + gap; k++) {
            const double *f = chain_first(c, off, starts[k].chain);
            double d = hypot(f[0] - e[0], f[1] - e[1]);
            if (d > gap) continue;
            if (*npairs == cap_pairs) {
                gpair *np = lam_grow(*pairs, &cap_pairs, *npairs + 1, sizeof *np, 16);
                if (!np) return nomem(err);
                *pairs = np;
            }
            (*pairs)[*npairs].d = d;
            (*pairs)[*npairs].from = (uint32_t)i;
            (*pairs)[*npairs].to = starts[k].chain;
            (*npairs)++;
        }
    }
    return LAM_OK;
}

/* Join nearest pairs first, each end and each start at most once. */
static void join_pairs(gpair *pairs, size_t npairs, uint32_t *succ, uint32_t *pred, lam_layer *L)
{
    if (npairs) qsort(pairs, npairs, sizeof *pairs, cmp_gpair);
    for (size_t p = 0; p < npairs; p++) {
        uint32_t a = pairs[p].from, b = pairs[p].to;
        if (succ[a] != NONE || pred[b] != NONE) continue;
        succ[a] = b;
        pred[b] = a;
        if (pairs[p].d > 0) {
            L->gaps_closed++;
            if (pairs[p].d > L->max_gap) L->max_gap = pairs[p].d;
        }
    }
}

/* Emit closed chains, then cycles of joined open chains, into out (marked
 * done); groups that stay open are left for report_open. */
static void emit_loops(const chains *c, const size_t *off, const uint32_t *succ, unsigned char *done,
                       lam_loops *out)
{
    size_t n = c->n;
    for (size_t i = 0; i < n; i++) {
        if (done[i] || c->len[i] == 0) continue;
        if (!c->closed[i]) {
            /* find whether i's group is a cycle: walk forward */
            size_t j = i, steps = 0;
            while (succ[j] != NONE && succ[j] != i && steps++ < n) j = succ[j];
            if (succ[j] != i) continue; /* open group: handled by report_open from its head */
        }
        size_t first = out->npoints;
        size_t j = i;
        do {
            done[j] = 1;
            for (size_t q = 0; q < c->len[j]; q++) {
                const double *p = c->uv + 2 * (off[j] + q);
                if (out->npoints > first && out->uv[2 * out->npoints - 2] == p[0] &&
                    out->uv[2 * out->npoints - 1] == p[1])
                    continue;
                out->uv[2 * out->npoints] = p[0];
                out->uv[2 * out->npoints + 1] = p[1];
                out->npoints++;
            }
            j = c->closed[j] ? j : succ[j];
        } while (!c->closed[i] && j != i);
        size_t len = lam_loop_simplify(out->uv + 2 * first, out->npoints - first);
        out->npoints = first + len;
        out->len[out->nloops++] = len; /* a point or a line: lam_loops_tidy drops and counts it */
    }
}

/* Record each group that stayed open, from its head, in L->open. */
static int report_open(const chains *c, const size_t *off, const uint32_t *succ, const uint32_t *pred,
                       unsigned char *done, lam_layer *L, lam_error *err)
{
    for (size_t i = 0; i < c->n; i++) {
        if (done[i] || c->closed[i] || pred[i] != NONE || c->len[i] == 0) continue;
        size_t j = i;
        while (succ[j] != NONE) {
            done[j] = 1;
            j = succ[j];
        }
        done[j] = 1;
        lam_open_end *no = lam_realloc_n(L->open, L->nopen + 1, sizeof *no);
        if (!no) return nomem(err);
        L->open = no;
        memcpy(L->open[L->nopen].start, chain_first(c, off, i), 2 * sizeof(double));
        memcpy(L->open[L->nopen].end, chain_last(c, off, j), 2 * sizeof(double));
        L->nopen++;
    }
    return LAM_OK;
}

/* Turn the layer's chains into closed loops: closed chains as they are,
 * open ones joined end-to-start, nearest pairs first, when the gap is at
 * most `gap`. What stays open is recorded in the layer. */
static int close_gaps(const chains *c, double gap, lam_layer *L, lam_loops *out, lam_error *err)
{
    int rc = LAM_OK;
    size_t n = c->n;
    size_t *off = malloc((n + 1) * sizeof *off);
    uint32_t *succ = malloc((n + 1) * sizeof *succ), *pred = malloc((n + 1) * sizeof *pred);
    skey *starts = malloc((n + 1) * sizeof *starts);
    unsigned char *done = calloc(n + 1, 1);
    gpair *pairs = NULL;
    size_t npairs = 0;
    out->uv = malloc((2 * c->npts + 2) * sizeof *out->uv);
    out->len = malloc((n + 1) * sizeof *out->len);
    out->nloops = out->npoints = 0;
    if (!off || !succ || !pred || !starts || !done || !out->uv || !out->len) {
        rc = nomem(err);
        goto done;
    }
    size_t nstarts = 0;
    for (size_t i = 0, o = 0; i < n; i++) {
        off[i] = o;
        o += c->len[i];
        succ[i] = pred[i] = NONE;
        if (!c->closed[i] && c->len[i] > 0) {
            starts[nstarts].u = chain_first(c, off, i)[0];
            starts[nstarts].chain = (uint32_t)i;
            nstarts++;
        }
    }
    if (gap > 0 && nstarts) {
        qsort(starts, nstarts, sizeof *starts, cmp_skey);
        if ((rc = find_pairs(c, off, starts, nstarts, gap, &pairs, &npairs, err))) goto done;
        join_pairs(pairs, npairs, succ, pred, L);
    }
    emit_loops(c, off, succ, done, out);
    rc = report_open(c, off, succ, pred, done, L, err);
done:
    free(off);
    free(succ);
    free(pred);
    free(starts);
    free(done);
    free(pairs);
    return rc;
}

int lam_slicer_next(lam_slicer *s, lam_layer **out, lam_error *err)
{
    *out = NULL;
    if (s->next >= s->nlayers) return LAM_OK;
    size_t i = s->next++;
    lam_layer *L = calloc(1, sizeof *L);
    if (!L) return nomem(err);
    L->index = i;
    L->floor = s->planes[i];
    L->ceiling = s->planes[i + 1];
    L->width = L->ceiling - L->floor;
    L->cut = s->cuts[i];
    chains ch = { 0 };
    lam_loops loops = { 0 };
    L->gap = s->o.gap;
    int rc = section(s, i, &ch, err);
    if (!rc) rc = close_gaps(&ch, s->o.gap, L, &loops, err);
    /* Degenerate loops go before anything else sees them. Under the
     * non-zero rule the winding decides what coincident loops bound (a pair
     * in opposite directions nothing, in the same direction material), so
     * only the even-odd rule cancels them here; the union's own outlines
     * are tidied again. */
    if (!rc) rc = lam_loops_tidy(&loops, s->min_area, !s->o.fill_nonzero, &L->slivers, &L->twins, err);
    if (!rc && s->o.fill_nonzero) {
        rc = lam_fill_nonzero(&loops, err);
        if (rc == LAM_EGEOM && err) lam_error_set(err, rc, NULL, 0, 0, "layer %zu: %s", i + 1, err->msg);
        if (!rc) rc = lam_loops_tidy(&loops, s->min_area, 0, &L->slivers, &L->twins, err);
    }
    if (!rc) rc = lam_contours_assign(L, &loops, err);
    chains_free(&ch);
    free(loops.uv);
    free(loops.len);
    if (rc) {
        lam_layer_free(L);
        return rc;
    }
    *out = L;
    return LAM_OK;
}
