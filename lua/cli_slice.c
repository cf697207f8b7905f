/* lamina slice MODEL [-m MACHINE] [options]: slice, plan and write a machine
 * program, optionally an SVG contact sheet. The machine profile's widths,
 * cut, gap and raster options are defaults the command line overrides.
 * Without -m the program is the thesis's SLS contour dialect (the built-in
 * twin of machines/sls-contours.yaml). Everything is written through atomic
 * writers: a run that fails leaves no output file. */
#include "cli.h"
#include "dialect.h"
#include "model.h"
#include "planner.h"
#include "plugin.h"
#include "profile.h"
#include "slice.h"
#include "svg.h"
#include "writer.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char usage_text[] =
    "usage: lamina slice MODEL [-m MACHINE] [-a x|y|z|DX,DY,DZ] [-w WIDTH | --widths W1,W2,... |\n"
    "                          --planes P1,P2,...] [--cut floor|middle|ceiling] [--gap TOL]\n"
    "                          [--allow-open] [--first-line edge|center] [--angle DEG]\n"
    "                          [--angle-step DEG] [--min-deposit LEN] [--no-alternate]\n"
    "                          [--perimeters N] [--beam-offset]\n"
    "                          [--frame model|machine] [--svg FILE] [-o FILE]\n"
    "  -m, --machine    machine profile: a shipped name (see 'lamina machines') or a path\n"
    "  -a, --axis       slice axis or direction (default z)\n"
    "  -w, --width      uniform layer width (default: the profile's, else 1/100 of the extent)\n"
    "      --widths     layer widths from the model's minimum; must cover the model\n"
    "      --planes     explicit layer boundaries, strictly increasing\n"
    "      --cut        where each layer's section is taken (default: profile, else middle)\n"
    "      --gap        close open outlines whose ends are at most TOL apart (default 0.05)\n"
    "      --allow-open drop outlines that stay open instead of failing\n"
    "      --first-line, --angle, --angle-step, --min-deposit, --no-alternate, --perimeters\n"
    "                   LADRP raster options (override the profile)\n"
    "      --beam-offset   SLS: move contours inward by half the spot width\n"
    "      --frame      coordinates of the program: model (default) or machine (layer frame)\n"
    "      --svg        write a contact sheet of the layers\n"
    "  -o, --output     program file (default: standard output)\n";

/* Parse "a,b,c" into a malloc'd array. Returns count, or -1 on a bad number. */
static long parse_list(const char *s, double **out)
{
    size_t cap = 8, n = 0;
    double *v = malloc(cap * sizeof *v);
    if (!v) return -1;
    const char *p = s;
    for (;;) {
        char *end;
        errno = 0;
        double x = strtod(p, &end);
        if (end == p || errno == ERANGE || !isfinite(x)) {
            free(v);
            return -1;
        }
        if (n == cap) {
            double *nv = realloc(v, 2 * cap * sizeof *nv);
            if (!nv) {
                free(v);
                return -1;
            }
            v = nv;
            cap *= 2;
        }
        v[n++] = x;
        if (*end == '\0') break;
        if (*end != ',') {
            free(v);
            return -1;
        }
        p = end + 1;
    }
    *out = v;
    return (long)n;
}

static int parse_number(const char *s, double *x)
{
    char *end;
    errno = 0;
    *x = strtod(s, &end);
    return end != s && *end == '\0' && errno != ERANGE && isfinite(*x);
}

/* What the command line said; "set" flags mark overrides of the profile. */
typedef struct args {
    const char *path, *out, *svg, *machine;
    lam_slice_opts so;
    double *list;
    int allow_open, set_width, set_cut, set_gap, set_frame;
    int set_first, first_center, set_angle, set_step, set_min, no_alternate, frame_machine;
    int perimeters, set_perimeters, beam_offset;
    double angle, angle_step, min_deposit;
} args;

static int parse_args(int argc, char **argv, args *a)
{
    memset(a, 0, sizeof *a);
    lam_slice_opts_init(&a->so);
    lam_error err;
    lam_error_clear(&err);
#define NEED() do { if (i + 1 >= argc) return cli_usage("slice", "option %s needs a value", argv[i]); } while (0)
    for (int i = 1; i < argc; i++) {
        const char *o = argv[i];
        if (!strcmp(o, "-h") || !strcmp(o, "--help")) {
            fputs(usage_text, stdout);
            return -1;
        } else if (!strcmp(o, "-m") || !strcmp(o, "--machine")) {
            NEED();
            a->machine = argv[++i];
        } else if (!strcmp(o, "-a") || !strcmp(o, "--axis")) {
            NEED();
            const char *v = argv[++i];
            if (strlen(v) == 1 && strchr("xyzXYZ", v[0])) {
                lam_frame_axis(v[0], &a->so.frame, &err);
            } else {
                double *d = NULL;
                long n = parse_list(v, &d);
                int bad = n != 3 || lam_frame_direction(d, &a->so.frame, &err) != LAM_OK;
                free(d);
                if (bad) return cli_usage("slice", "unknown axis '%s' (x, y, z or a direction DX,DY,DZ)", v);
            }
        } else if (!strcmp(o, "-w") || !strcmp(o, "--width")) {
            NEED();
            if (!parse_number(argv[++i], &a->so.width) || !(a->so.width > 0))
                return cli_usage("slice", "layer width must be a positive number (got '%s')", argv[i]);
            a->set_width = 1;
        } else if (!strcmp(o, "--widths") || !strcmp(o, "--planes")) {
            NEED();
            free(a->list);
            a->list = NULL;
            long n = parse_list(argv[++i], &a->list);
            if (n < 1) return cli_usage("slice", "%s takes numbers separated by commas (got '%s')", o, argv[i]);
            a->so.widths = a->so.planes = NULL;
            a->so.nwidths = a->so.nplanes = 0;
            if (!strcmp(o, "--widths")) {
                a->so.widths = a->list;
                a->so.nwidths = (size_t)n;
            } else {
                a->so.planes = a->list;
                a->so.nplanes = (size_t)n;
            }
        } else if (!strcmp(o, "--cut")) {
            NEED();
            const char *v = argv[++i];
            if (!strcmp(v, "floor")) a->so.cut = LAM_CUT_FLOOR;
            else if (!strcmp(v, "middle")) a->so.cut = LAM_CUT_MIDDLE;
            else if (!strcmp(v, "ceiling")) a->so.cut = LAM_CUT_CEILING;
            else return cli_usage("slice", "--cut takes floor, middle or ceiling (got '%s')", v);
            a->set_cut = 1;
        } else if (!strcmp(o, "--gap")) {
            NEED();
            if (!parse_number(argv[++i], &a->so.gap) || a->so.gap < 0)
                return cli_usage("slice", "--gap takes a tolerance >= 0 (got '%s')", argv[i]);
            a->set_gap = 1;
        } else if (!strcmp(o, "--allow-open")) {
            a->allow_open = 1;
        } else if (!strcmp(o, "--first-line")) {
            NEED();
            const char *v = argv[++i];
            if (strcmp(v, "edge") && strcmp(v, "center"))
                return cli_usage("slice", "--first-line takes edge or center (got '%s')", v);
            a->set_first = 1;
            a->first_center = !strcmp(v, "center");
        } else if (!strcmp(o, "--angle") || !strcmp(o, "--angle-step") || !strcmp(o, "--min-deposit")) {
            NEED();
            double x;
            if (!parse_number(argv[++i], &x)) return cli_usage("slice", "%s takes a number (got '%s')", o, argv[i]);
            if (!strcmp(o, "--angle")) a->angle = x, a->set_angle = 1;
            else if (!strcmp(o, "--angle-step")) a->angle_step = x, a->set_step = 1;
            else if (x < 0) return cli_usage("slice", "--min-deposit takes a length >= 0 (got '%s')", argv[i]);
            else a->min_deposit = x, a->set_min = 1;
        } else if (!strcmp(o, "--perimeters")) {
            NEED();
            double x;
            if (!parse_number(argv[++i], &x) || x < 0 || x > 1000 || x != floor(x))
                return cli_usage("slice", "--perimeters takes a whole number from 0 to 1000 (got '%s')", argv[i]);
            a->perimeters = (int)x;
            a->set_perimeters = 1;
        } else if (!strcmp(o, "--beam-offset")) {
            a->beam_offset = 1;
        } else if (!strcmp(o, "--no-alternate")) {
            a->no_alternate = 1;
        } else if (!strcmp(o, "--frame")) {
            NEED();
            const char *v = argv[++i];
            if (strcmp(v, "model") && strcmp(v, "machine"))
                return cli_usage("slice", "--frame takes model or machine (got '%s')", v);
            a->set_frame = 1;
            a->frame_machine = !strcmp(v, "machine");
        } else if (!strcmp(o, "--svg")) {
            NEED();
            a->svg = argv[++i];
        } else if (!strcmp(o, "-o") || !strcmp(o, "--output")) {
            NEED();
            a->out = argv[++i];
        } else if (o[0] == '-' && o[1]) {
            return cli_usage("slice", "unknown option '%s'", o);
        } else if (a->path) {
            return cli_usage("slice", "more than one model given ('%s' and '%s')", a->path, o);
        } else {
            a->path = o;
        }
    }
#undef NEED
    if (!a->path) return cli_usage("slice", "no model given");
    if ((a->so.widths || a->so.planes) && a->set_width)
        return cli_usage("slice", "give one of -w, --widths and --planes");
    return EXIT_OK;
}

/* Profile defaults under the command line's overrides. */
static void apply_profile(args *a, const lam_profile *p, lam_plan_opts *po)
{
    if (!a->set_width && !a->so.widths && !a->so.planes && p->layer_width > 0) a->so.width = p->layer_width;
    if (!a->set_cut) a->so.cut = (lam_cut)p->cut;
    if (!a->set_gap) a->so.gap = p->gap;
    po->kind = p->process == LAM_PROCESS_LADRP ? LAM_PLAN_LADRP : LAM_PLAN_SLS;
    po->name = p->name;
    po->units = p->units;
    po->bead = p->process == LAM_PROCESS_LADRP ? p->bead_width : p->spot_width;
    po->rate = p->feed_rate;
    po->travel_rate = p->travel_rate;
    po->frame_machine = p->frame_machine;
    po->first_center = p->first_line == LAM_FIRST_CENTER;
    po->angle = p->angle;
    po->angle_step = p->angle_step;
    po->alternate = p->alternate;
    po->min_deposit = p->min_deposit;
    po->perimeters = p->perimeters;
    po->beam_offset = p->beam_offset;
}

static void apply_overrides(const args *a, lam_plan_opts *po)
{
    if (a->set_frame) po->frame_machine = a->frame_machine;
    if (a->set_first) po->first_center = a->first_center;
    if (a->set_angle) po->angle = a->angle;
    if (a->set_step) po->angle_step = a->angle_step;
    if (a->set_min) po->min_deposit = a->min_deposit;
    if (a->no_alternate) po->alternate = 0;
    if (a->set_perimeters) po->perimeters = a->perimeters;
    if (a->beam_offset) po->beam_offset = 1;
}

/* Per-layer reports and the SVG preview, before each layer is planned. */
typedef struct report {
    const char *path;
    lam_svg *svg;
    size_t open_total, gaps_total, gap_layers;
    double gap_max;
} report;

static int on_layer(void *ctx, const lam_layer *L, lam_error *err)
{
    report *r = ctx;
    for (size_t k = 0; k < L->nopen; k++)
        if (r->open_total++ < 20)
            fprintf(stderr, "lamina: %s: layer %zu (h=%g): open outline from (%g, %g) to (%g, %g) could not be closed\n",
                    r->path, L->index, L->cut, L->open[k].start[0], L->open[k].start[1], L->open[k].end[0],
                    L->open[k].end[1]);
    if (L->gaps_closed) {
        if (r->gap_layers++ < 20)
            fprintf(stderr, "lamina: %s: layer %zu (h=%g): closed %zu gap%s, largest %g\n", r->path, L->index, L->cut,
                    L->gaps_closed, L->gaps_closed == 1 ? "" : "s", L->max_gap);
        r->gaps_total += L->gaps_closed;
        if (L->max_gap > r->gap_max) r->gap_max = L->max_gap;
    }
    return r->svg ? lam_svg_add(r->svg, L, err) : LAM_OK;
}

int cmd_slice(int argc, char **argv)
{
    args a;
    int rc = parse_args(argc, argv, &a);
    if (rc) {
        free(a.list);
        return rc < 0 ? EXIT_OK : rc;
    }
    lam_error err;
    lam_error_clear(&err);
    lam_profile *prof = NULL;
    lam_model *m = NULL;
    lam_slicer *s = NULL;
    lam_writer *w = NULL;
    lam_sink sink = { 0 };
    report rep = { a.path, NULL, 0, 0, 0, 0 };

    if (a.machine ? lam_profile_find(a.machine, &prof, &err) : lam_profile_builtin_sls(&prof, &err)) {
        rc = cli_fail(&err);
        goto done;
    }
    lam_plan_opts po;
    lam_plan_opts_init(&po);
    apply_profile(&a, prof, &po);
    apply_overrides(&a, &po);
    if (lam_model_load(a.path, &m, &err)) {
        rc = cli_fail(&err);
        goto done;
    }
    if (lam_slicer_new(m, &a.so, &s, &err)) {
        rc = err.code == LAM_EUSAGE ? cli_usage("slice", "%s", err.msg) : cli_fail(&err);
        goto done;
    }
    if (a.svg) {
        double box[4];
        lam_slicer_uv_bounds(s, box);
        char title[600];
        snprintf(title, sizeof title, "lamina: %s", a.path);
        if (lam_svg_new(lam_slicer_count(s), box, title, &rep.svg, &err)) {
            rc = cli_fail(&err);
            goto done;
        }
    }
    if (a.out && strcmp(a.out, "-") ? lam_writer_file(a.out, &w, &err) : lam_writer_stream(stdout, "stdout", &w, &err)) {
        rc = cli_fail(&err);
        goto done;
    }
    int src = !prof->writer || !strcmp(prof->writer, "text") ? lam_dialect_sink(&prof->dialect, w, &err, &sink)
                                                             : lam_plugin_writer_sink(prof->writer, w, &err, &sink);
    if (src) {
        rc = err.code == LAM_EUSAGE ? cli_usage("slice", "%s", err.msg) : cli_fail(&err);
        goto done;
    }
    if (lam_plan_run(s, m, &po, &sink, on_layer, &rep, &err)) {
        rc = err.code == LAM_EUSAGE ? cli_usage("slice", "%s", err.msg) : cli_fail(&err);
        goto done;
    }
    if (rep.gap_layers > 20)
        fprintf(stderr, "lamina: %s: closed %zu gaps in %zu layers, largest %g\n", a.path, rep.gaps_total,
                rep.gap_layers, rep.gap_max);
    if (rep.open_total) {
        fprintf(stderr, "lamina: %s: %zu outline%s stayed open (gap tolerance %g)%s\n", a.path, rep.open_total,
                rep.open_total == 1 ? "" : "s", a.so.gap,
                a.allow_open ? "; dropped (--allow-open)" : "; use --gap to close larger gaps or --allow-open to drop them");
        if (!a.allow_open) {
            rc = EXIT_INPUT;
            goto done;
        }
    }
    if (rep.svg) {
        lam_writer *sw;
        if (lam_writer_file(a.svg, &sw, &err)) {
            rc = cli_fail(&err);
            goto done;
        }
        lam_svg_write(rep.svg, sw);
        if (lam_writer_commit(sw, &err)) {
            rc = cli_fail(&err);
            goto done;
        }
    }
    {
        lam_writer *tmp = w;
        w = NULL;
        if (lam_writer_commit(tmp, &err)) rc = cli_fail(&err);
    }
done:
    if (sink.destroy) sink.destroy(sink.ctx);
    lam_writer_abort(w);
    lam_svg_free(rep.svg);
    lam_slicer_free(s);
    lam_model_free(m);
    lam_profile_free(prof);
    free(a.list);
    return rc;
}
