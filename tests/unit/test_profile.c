/* Machine profiles: the shipped ones load and speak their dialects (the
 * thesis's LADRP sample, the SLS program byte for byte), inheritance, every
 * kind of error with its exact line:column, and --show's YAML round trip. */
#include "dialect.h"
#include "model.h"
#include "profile.h"
#include "slice.h"
#include "util.h"
#include "writer.h"

#include <stdlib.h>
#include <unistd.h>

static char fixtures[1024], tmpdir[256];

static const char *fx(const char *name)
{
    static char path[4][1200];
    static int k;
    k = (k + 1) % 4;
    snprintf(path[k], sizeof path[k], "%s/%s", fixtures, name);
    return path[k];
}

/* Write text to a new file in tmpdir; returns its path (static, 4 slots). */
static const char *tmpfile_with(const char *name, const char *text)
{
    static char path[4][600];
    static int k;
    k = (k + 1) % 4;
    snprintf(path[k], sizeof path[k], "%s/%s", tmpdir, name);
    FILE *f = fopen(path[k], "wb");
    if (!f) abort();
    fputs(text, f);
    fclose(f);
    return path[k];
}

static const char *src(const lam_profile *p, lam_cmd c)
{
    return p->dialect.cmd[c].present ? p->dialect.cmd[c].source : "(absent)";
}

/* Load path; expect failure with code at line:col and msg. */
static void load_fails(const char *path, int code, long line, long col, const char *msg, const char *what)
{
    lam_profile *p = (lam_profile *)1;
    lam_error err;
    int rc = lam_profile_load(path, &p, &err);
    error_is(rc, &err, code, line, col, msg, what);
    ok(p == NULL, "%s: no profile returned", what);
    const char *base = strrchr(path, '/');
    if (!(strstr(err.file, base ? base + 1 : path))) diag("error names file '%s'", err.file);
}

/* Run a dialect over a sink script; returns the program text (caller frees). */
typedef void (*script_fn)(const lam_sink *s);

static char *program(const lam_profile *p, const lam_job_info *job, script_fn script)
{
    lam_writer *w;
    lam_error err;
    lam_sink s;
    if (lam_writer_memory(&w, &err) || lam_dialect_sink(&p->dialect, w, &s, &err)) abort();
    s.begin(s.ctx, job);
    script(&s);
    s.end(s.ctx);
    s.destroy(s.ctx);
    char *out;
    size_t len;
    if (lam_writer_take(w, &out, &len, &err)) abort();
    return out;
}

/* ---- shipped profiles ------------------------------------------------------ */

static void thesis_script(const lam_sink *s)
{
    /* the thesis's sample plan: a 2-unit cube centred on the origin, first
     * scan line on the top edge y = 1, stage starting at the origin (the
     * first "0.15 feedrate" comes from the preamble) */
    s->laser(s->ctx, 0);
    move_to(s, 0, (double[]){ -1, 1.08, 0 });
    move_to(s, 0, (double[]){ -1, 1.0, 0 });
    double y = 1.0;
    for (int line = 0; line < 4; line++) {
        s->laser(s->ctx, 1);
        s->feed(s->ctx, 0.15);
        move_to(s, 1, (double[]){ line % 2 ? -1 : 1, y, 0 });
        s->laser(s->ctx, 0);
        if (line < 3) {
            y = 1.0 - 0.08 * (line + 1);
            move_to(s, 0, (double[]){ line % 2 ? -1 : 1, y, 0 });
        }
    }
}

static const char thesis_sample[] = "start_plot\n3 set_dimension\n0.15 feedrate\n0 penup\n"
                                    "-1.00000 1.08000 0.0 uline\n0.0 -0.08 0.0 uline\n0 pendown\n0.15 feedrate\n"
                                    "2.00000 0.0 0.0 uline\n0 penup\n0.0 -0.08 0.0 uline\n0 pendown\n0.15 feedrate\n"
                                    "-2.00000 0.0 0.0 uline\n0 penup\n0.0 -0.08 0.0 uline\n0 pendown\n0.15 feedrate\n"
                                    "2.00000 0.0 0.0 uline\n0 penup\n0.0 -0.08 0.0 uline\n0 pendown\n0.15 feedrate\n"
                                    "-2.00000 0.0 0.0 uline\n0 penup\n";

/* Same words, numbers equal to 1e-9, line by line. */
static int same_program(const char *got, const char *want)
{
    int line = 1;
    while (*got || *want) {
        char *eg, *ew;
        double a = strtod(got, &eg), b = strtod(want, &ew);
        if (eg != got && ew != want) {
            if (fabs(a - b) > 1e-9) {
                diag("line %d: number %.17g, thesis %.17g", line, a, b);
                return 0;
            }
            got = eg;
            want = ew;
        } else if (*got == *want) {
            if (*got == '\n') line++;
            got++;
            want++;
        } else {
            diag("line %d: '%.20s' vs thesis '%.20s'", line, got, want);
            return 0;
        }
    }
    return 1;
}

static void test_shipped(void)
{
    lam_profile *p;
    lam_error err;
    int rc = lam_profile_find("creol-ladrp", &p, &err);
    ok(rc == LAM_OK, "creol-ladrp loads from the machine dirs%s%s", rc ? ": " : "", rc ? err.msg : "");
    if (rc) return;
    is_str(p->name, "creol-ladrp", "creol: name");
    ok(p->process == LAM_PROCESS_LADRP, "creol: process ladrp");
    is_str(p->units, "cm", "creol: units cm");
    is_num(p->bead_width, 0.08, 0, "creol: bead 0.08");
    is_num(p->layer_width, 0.08, 0, "creol: layer width 0.08");
    is_int(p->cut, LAM_CUT_FLOOR, "creol: floor cut");
    is_num(p->feed_rate, 0.15, 0, "creol: feed rate");
    is_num(p->travel_rate, 0.15, 0, "creol: travel rate defaults to the feed rate");
    ok(p->first_line == LAM_FIRST_EDGE && p->alternate, "creol: first line on the edge, alternating");
    is_str(p->writer, "text", "creol: the text writer");
    ok(!p->dialect.cmd[LAM_CMD_LAYER].present, "creol: no layer command");
    is_str(src(p, LAM_CMD_DEPOSIT), "{dx:%.5f} {dy:%.5f} {dz:%.5f} uline", "creol: deposit template");
    lam_job_info job;
    memset(&job, 0, sizeof job);
    job.name = p->name;
    job.process = "ladrp";
    job.units = p->units;
    job.bead = p->bead_width;
    job.rate = p->feed_rate;
    job.travel_rate = p->travel_rate;
    job.layers = 25;
    char *out = program(p, &job, thesis_script);
    ok(same_program(out, thesis_sample), "creol: the thesis's LADRP sample, numbers equal to 1e-9");
    ok(has(out, "-1.00000 1.08000 0.00000 uline\n0.00000 -0.08000 0.00000 uline\n0 pendown"),
       "creol: the first moves as printed");
    free(out);
    lam_profile_free(p);

    rc = lam_profile_find("sls-contours", &p, &err);
    ok(rc == LAM_OK, "sls-contours loads");
    if (rc) return;
    ok(p->process == LAM_PROCESS_SLS, "sls-contours: process sls");
    is_num(p->spot_width, 0.1, 0, "sls-contours: spot 0.1");
    is_num(p->bead_width, 0.1, 0, "sls-contours: bead is the spot");
    ok(p->dialect.cmd[LAM_CMD_SEPARATOR].present && !strcmp(p->dialect.cmd[LAM_CMD_SEPARATOR].source, ""),
       "sls-contours: an empty separator line");
    lam_profile_free(p);

    rc = lam_profile_find("ded-gcode", &p, &err);
    ok(rc == LAM_OK, "ded-gcode loads");
    if (rc) return;
    ok(p->process == LAM_PROCESS_LADRP && !strcmp(p->units, "mm"), "ded-gcode: ladrp in mm");
    ok(p->bead_width == 1.0 && p->layer_width == 0.5 && p->cut == LAM_CUT_MIDDLE,
       "ded-gcode: bead 1, layer 0.5, middle");
    ok(p->feed_rate == 600 && p->travel_rate == 3000, "ded-gcode: feed 600, travel 3000");
    lam_profile_free(p);

    rc = lam_profile_find("cli-ascii", &p, &err);
    ok(rc == LAM_OK, "cli-ascii loads");
    if (rc) return;
    ok(p->process == LAM_PROCESS_SLS && p->spot_width == 0.1, "cli-ascii: sls, spot 0.1");
    ok(p->dialect.close_polylines, "cli-ascii: closed polylines");
    is_str(src(p, LAM_CMD_POLYLINE), "$$POLYLINE/{id},{dir},{n},{points:%.5f}", "cli-ascii: polyline");
    lam_profile_free(p);
}

static void ded_script(const lam_sink *s)
{
    lam_layer_info L = { .index = 0, .z = 0.25, .width = 0.5, .floor = 0, .ceiling = 0.5 };
    s->layer(s->ctx, &L);
    move_to(s, 0, (double[]){ 1, 2, 0.25 });
    s->laser(s->ctx, 1);
    move_to(s, 1, (double[]){ 11.0005, 2, 0.25 });
    s->laser(s->ctx, 0);
    s->layer_end(s->ctx, &L);
}

static void cli_script(const lam_sink *s)
{
    static const double xyz[] = { 0, 0, 0.05, 10, 0, 0.05, 10, 5, 0.05, 0, 5, 0.05 };
    static const double uv[] = { 0, 0, 10, 0, 10, 5, 0, 5 };
    lam_layer_info L = { .index = 0, .z = 0.05, .width = 0.1, .floor = 0, .ceiling = 0.1 };
    s->layer(s->ctx, &L);
    lam_contour_info c = { { .part = 1 }, 1, 0, 0.05, xyz, uv, 4, 0, 0, 0, 0 };
    s->contour(s->ctx, &c);
    s->layer_end(s->ctx, &L);
}

static void test_dialect_programs(void)
{
    lam_profile *p;
    lam_error err;
    lam_job_info job;
    memset(&job, 0, sizeof job);
    job.process = "ladrp";
    job.units = "mm";
    job.layers = 2;
    double box[6] = { 0, 0, 0, 10, 5, 1 };
    memcpy(job.bbox, box, sizeof box);
    if (lam_profile_find("ded-gcode", &p, &err) == LAM_OK) {
        job.name = p->name;
        job.label = "bracket";
        job.bead = 1;
        job.rate = p->feed_rate;
        job.travel_rate = p->travel_rate;
        char *out = program(p, &job, ded_script);
        ok(has(out, "; lamina DED program: part bracket on ded-gcode (2 layers, bead 1 mm)\n"),
           "ded-gcode: the preamble names the part and the machine");
        ok(has(out, "; bounding box 0.000 0.000 0.000 to 10.000 5.000 1.000\nG21"), "ded-gcode: bounding box");
        ok(has(out, "; layer 1 z=0.250\nG0 X1.000 Y2.000 Z0.250 F3000\nM3 S1000 ; laser on\nM8 ; powder on\n"
                    "G1 X11.001 Y2.000 Z0.250 F600\nM5 ; laser off\nM9 ; powder off\n"),
           "ded-gcode: layer, travel at 3000, laser and powder on, deposit at 600");
        size_t n = strlen(out);
        ok(n > 52 && !strcmp(out + n - 52, "M5 ; laser off\nM9 ; powder off\nM30 ; end of program\n"),
           "ded-gcode: the last deposit's laser off, then the postamble ends the program (M5/M9 once)");
        free(out);
        job.label = NULL;
        lam_profile_free(p);
    }
    if (lam_profile_find("cli-ascii", &p, &err) == LAM_OK) {
        job.name = p->name;
        job.process = "sls";
        job.layers = 1;
        char *out = program(p, &job, cli_script);
        is_str(out,
               "$$HEADERSTART\n$$ASCII\n$$UNITS/1\n$$VERSION/200\n"
               "$$DIMENSION/0.00000,0.00000,0.00000,10.00000,5.00000,1.00000\n$$LAYERS/1\n$$LABEL/1,part\n"
               "$$HEADEREND\n$$GEOMETRYSTART\n"
               "$$LAYER/0.05000\n"
               "$$POLYLINE/1,1,5,0.00000,0.00000,10.00000,0.00000,10.00000,5.00000,0.00000,5.00000,0.00000,0.00000\n"
               "$$GEOMETRYEND\n",
               "cli-ascii: header, layer, closed polyline, end");
        free(out);
        lam_profile_free(p);
    }
}

/* The thesis's SLS dialect written directly with printf, as lamina did
 * before profiles existed: the reference the sls-contours profile must
 * match byte for byte (six decimals, no "-0.000000", blank lines between
 * blocks). */
static double tidy(double x)
{
    return fabs(x) < 5e-7 ? 0.0 : x;
}

static void lam_sls_write_layer(lam_writer *w, const lam_layer *L, const lam_frame *f, size_t *blocks)
{
    for (size_t i = 0; i < L->ncontours; i++) {
        const lam_contour *c = &L->contours[i];
        if ((*blocks)++) lam_writer_write(w, "\n", 1);
        lam_writer_printf(w, "contour %.6f\nloop %zu\n", tidy(L->cut), c->n);
        for (size_t k = 0; k < c->n; k++) {
            double p[3];
            lam_frame_to_model(f, L->uv[2 * (c->first + k)], L->uv[2 * (c->first + k) + 1], L->cut, p);
            lam_writer_printf(w, "%.6f %.6f %.6f\n", tidy(p[0]), tidy(p[1]), tidy(p[2]));
        }
        lam_writer_printf(w, "endloop\nendcontour\n");
    }
}

/* The sls-contours profile writes what `lamina slice` wrote without one. */
static int sls_same(const char *model, const double dir[3], double width, lam_cut cut)
{
    lam_error err;
    lam_model *m;
    lam_profile *p;
    if (lam_model_load(model, &m, &err) || lam_profile_find("sls-contours", &p, &err)) {
        diag("%s", err.msg);
        return 0;
    }
    lam_slice_opts o;
    lam_slice_opts_init(&o);
    lam_frame_direction(dir, &o.frame, &err);
    o.width = width;
    o.cut = cut;
    lam_slicer *s;
    if (lam_slicer_new(m, &o, &s, &err)) abort();
    lam_writer *wa, *wb;
    lam_writer_memory(&wa, &err);
    lam_writer_memory(&wb, &err);
    lam_sink sink;
    lam_dialect_sink(&p->dialect, wb, &sink, &err);
    lam_job_info job;
    memset(&job, 0, sizeof job);
    job.name = p->name;
    job.process = "sls";
    job.units = p->units;
    job.layers = lam_slicer_count(s);
    sink.begin(sink.ctx, &job);
    size_t blocks = 0, id = 1;
    lam_layer *L;
    while (lam_slicer_next(s, &L, &err) == LAM_OK && L) {
        lam_sls_write_layer(wa, L, &o.frame, &blocks);
        lam_layer_info li = { .index = L->index, .z = L->cut, .width = L->width, .floor = L->floor, .ceiling = L->ceiling };
        sink.layer(sink.ctx, &li);
        for (size_t k = 0; k < L->ncontours; k++) {
            const lam_contour *c = &L->contours[k];
            double *xyz = malloc(3 * c->n * sizeof *xyz);
            for (size_t i = 0; i < c->n; i++)
                lam_frame_to_model(&o.frame, L->uv[2 * (c->first + i)], L->uv[2 * (c->first + i) + 1], L->cut,
                                   xyz + 3 * i);
            lam_contour_info ci = { { .part = id++ }, c->kind == LAM_SOLID, c->depth, L->cut, xyz, L->uv + 2 * c->first, c->n, 0, 0, 0, 0 };
            sink.contour(sink.ctx, &ci);
            free(xyz);
        }
        sink.layer_end(sink.ctx, &li);
        lam_layer_free(L);
    }
    sink.end(sink.ctx);
    sink.destroy(sink.ctx);
    char *a, *b;
    size_t na, nb;
    lam_writer_take(wa, &a, &na, &err);
    lam_writer_take(wb, &b, &nb, &err);
    int same = na == nb && memcmp(a, b, na) == 0 && na > 0;
    if (!same) {
        size_t i = 0;
        while (i < na && i < nb && a[i] == b[i]) i++;
        diag("differ at byte %zu: sls.c '%.30s' vs profile '%.30s'", i, a + i, b + i);
    }
    free(a);
    free(b);
    lam_slicer_free(s);
    lam_model_free(m);
    lam_profile_free(p);
    return same;
}

/* ---- inheritance ---------------------------------------------------------- */

static void test_inherits(void)
{
    lam_profile *p;
    lam_error err;
    int rc = lam_profile_load(fx("child.yaml"), &p, &err);
    ok(rc == LAM_OK, "child inheriting creol-ladrp by name loads%s%s", rc ? ": " : "", rc ? err.msg : "");
    if (!rc) {
        is_str(p->name, "creol-child", "child: its own name");
        is_str(p->units, "cm", "child: units from the parent");
        is_num(p->bead_width, 0.08, 0, "child: bead from the parent");
        is_int(p->cut, LAM_CUT_FLOOR, "child: cut from the parent");
        is_num(p->angle, 90, 0, "child: raster.angle overridden");
        ok(p->first_line == LAM_FIRST_EDGE && p->alternate, "child: other raster keys kept");
        is_str(src(p, LAM_CMD_FEED), "{rate:%.3f} feedrate", "child: feed overridden");
        is_str(src(p, LAM_CMD_LASER_ON), "0 pendown", "child: laser_on kept");
        ok(!p->dialect.cmd[LAM_CMD_LASER_OFF].present, "child: laser_off removed by null");
        is_str(src(p, LAM_CMD_PREAMBLE), "start_plot\n{dimension} set_dimension\n{rate:%.2f} feedrate", "child: preamble kept");
        ok(strstr(p->path, "child.yaml") != NULL, "child: path is the child's");
        lam_profile_free(p);
    }

    rc = lam_profile_load(fx("leaf.yaml"), &p, &err);
    ok(rc == LAM_OK, "a chain of three (leaf -> mid -> base) loads%s%s", rc ? ": " : "", rc ? err.msg : "");
    if (!rc) {
        is_str(p->name, "leaf", "chain: leaf's name");
        is_str(p->description, "third of a chain", "chain: leaf's description");
        is_num(p->bead_width, 0.5, 0, "chain: bead from the grandparent");
        is_num(p->feed_rate, 20, 0, "chain: feed rate from the parent");
        is_num(p->travel_rate, 20, 0, "chain: travel rate defaults to the resolved feed rate");
        is_num(p->angle, 45, 0, "chain: raster.angle from the parent");
        ok(p->first_line == LAM_FIRST_CENTER, "chain: raster.first_line from the grandparent");
        is_int(p->perimeters, 2, "chain: raster.perimeters from the leaf");
        is_str(src(p, LAM_CMD_TRAVEL), "M {x} {y}", "chain: travel from the parent");
        is_str(src(p, LAM_CMD_DEPOSIT), "D {x} {y}", "chain: deposit from the grandparent");
        is_str(p->units, "mm", "chain: default units");
        lam_profile_free(p);
    }

    p = (lam_profile *)1;
    rc = lam_profile_load(fx("cycle_a.yaml"), &p, &err);
    error_is(rc, &err, LAM_EINVAL, 3, 11, "inherits cycle", "cycle a -> b -> a: error at b's inherits");
    ok(p == NULL, "cycle: no profile");
    ok(strstr(err.msg, "cycle_a.yaml -> ") && strstr(err.msg, "cycle_b.yaml -> ") && strstr(err.file, "cycle_b.yaml"),
       "cycle: the chain is spelled out: %s", err.msg);
    load_fails(fx("missing_parent.yaml"), LAM_EINVAL, 2, 11, "no machine profile no-such-machine.yaml",
               "inherits a missing profile");
    const char *self = tmpfile_with("self.yaml", "name: self\ninherits: self.yaml\n");
    load_fails(self, LAM_EINVAL, 2, 11, "inherits cycle", "a profile inheriting itself");
    const char *nofile = tmpfile_with("nofile.yaml", "name: x\ninherits: ./not-there.yaml\n");
    load_fails(nofile, LAM_EINVAL, 2, 11, "cannot open", "inherits a path that does not exist");
    /* errors inside the parent are reported in the parent */
    const char *badparent = tmpfile_with("badparent.yaml", "inherits: bad_child_parent.yaml\n");
    tmpfile_with("bad_child_parent.yaml", "name: p\nprocess: ladrp\nbead_width: -2\n");
    rc = lam_profile_load(badparent, &p, &err);
    ok(rc == LAM_EINVAL && strstr(err.file, "bad_child_parent.yaml") && err.line == 3 && err.column == 13,
       "an error in the parent names the parent's file and position (%s:%ld:%ld)", err.file, err.line, err.column);
}

/* ---- errors ----------------------------------------------------------------- */

static void test_errors(void)
{
    load_fails(fx("malformed.yaml"), LAM_ESYNTAX, 4, 10, "malformed YAML: did not find expected ',' or ']'",
               "malformed YAML");
    load_fails(fx("unknown_key.yaml"), LAM_EINVAL, 4, 1,
               "unknown key 'feedrate' (did you mean 'feed_rate'? allowed: name,",
               "unknown key, with the allowed ones");
    load_fails(fx("missing_name.yaml"), LAM_EINVAL, 2, 1, "missing key 'name'", "missing name: at the mapping");
    load_fails(fx("sls_no_spot.yaml"), LAM_EINVAL, 1, 1, "missing key 'spot_width'", "sls without spot_width");
    load_fails(fx("wrong_type.yaml"), LAM_EINVAL, 4, 3, "bead_width must be a number, got a mapping", "wrong type");
    load_fails(fx("bead_zero.yaml"), LAM_EINVAL, 3, 13, "bead_width must be greater than 0, got '0'", "bead_width 0");
    load_fails(fx("feed_negative.yaml"), LAM_EINVAL, 4, 12, "feed_rate must be 0 or more, got '-1'", "feed_rate -1");
    load_fails(fx("unknown_field.yaml"), LAM_EINVAL, 5, 33, "dialect.travel: unknown field 'dw' for the travel command",
               "unknown template field: line:column inside the template");
    load_fails(fx("bad_spec.yaml"), LAM_EINVAL, 6, 22, "dialect.deposit: length modifier 'l'",
               "bad format spec in a plain scalar: exact column");
    load_fails(fx("block_template.yaml"), LAM_EINVAL, 8, 24, "unknown field 'bogus'",
               "template error inside a literal block: its line and column");
    load_fails(fx("python_tag.yaml"), LAM_EINVAL, 3, 13, "YAML tag '!!python/object/apply:os.system' is not allowed",
               "a python tag is just an error");
    load_fails(fx("percent_n.yaml"), LAM_EINVAL, 5, 16, "%n is not allowed", "%%n in a template is just an error");
    load_fails(fx("quoted_number.yaml"), LAM_EINVAL, 3, 13, "bead_width must be a number, got the quoted string '0.08'",
               "a quoted number");
    load_fails(fx("nan.yaml"), LAM_EINVAL, 3, 13, "bead_width must be a finite number, got 'nan'", "nan");
    load_fails(fx("duplicate.yaml"), LAM_EINVAL, 6, 1, "duplicate key 'bead_width' (first given at line 3)",
               "duplicate key");
    load_fails(fx("two_docs.yaml"), LAM_EINVAL, 6, 1, "one YAML document", "two documents");
    load_fails(fx("not_mapping.yaml"), LAM_EINVAL, 1, 1, "got a list", "a list instead of a mapping");
    load_fails(fx("bad_process.yaml"), LAM_EINVAL, 2, 10, "process must be ladrp or sls, got 'fdm'", "unknown process");
    load_fails(fx("overhang.yaml"), LAM_EINVAL, 4, 19, "max_overhang_deg must be from 0 to 90",
               "overhang out of range");

    const char *hdr = "name: t\nprocess: ladrp\nbead_width: 1\n";
    char text[1024];
#define CASE(body, code, line, col, msg, what)                                            \
    do {                                                                                  \
        snprintf(text, sizeof text, "%s%s", hdr, body);                                  \
        load_fails(tmpfile_with("case.yaml", text), code, line, col, msg, what);         \
    } while (0)
    CASE("dialect:\n  preamble: \"start\\n{bogus}\"\n", LAM_EINVAL, 5, 22, "unknown field 'bogus'",
         "double-quoted template with an escape: exact column");
    CASE("dialect:\n  preamble: 'it''s {bogus}'\n", LAM_EINVAL, 5, 21, "unknown field 'bogus'",
         "single-quoted template with '': exact column");
    CASE("dialect:\n  preamble: start\n    {bogus}\n", LAM_EINVAL, 5, 13, "unknown field 'bogus'",
         "multi-line plain template: the scalar's start");
    CASE("dialect:\n  preamble:\n    - a\n", LAM_EINVAL, 6, 5,
         "dialect.preamble must be a template (text) or null, got a list", "a template that is a list");
    CASE("dialect: start_plot\n", LAM_EINVAL, 4, 10, "dialect must be a mapping", "dialect as text");
    CASE("dialect:\n  penup: \"0 penup\"\n", LAM_EINVAL, 5, 3,
         "unknown key 'penup' in dialect (allowed: close_polylines, preamble, postamble,", "unknown command");
    CASE("raster:\n  alternate: maybe\ndialect: {}\n", LAM_EINVAL, 5, 14,
         "raster.alternate must be true or false, got 'maybe'", "not a boolean");
    CASE("raster:\n  perimeters: 1.5\ndialect: {}\n", LAM_EINVAL, 5, 15, "raster.perimeters must be a whole number",
         "perimeters not whole");
    CASE("raster: [1]\ndialect: {}\n", LAM_EINVAL, 4, 9, "raster must be a mapping", "raster as a list");
    CASE("cut: top\ndialect: {}\n", LAM_EINVAL, 4, 6, "cut must be floor, middle or ceiling, got 'top'", "bad cut");
    CASE("gap: 1e999\ndialect: {}\n", LAM_EINVAL, 4, 6, "gap must be a finite number", "overflowing number");
    CASE("gap: 0x10\ndialect: {}\n", LAM_EINVAL, 4, 6, "gap must be a number or auto, got '0x10'", "hex is not a number");
    CASE("gap: 1.5mm\ndialect: {}\n", LAM_EINVAL, 4, 6, "gap must be a number or auto, got '1.5mm'", "trailing text");
    CASE("gap: .inf\ndialect: {}\n", LAM_EINVAL, 4, 6, "gap must be a number", "YAML .inf");
    CASE("name: again\ndialect: {}\n", LAM_EINVAL, 4, 1, "duplicate key 'name'", "duplicate name");
    CASE("units:\ndialect: {}\n", LAM_EINVAL, 4, 7, "units must be mm, cm, m, um, \xc2\xb5m, in, inch or ft, got null",
         "null units");
    CASE("units: \"<script>console.log(7)</script>\"\ndialect: {}\n", LAM_EINVAL, 4, 8,
         "units must be mm, cm, m, um, \xc2\xb5m, in, inch or ft, got '<script>", "units: a unit name, not markup");
    CASE("units: furlong\ndialect: {}\n", LAM_EINVAL, 4, 8, "units must be mm", "units: an unknown unit");
    CASE("hatch_distance: 0.5\ndialect: {}\n", LAM_EINVAL, 4, 1, "hatch_distance is read by the sls planner only",
         "an sls key in a ladrp profile: at the key");
    CASE("hatch_distance: 1e-9\ndialect: {}\n", LAM_EINVAL, 4, 17, "hatch_distance must be 1e-06 or more, got '1e-9'",
         "a hatch distance below the least: at the value");
    load_fails(tmpfile_with("case.yaml", "name: t\nprocess: sls\nspot_width: 1\nraster: {angle: 5}\ndialect: {}\n"),
               LAM_EINVAL, 4, 10,
               "raster.angle is read by the ladrp planner only, and this is an sls profile: set hatch_angle instead",
               "a raster key in an sls profile: at the key in its section");
    CASE("layer_thickness: 0.5\nlayer_width: 0.5\ndialect: {}\n", LAM_EINVAL, 5, 1,
         "duplicate key 'layer_width': layer_thickness is another name of layer_width (given at line 4)",
         "a key and its alias: a duplicate");
    CASE("layer_width: 0\ndialect: {}\n", LAM_EINVAL, 4, 14, "layer_width must be greater than 0", "layer_width 0");
    CASE("travel_rate: -0.5\ndialect: {}\n", LAM_EINVAL, 4, 14, "travel_rate must be 0 or more", "travel_rate < 0");
    CASE("frame: world\ndialect: {}\n", LAM_EINVAL, 4, 8, "frame must be model or machine", "bad frame");
    CASE("writer: \"\"\n", LAM_EINVAL, 4, 9, "writer must not be empty", "empty writer");
    CASE("dialect:\n  vertex: !custom '{x}'\n", LAM_EINVAL, 5, 11, "YAML tag '!custom' is not allowed", "local tag");
    CASE("", LAM_EINVAL, 1, 1, "missing key 'dialect'", "no dialect and no writer");
    CASE("dialect:\n  deposit: \"{dx\xff}\"\n", LAM_ESYNTAX, 5, 16, "malformed YAML: invalid", "invalid UTF-8");
    CASE("? [a, b]\n: 1\ndialect: {}\n", LAM_EINVAL, 4, 3, "keys must be text, got a list", "a list as a key");
#undef CASE
    load_fails(tmpfile_with("empty.yaml", ""), LAM_EINVAL, 1, 1, "empty profile", "an empty file");
    load_fails(tmpfile_with("comments.yaml", "# nothing\n"), LAM_EINVAL, 1, 1, "empty profile", "only comments");

    lam_profile *p;
    lam_error err;
    int rc = lam_profile_load(fx("no-such-file.yaml"), &p, &err);
    ok(rc == LAM_EIO && has(err.msg, "cannot open") && err.line == 0, "a missing file: LAM_EIO, no position");
    rc = lam_profile_load(fixtures, &p, &err);
    ok(rc == LAM_EIO && has(err.msg, "directory"), "a directory: LAM_EIO (%s)", err.msg);
    rc = lam_profile_find("no-such-machine", &p, &err);
    ok(rc == LAM_EINVAL && has(err.msg, "unknown machine 'no-such-machine'"), "find: unknown name (%s)", err.msg);

    /* aliases are fine (data), nothing expands beyond the schema */
    const char *alias = tmpfile_with("alias.yaml", "name: a\nprocess: ladrp\nbead_width: &w 0.25\nlayer_width: *w\n"
                                                   "dialect:\n  travel: &t \"{x} {y}\"\n  deposit: *t\n");
    rc = lam_profile_load(alias, &p, &err);
    ok(rc == LAM_OK && p->layer_width == 0.25 && !strcmp(src(p, LAM_CMD_DEPOSIT), "{x} {y}"), "anchors and aliases");
    if (!rc) lam_profile_free(p);

    /* a plugin writer instead of a dialect; yes/no booleans */
    rc = lam_profile_load(fx("plugin_writer.yaml"), &p, &err);
    ok(rc == LAM_OK, "writer without dialect loads%s%s", rc ? ": " : "", rc ? err.msg : "");
    if (!rc) {
        is_str(p->writer, "cli-binary", "writer name");
        ok(p->beam_offset == 1, "beam_offset: yes");
        is_num(p->bead_width, 0.08, 0, "sls bead_width is the spot");
        lam_profile_free(p);
    }
    /* block scalars: the final line break is not an extra empty line */
    const char *blk = tmpfile_with("block.yaml", "name: b\nprocess: ladrp\nbead_width: 1\ndialect:\n"
                                                 "  preamble: |\n    G21\n    G90\n  postamble: |+\n    M30\n\n"
                                                 "  layer: \"\"\n  feed: ~\n");
    rc = lam_profile_load(blk, &p, &err);
    ok(rc == LAM_OK, "block scalars load%s%s", rc ? ": " : "", rc ? err.msg : "");
    if (!rc) {
        is_str(src(p, LAM_CMD_PREAMBLE), "G21\nG90", "'|' block: final line break dropped");
        is_str(src(p, LAM_CMD_POSTAMBLE), "M30\n", "'|+' block: one kept line break is an empty line");
        is_str(src(p, LAM_CMD_LAYER), "", "\"\": present, an empty line");
        ok(!p->dialect.cmd[LAM_CMD_FEED].present, "~: absent");
        is_num(p->gap, LAM_GAP_AUTO, 0, "default gap: auto");
        is_int(p->cut, LAM_CUT_MIDDLE, "default cut middle");
        lam_profile_free(p);
    }
}

/* ---- --show round trip ------------------------------------------------------ */

static int same_profile(const lam_profile *a, const lam_profile *b)
{
    int same = !strcmp(a->name, b->name) && !a->description == !b->description &&
               (!a->description || !strcmp(a->description, b->description)) && a->process == b->process &&
               !strcmp(a->units, b->units) && a->bead_width == b->bead_width && a->spot_width == b->spot_width &&
               a->layer_width == b->layer_width && a->cut == b->cut && a->feed_rate == b->feed_rate &&
               a->travel_rate == b->travel_rate && a->gap == b->gap && a->frame_machine == b->frame_machine &&
               a->first_line == b->first_line && a->angle == b->angle && a->angle_step == b->angle_step &&
               a->alternate == b->alternate && a->min_deposit == b->min_deposit && a->perimeters == b->perimeters &&
               a->beam_offset == b->beam_offset && a->max_overhang_deg == b->max_overhang_deg &&
               !strcmp(a->writer, b->writer) && a->dialect.close_polylines == b->dialect.close_polylines;
    for (int c = 0; c < LAM_CMD_COUNT && same; c++) {
        const lam_template *x = &a->dialect.cmd[c], *y = &b->dialect.cmd[c];
        same = x->present == y->present && (!x->present || !strcmp(x->source, y->source));
        if (!same) diag("command %s differs", lam_cmd_name((lam_cmd)c));
    }
    return same;
}

static char *dump(const lam_profile *p)
{
    lam_writer *w;
    lam_error err;
    lam_writer_memory(&w, &err);
    lam_profile_dump(p, w);
    char *out;
    size_t n;
    lam_writer_take(w, &out, &n, &err);
    return out;
}

/* text without its comment lines */
static char *strip_comments(const char *s)
{
    char *out = malloc(strlen(s) + 1), *o = out;
    while (*s) {
        const char *nl = strchr(s, '\n');
        size_t len = nl ? (size_t)(nl - s) + 1 : strlen(s);
        if (*s != '#') {
            memcpy(o, s, len);
            o += len;
        }
        s += len;
    }
    *o = '\0';
    return out;
}

static void round_trip(const char *which)
{
    lam_profile *p, *q;
    lam_error err;
    if (lam_profile_find(which, &p, &err)) {
        ok(0, "round trip %s: %s", which, err.msg);
        return;
    }
    char *text = dump(p);
    char name[64];
    snprintf(name, sizeof name, "rt-%d.yaml", (int)strlen(which));
    const char *path = tmpfile_with(name, text);
    int rc = lam_profile_load(path, &q, &err);
    ok(rc == LAM_OK, "round trip %s: the dump loads%s%s", which, rc ? ": " : "", rc ? err.msg : "");
    if (rc) {
        diag("%s", text);
        free(text);
        lam_profile_free(p);
        return;
    }
    ok(same_profile(p, q), "round trip %s: identical profile", which);
    char *again = dump(q), *a = strip_comments(text), *b = strip_comments(again);
    is_str(b, a, "round trip %s: dumping again gives the same YAML", which);
    free(a);
    free(b);
    free(again);
    free(text);
    lam_profile_free(p);
    lam_profile_free(q);
}

int main(void)
{
    const char *tests = getenv("TESTS");
    if (!tests) tests = "tests";
    snprintf(fixtures, sizeof fixtures, "%s/models/machines", tests);
    char machines[1100];
    snprintf(machines, sizeof machines, "%s/../machines", tests);
    setenv("LAMINA_MACHINES", machines, 1);
    snprintf(tmpdir, sizeof tmpdir, "/tmp/lamina-profile-XXXXXX");
    if (!mkdtemp(tmpdir)) abort();

    char *dirs[8];
    size_t nd = lam_machine_dirs(dirs, 8);
    ok(nd >= 1 && !strcmp(dirs[0], machines), "LAMINA_MACHINES comes first in the machine dirs");
    for (size_t i = 0; i < nd; i++) free(dirs[i]);

    test_shipped();
    test_dialect_programs();
    char model[1100];
    snprintf(model, sizeof model, "%s/models/thesis_cube_hole.ug", tests);
    static const double X[3] = { 1, 0, 0 }, Y[3] = { 0, 1, 0 }, Z[3] = { 0, 0, 1 }, D[3] = { 1, 2, 2 };
    ok(sls_same(model, Z, 1, LAM_CUT_FLOOR), "sls-contours = lamina slice: thesis cube with hole");
    ok(sls_same(model, X, 0.25, LAM_CUT_FLOOR), "sls-contours = lamina slice: along x");
    ok(sls_same(model, D, 0.1, LAM_CUT_MIDDLE), "sls-contours = lamina slice: tilted (tiny negatives print as 0)");
    snprintf(model, sizeof model, "%s/models/frame_island.ug", tests);
    ok(sls_same(model, Z, 5, LAM_CUT_MIDDLE), "sls-contours = lamina slice: frame with an island");
    snprintf(model, sizeof model, "%s/models/cube_hole.stl", tests);
    ok(sls_same(model, Y, 0.1, LAM_CUT_CEILING), "sls-contours = lamina slice: STL along y, thin layers");
    test_inherits();
    test_errors();
    round_trip("creol-ladrp");
    round_trip("sls-contours");
    round_trip("ded-gcode");
    round_trip("cli-ascii");
    round_trip(fx("leaf.yaml"));
    round_trip(fx("child.yaml"));
    round_trip(fx("plugin_writer.yaml"));

    char cmd[400];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
    if (system(cmd) != 0) diag("could not remove %s", tmpdir);
    {
        /* the built-in SLS profile is the shipped file, to the byte */
        char path[1024];
        const char *tdir = getenv("TESTS");
        snprintf(path, sizeof path, "%s/../machines/sls-contours.yaml", tdir ? tdir : "tests");
        FILE *f = fopen(path, "rb");
        char text[8192];
        size_t n = f ? fread(text, 1, sizeof text - 1, f) : 0;
        if (f) fclose(f);
        text[n] = '\0';
        is_str(text, lam_profile_builtin_sls_text(), "built-in SLS profile text equals machines/sls-contours.yaml");
        lam_profile *bp = NULL;
        lam_error berr;
        lam_error_clear(&berr);
        ok(lam_profile_builtin_sls(&bp, &berr) == LAM_OK && bp && strcmp(bp->name, "sls-contours") == 0,
           "the built-in profile loads (%s)", berr.msg);
        lam_profile_free(bp);
    }
    return done_testing();
}
