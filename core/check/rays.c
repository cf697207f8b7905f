/* The Embree scene, the ray cast and the winding vote; see rays.h. */
#include "rays.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "embree_lazy.h"
#include "grow.h"
#include "section.h"

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

const double *lam_rays_direction(size_t k) { return k < NDIRS ? DIRS[k] : NULL; }

/* ---- the scene ------------------------------------------------------------------ */

typedef struct hit {
    double s;          /* distance from the query point along the ray */
    float t;           /* Embree's hit distance from the ray origin */
    uint32_t prim;
    int ng;            /* sign of dir . Ng (Embree's float normal) */
} hit;

struct lam_rays {
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
    double tol;             /* float32 tolerance: same-distance grouping of hits */
    double on_eps;          /* double rounding: a point this near a triangle's plane is in it */
    double dmin, dtarget;   /* smallest and preferred inset of layer test points */
    lam_section_index *sec; /* the model's sections along the last frame asked for */
    hit *hits;              /* hits of the ray being cast (filled by the filter) */
    size_t nhits, cap;
    int nomem;
    int ecode;              /* first Embree error reported to the callback */
    char emsg[256];
    lam_rays_stats st;
    lam_rays *parent;       /* a fork's (lam_rays_fork): it owns the device and the scene */
};

/* Intersection context handed to the filter: Embree's first, so the
 * filter gets back to the lam_rays from args->context. */
typedef struct ray_ctx {
    struct RTCIntersectContext rtc;
    lam_rays *v;
    int cross;              /* a crossing query (lam_rays_crossed_edges): */
    uint32_t ea, eb;        /* the edge's ends, whose triangles do not count */
    size_t calls;           /* filter calls: the query's work */
} ray_ctx;

static int touches(const lam_mesh *m, uint32_t t, uint32_t a, uint32_t b);

/* The crossing query's filter: a hit on a triangle of the edge's ends is
 * rejected, any other accepted, so that Embree keeps only the nearest and
 * looks no further than it (a stack of overlapping facets would otherwise
 * give each edge thousands of hits to gather). */
static void first_cross(const struct RTCFilterFunctionNArguments *a, ray_ctx *c)
{
    const unsigned *hu = (const unsigned *)a->hit;
    for (unsigned i = 0; i < a->N; i++) {
        if (!a->valid[i]) continue;
        c->calls++;
        if (touches(&c->v->m->mesh, hu[5 * a->N + i], c->ea, c->eb)) a->valid[i] = 0;
    }
}

static int nomem(lam_error *err) { return lam_error_nomem(err, "while validating"); }

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
    lam_rays *v = user;
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
    if (c->cross) {
        first_cross(a, c);
        return;
    }
    lam_rays *v = c->v;
    const unsigned N = a->N;
    const float *ray = (const float *)a->ray;
    const float *hf = (const float *)a->hit;
    const unsigned *hu = (const unsigned *)a->hit;
    for (unsigned i = 0; i < N; i++) {
        if (!a->valid[i]) continue;
        a->valid[i] = 0;
        if (v->nhits == v->cap) {
            hit *h = lam_grow(v->hits, &v->cap, v->nhits + 1, sizeof *h, 64);
            if (!h) {
                v->nomem = 1;
                continue;
            }
            v->hits = h;
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

/* The model's extent, the scale and tolerances that follow from it, and
 * the ray directions in float and double. Errors: LAM_EGEOM (a model no
 * double can measure). */
static int measure(lam_rays *v, const lam_mesh *mesh, lam_error *err)
{
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
        if (!isfinite(v->scale))
            return lam_error_set(err, LAM_EGEOM, NULL, 0, 0,
                                 "the model spans more than a double can measure: nothing to check");
        v->scale = 1;
    }
    v->unit = v->scale;
    /* Embree works in float: vertices, ray origins and hit distances are
     * good to a few ulps of the largest coordinate. */
    v->tol = fmax(1e-6 * v->scale, 16 * FLT_EPSILON * v->maxabs);
    v->dmin = fmax(1e-5 * v->scale, 1e3 * FLT_EPSILON * v->maxabs);
    v->dtarget = fmax(1e-3 * v->scale, 4 * v->dmin);
    double mag = 0;
    for (int k = 0; k < 3; k++) mag = fmax(mag, fabs(v->center[k]));
    v->on_eps = 64 * DBL_EPSILON * (mag + v->maxabs);
    for (int k = 0; k < NDIRS; k++)
        for (int j = 0; j < 3; j++) {
            v->dirf[k][j] = (float)DIRS[k][j];
            v->dird[k][j] = v->dirf[k][j];
        }
    return LAM_OK;
}

/* The model's triangles, centred and scaled (see lam_rays), as one
 * geometry of v's scene with the gathering filter; Embree's errors reach
 * on_rtc_error. */
static void add_mesh(lam_rays *v, const lam_mesh *mesh)
{
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

int lam_rays_new(const lam_model *m, lam_rays **out, lam_error *err)
{
    *out = NULL;
    if (!m) return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "no model to validate against");
    const lam_mesh *mesh = &m->mesh;
    if (mesh->nverts > UINT32_MAX)
        return lam_error_set(err, LAM_EGEOM, NULL, 0, 0, "too many vertices for Embree");
    int rc = lam_embree_load(err);
    if (rc) return rc;
    lam_rays *v = calloc(1, sizeof *v);
    if (!v) return nomem(err);
    v->m = m;
    v->ecode = RTC_ERROR_NONE;

    if ((rc = measure(v, mesh, err))) {
        free(v);
        return rc;
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
    if (v->scene && mesh->ntris) add_mesh(v, mesh);
    if (v->scene && v->ecode == RTC_ERROR_NONE) rtcCommitScene(v->scene);
    enum RTCError e = rtcGetDeviceError(v->dev);
    if (v->ecode == RTC_ERROR_NONE && (e != RTC_ERROR_NONE || !v->scene)) {
        v->ecode = e != RTC_ERROR_NONE ? (int)e : RTC_ERROR_UNKNOWN;
        snprintf(v->emsg, sizeof v->emsg, "%s", rtc_error_name((enum RTCError)v->ecode));
    }
    if (v->ecode != RTC_ERROR_NONE) {
        rc = lam_error_set(err, LAM_EGEOM, NULL, 0, 0, "Embree: %s", v->emsg);
        lam_rays_free(v);
        return rc;
    }
    *out = v;
    return LAM_OK;
}

int lam_rays_fork(lam_rays *v, lam_rays **out, lam_error *err)
{
    *out = NULL;
    lam_rays *f = malloc(sizeof *f);
    if (!f) return nomem(err);
    *f = *v;
    f->sec = NULL;
    f->hits = NULL;
    f->nhits = f->cap = 0;
    f->nomem = 0;
    memset(&f->st, 0, sizeof f->st);
    f->parent = v;
    if (v->sec && lam_section_index_fork(v->sec, &f->sec, err)) {
        free(f);
        return LAM_ENOMEM;
    }
    *out = f;
    return LAM_OK;
}

static void add_stats(lam_rays_stats *to, const lam_rays_stats *s)
{
    to->points += s->points;
    to->rays += s->rays;
    to->recasts += s->recasts;
    to->unreliable += s->unreliable;
    to->surface += s->surface;
    to->undecided += s->undecided;
}

void lam_rays_free(lam_rays *v)
{
    if (!v) return;
    if (v->parent) {
        add_stats(&v->parent->st, &v->st);
    } else {
        if (v->scene) rtcReleaseScene(v->scene);
        if (v->dev) rtcReleaseDevice(v->dev);
    }
    lam_section_index_free(v->sec);
    free(v->hits);
    free(v);
}

double lam_rays_tolerance(const lam_rays *v) { return v->tol; }
double lam_rays_min_inset(const lam_rays *v) { return v->dmin; }
double lam_rays_target_inset(const lam_rays *v) { return v->dtarget; }
double lam_rays_scale(const lam_rays *v) { return v->scale; }

int lam_rays_section(lam_rays *v, const lam_frame *f, lam_section_index **out, lam_error *err)
{
    if (v->sec && !memcmp(lam_section_index_frame(v->sec), f, sizeof *f)) {
        *out = v->sec;
        return LAM_OK;
    }
    lam_section_index_free(v->sec);
    v->sec = NULL;
    int rc = lam_section_index_new(v->m, f, &v->sec, err);
    *out = v->sec;
    return rc;
}

void lam_rays_get_stats(const lam_rays *v, lam_rays_stats *st) { *st = v->st; }

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
static int tri_sign(const lam_rays *v, uint32_t t, const double d[3])
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

/* Triangle t's unit normal (model's double vertices) into n and the signed
 * distance of p from its plane (> 0 on the normal's side); 0 for a
 * degenerate triangle (n then zero). */
static int tri_plane(const lam_rays *v, uint32_t t, const double p[3], double n[3], double *dist)
{
    const lam_mesh *m = &v->m->mesh;
    const double *a = m->xyz + 3 * (size_t)m->tris[3 * (size_t)t];
    const double *b = m->xyz + 3 * (size_t)m->tris[3 * (size_t)t + 1];
    const double *c = m->xyz + 3 * (size_t)m->tris[3 * (size_t)t + 2];
    double e1[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    double e2[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(len > 0)) return 0;
    for (int k = 0; k < 3; k++) n[k] /= len;
    *dist = n[0] * (p[0] - a[0]) + n[1] * (p[1] - a[1]) + n[2] * (p[2] - a[2]);
    return 1;
}

/* Cast one ray from o along d, gathering every hit into v->hits (the
 * filter rejects each hit so traversal goes on). Non-zero when the hit list
 * could not grow. */
static int trace_to(lam_rays *v, const float o[3], const float d[3], float tfar)
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
    rh.ray.tfar = tfar;
    rh.ray.mask = UINT32_MAX;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    ray_ctx c;
    memset(&c, 0, sizeof c);
    rtcInitIntersectContext(&c.rtc);
    c.v = v;
    v->nhits = 0;
    v->nomem = 0;
    rtcIntersect1(v->scene, &c.rtc, &rh);
    v->st.rays++;
    return v->nomem;
}

static int trace(lam_rays *v, const float o[3], const float d[3]) { return trace_to(v, o, d, INFINITY); }

/* Does triangle t have vertex a or b? */
static int touches(const lam_mesh *m, uint32_t t, uint32_t a, uint32_t b)
{
    const uint32_t *tv = m->tris + 3 * (size_t)t;
    for (int k = 0; k < 3; k++)
        if (tv[k] == a || tv[k] == b) return 1;
    return 0;
}

/* The work a crossing count may take (filter calls, edges cast): past it
 * the count stops and says it is incomplete. */
#define CROSS_BUDGET 50000000u
#define CROSS_EDGES 2000000u

/* The box of the triangles from `first` on, grown by a thousandth of the
 * model: the edges that can cross them lie in it. */
static void fill_box(const lam_model *md, size_t first, double box[6])
{
    const lam_mesh *m = &md->mesh;
    for (int k = 0; k < 3; k++) box[k] = INFINITY, box[k + 3] = -INFINITY;
    for (size_t i = 3 * first; i < 3 * m->ntris; i++)
        for (int k = 0; k < 3; k++) {
            double x = m->xyz[3 * (size_t)m->tris[i] + k];
            if (x < box[k]) box[k] = x;
            if (x > box[k + 3]) box[k + 3] = x;
        }
    const double *b = md->stats.bbox;
    double g = 1e-3 * fmax(b[3] - b[0], fmax(b[4] - b[1], b[5] - b[2]));
    for (int k = 0; k < 3; k++) box[k] -= g, box[k + 3] += g;
}

/* Is edge e one to cast: an edge of a triangle from `first` on, or one
 * whose box meets the box of those triangles? */
static int candidate(const lam_model *md, size_t e, size_t first, const double box[6])
{
    for (uint32_t j = md->edges.first[e]; j < md->edges.first[e + 1]; j++)
        if (md->edges.tris[j] >= first) return 1;
    const double *p = md->mesh.xyz + 3 * (size_t)md->edges.v[2 * e], *q = md->mesh.xyz + 3 * (size_t)md->edges.v[2 * e + 1];
    for (int k = 0; k < 3; k++)
        if (fmax(p[k], q[k]) < box[k] || fmin(p[k], q[k]) > box[k + 3]) return 0;
    return 1;
}

int lam_rays_crossed_edges(lam_rays *v, size_t first, size_t *count, unsigned char *crossed, lam_error *err)
{
    const lam_model *md = v->m;
    const lam_mesh *m = &md->mesh;
    *count = 0;
    if (first >= m->ntris) return LAM_OK;
    double box[6];
    fill_box(md, first, box);
    ray_ctx c;
    memset(&c, 0, sizeof c);
    c.v = v;
    c.cross = 1;
    size_t cast = 0;
    for (size_t e = 0; e < md->edges.n; e++) {
        if (!candidate(md, e, first, box)) continue;
        if (c.calls > CROSS_BUDGET || ++cast > CROSS_EDGES)
            return lam_error_set(err, LAM_ELIMIT, NULL, 0, 0, "counting self-intersections: past the budget");
        c.ea = md->edges.v[2 * e], c.eb = md->edges.v[2 * e + 1];
        struct RTCRayHit rh;
        memset(&rh, 0, sizeof rh);
        float o[3], d[3];
        for (int j = 0; j < 3; j++) {
            o[j] = (float)((m->xyz[3 * (size_t)c.ea + j] - v->center[j]) / v->unit);
            d[j] = (float)((m->xyz[3 * (size_t)c.eb + j] - v->center[j]) / v->unit) - o[j];
        }
        /* the segment a -> b is t in (0, 1); hits on the triangles at its
         * ends are theirs (they share a or b), any other is a crossing */
        rh.ray.org_x = o[0], rh.ray.org_y = o[1], rh.ray.org_z = o[2];
        rh.ray.dir_x = d[0], rh.ray.dir_y = d[1], rh.ray.dir_z = d[2];
        rh.ray.tnear = 0;
        rh.ray.tfar = 1;
        rh.ray.mask = UINT32_MAX;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcInitIntersectContext(&c.rtc);
        rtcIntersect1(v->scene, &c.rtc, &rh);
        v->st.rays++;
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID || !(rh.ray.tfar > 0 && rh.ray.tfar < 1)) continue;
        int filled = rh.hit.primID >= first;
        for (uint32_t j = md->edges.first[e]; j < md->edges.first[e + 1] && !filled; j++)
            filled = md->edges.tris[j] >= first;
        if (!filled) continue; /* the file's own crossing: not what is counted */
        (*count)++;
        if (crossed) {
            crossed[rh.hit.primID] = 1;
            for (uint32_t j = md->edges.first[e]; j < md->edges.first[e + 1]; j++) crossed[md->edges.tris[j]] = 1;
        }
    }
    return LAM_OK;
}

/* A point of a section: (u, v) at height h along the frame's w, taken just
 * above the plane (below 0) or just below it (below 1), as the slicer has it. */
typedef struct section_pt {
    const lam_frame *f;
    double u, v, h;
    int below;
} section_pt;

static double dot_skip(const double *p, const double *a)
{
    double s = 0;
    for (int k = 0; k < 3; k++)
        if (a[k] != 0) s += p[k] * a[k];
    return s;
}

/* Triangle t against section point q whose plane it (nearly) contains:
 * +1 when it passes above q, -1 below, from its vertices' heights along w
 * compared with h as the slicer compares them (a face lying in the plane is
 * on the far side of the symbolic step); 0 when it passes through q itself
 * or stands on edge. */
static int tri_side(const lam_rays *v, uint32_t t, const section_pt *q)
{
    const lam_mesh *m = &v->m->mesh;
    double U[3], V[3], W[3];
    int flat = 1;
    for (int i = 0; i < 3; i++) {
        const double *x = m->xyz + 3 * (size_t)m->tris[3 * (size_t)t + i];
        U[i] = dot_skip(x, q->f->u) - q->u;
        V[i] = dot_skip(x, q->f->v) - q->v;
        W[i] = dot_skip(x, q->f->w) - q->h;
        flat &= W[i] == 0;
    }
    if (flat) return q->below ? 1 : -1;
    double area = (U[1] - U[0]) * (V[2] - V[0]) - (V[1] - V[0]) * (U[2] - U[0]);
    if (area == 0) return 0;
    /* the height of the triangle's plane over q, times area */
    double c0 = U[1] * V[2] - V[1] * U[2], c1 = U[2] * V[0] - V[2] * U[0], c2 = U[0] * V[1] - V[0] * U[1];
    double hgt = c0 * W[0] + c1 * W[1] + c2 * W[2];
    if (hgt == 0) return 0;
    return (hgt > 0) == (area > 0) ? 1 : -1;
}

/* The winding along a ray in direction d from its hits h[0..n) (sorted by
 * s, each once): the crossings ahead (s >= 0), one per shell at one place
 * along the ray. CAST_OK with *w, or CAST_UNRELIABLE (a grazed edge or
 * silhouette). */
static int crossings(const lam_rays *v, hit *h, size_t n, const double *d, int *w)
{
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

/* Cast direction k from p (a section point q when not NULL); on CAST_OK *w
 * is the winding along that ray. */
static int cast_dir(lam_rays *v, const double p[3], const section_pt *q, int k, int *w)
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
    for (size_t i = 0; i < n; i++) {
        h[i].s = ((double)h[i].t * v->unit - sp) * len;
        /* near p, float32 cannot say on which side of the triangle p lies:
         * place the crossing again from the double vertices */
        if (!(fabs(h[i].s) <= 8 * v->tol)) continue;
        double nrm[3], dist;
        if (!tri_plane(v, h[i].prim, p, nrm, &dist)) continue;
        double nd = nrm[0] * d[0] + nrm[1] * d[1] + nrm[2] * d[2];
        if (nd == 0) return CAST_UNRELIABLE;
        if (fabs(dist) > v->on_eps) {
            h[i].s = -dist / nd;
            continue;
        }
        /* p is in the triangle's plane, to double rounding: at a section,
         * the side the triangle passes p on decides, as the slicer sees it
         * from the vertices' heights, and the ray meets it ahead when it
         * heads that way (along w when above) */
        int side = q ? tri_side(v, h[i].prim, q) : 0;
        double nw = q ? nrm[0] * q->f->w[0] + nrm[1] * q->f->w[1] + nrm[2] * q->f->w[2] : 0;
        /* a steep triangle this near p would cross the plane at p: p is
         * on the section's boundary, which test points keep away from */
        if (!side || !(fabs(nw) >= 0.5)) return CAST_SURFACE;
        h[i].s = (side > 0) == ((nw > 0) == (nd > 0)) ? 0.0 : -1.0;
    }
    /* a primitive may be reported more than once (spatial splits): keep one */
    if (n > 1) qsort(h, n, sizeof *h, by_prim);
    size_t u = 0;
    for (size_t i = 0; i < n; i++)
        if (u == 0 || h[i].prim != h[u - 1].prim) h[u++] = h[i];
    n = u;
    if (n > 1) qsort(h, n, sizeof *h, by_s);

    return crossings(v, h, n, d, w);
}

int lam_rays_cast(lam_rays *v, const double p[3], const double d[3], double tmin, double *t, uint32_t *tri,
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

int lam_rays_vote(const int *w, size_t n, size_t *count)
{
    int best = w[0];
    size_t bestn = 0;
    for (size_t i = 0; i < n; i++) {
        size_t c = 0;
        for (size_t j = 0; j < n; j++) c += w[j] == w[i];
        if (c > bestn) {
            bestn = c;
            best = w[i];
        }
    }
    *count = bestn;
    return best;
}

static int winding_at(lam_rays *v, const double p[3], const section_pt *q, int *w)
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
        int x = 0, r = cast_dir(v, p, q, k, &x);
        if (r == CAST_NOMEM) return W_NOMEM;
        if (r == CAST_SURFACE) {
            v->st.surface++;
            return W_SURFACE;
        }
        if (r == CAST_OK) vals[nrel++] = x;
        else v->st.unreliable++;
    }
    size_t bestn = 0;
    int best = nrel ? lam_rays_vote(vals, (size_t)nrel, &bestn) : 0;
    if (bestn >= 3 && 2 * bestn > (size_t)nrel) {
        *w = best;
        return W_DECIDED;
    }
    v->st.undecided++;
    return W_UNDECIDED;
}

static int winding_result(lam_rays *v, const double p[3], const section_pt *q, int *winding,
                          lam_error *err);

int lam_rays_winding(lam_rays *v, const double p[3], int *winding, lam_error *err)
{
    return winding_result(v, p, NULL, winding, err);
}

int lam_rays_winding_section(lam_rays *v, const lam_frame *f, double u, double w, double h, int below,
                                  double xyz[3], int *winding, lam_error *err)
{
    section_pt q = { f, u, w, h, below };
    lam_frame_to_model(f, u, w, h, xyz);
    return winding_result(v, xyz, &q, winding, err);
}

static int winding_result(lam_rays *v, const double p[3], const section_pt *q, int *winding,
                          lam_error *err)
{
    int w = 0;
    switch (winding_at(v, p, q, &w)) {
    case W_DECIDED:
        *winding = w;
        return LAM_OK;
    case W_SURFACE:
        return lam_error_set(err, LAM_EGEOM, NULL, 0, 0,
                             "the point (%.17g, %.17g, %.17g) is on the surface (within %g): "
                             "it has no winding number",
                             p[0], p[1], p[2], v->on_eps);
    case W_NOMEM:
        return nomem(err);
    }
    return lam_error_set(err, LAM_EGEOM, NULL, 0, 0, "cannot decide the winding at (%.17g, %.17g, %.17g)",
                         p[0], p[1], p[2]);
}

