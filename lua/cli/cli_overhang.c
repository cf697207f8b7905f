/* lamina check's overhang analysis: see cli_overhang.h. */
#include "cli_overhang.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

static const char *support_name(int type)
{
    const lam_key *k = lam_key_find("support_type");
    for (int i = 0; k && k->choices && k->choices[i]; i++)
        if (i == type) return k->choices[i];
    return "?";
}

static int alloc_report(cli_overhangs *o, size_t n, lam_error *err)
{
    o->n = n;
    o->z = calloc(n + 1, sizeof *o->z);
    o->over = calloc(n + 1, sizeof *o->over);
    o->left = calloc(n + 1, sizeof *o->left);
    o->support = calloc(n + 1, sizeof *o->support);
    return o->z && o->over && o->left && o->support ? LAM_OK : lam_error_nomem(err, "checking overhangs");
}

int cli_overhangs_run(const args *a, lam_model *m, const lam_profile *prof, cli_overhangs *o, lam_error *err)
{
    memset(o, 0, sizeof *o);
    if (prof->process != LAM_PROCESS_SLS) return LAM_OK;
    const lam_support_cfg *c = &prof->scan.support;
    o->ran = 1;
    o->type = support_name(c->type);
    o->units = prof->units;
    o->angle = c->angle;
    lam_slicer *s = NULL;
    lam_layer **L = NULL;
    lam_supports *sup = NULL;
    size_t n = 0;
    int rc = lam_slicer_new(m, &a->so, &s, err);
    if (!rc) rc = lam_slicer_all(s, &L, &n, err);
    if (!rc) rc = alloc_report(o, n, err);
    if (!rc && c->type != LAM_SUPPORT_NONE) rc = lam_supports_make((const lam_layer *const *)L, n, c, &sup, err);
    if (!rc) rc = lam_supports_unsupported((const lam_layer *const *)L, n, sup, c->angle, o->over, o->left, err);
    for (size_t i = 0; !rc && i < n; i++) {
        o->z[i] = L[i]->cut;
        o->support[i] = lam_supports_area(sup, L[i]->index);
        o->bad += o->left[i] > 0;
    }
    lam_supports_free(sup);
    lam_layers_free(L, n);
    lam_slicer_free(s);
    return rc;
}

static void print_json(const cli_overhangs *o)
{
    fputs(",\"overhangs\":{\"support_type\":", stdout);
    cli_json_string(stdout, o->type);
    fputs(",\"support_angle\":", stdout);
    cli_json_number(stdout, o->angle);
    fprintf(stdout, ",\"unsupported_layers\":%zu,\"layers\":[", o->bad);
    size_t k = 0;
    for (size_t i = 0; i < o->n; i++) {
        if (!(o->over[i] > 0 || o->left[i] > 0 || o->support[i] > 0)) continue;
        fprintf(stdout, "%s{\"layer\":%zu,\"z\":", k++ ? "," : "", i + 1);
        cli_json_number(stdout, o->z[i]);
        fputs(",\"overhang\":", stdout);
        cli_json_number(stdout, o->over[i]);
        fputs(",\"unsupported\":", stdout);
        cli_json_number(stdout, o->left[i]);
        fputs(",\"support\":", stdout);
        cli_json_number(stdout, o->support[i]);
        fputc('}', stdout);
    }
    fputs("]}", stdout);
}

void cli_overhangs_print(const cli_overhangs *o, const char *path, int json)
{
    if (!o->ran) return;
    if (json) {
        print_json(o);
        return;
    }
    double total = 0, area = 0;
    size_t with = 0;
    for (size_t i = 0; i < o->n; i++) {
        total += o->left[i];
        area += o->support[i];
        with += o->support[i] > 0;
        if (o->left[i] > 0)
            printf("unsupported: layer %zu (z %s): %.6g %s\xc2\xb2 of overhang beyond the reach of the layer below "
                   "(support_angle %s, supports: %s)\n", i + 1, LAM_NUM(o->z[i]), o->left[i], o->units,
                   LAM_NUM(o->angle), o->type);
    }
    if (o->bad)
        printf("%s: unsupported overhangs on %zu layer%s, %.6g %s\xc2\xb2 in all (supports: %s)\n", path, o->bad,
               o->bad == 1 ? "" : "s", total, o->units, o->type);
    else if (with)
        printf("%s: every overhang stands (support_angle %s; supports: %s, on %zu layer%s, %.6g %s\xc2\xb2)\n",
               path, LAM_NUM(o->angle), o->type, with, with == 1 ? "" : "s", area, o->units);
    else
        printf("%s: every overhang stands (support_angle %s; no support needed)\n", path, LAM_NUM(o->angle));
}

void cli_overhangs_free(cli_overhangs *o)
{
    free(o->z);
    free(o->over);
    free(o->left);
    free(o->support);
    memset(o, 0, sizeof *o);
}
