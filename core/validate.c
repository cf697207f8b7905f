/* Embree validation of sliced layers; see validate.h for the rules. */
#include "validate.h"

#include <embree3/rtcore.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "contour.h"

/* ---- fixed ray directions ------------------------------------------------------ */

/* Sixteen unit directions, every component at least 0.2 in magnitude and no
 * two components within 0.06 of each other in magnitude (so no ray lies in
 * an axis plane or a diagonal plane such as x = y), picked greedily from a
 * spherical Fibonacci set to spread out (the first five at least 85 degrees
 * apart, all sixteen at least 42). Literal constants: the same on every
 * platform. */
#define NDIRS 16
#define NFIRST 5
static const double DIRS[NDIRS][3] = {
    { -0.28331882421791266, -0.21111654090520601, 0.9355 },
    { 0.23336254304979526, 0.30139952471981818, -0.9245000000000001 },
    { -0.25419074911250711, -0.91144654975792327, -0.3234999999999999 },
    { 0.9122725367695258, 0.23636532879441977, 0.33450000000000002 },
    { -0.27042493660383632, 0.93967021005393747, 0.20950000000000002 },
    { -0.82624233200764008, 0.21541438855976333, -0.52049999999999996 },
    { 0.7531223999322374, -0.54566509941566455, -0.36749999999999994 },
    { 0.3094111915196136, -0.82060006371094862, 0.48050000000000004 },
    { -0.86764232924032025, -0.43005411114234432, 0.24950000000000006 },
    { 0.52102454749046601, 0.82868158596191532, -0.2044999999999999 },
    { 0.24528909590457054, 0.54242143157356759, 0.80349999999999999 },
    { -0.77256978154047362, 0.34270349086419444, 0.53449999999999998 },
    { -0.35476062643006545, -0.27205633228239218, -0.89450000000000007 },
    { -0.27813767823794983, 0.76679670183458837, -0.57850000000000001 },
    { 0.88203555391476829, 0.21455309746136933, -0.41949999999999998 },
    { 0.49617714029765869, -0.22146782033974469, 0.83950000000000002 },
};

const double *lam_validator_direction(size_t k) { return k < NDIRS ? DIRS[k] : NULL; }

/* ---- the validator ------------------------------------------------------------ */

typedef struct hit {
    double s;          /* distance from the query point along the ray */
    float t;           /* Embree's hit distance from the ray origin */
    uint32_t prim;
    int ng;            /* sign of dir . Ng (Embree's float normal) */
} hit;

struct lam_validator {
    const lam_model *m;
    RTCDevice dev;
    RTCScene scene;
    float dirf[NDIRS][3];   /* directions as Embree gets them */
    double dird[NDIRS][3];  /* the same values in double */
    double scale;           /* largest extent of the model */
    double maxabs;          /* largest |coordinate - center| */
    /* Embree gets the model centred and scaled to a unit box, (x - center)
     * / unit, before the float conversion: a part far from the origin, or
     * of kilometres or nanometres, keeps float32's full precision, and its
     * products stay far from float overflow and underflow. */
    double center[3], unit;
    double tol;             /* same-distance and on-surface tolerance */
    double dmin, dtarget;   /* smallest and preferred inset of layer test points */
    hit *hits;              /* hits of the ray being cast (filled by the filter) */
    size_t nhits, cap;
    int nomem;
    int ecode;              /* first Embree error reported to the callback */
    char emsg[256];
    lam_validator_stats st;
};

/* Intersection context handed to the filter: Embree's first, so the
 * filter gets back to the validator from args->context. */
typedef struct ray_ctx {
    struct RTCIntersectContext rtc;
    lam_validator *v;
} ray_ctx;

static int nomem(lam_error *err)
{
    return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory while validating");
}

static const char *rtc_error_name(enum RTCError e)
{
    switch (e) {
    case RTC_ERROR_NONE: return "no error";
    case RTC_ERROR_UNKNOWN: return "unknown error";
    case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
    case RTC_ERROR_CANCELLED: return "cancelled";
    }
    return "error";
}

static void on_rtc_error(void *user, enum RTCError code, const char *str)
{
    lam_validator *v = user;
    if (v->ecode != RTC_ERROR_NONE) return;
    v->ecode = (int)code;
    snprintf(v->emsg, sizeof v->emsg, "%s%s%s", rtc_error_name(code), str && *str ? ": " : "",
             str ? str : "");
}

/* The intersection filter: record every hit and reject it, so Embree goes
 * on to the next one. Ray and hit are in SOA layout of N (1 for
 * rtcIntersect1, but any N is handled). */
static void gather(const struct RTCFilterFunctionNArguments *a)
{
    ray_ctx *c = (ray_ctx *)a->context;
    lam_validator *v = c->v;
    const unsigned N = a->N;
    const float *ray = (const float *)a->ray;
    const float *hf = (const float *)a->hit;
    const unsigned *hu = (const unsigned *)a->hit;
    for (unsigned i = 0; i < N; i++) {
        if (!a->valid[i]) continue;
        a->valid[i] = 0;
        if (v->nhits == v->cap) {
            size_t cap = v->cap ? 2 * v->cap : 64;
            hit *h = realloc(v->hits, cap * sizeof *h);
            if (!h) {
                v->nomem = 1;
                continue;
            }
            v->hits = h;
            v->cap = cap;
        }
        double dot = (double)ray[4 * N + i] * hf[0 * N + i] + (double)ray[5 * N + i] * hf[1 * N + i] +
                     (double)ray[6 * N + i] * hf[2 * N + i];
        hit *h = &v->hits[v->nhits++];
        h->t = ray[8 * N + i];
        h->prim = hu[5 * N + i];
        h->ng = (dot > 0) - (dot < 0);
        h->s = 0;
    }
}

int lam_validator_new(const lam_model *m, lam_validator **out, lam_error *err)
{
    *out = NULL;
    if (!m) return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "no model to validate against");
    const lam_mesh *mesh = &m->mesh;
    if (mesh->nverts > UINT32_MAX)
        return lam_error_set(err, LAM_EGEOM, NULL, 0, 0, "too many vertices for Embree");
    lam_validator *v = calloc(1, sizeof *v);
    if (!v) return nomem(err);
    v->m = m;
    v->ecode = RTC_ERROR_NONE;

    double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (size_t i = 0; i < mesh->nverts; i++)
        for (int k = 0; k < 3; k++) {
            double x = mesh->xyz[3 * i + k];
            if (x < lo[k]) lo[k] = x;
            if (x > hi[k]) hi[k] = x;
        }
    for (int k = 0; k < 3; k++) {
        if (!mesh->nverts) lo[k] = hi[k] = 0;
        v->center[k] = lo[k] + (hi[k] - lo[k]) / 2;
        if (hi[k] - lo[k] > v->scale) v->scale = hi[k] - lo[k];
        if (hi[k] - v->center[k] > v->maxabs) v->maxabs = hi[k] - v->center[k];
        if (v->center[k] - lo[k] > v->maxabs) v->maxabs = v->center[k] - lo[k];
    }
    if (!(v->scale > 0) || !isfinite(v->scale)) {
        if (!isfinite(v->scale)) {
            free(v);
            return lam_error_set(err, LAM_EGEOM, NULL, 0, 0,
                                 "the model spans more than a double can measure: nothing to check");
        }
        v->scale = 1;
    }
    v->unit = v->scale;
    /* Embree works in float: vertices, ray origins and hit distances are
     * good to a few ulps of the largest coordinate. */
    v->tol = fmax(1e-6 * v->scale, 16 * FLT_EPSILON * v->maxabs);
    v->dmin = fmax(1e-5 * v->scale, 1e3 * FLT_EPSILON * v->maxabs);
    v->dtarget = fmax(1e-3 * v->scale, 4 * v->dmin);
    for (int k = 0; k < NDIRS; k++)
        for (int j = 0; j < 3; j++) {
            v->dirf[k][j] = (float)DIRS[k][j];
            v->dird[k][j] = v->dirf[k][j];
        }

    v->dev = rtcNewDevice(NULL);
    if (!v->dev) {
        enum RTCError e = rtcGetDeviceError(NULL);
        free(v);
        return lam_error_set(err, LAM_EGEOM, NULL, 0, 0, "Embree: cannot create a device: %s",
                             rtc_error_name(e));
    }
    rtcSetDeviceErrorFunction(v->dev, on_rtc_error, v);
    v->scene = rtcNewScene(v->dev);
    if (v->scene) {
        rtcSetSceneFlags(v->scene, RTC_SCENE_FLAG_ROBUST);
        rtcSetSceneBuildQuality(v->scene, RTC_BUILD_QUALITY_HIGH);
    }
    if (v->scene && mesh->ntris) {
        RTCGeometry g = rtcNewGeometry(v->dev, RTC_GEOMETRY_TYPE_TRIANGLE);
        if (g) {
            float *vb = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                3 * sizeof(float), mesh->nverts);
            unsigned *ib = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                   3 * sizeof(unsigned), mesh->ntris);
            if (vb && ib) {
                for (size_t i = 0; i < 3 * mesh->nverts; i++)
                    vb[i] = (float)((mesh->xyz[i] - v->center[i % 3]) / v->unit);
                for (size_t i = 0; i < 3 * mesh->ntris; i++) ib[i] = mesh->tris[i];
                rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_HIGH);
                rtcSetGeometryIntersectFilterFunction(g, gather);
                rtcCommitGeometry(g);
                rtcAttachGeometry(v->scene, g);
            }
            rtcReleaseGeometry(g);
        }
    }
    if (v->scene && v->ecode == RTC_ERROR_NONE) rtcCommitScene(v->scene);
    enum RTCError e = rtcGetDeviceError(v->dev);
    if (v->ecode == RTC_ERROR_NONE && (e != RTC_ERROR_NONE || !v->scene)) {
        v->ecode = e != RTC_ERROR_NONE ? (int)e : RTC_ERROR_UNKNOWN;
        snprintf(v->emsg, sizeof v->emsg, "%s", rtc_error_name((enum RTCError)v->ecode));
    }
    if (v->ecode != RTC_ERROR_NONE) {
        int rc = lam_error_set(err, LAM_EGEOM, NULL, 0, 0, "Embree: %s", v->emsg);
        lam_validator_free(v);
        return rc;
    }
    *out = v;
    return LAM_OK;
}

void lam_validator_free(lam_validator *v)
{
    if (!v) return;
    if (v->scene) rtcReleaseScene(v->scene);
    if (v->dev) rtcReleaseDevice(v->dev);
    free(v->hits);
    free(v);
}

double lam_validator_tolerance(const lam_validator *v) { return v->tol; }
double lam_validator_min_inset(const lam_validator *v) { return v->dmin; }

void lam_validator_get_stats(const lam_validator *v, lam_validator_stats *st) { *st = v->st; }

/* ---- one ray ------------------------------------------------------------------- */

enum { CAST_OK, CAST_UNRELIABLE, CAST_SURFACE, CAST_NOMEM };

static int by_prim(const void *a, const void *b)
{
    const hit *x = a, *y = b;
    if (x->prim != y->prim) return x->prim < y->prim ? -1 : 1;
    return (x->s > y->s) - (x->s < y->s);
}

static int by_s(const void *a, const void *b)
{
    const hit *x = a, *y = b;
    if (x->s != y->s) return x->s < y->s ? -1 : 1;
    return (x->prim > y->prim) - (x->prim < y->prim);
}

/* Sign of dir . n for triangle t, n from the model's double vertices;
 * 2 for a degenerate triangle (no normal). */
static int tri_sign(const lam_validator *v, uint32_t t, const double d[3])
{
    const lam_mesh *m = &v->m->mesh;
    const double *a = m->xyz + 3 * (size_t)m->tris[3 * (size_t)t];
    const double *b = m->xyz + 3 * (size_t)m->tris[3 * (size_t)t + 1];
    const double *c = m->xyz + 3 * (size_t)m->tris[3 * (size_t)t + 2];
    double e1[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    double e2[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    double n[3] = { e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                    e1[0] * e2[1] - e1[1] * e2[0] };
    if (n[0] == 0 && n[1] == 0 && n[2] == 0) return 2;
    double dot = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
    return (dot > 0) - (dot < 0);
}

/* Cast direction k from p; on CAST_OK *w is the winding along that ray. */
/* Cast one ray from o along d, gathering every hit into v->hits (the
 * filter rejects each hit so traversal goes on). Non-zero when the hit list
 * could not grow. */
static int trace(lam_validator *v, const float o[3], const float d[3])
{
    struct RTCRayHit rh;
    memset(&rh, 0, sizeof rh);
    rh.ray.org_x = o[0];
    rh.ray.org_y = o[1];
    rh.ray.org_z = o[2];
    rh.ray.dir_x = d[0];
    rh.ray.dir_y = d[1];
    rh.ray.dir_z = d[2];
    rh.ray.tnear = 0;
    rh.ray.tfar = INFINITY;
    rh.ray.mask = UINT32_MAX;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    ray_ctx c;
    rtcInitIntersectContext(&c.rtc);
    c.v = v;
    v->nhits = 0;
    v->nomem = 0;
    rtcIntersect1(v->scene, &c.rtc, &rh);
    v->st.rays++;
    return v->nomem;
}

static int cast_dir(lam_validator *v, const double p[3], int k, int *w)
{
    const double *d = v->dird[k];
    /* start a little behind p, so that a surface through p is seen in
     * every direction and not lost to the float rounding of the origin */
    double back = 4 * v->tol;
    float o[3];
    double om[3]; /* the origin Embree gets, back in model units */
    for (int j = 0; j < 3; j++) {
        o[j] = (float)((p[j] - back * d[j] - v->center[j]) / v->unit);
        om[j] = (double)o[j] * v->unit + v->center[j];
    }
    double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    double sp = ((p[0] - om[0]) * d[0] + (p[1] - om[1]) * d[1] + (p[2] - om[2]) * d[2]) / dd;

    if (trace(v, o, v->dirf[k])) return CAST_NOMEM;

    size_t n = v->nhits;
    hit *h = v->hits;
    double len = sqrt(dd);
    /* t is in unit-box lengths of the (float) direction */
    for (size_t i = 0; i < n; i++) h[i].s = ((double)h[i].t * v->unit - sp) * len;
    /* a primitive may be reported more than once (spatial splits): keep one */
    if (n > 1) qsort(h, n, sizeof *h, by_prim);
    size_t u = 0;
    for (size_t i = 0; i < n; i++)
        if (u == 0 || h[i].prim != h[u - 1].prim) h[u++] = h[i];
    n = u;
    if (n > 1) qsort(h, n, sizeof *h, by_s);
    for (size_t i = 0; i < n; i++)
        if (fabs(h[i].s) <= v->tol) return CAST_SURFACE;

    const uint32_t *shell = v->m->tri_shell;
    int sum = 0;
    size_t i = 0;
    while (i < n && h[i].s < 0) i++;
    while (i < n) {
        size_t j = i + 1;
        while (j < n && h[j].s - h[j - 1].s <= v->tol) j++;
        /* group [i, j): hits at the same place along the ray. The sign of
         * each crossing from the double normal must agree with Embree's
         * (else the ray grazes the triangle); it replaces ng. */
        for (size_t a = i; a < j; a++) {
            int s = tri_sign(v, h[a].prim, d);
            if (s == 2) s = 0; /* degenerate triangle: no side to cross */
            else if (s == 0 || s != h[a].ng) return CAST_UNRELIABLE;
            h[a].ng = s;
        }
        /* one crossing per shell: a ray through a shared edge or vertex
         * may hit several of its triangles, all with the same sign;
         * mixed signs mean an edge or a silhouette grazed */
        for (size_t a = i; a < j; a++) {
            int sa = h[a].ng;
            if (!sa) continue;
            uint32_t sh = shell ? shell[h[a].prim] : 0;
            int first = 1;
            for (size_t b = i; b < j; b++) {
                if (b == a || !h[b].ng || (shell ? shell[h[b].prim] : 0) != sh) continue;
                if (h[b].ng != sa) return CAST_UNRELIABLE;
                if (b < a) first = 0;
            }
            if (first) sum += sa;
        }
        i = j;
    }
    *w = sum;
    return CAST_OK;
}

int lam_validator_ray(lam_validator *v, const double p[3], const double d[3], double tmin, double *t, uint32_t *tri,
                      lam_error *err)
{
    *t = INFINITY;
    if (tri) *tri = UINT32_MAX;
    float o[3], df[3] = { (float)d[0], (float)d[1], (float)d[2] };
    for (int j = 0; j < 3; j++) o[j] = (float)((p[j] - v->center[j]) / v->unit);
    if (trace(v, o, df)) return nomem(err);
    /* every hit was gathered (and rejected): the nearest past tmin wins */
    for (size_t i = 0; i < v->nhits; i++) {
        double ti = (double)v->hits[i].t * v->unit;
        if (ti > tmin && ti < *t) {
            *t = ti;
            if (tri) *tri = v->hits[i].prim;
        }
    }
    return LAM_OK;
}

/* ---- votes ------------------------------------------------------------------------ */

enum { W_DECIDED, W_SURFACE, W_UNDECIDED, W_NOMEM };

static int winding_at(lam_validator *v, const double p[3], int *w)
{
    int vals[NDIRS];
    int nrel = 0;
    v->st.points++;
    for (int k = 0; k < NDIRS; k++) {
        if (k == NFIRST) {
            int agree = nrel >= 3;
            for (int i = 1; i < nrel && agree; i++) agree = vals[i] == vals[0];
            if (agree) {
                *w = vals[0];
                return W_DECIDED;
            }
            v->st.recasts++;
        }
        int x = 0, r = cast_dir(v, p, k, &x);
        if (r == CAST_NOMEM) return W_NOMEM;
        if (r == CAST_SURFACE) {
            v->st.surface++;
            return W_SURFACE;
        }
        if (r == CAST_OK) vals[nrel++] = x;
        else v->st.unreliable++;
    }
    int best = 0, bestn = 0;
    for (int i = 0; i < nrel; i++) {
        int c = 0;
        for (int j = 0; j < nrel; j++) c += vals[j] == vals[i];
        if (c > bestn) {
            bestn = c;
            best = vals[i];
        }
    }
    if (bestn >= 3 && 2 * bestn > nrel) {
        *w = best;
        return W_DECIDED;
    }
    v->st.undecided++;
    return W_UNDECIDED;
}

int lam_validator_winding(lam_validator *v, const double p[3], int *winding, lam_error *err)
{
    int w = 0;
    switch (winding_at(v, p, &w)) {
    case W_DECIDED:
        *winding = w;
        return LAM_OK;
    case W_SURFACE:
        return lam_error_set(err, LAM_EGEOM, NULL, 0, 0,
                             "the point (%.17g, %.17g, %.17g) is on the surface (within %g): "
                             "it has no winding number",
                             p[0], p[1], p[2], v->tol);
    case W_NOMEM:
        return nomem(err);
    }
    return lam_error_set(err, LAM_EGEOM, NULL, 0, 0, "cannot decide the winding at (%.17g, %.17g, %.17g)",
                         p[0], p[1], p[2]);
}

/* ---- a grid of the layer's edges ------------------------------------------------ */

/* Edge g of the layer runs from point g to point nxt[g]. Each edge is listed
 * in every cell its bounding box touches. */
typedef struct egrid {
    const double *uv;
    size_t *nxt;
    double u0, v0, cu, cv;
    size_t g;            /* g x g cells */
    size_t *first;       /* g*g + 1 offsets into items */
    size_t *items;
} egrid;

static size_t cell(double x, double x0, double c, size_t g)
{
    double q = (x - x0) / c;
    if (!(q > 0)) return 0;
    if (q >= (double)g) return g - 1;
    return (size_t)q;
}

static void edge_cells(const egrid *G, size_t e, size_t *iu0, size_t *iv0, size_t *iu1, size_t *iv1)
{
    const double *a = G->uv + 2 * e, *b = G->uv + 2 * G->nxt[e];
    *iu0 = cell(fmin(a[0], b[0]), G->u0, G->cu, G->g);
    *iu1 = cell(fmax(a[0], b[0]), G->u0, G->cu, G->g);
    *iv0 = cell(fmin(a[1], b[1]), G->v0, G->cv, G->g);
    *iv1 = cell(fmax(a[1], b[1]), G->v0, G->cv, G->g);
}

static void egrid_free(egrid *G)
{
    free(G->nxt);
    free(G->first);
    free(G->items);
    memset(G, 0, sizeof *G);
}

static int egrid_build(egrid *G, const lam_layer *L)
{
    memset(G, 0, sizeof *G);
    size_t P = L->npoints;
    G->uv = L->uv;
    G->nxt = malloc((P ? P : 1) * sizeof *G->nxt);
    if (!G->nxt) return -1;
    double lo[2] = { INFINITY, INFINITY }, hi[2] = { -INFINITY, -INFINITY };
    for (size_t c = 0; c < L->ncontours; c++) {
        const lam_contour *k = &L->contours[c];
        for (size_t i = 0; i < k->n; i++) {
            size_t g = k->first + i;
            G->nxt[g] = i + 1 < k->n ? g + 1 : k->first;
            for (int j = 0; j < 2; j++) {
                if (L->uv[2 * g + j] < lo[j]) lo[j] = L->uv[2 * g + j];
                if (L->uv[2 * g + j] > hi[j]) hi[j] = L->uv[2 * g + j];
            }
        }
    }
    if (!(hi[0] >= lo[0])) lo[0] = hi[0] = lo[1] = hi[1] = 0;
    size_t g = (size_t)ceil(sqrt((double)P));
    if (g < 1) g = 1;
    if (g > 1024) g = 1024;
    G->u0 = lo[0];
    G->v0 = lo[1];
    size_t total;
    for (;;) {
        G->g = g;
        G->cu = hi[0] > lo[0] ? (hi[0] - lo[0]) / (double)g : 1;
        G->cv = hi[1] > lo[1] ? (hi[1] - lo[1]) / (double)g : 1;
        total = 0;
        for (size_t c = 0; c < L->ncontours; c++)
            for (size_t i = 0; i < L->contours[c].n; i++) {
                size_t iu0, iv0, iu1, iv1;
                edge_cells(G, L->contours[c].first + i, &iu0, &iv0, &iu1, &iv1);
                total += (iu1 - iu0 + 1) * (iv1 - iv0 + 1);
            }
        /* long slanted edges fill many cells: coarsen until the lists stay
         * linear in the number of edges */
        if (total <= 16 * P + 1024 || g == 1) break;
        g /= 2;
    }
    G->first = calloc(g * g + 1, sizeof *G->first);
    G->items = malloc((total ? total : 1) * sizeof *G->items);
    if (!G->first || !G->items) return -1;
    for (int pass = 0; pass < 2; pass++) {
        for (size_t c = 0; c < L->ncontours; c++)
            for (size_t i = 0; i < L->contours[c].n; i++) {
                size_t e = L->contours[c].first + i, iu0, iv0, iu1, iv1;
                edge_cells(G, e, &iu0, &iv0, &iu1, &iv1);
                for (size_t y = iv0; y <= iv1; y++)
                    for (size_t x = iu0; x <= iu1; x++) {
                        size_t k = y * g + x;
                        if (pass == 0) G->first[k + 1]++;
                        else G->items[G->first[k]++] = e;
                    }
            }
        if (pass == 0) {
            for (size_t k = 0; k < g * g; k++) G->first[k + 1] += G->first[k];
        } else {
            /* first[k] now holds the end of cell k: shift back */
            for (size_t k = g * g; k > 0; k--) G->first[k] = G->first[k - 1];
            G->first[0] = 0;
        }
    }
    return 0;
}

/* Distance from m along +-n (unit) to the nearest edge of the layer other
 * than `self`, looking no further than r; r when there is none. */
static double clearance(const egrid *G, size_t self, const double m[2], const double n[2], double r)
{
    double best = r;
    size_t iu0 = cell(m[0] - r * fabs(n[0]), G->u0, G->cu, G->g);
    size_t iu1 = cell(m[0] + r * fabs(n[0]), G->u0, G->cu, G->g);
    size_t iv0 = cell(m[1] - r * fabs(n[1]), G->v0, G->cv, G->g);
    size_t iv1 = cell(m[1] + r * fabs(n[1]), G->v0, G->cv, G->g);
    for (size_t y = iv0; y <= iv1; y++)
        for (size_t x = iu0; x <= iu1; x++) {
            size_t k = y * G->g + x;
            for (size_t q = G->first[k]; q < G->first[k + 1]; q++) {
                size_t e = G->items[q];
                if (e == self) continue;
                const double *a = G->uv + 2 * e, *b = G->uv + 2 * G->nxt[e];
                double ex = b[0] - a[0], ey = b[1] - a[1];
                double ax = a[0] - m[0], ay = a[1] - m[1];
                double den = n[0] * ey - n[1] * ex;
                if (den == 0) {
                    /* parallel to the normal line: on it, it blocks at its
                     * nearest point */
                    if (ax * n[1] - ay * n[0] != 0) continue;
                    double sa = ax * n[0] + ay * n[1];
                    double sb = (b[0] - m[0]) * n[0] + (b[1] - m[1]) * n[1];
                    double d = (sa > 0) == (sb > 0) && sa != 0 && sb != 0 ? fmin(fabs(sa), fabs(sb)) : 0;
                    if (d < best) best = d;
                    continue;
                }
                double s = (ax * ey - ay * ex) / den;  /* along the normal */
                double t = (ax * n[1] - ay * n[0]) / den; /* along the edge */
                if (t < 0 || t > 1) continue;
                if (fabs(s) < best) best = fabs(s);
            }
        }
    return best;
}

/* ---- layers ------------------------------------------------------------------------ */

#define EDGES_TESTED 4
#define EDGES_TRIED 8

static const char *WHY_OK = "confirmed";
static const char *WHY_VOID = "the label says material here but the point is outside the part";
static const char *WHY_SOLID = "the label says void here but the point is inside the part";
static const char *WHY_OVERLAP =
    "the label says void here but bodies overlap here (an even winding: void under evenodd, "
    "material under nonzero)";
static const char *WHY_NOPOINT =
    "not checked: no edge is long enough or far enough from the others for a test point above "
    "float32 precision";
static const char *WHY_UNDECIDED = "not checked: the winding could not be decided at any test point";

/* Winding at (u, v) on layer L: at the cut height, or, when that point is on
 * the surface (a flat face in the cut plane), a small step toward the inside
 * of the slab. */
static int layer_point(lam_validator *v, const lam_layer *L, const lam_frame *f, const double uv[2],
                       double xyz[3], int *w)
{
    int up = !(L->cut >= L->ceiling && L->ceiling > L->floor);
    static const double steps[3] = { 0, 4, 32 };
    for (int i = 0; i < 3; i++) {
        double h = L->cut + (up ? 1 : -1) * steps[i] * v->tol;
        lam_frame_to_model(f, uv[0], uv[1], h, xyz);
        int r = winding_at(v, xyz, w);
        if (r != W_SURFACE) return r;
    }
    return W_UNDECIDED;
}

int lam_validate_layer(lam_validator *v, const lam_layer *L, const lam_frame *f, int fill_nonzero,
                       lam_layer_check *out, lam_error *err)
{
    memset(out, 0, sizeof *out);
    out->index = L->index;
    if (!L->ncontours) return LAM_OK;
    out->items = calloc(L->ncontours, sizeof *out->items);
    if (!out->items) return nomem(err);
    out->nitems = L->ncontours;
    egrid G;
    if (egrid_build(&G, L)) {
        egrid_free(&G);
        lam_layer_check_free(out);
        return nomem(err);
    }
    for (size_t ci = 0; ci < L->ncontours; ci++) {
        const lam_contour *c = &L->contours[ci];
        lam_contour_check *it = &out->items[ci];
        it->contour = ci;
        it->ok = -1;
        it->why = WHY_NOPOINT;
        const double *pts = L->uv + 2 * c->first;
        if (c->n < 3) {
            out->unchecked++;
            continue;
        }
        int interior_left = lam_loop_area(pts, c->n) > 0;
        int interior_material = c->kind == LAM_SOLID;
        /* the longest edges (ties: the first) */
        size_t cand[EDGES_TRIED];
        double clen[EDGES_TRIED];
        size_t ncand = 0;
        for (size_t i = 0; i < c->n; i++) {
            const double *a = pts + 2 * i, *b = pts + 2 * ((i + 1) % c->n);
            double len = hypot(b[0] - a[0], b[1] - a[1]);
            if (!(len > 0)) continue;
            size_t pos = ncand;
            while (pos > 0 && clen[pos - 1] < len) pos--;
            if (pos >= EDGES_TRIED) continue;
            size_t last = ncand < EDGES_TRIED ? ncand : EDGES_TRIED - 1;
            for (size_t q = last; q > pos; q--) {
                cand[q] = cand[q - 1];
                clen[q] = clen[q - 1];
            }
            cand[pos] = i;
            clen[pos] = len;
            if (ncand < EDGES_TRIED) ncand++;
        }
        int have_first = 0, disagree = 0, undecided = 0;
        for (size_t q = 0; q < ncand && it->edges < EDGES_TESTED; q++) {
            size_t i = cand[q];
            const double *a = pts + 2 * i, *b = pts + 2 * ((i + 1) % c->n);
            double len = clen[q];
            double m[2] = { a[0] + (b[0] - a[0]) / 2, a[1] + (b[1] - a[1]) / 2 };
            double nl[2] = { -(b[1] - a[1]) / len, (b[0] - a[0]) / len };
            double r = fmin(v->dtarget, len / 4);
            double d = fmin(r, clearance(&G, c->first + i, m, nl, 2 * r) / 2);
            if (!(d >= v->dmin)) continue;
            double side_uv[2][2] = { { m[0] + d * nl[0], m[1] + d * nl[1] },
                                     { m[0] - d * nl[0], m[1] - d * nl[1] } };
            double side_xyz[2][3];
            int wind[2], r0 = W_DECIDED;
            for (int sd = 0; sd < 2 && r0 == W_DECIDED; sd++) {
                r0 = layer_point(v, L, f, side_uv[sd], side_xyz[sd], &wind[sd]);
                if (r0 == W_NOMEM) {
                    egrid_free(&G);
                    lam_layer_check_free(out);
                    return nomem(err);
                }
            }
            if (r0 != W_DECIDED) {
                undecided = 1;
                continue;
            }
            it->edges++;
            for (int sd = 0; sd < 2; sd++) {
                int interior = sd == 0 ? interior_left : !interior_left;
                int expect = interior ? interior_material : !interior_material;
                int truth = wind[sd] != 0;
                int bad = truth != expect;
                if (!have_first || (bad && !disagree)) {
                    memcpy(it->uv, side_uv[sd], sizeof it->uv);
                    memcpy(it->xyz, side_xyz[sd], sizeof it->xyz);
                    it->winding_found = wind[sd];
                    it->expected_material = expect;
                    have_first = 1;
                }
                if (bad && !disagree) {
                    disagree = 1;
                    if (expect) it->why = WHY_VOID;
                    else if (!fill_nonzero && wind[sd] % 2 == 0) it->why = WHY_OVERLAP;
                    else it->why = WHY_SOLID;
                }
            }
        }
        if (!it->edges) {
            if (undecided) it->why = WHY_UNDECIDED;
            out->unchecked++;
            continue;
        }
        out->checked++;
        if (disagree) {
            it->ok = 0;
            out->disagreeing++;
        } else {
            it->ok = 1;
            it->why = WHY_OK;
            out->confirmed++;
        }
    }
    egrid_free(&G);
    return LAM_OK;
}

void lam_layer_check_free(lam_layer_check *c)
{
    if (!c) return;
    free(c->items);
    memset(c, 0, sizeof *c);
}

void lam_layer_flip_label_for_test(lam_layer *L, size_t contour)
{
    if (!L || contour >= L->ncontours) return;
    lam_contour *c = &L->contours[contour];
    c->kind = c->kind == LAM_SOLID ? LAM_HOLE : LAM_SOLID;
}
