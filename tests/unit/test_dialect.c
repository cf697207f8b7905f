/* Command templates (parse errors with offsets, rendering against printf)
 * and the dialect sink (command order, relative moves, separators, closed
 * polylines, write failures). */
#include "dialect.h"
#include "fmt.h"
#include "tap.h"
#include "util.h"

#include <stdint.h>
#include <stdlib.h>

static uint64_t rng = 0x9e3779b97f4a7c15ull;
static uint64_t next(void) { return xorshift64(&rng); }

/* text with newlines shown as \n (TAP descriptions are one line) */
static const char *oneline(const char *text)
{
    static char buf[256];
    size_t k = 0;
    for (const char *p = text; *p && k + 3 < sizeof buf; p++) {
        if (*p == '\n') buf[k++] = '\\', buf[k++] = 'n';
        else buf[k++] = *p;
    }
    buf[k] = '\0';
    return buf;
}

/* printf's text is a negative zero ("-0.00", "  -0.000"): lamina prints it positive */
static int negative_zero_text(const char *s)
{
    const char *m = strchr(s, '-');
    if (!m) return 0;
    for (const char *p = m + 1; *p && *p != 'e' && *p != 'E'; p++)
        if (*p >= '1' && *p <= '9') return 0;
    return 1;
}

/* One parse error: rc LAM_EINVAL, offset, message containing msg. */
static void parse_fails(lam_cmd c, const char *text, size_t want_off, const char *msg)
{
    lam_template t;
    lam_error err;
    lam_error_clear(&err);
    size_t off = 999;
    int rc = lam_template_parse(c, text, &t, &off, &err);
    int good = rc == LAM_EINVAL && off == want_off && strstr(err.msg, msg) && !t.present && !t.segs;
    ok(good, "%s '%s': error at %zu (%s)", lam_cmd_name(c), oneline(text), want_off, msg);
    if (!good) diag("got rc %d offset %zu msg '%s'", rc, off, err.msg);
    lam_template_free(&t);
}

static void parse_ok(lam_cmd c, const char *text)
{
    lam_template t;
    lam_error err;
    lam_error_clear(&err);
    size_t off = 0;
    int rc = lam_template_parse(c, text, &t, &off, &err);
    ok(rc == LAM_OK && t.present && t.source && strcmp(t.source, text) == 0, "%s '%s' parses", lam_cmd_name(c),
       oneline(text));
    if (rc) diag("%s at %zu", err.msg, off);
    lam_template_free(&t);
}

/* A dialect from (command, template) pairs; NULL template ends. */
static void set(lam_dialect *d, lam_cmd c, const char *text)
{
    lam_error err;
    size_t off;
    lam_template_free(&d->cmd[c]);
    if (lam_template_parse(c, text, &d->cmd[c], &off, &err)) {
        diag("bad test template '%s': %s", text, err.msg);
        abort();
    }
}

typedef struct run {
    lam_dialect d;
    lam_writer *w;
    lam_error err;
    lam_sink sink;
    int end_rc; /* what end returned */
} run;

static void run_start(run *r)
{
    lam_error_clear(&r->err);
    if (lam_writer_memory(&r->w, &r->err) || lam_dialect_sink(&r->d, r->w, &r->sink, &r->err)) abort();
}

/* Finish as a planner does (end, then destroy: the sink's output is
 * complete when end returns) and return the output (caller frees). */
static char *run_take(run *r)
{
    r->end_rc = r->sink.end(r->sink.ctx);
    r->sink.destroy(r->sink.ctx);
    char *out;
    size_t len;
    if (lam_writer_take(r->w, &out, &len, &r->err)) abort();
    return out;
}

static lam_job_info job(void)
{
    lam_job_info j;
    memset(&j, 0, sizeof j);
    j.name = "test-cell";
    j.process = "ladrp";
    j.units = "mm";
    j.layers = 7;
    double box[6] = { -1, -2, -3, 1, 2, 3.5 };
    memcpy(j.bbox, box, sizeof box);
    j.bead = 0.08;
    j.rate = 0.15;
    j.travel_rate = 30;
    return j;
}

/* Render a travel template for one move to x from origin 0 (absolute fields). */
static char *render_x(const char *tpl, double x)
{
    run r;
    memset(&r, 0, sizeof r);
    set(&r.d, LAM_CMD_TRAVEL, tpl);
    run_start(&r);
    lam_job_info j = job();
    r.sink.begin(r.sink.ctx, &j);
    double p[3] = { x, 0, 0 };
    move_to(&r.sink, 0, p);
    char *out = run_take(&r);
    lam_dialect_free(&r.d);
    size_t n = strlen(out);
    if (n && out[n - 1] == '\n') out[n - 1] = '\0';
    return out;
}

static void test_parse_errors(void)
{
    parse_ok(LAM_CMD_DEPOSIT, "{dx:%.5f} {dy:%.5f} {dz:%.5f} uline");
    parse_ok(LAM_CMD_PREAMBLE, "start_plot\n{dimension} set_dimension\n{{literal}} {name:%-12s}|");
    parse_ok(LAM_CMD_VERTEX, "{x:%+012.4e} {y:%G} {z:% .3F} {i:%05d} {x:%#.0f} {i:%-3i}");
    parse_ok(LAM_CMD_SEPARATOR, "");
    parse_ok(LAM_CMD_POLYLINE, "$$POLYLINE/{id},{dir},{n},{points:%.5f}");

    parse_fails(LAM_CMD_DEPOSIT, "{dx:%.5f} {dw:%.5f} uline", 11, "unknown field 'dw' for the deposit command");
    parse_fails(LAM_CMD_FEED, "{x} feedrate", 1, "unknown field 'x' for the feed command (fields: rate)");
    parse_fails(LAM_CMD_SEPARATOR, "-- {index} --", 4, "the separator command has no fields");
    parse_fails(LAM_CMD_LAYER, "layer {number", 6, "unterminated '{'");
    parse_fails(LAM_CMD_LAYER, "layer {z:%.3f\nnext}", 6, "unterminated '{'");
    parse_fails(LAM_CMD_LAYER, "z={z:%.3f}} ", 10, "single '}'");
    parse_fails(LAM_CMD_LAYER, "a } b", 2, "single '}'");
    parse_fails(LAM_CMD_LAYER, "x{}", 1, "empty field name");
    parse_fails(LAM_CMD_LAYER, "{z:.3f}", 3, "a format starts with '%'");
    parse_fails(LAM_CMD_VERTEX, "{x:%n}", 4, "%n is not allowed");
    parse_fails(LAM_CMD_VERTEX, "{x:%s}", 4, "%s is for text fields");
    parse_fails(LAM_CMD_PREAMBLE, "{name:%d}", 7, "'name' is text: format it with %s");
    parse_fails(LAM_CMD_PREAMBLE, "{name:%05s}", 7, "flag '0' does not apply to %s");
    parse_fails(LAM_CMD_VERTEX, "{x:%41.2f}", 4, "width of 'x' is more than 40");
    parse_fails(LAM_CMD_VERTEX, "{x:%.41f}", 5, "precision of 'x' is more than 40");
    parse_fails(LAM_CMD_VERTEX, "{x:%.99999999999999999999f}", 5, "precision of 'x' is more than 40");
    parse_fails(LAM_CMD_VERTEX, "{x:%.f}", 5, "needs digits after '.'");
    parse_fails(LAM_CMD_VERTEX, "{x:%*f}", 4, "'*' is not allowed");
    parse_fails(LAM_CMD_VERTEX, "{x:%.*f}", 5, "'*' is not allowed");
    parse_fails(LAM_CMD_VERTEX, "{x:%.3lf}", 6, "length modifier 'l'");
    parse_fails(LAM_CMD_VERTEX, "{x:%x}", 4, "unsupported conversion '%x'");
    parse_fails(LAM_CMD_VERTEX, "{x:%p}", 4, "unsupported conversion '%p'");
    parse_fails(LAM_CMD_VERTEX, "{x:%--5f}", 5, "flag '-' given twice");
    parse_fails(LAM_CMD_VERTEX, "{i:%#d}", 4, "flag '#' does not apply to %d");
    parse_fails(LAM_CMD_VERTEX, "{x:%.3f mm}", 7, "unexpected ' ' after the conversion");
    parse_fails(LAM_CMD_VERTEX, "{x:%f%f}", 5, "unexpected '%' after the conversion");
    parse_fails(LAM_CMD_VERTEX, "{x:%.3}", 6, "has no conversion letter");
    parse_fails(LAM_CMD_POLYLINE, "{points:%d}", 9, "'points' are coordinates");
    parse_fails(LAM_CMD_VERTEX, "ok {x} {X}", 8, "unknown field 'X'");
    parse_fails(LAM_CMD_VERTEX, "{ x }", 1, "unknown field ' x '");
}

static void test_render_numbers(void)
{
    /* %.5f: lam_fmt_fixed, the same characters as printf */
    int good = 1;
    for (int i = 0; i < 20000 && good; i++) {
        uint64_t b = next();
        double x;
        if (i % 2) x = ((double)(b >> 11) / 9007199254740992.0 - 0.5) * 2000.0;
        else {
            memcpy(&x, &b, sizeof x);
            if (!isfinite(x) || fabs(x) > 1e30) x = (double)(int64_t)b / 1e12;
        }
        char want[512];
        snprintf(want, sizeof want, "%.5f", x);
        if (negative_zero_text(want)) continue; /* see below */
        char *got = render_x("{x:%.5f}", x);
        if (strcmp(got, want) != 0) {
            diag("x=%.17g: got %s, printf %s", x, got, want);
            good = 0;
        }
        free(got);
    }
    ok(good, "{x:%%.5f} prints what printf prints for 20000 values");

    static const double tricky[] = { 0.000005, 0.000015, 0.000025, 1.000005, 2.5e-6, 1e15, 123456.789015,
                                     -2.000005, 0.1, 1e-300, 4503599627370495.5 };
    good = 1;
    for (size_t i = 0; i < sizeof tricky / sizeof *tricky; i++) {
        char want[512];
        snprintf(want, sizeof want, "%.5f", tricky[i]);
        char *got = render_x("{x:%.5f}", tricky[i]);
        good &= strcmp(got, want) == 0;
        if (strcmp(got, want)) diag("x=%.17g: got %s, printf %s", tricky[i], got, want);
        free(got);
    }
    ok(good, "{x:%%.5f} matches printf on ties and large values");

    /* other specs go through snprintf with the same flags */
    static const char *const specs[] = { "%+10.3f", "%-12.2e", "%G",  "%#.0f",  "% 08.2f",
                                         "%.3E",    "%g",      "%F", "%40.40f" };
    static const double xs[] = { 3.14159, -2.5e-7, 123456789.5, 1e-5, -1, 0.5 };
    good = 1;
    for (size_t s = 0; s < sizeof specs / sizeof *specs; s++)
        for (size_t k = 0; k < sizeof xs / sizeof *xs; k++) {
            char tpl[64], want[512];
            snprintf(tpl, sizeof tpl, "{x:%s}", specs[s]);
            snprintf(want, sizeof want, specs[s], xs[k]);
            if (negative_zero_text(want)) continue; /* see below */
            char *got = render_x(tpl, xs[k]);
            if (strcmp(got, want) != 0) {
                diag("%s of %.17g: got '%s', printf '%s'", specs[s], xs[k], got, want);
                good = 0;
            }
            free(got);
        }
    ok(good, "flags, widths and e/E/g/G/F conversions print as printf does");

    char *got;
    is_str(got = render_x("{x:%.6f}", -1e-7), "0.000000", "%%.6f of -1e-7 is 0.000000, not -0.000000");
    free(got);
    is_str(got = render_x("{x:%.6f}", -0.0), "0.000000", "%%.6f of -0.0 is 0.000000");
    free(got);
    is_str(got = render_x("{x:%+.2f}", -0.001), "+0.00", "%%+.2f of -0.001 is +0.00");
    free(got);
    is_str(got = render_x("{x:%8.3f}|", -0.0004), "   0.000|", "%%8.3f of -0.0004 pads a positive zero");
    free(got);
    is_str(got = render_x("{x:%.6f}", -5e-6), "-0.000005", "%%.6f of -5e-6 keeps its sign");
    free(got);
    is_str(got = render_x("{x:%e}", -0.0), "0.000000e+00", "%%e of -0.0 is positive");
    free(got);
    is_str(got = render_x("{x:%d}", 2.5), "3", "%%d of a number rounds half away from zero");
    free(got);
    is_str(got = render_x("{x:%05d}", -41.6), "-0042", "%%05d of -41.6");
    free(got);

    /* default formats */
    is_str(got = render_x("{x}", 600), "600", "default: 600");
    free(got);
    is_str(got = render_x("{x}", 0.1), "0.1", "default: 0.1");
    free(got);
    is_str(got = render_x("{x}", 1.0 / 3), "0.3333333333333333", "default: 1/3 with 16 digits");
    free(got);
    is_str(got = render_x("{x}", 1e-5), "1e-05", "default: 1e-05 as %%g writes it");
    free(got);
    is_str(got = render_x("{x}", 1e20), "1e+20", "default: 1e+20");
    free(got);
    is_str(got = render_x("{x}", 1e15), "1000000000000000", "default: 1e15 in plain digits");
    free(got);
    is_str(got = render_x("{x}", -0.0), "0", "default: -0 is 0");
    free(got);
    is_str(got = render_x("{x}", 0.1 + 0.2), "0.30000000000000004", "default: 0.1+0.2 keeps 17 digits");
    free(got);
    good = 1;
    for (int i = 0; i < 5000 && good; i++) {
        uint64_t b = next();
        double x;
        memcpy(&x, &b, sizeof x);
        if (!isfinite(x)) continue;
        char buf[LAM_FMT_MAX];
        lam_dialect_number(buf, x);
        double back = strtod(buf, NULL);
        if (back != x && !(x == 0 && back == 0)) {
            diag("%.17g printed as %s", x, buf);
            good = 0;
        }
        char g17[64];
        snprintf(g17, sizeof g17, "%.17g", x);
        if ((strchr(g17, 'e') != NULL) != (strchr(buf, 'e') != NULL)) {
            diag("%.17g printed as %s: notation differs from %%.17g", x, buf);
            good = 0;
        }
    }
    ok(good, "default numbers read back exactly and use %%.17g's notation");

    /* literal braces and text */
    run r;
    memset(&r, 0, sizeof r);
    set(&r.d, LAM_CMD_PREAMBLE, "{{{name}}} [{name:%-10s}] [{name:%12s}] {process} {units} {layers} {dimension} {bead} "
                                "{rate} {travel_rate}\n{xmin} {ymin} {zmin} {xmax} {ymax} {zmax:%.2f}");
    set(&r.d, LAM_CMD_POSTAMBLE, "; end of {name} ({layers:%03d} layers)");
    run_start(&r);
    lam_job_info j = job();
    ok(r.sink.begin(r.sink.ctx, &j) == LAM_OK, "begin");
    char *out = run_take(&r);
    ok(r.end_rc == LAM_OK, "end");
    is_str(out,
           "{test-cell} [test-cell ] [   test-cell] ladrp mm 7 3 0.08 0.15 30\n-1 -2 -3 1 2 3.50\n"
           "; end of test-cell (007 layers)\n",
           "preamble and postamble: text fields, integers, defaults, escaped braces, two lines");
    free(out);
    lam_dialect_free(&r.d);
}

static void test_moves(void)
{
    run r;
    memset(&r, 0, sizeof r);
    set(&r.d, LAM_CMD_TRAVEL, "T {dx} {dy} {dz} | {x} {y} {z} @{rate}");
    set(&r.d, LAM_CMD_DEPOSIT, "D {dx} {dy} {dz} @{rate}");
    set(&r.d, LAM_CMD_FEED, "{rate:%.2f} feedrate");
    set(&r.d, LAM_CMD_LASER_ON, "on {rate}");
    set(&r.d, LAM_CMD_LASER_OFF, "off");
    set(&r.d, LAM_CMD_LAYER, "layer {index} {number} {z} {width} {floor} {ceiling}");
    set(&r.d, LAM_CMD_LAYER_END, "end {number}");
    run_start(&r);
    lam_job_info j = job();
    j.origin[0] = 1;
    j.origin[1] = 2;
    j.origin[2] = 3;
    r.sink.begin(r.sink.ctx, &j);
    lam_layer_info L = { .index = 4, .z = 3.25, .width = 0.5, .floor = 3, .ceiling = 3.5 };
    r.sink.layer(r.sink.ctx, &L);
    r.sink.feed(r.sink.ctx, 0.15);
    r.sink.laser(r.sink.ctx, 0);
    move_to(&r.sink, 0, (double[]){ 2, 2, 3 });
    r.sink.laser(r.sink.ctx, 1);
    move_to(&r.sink, 1, (double[]){ 2, 5, 3 });
    move_to(&r.sink, 1, (double[]){ 0, 0, 4 });
    move_to(&r.sink, 0, (double[]){ 0.5, -1.5, 4 });
    r.sink.layer_end(r.sink.ctx, &L);
    char *out = run_take(&r);
    is_str(out,
           "layer 4 5 3.25 0.5 3 3.5\n"
           "0.15 feedrate\n"
           "off\n"
           "T 1 0 0 | 2 2 3 @30\n"
           "on 0.15\n"
           "D 0 3 0 @0.15\n"
           "D -2 -5 1 @0.15\n"
           "T 0.5 -1.5 0 | 0.5 -1.5 4 @30\n"
           "end 5\n",
           "layer, feed, laser, relative moves from the origin (1,2,3), rates by move kind");
    free(out);
    lam_dialect_free(&r.d);

    /* Relative moves are measured from where the written numbers took the
     * stage: 10 steps of 0.000004 at %.5f must not vanish in rounding. */
    memset(&r, 0, sizeof r);
    set(&r.d, LAM_CMD_DEPOSIT, "{dx:%.5f}");
    run_start(&r);
    j = job();
    r.sink.begin(r.sink.ctx, &j);
    for (int k = 1; k <= 10; k++) move_to(&r.sink, 1, (double[]){ 0.000004 * k, 0, 0 });
    out = run_take(&r);
    double sum = 0;
    int lines = 0;
    for (char *p = out; *p; lines++) {
        char *end;
        sum += strtod(p, &end);
        p = end + (*end == '\n');
    }
    is_int(lines, 10, "ten deposit lines");
    is_num(sum, 0.00004, 5e-6 + 1e-12, "the machine's sum of rounded dx reaches the target (got %.5f)", sum);
    free(out);
    lam_dialect_free(&r.d);

    /* An absent command moves nothing: the next relative move starts where
     * the machine still is. */
    memset(&r, 0, sizeof r);
    set(&r.d, LAM_CMD_DEPOSIT, "{dx} {dy}");
    run_start(&r);
    r.sink.begin(r.sink.ctx, &j);
    move_to(&r.sink, 0, (double[]){ 5, 5, 0 });
    move_to(&r.sink, 1, (double[]){ 6, 7, 0 });
    out = run_take(&r);
    is_str(out, "6 7\n", "no travel command: the deposit is measured from the last written position");
    free(out);
    lam_dialect_free(&r.d);
}

static void test_contours(void)
{
    static const double sq_xyz[] = { -1, -1, 0.5, 1, -1, 0.5, 1, 1, 0.5, -1, 1, 0.5 };
    static const double sq_uv[] = { -1, -1, 1, -1, 1, 1, -1, 1 };
    static const double hole_xyz[] = { -0.5, -0.5, 0.5, -0.5, 0.5, 0.5, 0.5, 0.5, 0.5 };
    static const double hole_uv[] = { -0.5, -0.5, -0.5, 0.5, 0.5, 0.5 };
    lam_contour_info a = { { .part = 1 }, 1, 0, 0.5, sq_xyz, sq_uv, 4, 0, 0, 0, 0 };
    lam_contour_info b = { { .part = 2 }, 0, 1, 0.5, hole_xyz, hole_uv, 3, 0, 0, 0, 0 };
    lam_contour_info c = { { .part = 3 }, 1, 0, 1.5, sq_xyz, sq_uv, 4, 0, 0, 0, 0 };
    lam_layer_info L0 = { .index = 0, .z = 0.5, .width = 1, .floor = 0, .ceiling = 1 }, L1 = { .index = 1, .z = 1.5, .width = 1, .floor = 1, .ceiling = 2 };

    run r;
    memset(&r, 0, sizeof r);
    set(&r.d, LAM_CMD_CONTOUR_BEGIN, "contour {z:%.6f} #{id} [{index}] {kind} d{depth} dir{dir}");
    set(&r.d, LAM_CMD_LOOP_BEGIN, "loop {n}");
    set(&r.d, LAM_CMD_VERTEX, "{i}: {x:%.6f} {y:%.6f} {z:%.6f}");
    set(&r.d, LAM_CMD_LOOP_END, "endloop");
    set(&r.d, LAM_CMD_CONTOUR_END, "endcontour");
    set(&r.d, LAM_CMD_SEPARATOR, "");
    run_start(&r);
    lam_job_info j = job();
    r.sink.begin(r.sink.ctx, &j);
    r.sink.layer(r.sink.ctx, &L0);
    r.sink.contour(r.sink.ctx, &a);
    r.sink.contour(r.sink.ctx, &b);
    r.sink.layer_end(r.sink.ctx, &L0);
    r.sink.layer(r.sink.ctx, &L1);
    r.sink.contour(r.sink.ctx, &c);
    r.sink.layer_end(r.sink.ctx, &L1);
    char *out = run_take(&r);
    is_str(out,
           "contour 0.500000 #1 [0] solid d0 dir1\nloop 4\n"
           "0: -1.000000 -1.000000 0.500000\n1: 1.000000 -1.000000 0.500000\n"
           "2: 1.000000 1.000000 0.500000\n3: -1.000000 1.000000 0.500000\nendloop\nendcontour\n"
           "\n"
           "contour 0.500000 #2 [1] hole d1 dir0\nloop 3\n"
           "0: -0.500000 -0.500000 0.500000\n1: -0.500000 0.500000 0.500000\n2: 0.500000 0.500000 0.500000\n"
           "endloop\nendcontour\n"
           "\n"
           "contour 1.500000 #3 [0] solid d0 dir1\nloop 4\n"
           "0: -1.000000 -1.000000 0.500000\n1: 1.000000 -1.000000 0.500000\n"
           "2: 1.000000 1.000000 0.500000\n3: -1.000000 1.000000 0.500000\nendloop\nendcontour\n",
           "contour blocks: separator between blocks (also across layers), not before the first");
    free(out);
    lam_dialect_free(&r.d);

    /* CLI polylines: closed by repeating the first point, n counts it */
    memset(&r, 0, sizeof r);
    set(&r.d, LAM_CMD_LAYER, "$$LAYER/{z:%.5f}");
    set(&r.d, LAM_CMD_POLYLINE, "$$POLYLINE/{id},{dir},{n},{points:%.5f}");
    set(&r.d, LAM_CMD_VERTEX, "v{i} {x}");
    r.d.close_polylines = 1;
    run_start(&r);
    r.sink.begin(r.sink.ctx, &j);
    r.sink.layer(r.sink.ctx, &L0);
    r.sink.contour(r.sink.ctx, &b);
    out = run_take(&r);
    is_str(out,
           "$$LAYER/0.50000\nv0 -0.5\nv1 -0.5\nv2 0.5\nv3 -0.5\n"
           "$$POLYLINE/2,0,4,-0.50000,-0.50000,-0.50000,0.50000,0.50000,0.50000,-0.50000,-0.50000\n",
           "close_polylines: points and vertices repeat the first point, n = 4");
    free(out);
    lam_dialect_free(&r.d);

    /* default points format is %.6f; without uv the output xy are used */
    memset(&r, 0, sizeof r);
    set(&r.d, LAM_CMD_POLYLINE, "P {n} {points}");
    run_start(&r);
    r.sink.begin(r.sink.ctx, &j);
    lam_contour_info nouv = { { .part = 9 }, 1, 0, 0.5, hole_xyz, NULL, 3, 0, 0, 0, 0 };
    r.sink.contour(r.sink.ctx, &nouv);
    out = run_take(&r);
    is_str(out, "P 3 -0.500000,-0.500000,-0.500000,0.500000,0.500000,0.500000\n", "points default %%.6f, open");
    free(out);
    lam_dialect_free(&r.d);
}

static void test_write_failure(void)
{
    FILE *f = fopen("/dev/full", "w");
    if (!f) {
        ok(1, "# SKIP no /dev/full");
        return;
    }
    setvbuf(f, NULL, _IONBF, 0);
    lam_dialect d;
    memset(&d, 0, sizeof d);
    set(&d, LAM_CMD_PREAMBLE, "start_plot");
    set(&d, LAM_CMD_FEED, "{rate} feedrate");
    lam_writer *w;
    lam_error err;
    lam_error_clear(&err);
    lam_writer_stream(f, "/dev/full", &w, &err);
    lam_sink s;
    lam_dialect_sink(&d, w, &s, &err);
    lam_job_info j = job();
    /* the sink buffers: the failure shows at the latest when end returns */
    int rc1 = s.begin(s.ctx, &j);
    int rc2 = rc1 ? rc1 : s.feed(s.ctx, 1);
    int rc3 = rc2 ? rc2 : s.end(s.ctx);
    ok(rc3 == LAM_EIO && err.code == LAM_EIO, "a full disk: LAM_EIO from the sink (%d, %d, %d)", rc1, rc2, rc3);
    ok(strstr(err.msg, "cannot write") != NULL, "the message says so: %s", err.msg);
    s.destroy(s.ctx);
    lam_writer_abort(w);
    fclose(f);
    lam_dialect_free(&d);
}

int main(void)
{
    static const char *const names[] = { "preamble", "postamble", "layer", "layer_end", "feed", "laser_on",
                                         "laser_off", "travel", "deposit", "contour_begin", "contour_end",
                                         "loop_begin", "loop_end", "vertex", "polyline", "separator",
                                         "hatches_begin", "hatch", "hatches_end", "hatches" };
    int good = 1;
    for (int c = 0; c < LAM_CMD_COUNT; c++) good &= strcmp(lam_cmd_name((lam_cmd)c), names[c]) == 0;
    ok(good, "command names");
    test_parse_errors();
    test_render_numbers();
    test_moves();
    test_contours();
    test_write_failure();
    return done_testing();
}
