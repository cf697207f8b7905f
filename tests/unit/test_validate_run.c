/* validate_run.h: the layer checks of a run on 1, 2, 3 and 8 threads give
 * the very results of one thread (every number bit for bit, every contour
 * check byte for byte), handed back strictly in layer order; the rays'
 * statistics of the forks add up to a single thread's; the first error in
 * layer order wins, after exactly the layers before it; a report that
 * stops the run stops it there. And the forks underneath: a forked section
 * index measures what its parent measures. */
#include "meshes.h"
#include "rays.h"
#include "section.h"
#include "slice.h"
#include "validate.h"
#include "validate_run.h"

#include <stdlib.h>
#include <string.h>

#define MAXL 512

typedef struct got {
    size_t n;                     /* layers reported */
    int out_of_order;
    size_t index[MAXL];
    lam_layer_check chk[MAXL];    /* taken from the run */
    size_t stop_at;               /* report returns 42 here (MAXL: never) */
} got;

static int collect(void *ctx, size_t i, const lam_vlayer *l, lam_layer_check *chk, lam_error *err)
{
    (void)err;
    got *g = ctx;
    if (i != g->n || i >= MAXL) {
        g->out_of_order = 1;
        return LAM_OK;
    }
    g->index[i] = l->L->index;
    g->chk[i] = *chk;
    memset(chk, 0, sizeof *chk);
    g->n++;
    return i == g->stop_at ? 42 : LAM_OK;
}

static void got_init(got *g)
{
    memset(g, 0, sizeof *g);
    g->stop_at = MAXL;
}

static void got_free(got *g)
{
    for (size_t i = 0; i < g->n; i++) lam_layer_check_free(&g->chk[i]);
}

static int same_bits(double a, double b) { return !memcmp(&a, &b, sizeof a); }

/* Layer check a against b: counts, areas bit for bit, each contour's check
 * byte for byte (its texts are static, so their pointers agree too). */
static int same_check(const lam_layer_check *a, const lam_layer_check *b)
{
    if (a->index != b->index || a->checked != b->checked || a->confirmed != b->confirmed ||
        a->disagreeing != b->disagreeing || a->unchecked != b->unchecked || a->nitems != b->nitems ||
        a->area_checked != b->area_checked || a->area_ok != b->area_ok || a->area_why != b->area_why)
        return 0;
    if (!same_bits(a->net_area, b->net_area) || !same_bits(a->section_area, b->section_area) ||
        !same_bits(a->area_tolerance, b->area_tolerance))
        return 0;
    return !a->nitems || !memcmp(a->items, b->items, a->nitems * sizeof *a->items);
}

static void runs(const char *name, const lam_slice_opts *so, size_t min_disagreeing)
{
    lam_model *m = load_model(name);
    if (!m) return;
    lam_error err;
    lam_error_clear(&err);
    lam_slicer *s = NULL;
    lam_rays *v = NULL;
    if (lam_slicer_new(m, so, &s, &err) || lam_rays_new(m, &v, &err)) {
        ok(0, "%s: slicer and rays (%s)", name, err.msg);
        lam_slicer_free(s);
        lam_model_free(m);
        return;
    }
    size_t S = lam_slicer_count(s);
    static got one, many;
    got_init(&one);
    lam_rays_stats st0, st1, st2;
    lam_rays_get_stats(v, &st0);
    int rc = lam_validate_slicer(s, v, NULL, 1, collect, &one, &err);
    lam_rays_get_stats(v, &st1);
    size_t points1 = st1.points - st0.points, rays1 = st1.rays - st0.rays;
    size_t dis = 0;
    for (size_t i = 0; i < one.n; i++) dis += one.chk[i].disagreeing;
    ok(rc == LAM_OK && one.n == S && S > 4 && !one.out_of_order && dis >= min_disagreeing,
       "%s: one thread checks all %zu layers in order (%zu disagreeing)", name, S, dis);
    for (unsigned threads = 2; threads <= 8; threads += threads == 3 ? 5 : 1) {
        got_init(&many);
        lam_slicer_seek(s, 0);
        rc = lam_validate_slicer(s, v, NULL, threads, collect, &many, &err);
        lam_rays_get_stats(v, &st2);
        int same = rc == LAM_OK && many.n == one.n && !many.out_of_order;
        size_t first_diff = SIZE_MAX;
        for (size_t i = 0; same && i < many.n; i++)
            if (many.index[i] != i || !same_check(&one.chk[i], &many.chk[i])) {
                same = 0;
                first_diff = i;
            }
        ok(same, "%s: %u threads: every layer's check is one thread's, in layer order", name, threads);
        if (first_diff != SIZE_MAX) diag("first difference at layer %zu", first_diff + 1);
        /* the forks' statistics were added to v's when they were freed */
        ok(st2.points - st1.points == points1 && st2.rays - st1.rays == rays1 && points1 > 0,
           "%s: %u threads: the forks' %zu winding queries and %zu rays, as one thread's", name, threads,
           (size_t)(st2.points - st1.points), (size_t)(st2.rays - st1.rays));
        st1 = st2;
        got_free(&many);
    }
    /* a report that stops the run */
    for (unsigned threads = 1; threads <= 8; threads *= 2) {
        got_init(&many);
        many.stop_at = 3;
        lam_slicer_seek(s, 0);
        rc = lam_validate_slicer(s, v, NULL, threads, collect, &many, &err);
        ok(rc == 42 && many.n == 4 && !many.out_of_order,
           "%s: %u threads: the report's stop after layer 4 is the run's result, nothing reported after", name,
           threads);
        got_free(&many);
    }
    got_free(&one);
    lam_rays_free(v);
    lam_slicer_free(s);
    lam_model_free(m);
}

/* ---- a source that fails ---------------------------------------------------------- */

typedef struct list {
    lam_layer *L[MAXL];
    size_t n;
    const lam_frame *f;
    int owned;                    /* hand out clones the run frees */
} list;

static int list_make(void *ctx, unsigned worker, lam_rays *v, size_t i, lam_vlayer *out, lam_error *err)
{
    (void)worker, (void)v;
    list *x = ctx;
    if (i == 5 || i == 7) return lam_error_set(err, LAM_EINVAL, "prog", (long)i + 1, 1, "layer %zu is bad", i + 1);
    out->f = x->f;
    lam_validate_opts_init(&out->o);
    if (x->owned) {
        if (!(out->owned = lam_layer_clone(x->L[i]))) return lam_error_nomem(err, "cloning");
        out->L = out->owned;
    } else {
        out->L = x->L[i];
    }
    return LAM_OK;
}

typedef struct lctx {
    list *x;
    got *g;
} lctx;

static int l_make(void *ctx, unsigned worker, lam_rays *v, size_t i, lam_vlayer *out, lam_error *err)
{
    return list_make(((lctx *)ctx)->x, worker, v, i, out, err);
}

static int l_report(void *ctx, size_t i, const lam_vlayer *l, lam_layer_check *chk, lam_error *err)
{
    return collect(((lctx *)ctx)->g, i, l, chk, err);
}

static void first_error(void)
{
    lam_model *m = load_model("frame_island.ug");
    if (!m) return;
    lam_error err;
    lam_error_clear(&err);
    lam_slice_opts so;
    lam_slice_opts_init(&so);
    so.width = 0.5;
    lam_slicer *s = NULL;
    lam_rays *v = NULL;
    static list x;
    memset(&x, 0, sizeof x);
    if (lam_slicer_new(m, &so, &s, &err) || lam_rays_new(m, &v, &err)) {
        ok(0, "frame_island: slicer and rays (%s)", err.msg);
        goto done;
    }
    x.f = lam_slicer_frame(s);
    for (lam_layer *L; x.n < MAXL && !lam_slicer_next(s, &L, &err) && L;) x.L[x.n++] = L;
    ok(x.n > 12, "frame_island: %zu layers sliced", x.n);
    for (int owned = 0; owned < 2; owned++)
        for (unsigned threads = 1; threads <= 8; threads *= 2) {
            static got g;
            got_init(&g);
            x.owned = owned;
            lctx c = { &x, &g };
            lam_error_clear(&err);
            int rc = lam_validate_layers(v, x.n, threads, x.f, l_make, l_report, &c, &err);
            ok(rc == LAM_EINVAL && err.line == 6 && !strcmp(err.msg, "layer 6 is bad") && g.n == 5 && !g.out_of_order,
               "%s layers, %u threads: layer 6's error, after layers 1-5 and none later (got %d '%s', %zu layers)",
               owned ? "owned" : "borrowed", threads, rc, err.msg, g.n);
            got_free(&g);
        }
done:
    for (size_t i = 0; i < x.n; i++) lam_layer_free(x.L[i]);
    lam_rays_free(v);
    lam_slicer_free(s);
    lam_model_free(m);
}

/* ---- a forked section index --------------------------------------------------------- */

static void section_fork(void)
{
    lam_model *m = load_model_quiet("validate/counterbores.ug");
    if (!m) {
        ok(0, "load counterbores.ug");
        return;
    }
    lam_error err;
    lam_frame f;
    lam_frame_axis('z', &f, &err);
    lam_section_index *x = NULL, *y = NULL, *z = NULL;
    double h0;
    int rc = lam_section_index_new(m, &f, &x, &err);
    if (!rc) rc = lam_section_index_fork(x, &y, &err); /* before x sorts its heights: y sorts its own */
    if (!rc) rc = lam_section_snap(x, 5, 0, &h0, &err);
    if (!rc) rc = lam_section_index_fork(x, &z, &err); /* after: z shares them */
    int same = !rc, snaps = !rc;
    for (int k = 0; same && k <= 100; k++) {
        double h = -0.5 + k * 0.11;
        for (int below = 0; below < 2; below++) {
            lam_section_measure a, b, c;
            lam_section_measure_at(x, h, below, &a);
            lam_section_measure_at(y, h, below, &b);
            lam_section_measure_at(z, h, below, &c);
            same &= !memcmp(&a, &b, sizeof a) && !memcmp(&a, &c, sizeof a);
        }
        double sx, sy, sz;
        lam_section_snap(x, h, 0.06, &sx, &err);
        lam_section_snap(y, h, 0.06, &sy, &err);
        lam_section_snap(z, h, 0.06, &sz, &err);
        snaps &= same_bits(sx, sy) && same_bits(sx, sz);
    }
    ok(same, "a forked section index measures its parent's sections (areas, perimeters, shells)");
    ok(snaps, "... and snaps heights as its parent does, with its own sorted heights or the parent's");
    lam_section_index_free(y);
    lam_section_index_free(z);
    lam_section_index_free(x);
    lam_model_free(m);
}

int main(void)
{
    lam_slice_opts so;
    lam_slice_opts_init(&so);
    so.width = 0.3;
    runs("thesis_cube_hole.ug", &so, 0);
    lam_slice_opts_init(&so);
    so.width = 0.25;
    so.cut = LAM_CUT_FLOOR;
    runs("frame_island.ug", &so, 0);
    lam_slice_opts_init(&so);
    double d[3] = { 1, 1, 2 };
    lam_error err;
    lam_frame_direction(d, &so.frame, &err);
    so.width = 0.2;
    runs("frame_island.stl", &so, 0);
    lam_slice_opts_init(&so);
    so.width = 0.25;
    runs("validate/overlap_cubes.ug", &so, 2);
    first_error();
    section_fork();
    return done_testing();
}
