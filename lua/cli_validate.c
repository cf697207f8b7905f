/* lamina validate MODEL [slice options] [--json]: an independent 3D check
 * of every solid/hole label with Embree rays (SPEC 6). Exit 0 when every
 * checked contour is confirmed, 3 when any disagrees. Contours too small
 * to place a test point in are reported as unchecked, not as failures. */
#include "cli.h"
#include "cli_args.h"
#include "cli_check.h"
#include "model.h"
#include "validate.h"

#include <string.h>

static const char usage_text[] =
    "usage: lamina validate MODEL [-m MACHINE] [-a AXIS] [-w WIDTH | --widths ... | --planes ...]\n"
    "                             [--cut floor|middle|ceiling] [--gap TOL] [--allow-open]\n"
    "                             [--fill evenodd|nonzero] [--json]\n"
    "Slices like 'lamina slice' and checks every contour's label against the 3D model:\n"
    "test points beside its edges, lifted to the cut height, get their winding number\n"
    "from rays cast through the model (Embree). Exit 3 when any label disagrees.\n";

static const char *kind_name(const lam_layer *L, size_t c)
{
    return L->contours[c].kind == LAM_SOLID ? "solid" : "hole";
}

int vreport_layer(vreport *r, lam_validator *v, const lam_layer *L, const lam_frame *f, int fill_nonzero,
                  lam_error *err)
{
    lam_layer_check chk;
    int rc = lam_validate_layer(v, L, f, fill_nonzero, &chk, err);
    if (rc) return rc;
    r->layers++;
    r->checked += chk.checked;
    r->confirmed += chk.confirmed;
    r->disagreeing += chk.disagreeing;
    r->unchecked += chk.unchecked;
    if (r->json) {
        fprintf(r->out, "%s{\"index\":%zu,\"z\":", r->first ? "" : ",", L->index);
        cli_json_number(r->out, L->cut);
        fprintf(r->out, ",\"contours\":%zu,\"checked\":%zu,\"confirmed\":%zu,\"disagreeing\":%zu,\"unchecked\":%zu,"
                        "\"disagreements\":[",
                L->ncontours, chk.checked, chk.confirmed, chk.disagreeing, chk.unchecked);
        int firstd = 1;
        for (size_t i = 0; i < chk.nitems; i++) {
            const lam_contour_check *c = &chk.items[i];
            if (c->ok != 0) continue;
            fprintf(r->out, "%s{\"contour\":%zu,\"label\":\"%s\",\"position\":[", firstd ? "" : ",", c->contour,
                    kind_name(L, c->contour));
            for (int k = 0; k < 3; k++) {
                if (k) fputc(',', r->out);
                cli_json_number(r->out, c->xyz[k]);
            }
            fprintf(r->out, "],\"winding\":%d,\"label_says\":\"%s\",\"why\":", c->winding_found,
                    c->expected_material ? "material" : "void");
            cli_json_string(r->out, c->why ? c->why : "");
            fputc('}', r->out);
            firstd = 0;
        }
        fputs("]}", r->out);
        r->first = 0;
    } else {
        if (r->verbose || chk.disagreeing || chk.unchecked)
            fprintf(r->out, "layer %zu (h=%g): %zu contour%s, %zu confirmed, %zu disagreeing%s\n", L->index, L->cut,
                    L->ncontours, L->ncontours == 1 ? "" : "s", chk.confirmed, chk.disagreeing,
                    chk.unchecked ? ", some too small to check" : "");
        for (size_t i = 0; i < chk.nitems; i++) {
            const lam_contour_check *c = &chk.items[i];
            if (c->ok == 0)
                fprintf(r->out, "  contour %zu (%s) disagrees at (%g, %g, %g): winding %d, the label says %s (%s)\n",
                        c->contour, kind_name(L, c->contour), c->xyz[0], c->xyz[1], c->xyz[2], c->winding_found,
                        c->expected_material ? "material" : "void", c->why ? c->why : "");
            else if (c->ok < 0)
                fprintf(r->out, "  contour %zu (%s) not checked: %s\n", c->contour, kind_name(L, c->contour),
                        c->why ? c->why : "no test point");
        }
    }
    lam_layer_check_free(&chk);
    return LAM_OK;
}

int cmd_validate(int argc, char **argv)
{
    args a;
    int rc = cli_parse_args("validate", usage_text, OPT_SLICE | OPT_JSON, argc, argv, &a);
    if (rc) {
        cli_args_free(&a);
        return rc < 0 ? EXIT_OK : rc;
    }
    lam_error err;
    lam_error_clear(&err);
    lam_profile *prof = NULL;
    lam_model *m = NULL;
    lam_slicer *s = NULL;
    lam_validator *v = NULL;
    vreport r;
    memset(&r, 0, sizeof r);
    r.out = stdout;
    r.json = a.json;
    r.verbose = 1;
    r.first = 1;
    if (a.machine) {
        lam_plan_opts po;
        lam_plan_opts_init(&po);
        if (cli_load_profile(&a, &prof, &err)) {
            rc = cli_fail(&err);
            goto done;
        }
        cli_apply_profile(&a, prof, &po);
    }
    if (lam_model_load(a.path, &m, &err)) {
        rc = cli_fail(&err);
        goto done;
    }
    if (lam_slicer_new(m, &a.so, &s, &err)) {
        rc = err.code == LAM_EUSAGE ? cli_usage("validate", "%s", err.msg) : cli_fail_limit(&err, 0, CLI_RAISE_LAYERS);
        goto done;
    }
    if (lam_validator_new(m, &v, &err)) {
        rc = cli_fail(&err);
        goto done;
    }
    if (r.json) {
        fputs("{\"model\":", stdout);
        cli_json_string(stdout, a.path);
        fprintf(stdout, ",\"fill\":\"%s\",\"layers\":[", a.so.fill_nonzero ? "nonzero" : "evenodd");
    }
    size_t open = 0;
    for (;;) {
        lam_layer *L;
        if (lam_slicer_next(s, &L, &err)) {
            rc = cli_fail(&err);
            goto done;
        }
        if (!L) break;
        open += L->nopen;
        int vrc = vreport_layer(&r, v, L, lam_slicer_frame(s), a.so.fill_nonzero, &err);
        lam_layer_free(L);
        if (vrc) {
            rc = cli_fail(&err);
            goto done;
        }
    }
    if (r.json) {
        fprintf(stdout, "],\"checked\":%zu,\"confirmed\":%zu,\"disagreeing\":%zu,\"unchecked\":%zu,\"open_outlines\":%zu}\n",
                r.checked, r.confirmed, r.disagreeing, r.unchecked, open);
    } else {
        printf("%s: %zu layers, %zu contours checked, %zu confirmed, %zu disagreeing", a.path, r.layers, r.checked,
               r.confirmed, r.disagreeing);
        if (r.unchecked) printf(", %zu too small to check", r.unchecked);
        printf("\n");
    }
    if (open && !a.allow_open) {
        fprintf(stderr, "lamina: %s: %zu outline%s stayed open (gap tolerance %g); use --gap or --allow-open\n", a.path,
                open, open == 1 ? "" : "s", a.so.gap);
        rc = EXIT_INPUT;
    } else {
        rc = r.disagreeing ? EXIT_CHECK : EXIT_OK;
    }
done:
    fflush(stdout);
    lam_validator_free(v);
    lam_slicer_free(s);
    lam_model_free(m);
    lam_profile_free(prof);
    cli_args_free(&a);
    return rc;
}
