/* lamina check MODEL -m MACHINE [--json] [--svg FILE]: design rules of the
 * machine checked on the model (drc.h): walls thinner than the bead or spot,
 * overhangs steeper than the profile's max_overhang_deg. Exit 0 clean, 3
 * with violations. --svg draws the layers (the machine's slicing) with the
 * violations ringed on the layers whose slab holds them. */
#include "cli.h"
#include "repair_note.h"
#include "cli_args.h"
#include "cli_overhang.h"
#include "drc.h"
#include "fmt.h"
#include "model.h"
#include "svg.h"
#include "validate.h"
#include "writer.h"

#include <math.h>
#include <string.h>

static const char usage_text[] =
    "usage: lamina check MODEL -m MACHINE [-s KEY=VALUE ...] [-a AXIS] [-w WIDTH ...] [--json]\n"
    "                          [--svg FILE]\n"
    "Design-rule check: walls thinner than the machine's bead (or spot) width,\n"
    "downward faces steeper than its max_overhang_deg (when the profile sets it), and\n"
    "for a powder-bed machine each layer's overhang that stands on nothing within\n"
    "support_angle of the layer below, with the supports its support_type makes.\n"
    "-a gives the build direction (default z). Exit 3 when any rule is violated.\n";

static int draw(const args *a, lam_model *m, const lam_drc_result *res, const char *units, lam_error *err)
{
    lam_slicer *s = NULL;
    lam_svg *svg = NULL;
    int rc = lam_slicer_new(m, &a->so, &s, err);
    if (!rc) {
        double box[4];
        lam_slicer_uv_bounds(s, box);
        char title[600];
        snprintf(title, sizeof title, "lamina check: %s (%zu violation%s ringed)", a->path, res->n, res->n == 1 ? "" : "s");
        rc = lam_svg_new(lam_slicer_count(s), box, title, &svg, err);
        if (!rc) rc = lam_svg_set_units(svg, units, err); /* the scale bar's */
    }
    const lam_frame *f = s ? lam_slicer_frame(s) : NULL;
    const double *planes = s ? lam_slicer_planes(s) : NULL;
    size_t nl = s ? lam_slicer_count(s) : 0;
    for (size_t i = 0; i < res->n && !rc; i++) {
        const double *p = res->items[i].pos;
        double u = p[0] * f->u[0] + p[1] * f->u[1] + p[2] * f->u[2];
        double v = p[0] * f->v[0] + p[1] * f->v[1] + p[2] * f->v[2];
        double h = p[0] * f->w[0] + p[1] * f->w[1] + p[2] * f->w[2];
        /* a point on a slab's boundary (a flat face) belongs to the slab it
         * bounds, up to rounding of the point's coordinates */
        double tol = 1e-9 * (fabs(planes[0]) + fabs(planes[nl]) + 1);
        for (size_t k = 0; k < nl && !rc; k++)
            if (h >= planes[k] - tol && h <= planes[k + 1] + tol) rc = lam_svg_mark(svg, k, u, v, err);
    }
    while (!rc) {
        lam_layer *L;
        if ((rc = lam_slicer_next(s, &L, err)) || !L) break;
        rc = lam_svg_add(svg, L, err);
        lam_layer_free(L);
    }
    if (!rc) rc = cli_save_svg(svg, a->svg, a->max_output, err);
    lam_svg_free(svg);
    lam_slicer_free(s);
    return rc;
}

/* Violation i of the report, as JSON (where: its triangles' source). */
static void json_violation(const lam_violation *x, size_t i, const char *where)
{
    fprintf(stdout, "%s{\"rule\":\"%s\",\"position\":[", i ? "," : "", lam_rule_name(x->rule));
    for (int k = 0; k < 3; k++) {
        if (k) fputc(',', stdout);
        cli_json_number(stdout, x->pos[k]);
    }
    fputs("],\"value\":", stdout);
    cli_json_number(stdout, x->value);
    fputs(",\"limit\":", stdout);
    cli_json_number(stdout, x->limit);
    fputs(",\"area\":", stdout);
    cli_json_number(stdout, x->area);
    fprintf(stdout, ",\"triangles\":%zu,\"source\":", x->triangles);
    cli_json_string(stdout, where);
    fputc('}', stdout);
}

/* The report of res (the rules o of profile prof) on standard output: text
 * or, with --json, JSON. */
static void report(const args *a, const lam_model *m, const lam_profile *prof, const lam_drc_opts *o,
                   const lam_drc_result *res, const cli_overhangs *ov)
{
    if (a->json) {
        fputs("{\"model\":", stdout);
        cli_json_string(stdout, a->path);
        fputs(",\"machine\":", stdout);
        cli_json_string(stdout, prof->name);
        fputs(",\"rules\":{\"min_wall\":", stdout);
        cli_json_number(stdout, o->min_wall);
        fputs(",\"max_overhang_deg\":", stdout);
        if (o->max_overhang_deg > 0) cli_json_number(stdout, o->max_overhang_deg);
        else fputs("null", stdout);
        fputs("},\"violations\":[", stdout);
    }
    for (size_t i = 0; i < res->n; i++) {
        const lam_violation *x = &res->items[i];
        char where[700];
        lam_mesh_describe_tri(&m->mesh, x->tri, where, sizeof where);
        if (a->json) {
            json_violation(x, i, where);
        } else if (x->rule == LAM_RULE_WALL) {
            /* the powder bed's word for the width is the spot (profile_keys.c) */
            printf("%s: wall %.6g thick at (%g, %g, %g), thinner than the %s %s (%s; region of %zu triangles, area %g)\n",
                   lam_rule_name(x->rule), x->value, x->pos[0], x->pos[1], x->pos[2],
                   prof->process == LAM_PROCESS_SLS ? "spot" : "bead", LAM_NUM(x->limit), where, x->triangles, x->area);
        } else {
            printf("%s: overhang %.4g degrees from vertical at (%g, %g, %g), limit %s (%s; region of %zu triangles, area %g)\n",
                   lam_rule_name(x->rule), x->value, x->pos[0], x->pos[1], x->pos[2], LAM_NUM(x->limit), where, x->triangles,
                   x->area);
        }
    }
    if (a->json) {
        fprintf(stdout, "],\"samples\":%zu", res->samples);
        cli_overhangs_print(ov, a->path, 1);
        fputs("}\n", stdout);
    } else {
        printf("%s: %zu violation%s of %s's rules (min_wall %s", a->path, res->n, res->n == 1 ? "" : "s", prof->name,
               LAM_NUM(o->min_wall));
        if (o->max_overhang_deg > 0) printf(", max_overhang %s degrees", LAM_NUM(o->max_overhang_deg));
        printf(")\n");
        cli_overhangs_print(ov, a->path, 0);
    }
}

int cmd_check(int argc, char **argv)
{
    args a;
    int rc = cli_parse_args("check", usage_text, OPT_MODEL | OPT_SLICE | OPT_SET | OPT_JSON | OPT_SVG, argc, argv, &a);
    if (rc) {
        cli_args_free(&a);
        return rc < 0 ? EXIT_OK : rc;
    }
    if (!a.machine) {
        cli_args_free(&a);
        return cli_usage("check", "a machine is needed (-m NAME or PATH): its bead (or spot) width and overhang limit are the rules");
    }
    lam_error err;
    lam_error_clear(&err);
    lam_profile *prof = NULL;
    lam_model *m = NULL;
    lam_rays *v = NULL;
    lam_drc_result res;
    memset(&res, 0, sizeof res);
    if ((rc = cli_profile("check", &a, &prof, NULL))) goto done;
    if (cli_load_model(&a, prof, &m, &err)) {
        rc = cli_fail(&err);
        goto done;
    }
    a.path = m->path; /* "<stdin>" for "-" */
    if (cli_output_check("--svg", a.svg, &err)) { /* written last: told now (cli.h) */
        rc = cli_fail_cmd("check", &err);
        goto done;
    }
    if (lam_rays_new(m, &v, &err)) {
        rc = cli_fail(&err);
        goto done;
    }
    lam_drc_opts o;
    lam_drc_opts_from_profile(&o, prof, a.so.frame.w);
    if (lam_drc_run(m, v, &o, &res, &err)) {
        rc = cli_fail(&err);
        goto done;
    }
    cli_overhangs ov;
    if (cli_overhangs_run(&a, m, prof, &ov, &err)) {
        cli_overhangs_free(&ov);
        rc = cli_fail_limit(&err, 0, CLI_RAISE_LAYERS);
        goto done;
    }
    report(&a, m, prof, &o, &res, &ov);
    size_t bad = ov.bad;
    cli_overhangs_free(&ov);
    if (a.svg && draw(&a, m, &res, prof->units, &err)) {
        rc = cli_fail_limit(&err, 0, CLI_RAISE_LAYERS);
        goto done;
    }
    rc = res.n || bad ? EXIT_CHECK : EXIT_OK;
done:
    fflush(stdout);
    lam_drc_result_free(&res);
    lam_rays_free(v);
    lam_model_free(m);
    lam_profile_free(prof);
    cli_args_free(&a);
    return rc;
}
