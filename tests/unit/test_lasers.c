/* core/build/lasers.c: sharing a layer's blocks between lasers. The
 * expected times are the test's own arithmetic (length / speed, and per
 * jump distance / jump_speed + jump_delay, no jump before a laser's first
 * path, as plan_sls.c times a layer); fields are checked with the test's
 * own point-in-box; the balance, order and cut properties over seeded
 * random layers. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "blayer.h"
#include "lasers.h"
#include "tap.h"

#define SPEED 1000.0
#define JSPEED 5000.0
#define JDELAY 1e-3
#define PLATE 100.0

static uint64_t rng = 88172645463325252ull;
static double rnd(void) /* xorshift64: [0, 1) */
{
    rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
    return (double)(rng >> 11) / 9007199254740992.0;
}

static lam_scan_cfg cfg_make(void)
{
    lam_scan_cfg c;
    memset(&c, 0, sizeof c);
    c.jump_speed = JSPEED;
    c.jump_delay = JDELAY;
    return c;
}

static lam_bblock blk(long long part, int kind, int polyline, size_t n)
{
    lam_bblock b;
    memset(&b, 0, sizeof b);
    b.attrs = lam_attrs_default();
    b.attrs.part = part;
    b.kind = kind;
    b.polyline = polyline;
    b.exposure.speed = SPEED;
    b.n = n;
    return b;
}

static void push(lam_blayer *l, long long part, int kind, int polyline, const double *uv, size_t n, long long tag)
{
    lam_bblock b = blk(part, kind, polyline, n);
    b.attrs.label = tag; /* the test's own mark: the block's place in `in` */
    if (lam_blayer_push(l, &b, uv, polyline ? n : 2 * n, NULL)) abort();
}

static double seg(const double *p) { return hypot(p[2] - p[0], p[3] - p[1]); }

static double block_length(const lam_bblock *b)
{
    double s = 0;
    if (!b->polyline)
        for (size_t i = 0; i < b->n; i++) s += seg(b->uv + 4 * i);
    else
        for (size_t i = 0; i < b->n; i++) {
            size_t j = (i + 1) % b->n;
            s += hypot(b->uv[2 * j] - b->uv[2 * i], b->uv[2 * j + 1] - b->uv[2 * i + 1]);
        }
    return s;
}

static double layer_length(const lam_blayer *l)
{
    double s = 0;
    for (size_t i = 0; i < l->n; i++) s += block_length(&l->b[i]);
    return s;
}

/* every point of every block inside its laser's field (grown by tol) */
static int all_in_fields(const lam_laser_set *ls, const lam_blayer *l, double tol)
{
    for (size_t i = 0; i < l->n; i++) {
        const lam_bblock *b = &l->b[i];
        if (b->attrs.laser < 1 || (size_t)b->attrs.laser > ls->n) return 0;
        const double *f = ls->field[b->attrs.laser - 1];
        size_t np = b->polyline ? b->n : 2 * b->n;
        for (size_t k = 0; k < np; k++) {
            double x = b->uv[2 * k], y = b->uv[2 * k + 1];
            if (x < f[0] - tol || x > f[2] + tol || y < f[1] - tol || y > f[3] + tol) return 0;
        }
    }
    return 1;
}

static lam_laser_set set_of(size_t n, const double (*fields)[4])
{
    lam_laser_set ls;
    memset(&ls, 0, sizeof ls);
    ls.n = n;
    memcpy(ls.field, fields, n * sizeof fields[0]);
    return ls;
}

/* a random hatch block: nv parallel vectors of a random direction and
 * length, meandering, somewhere on the plate */
static void random_block(lam_blayer *l, long long part, size_t nv, long long tag)
{
    double *v = malloc((nv ? nv : 1) * 4 * sizeof *v);
    double len = 1 + 30 * rnd(), a = 6.283185307179586 * rnd();
    double du = cos(a) * len, dv = sin(a) * len, h = 0.1;
    double x = (PLATE - 40) * rnd() + 5, y = (PLATE - 40) * rnd() + 5;
    for (size_t i = 0; i < nv; i++) {
        double ox = x - sin(a) * h * (double)i, oy = y + cos(a) * h * (double)i;
        double *p = v + 4 * i;
        if (i % 2) p[0] = ox + du, p[1] = oy + dv, p[2] = ox, p[3] = oy;
        else p[0] = ox, p[1] = oy, p[2] = ox + du, p[3] = oy + dv;
        for (int k = 0; k < 4; k++) p[k] = fmin(fmax(p[k], 0), PLATE);
    }
    push(l, part, LAM_KIND_CORE, 0, v, nv, tag);
    free(v);
}

/* one laser's field over everything: the SLS planner's time, nothing cut */
static void test_single(void)
{
    const double f[1][4] = { { 0, 0, PLATE, PLATE } };
    lam_laser_set ls = set_of(1, f);
    lam_scan_cfg cfg = cfg_make();
    lam_blayer in = { 0 }, out = { 0 };
    const double sq[8] = { 0, 0, 10, 0, 10, 10, 0, 10 };
    const double hv[12] = { 1, 1, 9, 1, 9, 2, 1, 2, 1, 3, 9, 3 };
    push(&in, 1, LAM_KIND_CONTOUR, 1, sq, 4, 0);
    push(&in, 1, LAM_KIND_CORE, 0, hv, 3, 1);
    lam_scan_time t[1];
    lam_error err;
    lam_error_clear(&err);
    int rc = lam_lasers_share(&ls, &cfg, &in, &out, t, &err);
    is_int(rc, LAM_OK, "one laser: shared (%s)", err.msg);
    is_int(out.n, 2, "one laser: the two blocks, uncut");
    int same = out.n == 2;
    for (size_t i = 0; same && i < 2; i++) {
        const lam_bblock *a = &in.b[i], *b = &out.b[i];
        same = a->polyline == b->polyline && a->n == b->n && a->kind == b->kind && b->attrs.laser == 1 &&
               memcmp(a->uv, b->uv, lam_bblock_points(a) * 2 * sizeof(double)) == 0;
    }
    ok(same, "one laser: the input's blocks in their order, laser 1");
    /* contour: perimeter 40 from (0, 0) back to it; hatch: 3 x 8; jumps
     * (0,0)->(1,1), (9,1)->(9,2), (1,2)->(1,3) */
    is_num(t[0].exposure, 40 / SPEED + 24 / SPEED, 1e-15, "one laser: exposure = length / speed");
    is_num(t[0].jump, (sqrt(2) + 2) / JSPEED + 3 * JDELAY, 1e-15, "one laser: jumps = distance / jump speed + delays");
    is_int(t[0].jumps, 3, "one laser: 3 jumps (none before the first path)");
    is_int(t[0].contours * 100 + t[0].vectors, 103, "one laser: 1 contour, 3 vectors");
    is_num(t[0].exposure_length, 64, 1e-12, "one laser: exposed length");
    is_num(t[0].hatch_length, 24, 1e-12, "one laser: hatch length");
    is_int(t[0].layers, 1, "one laser: a layer with work");
    lam_blayer_free(&in);
    lam_blayer_free(&out);
}

/* one laser, two parts and a gas flow: only the parts' order changes */
static void test_single_order(void)
{
    const double f[1][4] = { { 0, 0, PLATE, PLATE } };
    lam_laser_set ls = set_of(1, f);
    const double centres[4] = { 10, 0, 50, 0 };
    ls.gas_flow[0] = 1;
    ls.part_centre = centres;
    ls.nparts = 2;
    lam_scan_cfg cfg = cfg_make();
    lam_blayer in = { 0 }, out = { 0 };
    const double v[4] = { 5, 5, 15, 5 };
    push(&in, 1, LAM_KIND_CORE, 0, v, 1, 0);
    push(&in, 2, LAM_KIND_CORE, 0, v, 1, 1);
    push(&in, 1, LAM_KIND_CORE, 0, v, 1, 2);
    lam_scan_time t[1];
    int rc = lam_lasers_share(&ls, &cfg, &in, &out, t, NULL);
    ok(rc == LAM_OK && out.n == 3 && out.b[0].attrs.label == 1 && out.b[1].attrs.label == 0 &&
           out.b[2].attrs.label == 2,
       "one laser: part 2 (downstream, x 50 > 10) first, part 1's blocks in their order");
    lam_blayer_free(&in);
    lam_blayer_free(&out);
}

/* the plate in two halves: a square contour across the seam is cut */
static void test_halves(void)
{
    const double f[2][4] = { { 0, 0, 50, PLATE }, { 50, 0, PLATE, PLATE } };
    lam_laser_set ls = set_of(2, f);
    lam_scan_cfg cfg = cfg_make();
    lam_blayer in = { 0 }, out = { 0 };
    const double sq[8] = { 40, 40, 60, 40, 60, 60, 40, 60 };
    const double left[4] = { 10, 10, 20, 10 }, across[8] = { 10, 20, 90, 20, 90, 21, 10, 21 };
    push(&in, 1, LAM_KIND_CONTOUR, 1, sq, 4, 0);
    push(&in, 1, LAM_KIND_CORE, 0, left, 1, 1);
    push(&in, 1, LAM_KIND_CORE, 0, across, 2, 2);
    lam_scan_time t[2];
    lam_error err;
    lam_error_clear(&err);
    int rc = lam_lasers_share(&ls, &cfg, &in, &out, t, &err);
    is_int(rc, LAM_OK, "halves: shared (%s)", err.msg);
    ok(all_in_fields(&ls, &out, 2e-9 * PLATE), "halves: every vector in its laser's field");
    is_num(layer_length(&out), layer_length(&in), 1e-9 * layer_length(&in), "halves: exposed length kept");
    size_t ncont = 0, nacross = 0;
    int cut_ok = 1;
    for (size_t i = 0; i < out.n; i++) {
        const lam_bblock *b = &out.b[i];
        if (b->attrs.label == 0) {
            ncont++;
            /* each side: the left or right edge (20) and half the bottom and top (10 + 10) */
            cut_ok &= b->kind == LAM_KIND_CONTOUR && !b->polyline && b->n == 3 && fabs(block_length(b) - 40) < 1e-9;
        }
        if (b->attrs.label == 2) nacross++, cut_ok &= b->n == 2 && fabs(block_length(b) - 80) < 1e-9;
    }
    is_int(ncont, 2, "halves: the contour as one block of contour vectors per laser");
    is_int(nacross, 2, "halves: the hatch block across the seam, one block per laser");
    ok(cut_ok, "halves: the cut blocks' vectors and lengths");
    is_num(t[0].exposure + t[1].exposure, layer_length(&in) / SPEED, 1e-12, "halves: the lasers' exposure sums");
    is_num(t[0].hatch_length + t[1].hatch_length, 10 + 160, 1e-9, "halves: cut contour vectors are not hatches");
    lam_blayer_free(&in);
    lam_blayer_free(&out);
}

/* long random vectors over quadrants and overlapping fields */
static void test_random_cuts(void)
{
    const double quad[4][4] = { { 0, 0, 50, 50 }, { 50, 0, 100, 50 }, { 0, 50, 50, 100 }, { 50, 50, 100, 100 } };
    const double lap[3][4] = { { 0, 0, 60, 100 }, { 40, 0, 100, 70 }, { 30, 50, 100, 100 } };
    for (int which = 0; which < 2; which++) {
        lam_laser_set ls = which ? set_of(3, lap) : set_of(4, quad);
        lam_scan_cfg cfg = cfg_make();
        lam_blayer in = { 0 }, out = { 0 };
        for (int b = 0; b < 30; b++) {
            double v[40];
            for (int k = 0; k < 40; k++) v[k] = PLATE * rnd();
            push(&in, 1 + b % 3, b % 4 ? LAM_KIND_CORE : LAM_KIND_CONTOUR, b % 4 == 0, v, b % 4 ? 10 : 20, b);
        }
        lam_scan_time t[4];
        int rc = lam_lasers_share(&ls, &cfg, &in, &out, t, NULL);
        is_int(rc, LAM_OK, "%s: shared", which ? "overlaps" : "quadrants");
        ok(all_in_fields(&ls, &out, 2e-9 * PLATE), "%s: every vector in its laser's field", which ? "overlaps" : "quadrants");
        double a = layer_length(&in), b = layer_length(&out);
        is_num(b, a, 1e-9 * a, "%s: exposed length kept", which ? "overlaps" : "quadrants");
        int once = 1; /* one block per (block, laser) */
        for (size_t i = 0; i < out.n; i++)
            for (size_t j = i + 1; j < out.n; j++)
                once &= !(out.b[i].attrs.label == out.b[j].attrs.label && out.b[i].attrs.laser == out.b[j].attrs.laser);
        ok(once, "%s: one block per (block, laser)", which ? "overlaps" : "quadrants");
        lam_blayer_free(&in);
        lam_blayer_free(&out);
    }
}

/* a block's work by the test's arithmetic: exposure, inner jumps, a delay */
static double work_of(const lam_bblock *b)
{
    double w = b->n ? JDELAY : 0;
    for (size_t i = 0; i < b->n; i++) {
        w += seg(b->uv + 4 * i) / SPEED;
        if (i) w += hypot(b->uv[4 * i] - b->uv[4 * i - 2], b->uv[4 * i + 1] - b->uv[4 * i - 1]) / JSPEED + JDELAY;
    }
    return w;
}

static void test_balance(void)
{
    const double f[4][4] = { { 0, 0, PLATE, PLATE }, { 0, 0, PLATE, PLATE }, { 0, 0, PLATE, PLATE },
                             { 0, 0, PLATE, PLATE } };
    lam_laser_set ls = set_of(4, f);
    lam_scan_cfg cfg = cfg_make();
    int good = 1, bal = 1;
    double worst = 0;
    for (int layer = 0; layer < 40; layer++) {
        lam_blayer in = { 0 }, out = { 0 };
        size_t nb = 20 + (size_t)(200 * rnd());
        double most = 0;
        for (size_t b = 0; b < nb; b++) {
            random_block(&in, 1, (size_t)(1 + 60 * rnd() * rnd()), (long long)b);
            most = fmax(most, work_of(&in.b[b]));
        }
        lam_scan_time t[4];
        if (lam_lasers_share(&ls, &cfg, &in, &out, t, NULL)) good = 0;
        double sum = 0, busiest = 0;
        for (int k = 0; k < 4; k++) sum += t[k].exposure + t[k].jump, busiest = fmax(busiest, t[k].exposure + t[k].jump);
        double ideal = sum / 4;
        good &= busiest <= 1.05 * (ideal + most);
        worst = fmax(worst, (busiest - ideal) / most);
        bal &= fabs(lam_lasers_balance(t, 4) - busiest / ideal) < 1e-12;
        lam_blayer_free(&in);
        lam_blayer_free(&out);
    }
    ok(good, "balance: 4 full fields, the busiest within 5%% of ideal + one block (worst: ideal + %.3g blocks)", worst);
    ok(bal, "balance: lam_lasers_balance is busiest / ideal");
    lam_scan_time t[3];
    memset(t, 0, sizeof t);
    t[0].exposure = 3, t[0].jump = 1, t[1].exposure = 2;
    is_num(lam_lasers_balance(t, 3), 4.0 / 3.0, 1e-15, "balance: 4 over (4 + 2) / 2 lasers with work");
    memset(t, 0, sizeof t);
    is_num(lam_lasers_balance(t, 3), 1, 0, "balance: 1 without work");
}

/* a block only one field holds goes to it, however busy; the shared
 * ones fill the other laser first */
static void test_single_candidate(void)
{
    const double f[2][4] = { { 0, 0, 60, PLATE }, { 40, 0, PLATE, PLATE } };
    lam_laser_set ls = set_of(2, f);
    lam_scan_cfg cfg = cfg_make();
    lam_blayer in = { 0 }, out = { 0 };
    const double left[4] = { 5, 5, 35, 5 }, mid[4] = { 45, 5, 55, 5 };
    for (int b = 0; b < 6; b++) push(&in, 1, LAM_KIND_CORE, 0, b < 4 ? left : mid, 1, b);
    lam_scan_time t[2];
    int rc = lam_lasers_share(&ls, &cfg, &in, &out, t, NULL);
    int good = rc == LAM_OK && out.n == 6;
    for (size_t i = 0; good && i < out.n; i++) good = out.b[i].attrs.laser == (out.b[i].attrs.label < 4 ? 1 : 2);
    ok(good, "single candidates: the left blocks on laser 1, the shared ones on idle laser 2");
    is_num(t[0].exposure, 4 * 30 / SPEED, 1e-15, "single candidates: laser 1's exposure");
    is_num(t[1].jump, 10 / JSPEED + JDELAY, 1e-15, "single candidates: laser 2's one jump");
    lam_blayer_free(&in);
    lam_blayer_free(&out);
}

/* parts downstream first per laser, a part's blocks in their order */
static void test_order(void)
{
    const double f[2][4] = { { 0, 0, 55, PLATE }, { 45, 0, PLATE, PLATE } };
    lam_laser_set ls = set_of(2, f);
    double centres[12];
    for (int k = 0; k < 12; k++) centres[k] = PLATE * rnd();
    ls.part_centre = centres;
    ls.nparts = 6;
    ls.gas_flow[0] = 0.6, ls.gas_flow[1] = -0.8;
    lam_scan_cfg cfg = cfg_make();
    lam_blayer in = { 0 }, out = { 0 };
    for (int b = 0; b < 60; b++) random_block(&in, 1 + (long long)(6 * rnd()), 1 + (size_t)(10 * rnd()), b);
    lam_scan_time t[2];
    int rc = lam_lasers_share(&ls, &cfg, &in, &out, t, NULL);
    is_int(rc, LAM_OK, "order: shared");
    int good = 1;
    long long laser = 0;
    for (size_t i = 1; i < out.n; i++) {
        const lam_bblock *a = &out.b[i - 1], *b = &out.b[i];
        good &= a->attrs.laser <= b->attrs.laser;
        if (a->attrs.laser != b->attrs.laser) continue;
        const double *ca = centres + 2 * (a->attrs.part - 1), *cb = centres + 2 * (b->attrs.part - 1);
        double da = 0.6 * ca[0] - 0.8 * ca[1], db = 0.6 * cb[0] - 0.8 * cb[1];
        good &= da >= db;
        if (a->attrs.part == b->attrs.part) good &= a->attrs.label < b->attrs.label;
        laser = b->attrs.laser;
    }
    ok(good && laser == 2, "order: lasers in turn, parts downstream first, a part's blocks in their order");
    lam_blayer_free(&in);
    lam_blayer_free(&out);
}

static int same_layer(const lam_blayer *a, const lam_blayer *b)
{
    if (a->n != b->n) return 0;
    for (size_t i = 0; i < a->n; i++) {
        const lam_bblock *x = &a->b[i], *y = &b->b[i];
        if (memcmp(&x->attrs, &y->attrs, sizeof x->attrs) || x->kind != y->kind || x->polyline != y->polyline ||
            x->n != y->n || memcmp(x->uv, y->uv, lam_bblock_points(x) * 2 * sizeof(double)))
            return 0;
    }
    return 1;
}

static void test_determinism(void)
{
    const double f[4][4] = { { 0, 0, 60, 60 }, { 40, 0, 100, 60 }, { 0, 40, 60, 100 }, { 40, 40, 100, 100 } };
    lam_laser_set ls = set_of(4, f);
    lam_scan_cfg cfg = cfg_make();
    lam_blayer in = { 0 }, o1 = { 0 }, o2 = { 0 };
    for (int b = 0; b < 80; b++) random_block(&in, 1, 1 + (size_t)(30 * rnd()), b);
    lam_scan_time t1[4], t2[4];
    int r1 = lam_lasers_share(&ls, &cfg, &in, &o1, t1, NULL), r2 = lam_lasers_share(&ls, &cfg, &in, &o2, t2, NULL);
    ok(r1 == LAM_OK && r2 == LAM_OK && same_layer(&o1, &o2) && memcmp(t1, t2, sizeof t1) == 0,
       "determinism: the same input twice, the same blocks and times");
    lam_blayer_free(&in);
    lam_blayer_free(&o1);
    lam_blayer_free(&o2);
}

static void expect_outside(const double (*f)[4], size_t n, const double v[4], const char *msg, const char *what)
{
    lam_laser_set ls = set_of(n, f);
    lam_scan_cfg cfg = cfg_make();
    lam_blayer in = { 0 }, out = { 0 };
    const double ok_v[4] = { 1, 1, 2, 2 };
    push(&in, 1, LAM_KIND_CORE, 0, ok_v, 1, 0);
    push(&in, 3, LAM_KIND_CORE, 0, v, 1, 1);
    lam_scan_time t[4];
    lam_error err;
    lam_error_clear(&err);
    int rc = lam_lasers_share(&ls, &cfg, &in, &out, t, &err);
    is_int(rc, LAM_EINVAL, "%s: invalid", what);
    is_str(err.msg, msg, "%s: the message", what);
    is_int(out.n, 0, "%s: no output", what);
    lam_blayer_free(&in);
    lam_blayer_free(&out);
}

static void test_errors(void)
{
    const double one[1][4] = { { 0, 0, PLATE, PLATE } }, gap[2][4] = { { 0, 0, 40, PLATE }, { 60, 0, PLATE, PLATE } };
    const double leaves[4] = { 10, 10, 120, 10 }, away[4] = { 150, 150, 160, 150 }, across[4] = { 10, 5, 90, 5 };
    expect_outside(one, 1, leaves, "a vector at (100, 10) of part 3 lies outside every laser's field", "leaving the field");
    expect_outside(one, 1, away, "a vector at (150, 150) of part 3 lies outside every laser's field", "off the plate");
    expect_outside(gap, 2, across, "a vector at (40, 5) of part 3 lies outside every laser's field", "across a gap");
    /* a gas flow needs every part's centre */
    lam_laser_set g = set_of(1, one);
    g.gas_flow[1] = 1;
    lam_scan_cfg c = cfg_make();
    lam_blayer gi = { 0 }, go = { 0 };
    const double inside[4] = { 1, 1, 2, 2 };
    push(&gi, 2, LAM_KIND_CORE, 0, inside, 1, 0);
    lam_scan_time gt[1];
    lam_error err;
    lam_error_clear(&err);
    int grc = lam_lasers_share(&g, &c, &gi, &go, gt, &err);
    ok(grc == LAM_EINVAL && !strcmp(err.msg, "part 2 has no footprint centre for the gas flow") && go.n == 0,
       "a gas flow without the part's centre: invalid (%s)", err.msg);
    lam_blayer_free(&gi);
    lam_blayer_free(&go);
    /* on the boundary is inside */
    lam_laser_set ls = set_of(2, gap);
    lam_scan_cfg cfg = cfg_make();
    lam_blayer in = { 0 }, out = { 0 };
    const double edge[4] = { 40, 0, 40, PLATE };
    push(&in, 1, LAM_KIND_CORE, 0, edge, 1, 0);
    lam_scan_time t[2];
    int rc = lam_lasers_share(&ls, &cfg, &in, &out, t, NULL);
    ok(rc == LAM_OK && out.n == 1 && out.b[0].attrs.laser == 1, "a vector along a field's edge is in the field");
    lam_blayer_free(&in);
    lam_blayer_free(&out);
}

static void test_empty(void)
{
    const double f[2][4] = { { 0, 0, 50, PLATE }, { 50, 0, PLATE, PLATE } };
    lam_laser_set ls = set_of(2, f);
    lam_scan_cfg cfg = cfg_make();
    lam_blayer in = { 0 }, out = { 0 };
    lam_scan_time t[2];
    memset(t, 0x55, sizeof t);
    int rc = lam_lasers_share(&ls, &cfg, &in, &out, t, NULL);
    ok(rc == LAM_OK && out.n == 0 && t[0].jumps == 0 && t[1].exposure == 0 && t[1].layers == 0,
       "zero blocks: nothing, zero times");
    is_num(lam_lasers_balance(t, 2), 1, 0, "zero blocks: balance 1");
    push(&in, 1, LAM_KIND_CORE, 0, NULL, 0, 0);
    push(&in, 1, LAM_KIND_CONTOUR, 1, NULL, 0, 1);
    rc = lam_lasers_share(&ls, &cfg, &in, &out, t, NULL);
    ok(rc == LAM_OK && out.n == 2 && out.b[0].n == 0 && out.b[1].n == 0 && out.b[0].attrs.laser >= 1,
       "blocks of zero vectors: kept, each on a laser");
    ok(t[0].vectors + t[1].vectors + t[0].jumps + t[1].jumps == 0 && t[0].exposure + t[1].exposure == 0,
       "blocks of zero vectors: no time");
    lam_blayer_free(&in);
    lam_blayer_free(&out);
}

int main(void)
{
    test_single();
    test_single_order();
    test_halves();
    test_random_cuts();
    test_balance();
    test_single_candidate();
    test_order();
    test_determinism();
    test_errors();
    test_empty();
    return done_testing();
}
