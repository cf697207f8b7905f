/* Support regions: the top-down sweep of support.h, and what does not
 * stand on a run's layers. */
#include "support.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "contour.h"
#include "geos.h"

struct lam_supports {
    size_t n;
    lam_layer **region, **teeth, **over; /* n each, NULL: none */
};

/* The reach of a layer of width w at angle degrees from the vertical:
 * w * tan(angle); HUGE_VAL from 90 degrees on. */
static double support_reach(double width, double angle)
{
    if (angle >= 90) return HUGE_VAL;
    return width * tan(angle * (3.14159265358979323846 / 180.0));
}

lam_supports *lam_supports_new(size_t n)
{
    lam_supports *s = calloc(1, sizeof *s);
    if (!s) return NULL;
    s->n = n;
    s->region = calloc(n + 1, sizeof *s->region);
    s->teeth = calloc(n + 1, sizeof *s->teeth);
    s->over = calloc(n + 1, sizeof *s->over);
    if (!s->region || !s->teeth || !s->over) {
        lam_supports_free(s);
        return NULL;
    }
    return s;
}

void lam_supports_free(lam_supports *s)
{
    if (!s) return;
    for (size_t i = 0; i < s->n; i++) {
        if (s->region) lam_layer_free(s->region[i]);
        if (s->teeth) lam_layer_free(s->teeth[i]);
        if (s->over) lam_layer_free(s->over[i]);
    }
    free(s->region);
    free(s->teeth);
    free(s->over);
    free(s);
}

static double layer_area(const lam_layer *L)
{
    double a = 0;
    for (size_t k = 0; L && k < L->ncontours; k++) a += L->contours[k].area;
    return a;
}

int lam_supports_set(lam_supports *s, size_t i, lam_layer *R)
{
    if (i >= s->n) {
        lam_layer_free(R);
        return LAM_EUSAGE;
    }
    lam_layer_free(s->region[i]);
    s->region[i] = R && R->ncontours ? R : (lam_layer_free(R), NULL);
    return LAM_OK;
}

const lam_layer *lam_supports_region(const lam_supports *s, size_t i)
{
    return s && i < s->n ? s->region[i] : NULL;
}

const lam_layer *lam_supports_teeth(const lam_supports *s, size_t i)
{
    return s && i < s->n ? s->teeth[i] : NULL;
}

const lam_layer *lam_supports_overhang(const lam_supports *s, size_t i)
{
    return s && i < s->n ? s->over[i] : NULL;
}

double lam_supports_area(const lam_supports *s, size_t i)
{
    return layer_area(lam_supports_region(s, i));
}

/* ---- the sweep ------------------------------------------------------------ */

typedef struct sweep {
    lam_geos g;
    const lam_layer *const *layers;
    size_t n;
    const lam_support_cfg *cfg;
    GEOSGeometry **part;     /* each layer's region */
    GEOSGeometry **sup;      /* each layer's support (NULL: none) */
    GEOSGeometry **over;     /* each layer's overhang: its part beyond the reach of the part below */
    const char *stage;
    size_t at;               /* the layer being made */
} sweep;

static void drop(sweep *w, GEOSGeometry *x)
{
    if (x) GEOSGeom_destroy_r(w->g.h, x);
}

static int empty(sweep *w, const GEOSGeometry *x)
{
    return !x || GEOSisEmpty_r(w->g.h, x);
}

/* The reach used: a millionth more (support.h), and a few grid cells. */
static double reach_of(const sweep *w, size_t upper)
{
    double r = support_reach(w->layers[upper]->width, w->cfg->angle);
    return r + fmax(1e-6 * r, 64 * w->g.grid);
}

/* The polygons of x (a polygon, or any collection of them and of lines
 * and points, nested), each of at least `least` area, appended to parts. */
static int add_areal(sweep *w, const GEOSGeometry *x, double least, GEOSGeometry ***parts, size_t *n, size_t *cap)
{
    int type = GEOSGeomTypeId_r(w->g.h, x);
    if (type == GEOS_MULTIPOLYGON || type == GEOS_GEOMETRYCOLLECTION) {
        int m = GEOSGetNumGeometries_r(w->g.h, x), rc = LAM_OK;
        for (int i = 0; i < m && !rc; i++) rc = add_areal(w, GEOSGetGeometryN_r(w->g.h, x, i), least, parts, n, cap);
        return rc;
    }
    double a = 0;
    if (type != GEOS_POLYGON || !GEOSArea_r(w->g.h, x, &a) || a < least || a == 0) return LAM_OK;
    if (*n == *cap) {
        size_t c = *cap ? 2 * *cap : 16;
        GEOSGeometry **p = realloc(*parts, c * sizeof *p);
        if (!p) return LAM_ENOMEM;
        *parts = p;
        *cap = c;
    }
    GEOSGeometry *copy = GEOSGeom_clone_r(w->g.h, x);
    if (!copy) return LAM_EGEOM;
    (*parts)[(*n)++] = copy;
    return LAM_OK;
}

/* x (taken) as a multipolygon of its polygons of at least `least` area:
 * an overlay's result may hold lines and points where regions touch, which
 * the next overlay refuses ("mixed-dimension"). NULL when GEOS fails. */
static GEOSGeometry *areal(sweep *w, GEOSGeometry *x, double least)
{
    if (!x) return NULL;
    GEOSGeometry **parts = NULL;
    size_t n = 0, cap = 0;
    int rc = add_areal(w, x, least, &parts, &n, &cap);
    drop(w, x);
    GEOSGeometry *r = rc ? NULL : GEOSGeom_createCollection_r(w->g.h, GEOS_MULTIPOLYGON, parts, (unsigned)n);
    if (!r)
        for (size_t i = 0; i < n; i++) drop(w, parts[i]);
    free(parts);
    return r;
}

/* x without its polygons of less than min_area (and the rounding's
 * slivers: under a millionth of the reach's square); taken. */
static GEOSGeometry *keep_large(sweep *w, GEOSGeometry *x, double tiny)
{
    return areal(w, x, fmax(w->cfg->min_area, tiny));
}

/* x (taken) closed by a little more than half the reach (grown, then
 * shrunk back), less `held` again: each layer's new piece of support
 * stands a reach from the column above it (that gap is held by the part
 * above), so without this a sphere's support is a ring a layer, each a
 * reach apart (hundreds of thin rings, each layer's overlays slower than
 * the last); closed, it is one block under the overhang. Mitred offsets:
 * round ones would put arcs at every vertex, layer after layer (a sphere's
 * support had 20 times its section's vertices). NULL when GEOS fails. */
static GEOSGeometry *close_gaps(sweep *w, GEOSGeometry *x, const GEOSGeometry *held, double r)
{
    double c = 0.55 * r;
    GEOSGeometry *g = areal(w, lam_geos_offset(&w->g, x, c), 0);
    drop(w, x);
    GEOSGeometry *sh = g ? areal(w, lam_geos_offset(&w->g, g, -c), 0) : NULL;
    drop(w, g);
    GEOSGeometry *out = sh ? lam_geos_difference(&w->g, sh, held) : NULL;
    drop(w, sh);
    return out;
}

/* x (taken) less P[k] grown by support_gap_xy. NULL when GEOS fails. */
static GEOSGeometry *clear_gap(sweep *w, GEOSGeometry *x, size_t k)
{
    w->stage = "gap";
    GEOSGeometry *gap = areal(w, lam_geos_grow(&w->g, w->part[k], w->cfg->gap_xy), 0);
    GEOSGeometry *out = gap ? lam_geos_difference(&w->g, x, gap) : NULL;
    drop(w, gap);
    drop(w, x);
    return out;
}

/* Layer k+1's overhang: its part beyond `held` (the reach of P[k]); *all
 * (when not NULL) gets a copy before the small pieces go. */
static int note_overhang(sweep *w, size_t k, const GEOSGeometry *held, double r, GEOSGeometry **all)
{
    GEOSGeometry *d = lam_geos_difference(&w->g, w->part[k + 1], held);
    if (d && all && !(*all = GEOSGeom_clone_r(w->g.h, d))) {
        drop(w, d);
        return LAM_EGEOM;
    }
    GEOSGeometry *o = keep_large(w, d, 1e-6 * r * r);
    if (!o) return LAM_EGEOM;
    if (GEOSisEmpty_r(w->g.h, o)) drop(w, o);
    else w->over[k + 1] = o;
    return LAM_OK;
}

/* S[k] from S[k+1], P[k+1] and P[k] (support.h). */
static int sweep_layer(sweep *w, size_t k)
{
    w->at = k;
    GEOSGeometry *above = w->part[k + 1], *u = NULL, *held = NULL, *rest = NULL;
    double r = reach_of(w, k + 1);
    if (isinf(r)) return LAM_OK; /* nothing needs support */
    /* a layer within the one below (a predicate, no overlay: most layers
     * of most parts) has no overhang, and without support above none */
    if (!w->sup[k + 1] && GEOSCoveredBy_r(w->g.h, w->part[k + 1], w->part[k]) == 1) return LAM_OK;
    if (w->sup[k + 1] && !(above = u = areal(w, lam_geos_union(&w->g, w->part[k + 1], w->sup[k + 1]), 0)))
        return LAM_EGEOM;
    if (empty(w, above)) {
        drop(w, u);
        return LAM_OK;
    }
    w->stage = "reach";
    int rc = (held = areal(w, lam_geos_grow(&w->g, w->part[k], r), 0)) ? LAM_OK : LAM_EGEOM;
    w->stage = "support";
    /* without support above, what needs support is the overhang itself */
    if (!rc) rc = note_overhang(w, k, held, r, w->sup[k + 1] ? NULL : &rest);
    if (!rc && w->sup[k + 1] && !(rest = lam_geos_difference(&w->g, above, held))) rc = LAM_EGEOM;
    if (!rc && !empty(w, rest) && !(rest = close_gaps(w, rest, held, r))) rc = LAM_EGEOM;
    if (!rc && w->cfg->gap_xy > r && !(rest = clear_gap(w, rest, k))) rc = LAM_EGEOM;
    drop(w, u);
    drop(w, held);
    if (!rc && rest) {
        w->sup[k] = keep_large(w, rest, 1e-6 * r * r);
        rest = NULL;
        if (!w->sup[k]) rc = LAM_EGEOM;
        else if (GEOSisEmpty_r(w->g.h, w->sup[k])) drop(w, w->sup[k]), w->sup[k] = NULL;
    }
    drop(w, rest);
    return rc;
}

/* x as a layer like L (index, heights), or NULL (x NULL: none). */
static int to_layer(sweep *w, const GEOSGeometry *x, const lam_layer *L, lam_layer **out, lam_error *err)
{
    *out = NULL;
    if (empty(w, x)) return LAM_OK;
    lam_layer *R = calloc(1, sizeof *R);
    if (!R) return lam_error_nomem(err, "making supports");
    R->index = L->index;
    R->floor = L->floor;
    R->ceiling = L->ceiling;
    R->width = L->width;
    R->cut = L->cut;
    lam_loops_builder b = { 0 };
    int rc = lam_geos_add_polygons(&w->g, x, &b);
    if (!rc) rc = lam_contours_assign(R, &b.loops, err);
    lam_loops_builder_free(&b);
    if (rc || !R->ncontours) {
        lam_layer_free(R);
        return rc == LAM_ENOMEM ? lam_error_nomem(err, "making supports") : rc;
    }
    *out = R;
    return LAM_OK;
}

/* The union of the parts of layers lo .. hi-1 (hi <= n), NULL if none. */
static GEOSGeometry *parts_union(sweep *w, size_t lo, size_t hi, int *rc)
{
    GEOSGeometry *acc = NULL;
    for (size_t j = lo; j < hi && !*rc; j++) {
        if (empty(w, w->part[j])) continue;
        GEOSGeometry *x = areal(w, acc ? lam_geos_union(&w->g, acc, w->part[j]) : GEOSGeom_clone_r(w->g.h, w->part[j]), 0);
        if (!x) *rc = LAM_EGEOM;
        drop(w, acc);
        acc = x;
    }
    return acc;
}

/* support_gap_z: layer k's support minus the parts of the layers above
 * it within the gap. */
static int clear_below_part(sweep *w, size_t k, size_t layers)
{
    if (!w->sup[k] || !layers) return LAM_OK;
    int rc = LAM_OK;
    size_t hi = k + 1 + layers < w->n ? k + 1 + layers : w->n;
    GEOSGeometry *over = parts_union(w, k + 1, hi, &rc), *x = NULL;
    if (!rc && over && !(x = areal(w, lam_geos_difference(&w->g, w->sup[k], over), 0))) rc = LAM_EGEOM;
    drop(w, over);
    if (x) {
        drop(w, w->sup[k]);
        w->sup[k] = x;
    }
    return rc;
}

/* The contact of S[j] with the part above it, S[j] n P[j+1], into
 * c[j] (made once: each is asked for by `layers` layers; NULL: none). */
static int contact(sweep *w, size_t j, GEOSGeometry **c, char *made)
{
    if (made[j]) return LAM_OK;
    made[j] = 1;
    if (!w->sup[j] || j + 1 >= w->n || empty(w, w->part[j + 1])) return LAM_OK;
    c[j] = areal(w, lam_geos_intersection(&w->g, w->sup[j], w->part[j + 1]), 0);
    if (!c[j]) return LAM_EGEOM;
    if (GEOSisEmpty_r(w->g.h, c[j])) drop(w, c[j]), c[j] = NULL;
    return LAM_OK;
}

/* Layer i's teeth: its part over the contacts of the `layers` layers
 * below it. */
static int teeth_of(sweep *w, size_t i, size_t layers, GEOSGeometry **c, char *made, GEOSGeometry **out)
{
    *out = NULL;
    GEOSGeometry *acc = NULL;
    int rc = LAM_OK;
    for (size_t j = i > layers ? i - layers : 0; j < i && !rc; j++) {
        if ((rc = contact(w, j, c, made)) || !c[j]) continue;
        GEOSGeometry *x = areal(w, acc ? lam_geos_union(&w->g, acc, c[j]) : GEOSGeom_clone_r(w->g.h, c[j]), 0);
        if (!x) rc = LAM_EGEOM;
        drop(w, acc);
        acc = x;
    }
    if (!rc && acc && !(*out = areal(w, lam_geos_intersection(&w->g, acc, w->part[i]), 0))) rc = LAM_EGEOM;
    drop(w, acc);
    return rc;
}

/* Every layer's teeth into s (layers: their height in layers). */
static int all_teeth(sweep *w, lam_supports *s, size_t layers, lam_error *err)
{
    GEOSGeometry **c = calloc(w->n + 1, sizeof *c);
    char *made = calloc(w->n + 1, 1);
    int rc = c && made ? LAM_OK : lam_error_nomem(err, "making supports");
    for (size_t i = 0; i < w->n && !rc; i++) {
        GEOSGeometry *t = NULL;
        w->at = i;
        w->stage = "teeth";
        if ((rc = teeth_of(w, i, layers, c, made, &t))) break;
        rc = to_layer(w, t, w->layers[i], &s->teeth[w->layers[i]->index], err);
        drop(w, t);
        if (i >= layers) drop(w, c[i - layers]), c[i - layers] = NULL; /* no layer above asks again */
    }
    for (size_t j = 0; c && j < w->n; j++) drop(w, c[j]);
    free(c);
    free(made);
    return rc;
}

static size_t whole_layers(double height, double width)
{
    if (!(height > 0) || !(width > 0)) return 0;
    double n = ceil(height / width - 1e-9);
    return n > 1e6 ? 1000000 : (size_t)n;
}

/* The regions and teeth into s, from the swept w. */
static int regions(sweep *w, lam_supports *s, lam_error *err)
{
    int rc = LAM_OK;
    double width = w->n ? w->layers[0]->width : 0;
    size_t gap = whole_layers(w->cfg->gap_z, width), teeth = gap ? 0 : whole_layers(w->cfg->teeth_height, width);
    if (teeth) rc = all_teeth(w, s, teeth, err);
    for (size_t k = 0; k < w->n && !rc; k++) {
        w->at = k;
        w->stage = "gap below the part";
        if ((rc = clear_below_part(w, k, gap))) break;
        size_t at = w->layers[k]->index;
        rc = to_layer(w, w->sup[k], w->layers[k], &s->region[at], err);
        if (!rc) rc = to_layer(w, w->over[k], w->layers[k], &s->over[at], err);
    }
    return rc;
}

static int sweep_start(sweep *w, lam_error *err)
{
    int rc = lam_geos_init(&w->g, err);
    if (rc) return rc;
    double m = 0;
    for (size_t i = 0; i < w->n; i++) m = fmax(m, lam_geos_layer_magnitude(w->layers[i]));
    w->g.grid = lam_geos_grid(m);
    w->part = calloc(w->n + 1, sizeof *w->part);
    w->sup = calloc(w->n + 1, sizeof *w->sup);
    w->over = calloc(w->n + 1, sizeof *w->over);
    if (!w->part || !w->sup || !w->over) return lam_error_nomem(err, "making supports");
    w->stage = "region";
    for (size_t i = 0; i < w->n; i++) {
        w->at = i;
        if (!(w->part[i] = areal(w, lam_geos_layer_region(&w->g, w->layers[i]), 0))) return LAM_EGEOM;
    }
    return LAM_OK;
}

static void sweep_finish(sweep *w)
{
    for (size_t i = 0; i < w->n; i++) {
        if (w->part) drop(w, w->part[i]);
        if (w->sup) drop(w, w->sup[i]);
        if (w->over) drop(w, w->over[i]);
    }
    free(w->part);
    free(w->sup);
    free(w->over);
    lam_geos_finish(&w->g);
}

static int geom_error(sweep *w, int rc, lam_error *err)
{
    if (rc == LAM_EGEOM && (!err || err->code == LAM_OK))
        lam_error_set(err, rc, NULL, 0, 0, "layer %zu: supports: %s: GEOS: %s", w->at + 1, w->stage,
                      w->g.msg[0] ? w->g.msg : "failed");
    return rc;
}

/* Room for the layers' run indices: the largest, plus one. */
static size_t index_room(const lam_layer *const *layers, size_t n)
{
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if (layers[i]->index + 1 > m) m = layers[i]->index + 1;
    return m;
}

int lam_supports_make(const lam_layer *const *layers, size_t n, const lam_support_cfg *cfg, lam_supports **out,
                      lam_error *err)
{
    *out = NULL;
    lam_supports *s = lam_supports_new(index_room(layers, n));
    if (!s) return lam_error_nomem(err, "making supports");
    sweep w;
    memset(&w, 0, sizeof w);
    w.layers = layers;
    w.n = n;
    w.cfg = cfg;
    int rc = sweep_start(&w, err);
    for (size_t k = n > 1 ? n - 1 : 0; k-- > 0 && !rc;) rc = sweep_layer(&w, k);
    if (!rc) rc = regions(&w, s, err);
    geom_error(&w, rc, err);
    sweep_finish(&w);
    if (rc) {
        lam_supports_free(s);
        return rc;
    }
    *out = s;
    return LAM_OK;
}

/* ---- what does not stand --------------------------------------------------- */

/* a (taken) united with layer R's region, or a itself without R */
static GEOSGeometry *with(sweep *w, GEOSGeometry *a, const lam_layer *R)
{
    if (!R || !a) return a;
    GEOSGeometry *r = lam_geos_layer_region(&w->g, R), *x = r ? areal(w, lam_geos_union(&w->g, a, r), 0) : NULL;
    drop(w, r);
    drop(w, a);
    return x;
}

/* The area of `top` beyond reach r of `base`. */
static int beyond(sweep *w, const GEOSGeometry *top, const GEOSGeometry *base, double r, double *area)
{
    *area = 0;
    if (isinf(r) || empty(w, top) || GEOSCoveredBy_r(w->g.h, top, base) == 1) return LAM_OK;
    GEOSGeometry *held = areal(w, lam_geos_grow(&w->g, base, r), 0);
    GEOSGeometry *x = held ? lam_geos_difference(&w->g, top, held) : NULL;
    int rc = x ? LAM_OK : LAM_EGEOM;
    x = x ? keep_large(w, x, 1e-6 * r * r) : NULL;
    if (!rc && !(x && GEOSArea_r(w->g.h, x, area))) rc = LAM_EGEOM;
    drop(w, held);
    drop(w, x);
    return rc;
}

int lam_supports_unsupported(const lam_layer *const *layers, size_t n, const lam_supports *s, double angle,
                             double *over, double *left, lam_error *err)
{
    sweep w;
    memset(&w, 0, sizeof w);
    lam_support_cfg cfg = { .angle = angle };
    w.layers = layers;
    w.n = n;
    w.cfg = &cfg;
    int rc = sweep_start(&w, err);
    GEOSGeometry *below = NULL;
    for (size_t i = 0; i < n && !rc; i++) {
        w.at = i;
        w.stage = "overhang";
        over[i] = left[i] = 0;
        double r = reach_of(&w, i);
        GEOSGeometry *both = with(&w, GEOSGeom_clone_r(w.g.h, w.part[i]), lam_supports_region(s, layers[i]->index));
        if (!both) rc = LAM_EGEOM;
        if (!rc && i) rc = beyond(&w, w.part[i], w.part[i - 1], r, &over[i]);
        if (!rc && i) rc = s ? beyond(&w, both, below, r, &left[i]) : (left[i] = over[i], LAM_OK);
        drop(&w, below);
        below = both;
    }
    drop(&w, below);
    geom_error(&w, rc, err);
    sweep_finish(&w);
    return rc;
}
