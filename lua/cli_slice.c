/* lamina slice MODEL [options]: slice and write the thesis's SLS contour
 * dialect (until machine profiles choose the dialect), optionally an SVG
 * contact sheet. Everything is written through atomic writers: a run that
 * fails leaves no output file. */
#include "cli.h"
#include "model.h"
#include "slice.h"
#include "sls.h"
#include "svg.h"
#include "writer.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char usage_text[] =
    "usage: lamina slice MODEL [-a x|y|z|DX,DY,DZ] [-w WIDTH | --widths W1,W2,... |\n"
    "                          --planes P1,P2,...] [--cut floor|middle|ceiling]\n"
    "                          [--gap TOL] [--allow-open] [--svg FILE] [-o FILE]\n"
    "  -a, --axis       slice axis or direction (default z)\n"
    "  -w, --width      uniform layer width (default: 1/100 of the extent, rounded)\n"
    "      --widths     layer widths from the model's minimum; must cover the model\n"
    "      --planes     explicit layer boundaries, strictly increasing\n"
    "      --cut        where each layer's section is taken (default middle)\n"
    "      --gap        close open outlines whose ends are at most TOL apart (default 0.05)\n"
    "      --allow-open drop outlines that stay open instead of failing\n"
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

static int need_arg(int i, int argc, char **argv)
{
    if (i + 1 >= argc) {
        cli_usage("slice", "option %s needs a value", argv[i]);
        return 0;
    }
    return 1;
}

int cmd_slice(int argc, char **argv)
{
    const char *path = NULL, *out_path = NULL, *svg_path = NULL;
    lam_slice_opts o;
    lam_slice_opts_init(&o);
    double *list = NULL;
    int allow_open = 0, rc = EXIT_OK;
    lam_error err;
    lam_error_clear(&err);
#define USAGE(...) do { rc = cli_usage("slice", __VA_ARGS__); goto done; } while (0)
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            fputs(usage_text, stdout);
            goto done;
        } else if (!strcmp(a, "-a") || !strcmp(a, "--axis")) {
            if (!need_arg(i, argc, argv)) { rc = EXIT_USAGE; goto done; }
            const char *v = argv[++i];
            if (strlen(v) == 1 && strchr("xyzXYZ", v[0])) {
                lam_frame_axis(v[0], &o.frame, &err);
            } else {
                double *d = NULL;
                long n = parse_list(v, &d);
                int bad = n != 3 || lam_frame_direction(d, &o.frame, &err) != LAM_OK;
                free(d);
                if (bad) USAGE("unknown axis '%s' (x, y, z or a direction DX,DY,DZ)", v);
            }
        } else if (!strcmp(a, "-w") || !strcmp(a, "--width")) {
            if (!need_arg(i, argc, argv)) { rc = EXIT_USAGE; goto done; }
            if (!parse_number(argv[++i], &o.width) || !(o.width > 0))
                USAGE("layer width must be a positive number (got '%s')", argv[i]);
        } else if (!strcmp(a, "--widths") || !strcmp(a, "--planes")) {
            if (!need_arg(i, argc, argv)) { rc = EXIT_USAGE; goto done; }
            free(list);
            list = NULL;
            long n = parse_list(argv[++i], &list);
            if (n < 1) USAGE("%s takes numbers separated by commas (got '%s')", a, argv[i]);
            if (!strcmp(a, "--widths")) {
                o.widths = list; o.nwidths = (size_t)n; o.planes = NULL; o.nplanes = 0;
            } else {
                o.planes = list; o.nplanes = (size_t)n; o.widths = NULL; o.nwidths = 0;
            }
        } else if (!strcmp(a, "--cut")) {
            if (!need_arg(i, argc, argv)) { rc = EXIT_USAGE; goto done; }
            const char *v = argv[++i];
            if (!strcmp(v, "floor")) o.cut = LAM_CUT_FLOOR;
            else if (!strcmp(v, "middle")) o.cut = LAM_CUT_MIDDLE;
            else if (!strcmp(v, "ceiling")) o.cut = LAM_CUT_CEILING;
            else USAGE("--cut takes floor, middle or ceiling (got '%s')", v);
        } else if (!strcmp(a, "--gap")) {
            if (!need_arg(i, argc, argv)) { rc = EXIT_USAGE; goto done; }
            if (!parse_number(argv[++i], &o.gap) || o.gap < 0)
                USAGE("--gap takes a tolerance >= 0 (got '%s')", argv[i]);
        } else if (!strcmp(a, "--allow-open")) {
            allow_open = 1;
        } else if (!strcmp(a, "--svg")) {
            if (!need_arg(i, argc, argv)) { rc = EXIT_USAGE; goto done; }
            svg_path = argv[++i];
        } else if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
            if (!need_arg(i, argc, argv)) { rc = EXIT_USAGE; goto done; }
            out_path = argv[++i];
        } else if (a[0] == '-' && a[1]) {
            USAGE("unknown option '%s'", a);
        } else if (path) {
            USAGE("more than one model given ('%s' and '%s')", path, a);
        } else {
            path = a;
        }
    }
    if (!path) USAGE("no model given");
    if (o.widths && o.width > 0) USAGE("give either -w or --widths, not both");
    if (o.planes && o.width > 0) USAGE("give either -w or --planes, not both");

    lam_model *m = NULL;
    lam_slicer *s = NULL;
    lam_writer *w = NULL;
    lam_svg *svg = NULL;
    if (lam_model_load(path, &m, &err)) {
        rc = cli_fail(&err);
        goto done;
    }
    if (lam_slicer_new(m, &o, &s, &err)) {
        rc = err.code == LAM_EUSAGE ? cli_usage("slice", "%s", err.msg) : cli_fail(&err);
        goto cleanup;
    }
    if ((out_path && strcmp(out_path, "-") ? lam_writer_file(out_path, &w, &err)
                                          : lam_writer_stream(stdout, "stdout", &w, &err))) {
        rc = cli_fail(&err);
        goto cleanup;
    }
    if (svg_path) {
        double box[4];
        lam_slicer_uv_bounds(s, box);
        char title[600];
        snprintf(title, sizeof title, "lamina: %s", path);
        if (lam_svg_new(lam_slicer_count(s), box, title, &svg, &err)) {
            rc = cli_fail(&err);
            goto cleanup;
        }
    }
    size_t blocks = 0, open_total = 0, gaps_total = 0, gap_layers = 0;
    double gap_max = 0;
    for (;;) {
        lam_layer *L;
        if (lam_slicer_next(s, &L, &err)) {
            rc = cli_fail(&err);
            goto cleanup;
        }
        if (!L) break;
        for (size_t k = 0; k < L->nopen; k++) {
            if (open_total++ < 20)
                fprintf(stderr, "lamina: %s: layer %zu (h=%g): open outline from (%g, %g) to (%g, %g) could not be closed\n",
                        path, L->index, L->cut, L->open[k].start[0], L->open[k].start[1], L->open[k].end[0],
                        L->open[k].end[1]);
        }
        if (L->gaps_closed) {
            if (gap_layers++ < 20)
                fprintf(stderr, "lamina: %s: layer %zu (h=%g): closed %zu gap%s, largest %g\n", path, L->index,
                        L->cut, L->gaps_closed, L->gaps_closed == 1 ? "" : "s", L->max_gap);
            gaps_total += L->gaps_closed;
            if (L->max_gap > gap_max) gap_max = L->max_gap;
        }
        int wrc = lam_sls_write_layer(w, L, lam_slicer_frame(s), &blocks);
        if (!wrc && svg) wrc = lam_svg_add(svg, L, &err);
        lam_layer_free(L);
        if (wrc) {
            rc = cli_fail(&err);
            goto cleanup;
        }
    }
    if (gap_layers > 20) fprintf(stderr, "lamina: %s: closed %zu gaps in %zu layers, largest %g\n", path, gaps_total, gap_layers, gap_max);
    if (open_total) {
        fprintf(stderr, "lamina: %s: %zu outline%s stayed open (gap tolerance %g)%s\n", path, open_total,
                open_total == 1 ? "" : "s", o.gap,
                allow_open ? "; dropped (--allow-open)" : "; use --gap to close larger gaps or --allow-open to drop them");
        if (!allow_open) {
            rc = EXIT_INPUT;
            goto cleanup;
        }
    }
    if (svg) {
        lam_writer *sw;
        if (lam_writer_file(svg_path, &sw, &err)) {
            rc = cli_fail(&err);
            goto cleanup;
        }
        lam_svg_write(svg, sw);
        if (lam_writer_commit(sw, &err)) {
            rc = cli_fail(&err);
            goto cleanup;
        }
    }
    int crc = lam_writer_commit(w, &err);
    w = NULL;
    if (crc) rc = cli_fail(&err);
cleanup:
    lam_writer_abort(w);
    lam_svg_free(svg);
    lam_slicer_free(s);
    lam_model_free(m);
done:
    free(list);
    return rc;
#undef USAGE
}
