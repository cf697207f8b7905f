/* Nesting of loops (core/layer/nest.c): the three methods against answers known
 * by construction. Layouts: cells of a grid, each holding a stack of
 * concentric squares or diamonds (so depth and parent are known), wound
 * either way, starting anywhere, with extra points on their sides; an
 * optional frame around everything; stacks whose squares touch (an inner
 * square standing on the bottom side of the one around it, as the thesis's
 * through hole cut lengthwise); a comb of squares all spanning the same
 * heights, where the tree sweep must not fall back. */
#include "nest.h"
#include "tap.h"
#include "util.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct layout {
    double *uv;
    size_t npts, cap;
    lam_nest_loop *loops;
    size_t nloops, cap_loops;
    int *want_depth;
    long *want_parent;
} layout;

static uint64_t rng = 0x9e3779b97f4a7c15ull;

static void grow(layout *L)
{
    if (L->npts + 64 > L->cap) {
        L->cap = L->cap ? 2 * L->cap : 1024;
        while (L->npts + 64 > L->cap) L->cap *= 2;
        L->uv = realloc(L->uv, 2 * L->cap * sizeof *L->uv);
    }
    if (L->nloops + 1 > L->cap_loops) {
        L->cap_loops = L->cap_loops ? 2 * L->cap_loops : 64;
        L->loops = realloc(L->loops, L->cap_loops * sizeof *L->loops);
        L->want_depth = realloc(L->want_depth, L->cap_loops * sizeof *L->want_depth);
        L->want_parent = realloc(L->want_parent, L->cap_loops * sizeof *L->want_parent);
    }
    if (!L->uv || !L->loops || !L->want_depth || !L->want_parent) abort();
}

/* A square (diamond when `turned`) of half-size h around (cu, cv), or one
 * standing on v = cv - h when `standing` (its bottom side there, h wide
 * and 2h tall): wound clockwise when cw, starting at corner `rot`, with a
 * point added in the middle of side `mid` (-1: none). The point just inside
 * is taken a hair into the corner at the lowest-leftmost vertex, as
 * contour.c takes it. */
static long add_loop(layout *L, double cu, double cv, double h, int turned, int cw, int rot, int mid,
                     int depth, long parent)
{
    grow(L);
    double c[4][2];
    if (turned) {
        double d[4][2] = { { cu, cv - h }, { cu + h, cv }, { cu, cv + h }, { cu - h, cv } };
        memcpy(c, d, sizeof c);
    } else {
        double d[4][2] = { { cu - h, cv - h }, { cu + h, cv - h }, { cu + h, cv + h }, { cu - h, cv + h } };
        memcpy(c, d, sizeof c);
    }
    lam_nest_loop *lp = &L->loops[L->nloops];
    lp->first = L->npts;
    size_t n = 0;
    for (int k = 0; k < 4; k++) {
        int a = cw ? (rot - k + 8) % 4 : (rot + k) % 4, b = cw ? (a + 3) % 4 : (a + 1) % 4;
        L->uv[2 * (lp->first + n)] = c[a][0];
        L->uv[2 * (lp->first + n) + 1] = c[a][1];
        n++;
        if (k == mid) {
            L->uv[2 * (lp->first + n)] = (c[a][0] + c[b][0]) / 2;
            L->uv[2 * (lp->first + n) + 1] = (c[a][1] + c[b][1]) / 2;
            n++;
        }
    }
    lp->n = n;
    L->npts += n;
    double area = 0;
    const double *p = L->uv + 2 * lp->first;
    for (size_t i = 0; i < n; i++) {
        size_t j = (i + 1) % n;
        area += p[2 * i] * p[2 * j + 1] - p[2 * j] * p[2 * i + 1];
    }
    lp->area = area / 2;
    /* lowest-leftmost corner, and a point a hair inside from it */
    double eps = 1e-6 * h;
    if (turned) {
        lp->q[0] = cu;
        lp->q[1] = cv - h + eps;
    } else {
        lp->q[0] = cu - h + eps;
        lp->q[1] = cv - h + eps;
    }
    L->want_depth[L->nloops] = depth;
    L->want_parent[L->nloops] = parent;
    return (long)L->nloops++;
}

/* Run one method on a copy of the loops; 1 when every depth and parent is
 * the known one. */
static int check(const layout *L, int method, int *agreed, char *why, size_t whylen)
{
    lam_nest_loop *li = malloc(L->nloops * sizeof *li + 1);
    if (L->nloops) memcpy(li, L->loops, L->nloops * sizeof *li);
    lam_error err;
    lam_error_clear(&err);
    int rc = lam_nest_method(L->uv, li, L->nloops, method, agreed, &err), good = rc == LAM_OK;
    for (size_t l = 0; l < L->nloops && good; l++) {
        if (li[l].depth != L->want_depth[l] || li[l].parent != L->want_parent[l]) {
            snprintf(why, whylen, "loop %zu: depth %d parent %ld, want %d and %ld", l, li[l].depth, li[l].parent,
                     L->want_depth[l], L->want_parent[l]);
            good = 0;
        }
    }
    free(li);
    return good;
}

/* A random layout: gx x gy cells, each a stack of 0..4 nested loops; with
 * a frame around all when framed; stacks touching when touching. */
static void make_layout(layout *L, int gx, int gy, int framed, int touching)
{
    memset(L, 0, sizeof *L);
    long frame = -1;
    int base = 0;
    if (framed) {
        frame = add_loop(L, gx * 5.0, gy * 5.0, gx * 5.0 + gy * 5.0 + 10, 0, (int)(xorshift64(&rng) & 1),
                         (int)(xorshift64(&rng) % 4), (int)(xorshift64(&rng) % 5) - 1, 0, -1);
        base = 1;
    }
    for (int i = 0; i < gx; i++)
        for (int j = 0; j < gy; j++) {
            int k = (int)(xorshift64(&rng) % 5);
            int turned = !touching && (xorshift64(&rng) & 1);
            long parent = frame;
            double cu = i * 10.0 + 5, cv = j * 10.0 + 5, h = 4;
            for (int d = 0; d < k; d++) {
                double hd = h * (1 - 0.2 * d);
                /* touching: each square stands on the bottom side of the
                 * one around it */
                double cvd = touching ? cv - h + hd : cv;
                parent = add_loop(L, cu, cvd, hd, turned, (int)(xorshift64(&rng) & 1), (int)(xorshift64(&rng) % 4),
                                  (int)(xorshift64(&rng) % 5) - 1, base + d, parent);
            }
        }
}

static void free_layout(layout *L)
{
    free(L->uv);
    free(L->loops);
    free(L->want_depth);
    free(L->want_parent);
}

int main(void)
{
    char why[200] = "";
    /* separate squares and diamonds, framed or not */
    for (int framed = 0; framed < 2; framed++) {
        int good[3] = { 1, 1, 1 }, all_agreed = 1;
        for (int round = 0; round < 60; round++) {
            layout L;
            make_layout(&L, 1 + round % 7, 1 + round % 5, framed, 0);
            for (int m = 0; m < 3; m++) {
                int agreed = 1;
                if (good[m] && !check(&L, m, &agreed, why, sizeof why)) {
                    good[m] = 0;
                    diag("method %d, round %d: %s", m, round, why);
                }
                if (m == 1 && !agreed) all_agreed = 0;
            }
            free_layout(&L);
        }
        ok(good[0], "each against each: nested stacks in a grid%s", framed ? " inside a frame" : "");
        ok(good[1], "tree sweep: nested stacks in a grid%s", framed ? " inside a frame" : "");
        ok(all_agreed, "tree sweep: no fall-back needed%s", framed ? " (framed)" : "");
        ok(good[2], "scan sweep: nested stacks in a grid%s", framed ? " inside a frame" : "");
    }
    /* touching loops: the answers must hold whichever way the tree sweep
     * goes (answering itself or falling back) */
    {
        int good[3] = { 1, 1, 1 };
        for (int round = 0; round < 60; round++) {
            layout L;
            make_layout(&L, 1 + round % 6, 1 + round % 4, round & 1, 1);
            for (int m = 0; m < 3; m++) {
                int agreed;
                if (good[m] && !check(&L, m, &agreed, why, sizeof why)) {
                    good[m] = 0;
                    diag("method %d, round %d: %s", m, round, why);
                }
            }
            free_layout(&L);
        }
        ok(good[0] && good[1] && good[2], "touching stacks (the thesis's hole on the outline): all three methods");
    }
    /* the comb: 3000 squares side by side, all spanning the same heights,
     * inside a frame, every other one holding a hole */
    {
        layout L;
        memset(&L, 0, sizeof L);
        long frame = add_loop(&L, 3000, 10, 3100, 0, 0, 0, -1, 0, -1);
        for (int i = 0; i < 3000; i++) {
            long s = add_loop(&L, 2.0 * i, 10, 0.8, 0, 1, 1, 2, 1, frame);
            if (i % 2 == 0) add_loop(&L, 2.0 * i, 10, 0.4, 0, 0, 3, -1, 2, s);
        }
        int agreed = 0;
        ok(check(&L, 1, &agreed, why, sizeof why), "comb of 3000 squares in a row: tree sweep right (%s)", why);
        ok(agreed, "comb: the tree sweep answered without falling back");
        ok(check(&L, 2, &agreed, why, sizeof why), "comb: scan sweep right too");
        free_layout(&L);
    }
    /* Regression: a layer of the thesis's cube with a hole cut along
     * (1, 2, 3). The hole's two lower sides run along the outline's lower
     * side (collinear), its lowest vertex lies on that side; rounding must
     * not put the vertex on one side of it. Loops as the slicer hands them
     * over (these start points once misled the tree sweep). */
    {
        double uv[] = { -1.5226169985143785, -0.46821147908163674, -0.29764891762534873, -0.95929121498385839,
                        0.55288108813670511, -1.3002617734194803, 0.55288108813670511, -0.41373832148686329,
                        0.552881088136705, 0.17727731313488143, -0.085016416184835353, 0.063620460323007444,
                        -1.5226169985143785, -0.1925228176819378,
                        0.034006566473934123, -0.516097932146655, 0.034006566473934172, -1.0922491998350194,
                        -0.29764891762534873, -0.95929121498385839, -0.96095988582391489, -0.69337524528153638 };
        lam_nest_loop base[2] = { { 0, 7, { 0.5528805914082735, -1.3002610391275111 }, 1.8194104181711204, 0, 0 },
                                  { 7, 4, { 0.034006366267220124, -1.0922489038781686 }, -0.28662559139940008, 0, 0 } };
        int good = 1, agreed = 0;
        for (int m = 0; m < 3; m++) {
            lam_nest_loop li[2] = { base[0], base[1] };
            lam_error err;
            lam_error_clear(&err);
            lam_nest_method(uv, li, 2, m, m == 1 ? &agreed : NULL, &err);
            if (li[0].depth != 0 || li[0].parent != -1 || li[1].depth != 1 || li[1].parent != 0) {
                diag("method %d: depths %d %d parents %ld %ld", m, li[0].depth, li[1].depth, li[0].parent, li[1].parent);
                good = 0;
            }
        }
        ok(good, "a hole lying along the outline's side: a hole to every method");
        ok(agreed, "... the tree sweep answering by itself");
    }
    /* Crossing loops (overlapping bodies under the even-odd rule): the tree
     * sweep's order does not hold, it must notice and hand over, and every
     * method must give the ray-parity answer of the each-against-each one. */
    {
        int good = 1, handed = 1;
        for (int round = 0; round < 40; round++) {
            layout L;
            memset(&L, 0, sizeof L);
            int n = 9 + round % 12;
            for (int i = 0; i < n; i++)
                add_loop(&L, (double)(xorshift64(&rng) % 100) / 10, (double)(xorshift64(&rng) % 100) / 10,
                         1 + (double)(xorshift64(&rng) % 30) / 10, (int)(xorshift64(&rng) & 1), (int)(xorshift64(&rng) & 1),
                         (int)(xorshift64(&rng) % 4), -1, 0, -1);
            lam_nest_loop *want = malloc(L.nloops * sizeof *want);
            memcpy(want, L.loops, L.nloops * sizeof *want);
            lam_error err;
            lam_error_clear(&err);
            lam_nest_method(L.uv, want, L.nloops, 0, NULL, &err);
            int crossing = 0;
            for (int m = 1; m < 3; m++) {
                lam_nest_loop *got = malloc(L.nloops * sizeof *got);
                memcpy(got, L.loops, L.nloops * sizeof *got);
                int agreed = 1;
                lam_nest_method(L.uv, got, L.nloops, m, &agreed, &err);
                if (m == 1) crossing = !agreed;
                for (size_t l = 0; l < L.nloops; l++)
                    if (got[l].depth != want[l].depth) {
                        if (good) diag("round %d method %d loop %zu: depth %d, want %d", round, m, l, got[l].depth, want[l].depth);
                        good = 0;
                    }
                free(got);
            }
            /* random squares of these sizes nearly always overlap somewhere */
            if (!crossing) handed = 0;
            free(want);
            free_layout(&L);
        }
        ok(good, "crossing loops: every method gives the each-against-each depths");
        ok(handed, "crossing loops: the tree sweep noticed and handed over every time");
    }
    return done_testing();
}
