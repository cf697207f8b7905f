/* lamina info MODEL [--json] [slice options]: the model report of SPEC
 * 2.4, the memory the model takes, and the size of the run the slice
 * options (default: the built-in SLS profile, its default layers) define:
 * layers and program bytes estimated before anything is sliced
 * (lam_plan_estimate), then the command's peak memory. */
#include "cli.h"
#include "repair.h"
#include "repair_note.h"
#include "cli_args.h"
#include "support.h"
#include "model.h"
#include "fmt.h"
#include "planner.h"

#include <string.h>
#include <sys/resource.h>

/* What `info` reports beyond the model's statistics. */
typedef struct sizes {
    size_t model, parts[3];     /* lam_model_bytes */
    int sliced;                 /* 0: the run could not be set up (why) */
    char why[1100];
    char machine[200];
    lam_job_estimate est;
    size_t peak;                /* bytes (getrusage ru_maxrss) */
} sizes;

/* EXIT_OK, or cli_profile's status (a profile or option that is wrong:
 * reported). A model the slicer refuses is reported in z->why. */
static int measure(const char *cmd, args *a, const lam_model *m, sizes *z)
{
    z->model = lam_model_bytes(m, z->parts);
    lam_profile *prof = NULL;
    lam_plan_opts po;
    lam_slicer *s = NULL;
    lam_error err;
    lam_error_clear(&err);
    int rc = cli_profile(cmd, a, &prof, &po);
    if (rc) {
        return rc;
    } else if (lam_slicer_new(m, &a->so, &s, &err)) {
        snprintf(z->why, sizeof z->why, "%s", err.msg);
    } else {
        lam_job_info cj;
        char label[128];
        lam_plan_job(s, m, &po, &cj, label);
        lam_program_costs(prof, &cj, &po.costs, NULL);
        lam_plan_estimate(s, &po, &z->est);
        lam_supports *sup = NULL; /* the estimate counts the supports' walls (slicing every layer) */
        if (!lam_plan_supports(s, &po, &sup, NULL) && sup) {
            po.supports = sup;
            lam_plan_estimate(s, &po, &z->est);
        }
        lam_supports_free(sup);
        z->sliced = 1;
        snprintf(z->machine, sizeof z->machine, "%s", prof->name ? prof->name : "lamina");
    }
    lam_slicer_free(s);
    lam_profile_free(prof);
    struct rusage ru;
    z->peak = getrusage(RUSAGE_SELF, &ru) == 0 ? (size_t)ru.ru_maxrss * 1024 : 0;
    return EXIT_OK;
}

static void warnings(const lam_model_stats *s, const char *w[4], int *n)
{
    static char buf[4][128];
    *n = 0;
    if (s->boundary_edges) {
        snprintf(buf[*n], sizeof buf[0], "the mesh is open: %zu boundary edges", s->boundary_edges);
        w[*n] = buf[*n], ++*n;
    }
    if (s->nonmanifold_edges) {
        snprintf(buf[*n], sizeof buf[0], "%zu non-manifold edges (more than two faces)", s->nonmanifold_edges);
        w[*n] = buf[*n], ++*n;
    }
    if (s->degenerate_tris) {
        snprintf(buf[*n], sizeof buf[0], "%zu degenerate triangles (zero area)", s->degenerate_tris);
        w[*n] = buf[*n], ++*n;
    }
    if (s->orientation_conflicts) {
        snprintf(buf[*n], sizeof buf[0], "%zu edges where the surface cannot be oriented consistently",
                 s->orientation_conflicts);
        w[*n] = buf[*n], ++*n;
    }
}

static void print_json(const lam_model *m, const char *w[4], int nw, const sizes *z)
{
    const lam_model_stats *s = &m->stats;
    FILE *o = stdout;
    fputs("{\"model\":", o);
    cli_json_string(o, m->path);
    fputs(",\"format\":", o);
    cli_json_string(o, m->format);
    fprintf(o, ",\"triangles\":%zu,\"vertices\":%zu,\"edges\":%zu,\"shells\":%zu,\"cavities\":%zu,\"wires\":%zu",
            s->triangles, s->vertices, s->edges, s->shells, s->cavities, s->wires);
    fputs(",\"bbox\":{\"min\":[", o);
    for (int j = 0; j < 3; j++) {
        if (j) fputc(',', o);
        cli_json_number(o, s->bbox[j]);
    }
    fputs("],\"max\":[", o);
    for (int j = 0; j < 3; j++) {
        if (j) fputc(',', o);
        cli_json_number(o, s->bbox[j + 3]);
    }
    fputs("]},\"area\":", o);
    cli_json_number(o, s->area);
    fputs(",\"volume\":", o);
    cli_json_number(o, s->volume);
    fprintf(o, ",\"boundary_edges\":%zu,\"nonmanifold_edges\":%zu,\"degenerate_triangles\":%zu,"
               "\"orientation_conflicts\":%zu,\"closed\":%s,\"warnings\":[",
            s->boundary_edges, s->nonmanifold_edges, s->degenerate_tris, s->orientation_conflicts,
            s->boundary_edges == 0 ? "true" : "false");
    for (int i = 0; i < nw; i++) {
        if (i) fputc(',', o);
        cli_json_string(o, w[i]);
    }
    fputs("],\"repair\":", o);
    cli_repair_json(o, &m->repair);
    fprintf(o, ",\"memory\":{\"model\":%zu,\"mesh\":%zu,\"edges\":%zu,\"shells\":%zu,\"peak\":%zu}", z->model,
            z->parts[0], z->parts[1], z->parts[2], z->peak);
    fputs(",\"run\":", o);
    if (z->sliced) {
        fputs("{\"machine\":", o);
        cli_json_string(o, z->machine);
        fprintf(o, ",\"layers\":%zu,\"bytes\":%.0f}", z->est.layers, z->est.bytes);
    } else {
        fputs("{\"error\":", o);
        cli_json_string(o, z->why);
        fputc('}', o);
    }
    fputs("}\n", o);
}

static void print_text(const lam_model *m, const sizes *z)
{
    const lam_model_stats *s = &m->stats;
    char a[32], b[32], c[32], d[32];
    printf("model                 %s\n", m->path);
    printf("format                %s\n", m->format);
    printf("triangles             %zu\n", s->triangles);
    printf("vertices              %zu\n", s->vertices);
    printf("edges                 %zu\n", s->edges);
    printf("shells                %zu (%zu cavit%s)\n", s->shells, s->cavities, s->cavities == 1 ? "y" : "ies");
    const char *axis = "xyz";
    for (int j = 0; j < 3; j++)
        printf("bbox %c                [%s, %s] (size %s)\n", axis[j], LAM_NUM(s->bbox[j]), LAM_NUM(s->bbox[j + 3]),
               LAM_NUM(s->bbox[j + 3] - s->bbox[j]));
    /* sums over every triangle: 12 digits, past the rounding of thousands of terms */
    printf("surface area          %s\n", lam_fmt_num((char[LAM_FMT_NUM]){ 0 }, s->area, 12));
    printf("volume                %s\n", lam_fmt_num((char[LAM_FMT_NUM]){ 0 }, s->volume, 12));
    printf("boundary edges        %zu\n", s->boundary_edges);
    printf("non-manifold edges    %zu\n", s->nonmanifold_edges);
    printf("degenerate triangles  %zu\n", s->degenerate_tris);
    printf("orientation conflicts %zu\n", s->orientation_conflicts);
    printf("wires                 %zu\n", s->wires);
    char line[512];
    const lam_repair_report *r = &m->repair;
    printf("repair                %s\n", !r->ran ? "off (--no-repair)"
                                      : lam_repair_acted(r) ? lam_repair_summary(r, line, sizeof line)
                                                           : "nothing to repair");
    if (r->ran && (r->boundary_edges || r->nonmanifold_edges || r->crossing_edges))
        printf("after repair          %zu open edges, %zu non-manifold edges, %zu edges through other facets\n",
               r->boundary_edges, r->nonmanifold_edges, r->crossing_edges);
    printf("model memory          %s (mesh %s, edges %s, shells %s)\n", lam_fmt_bytes(a, sizeof a, (double)z->model),
           lam_fmt_bytes(b, sizeof b, (double)z->parts[0]), lam_fmt_bytes(c, sizeof c, (double)z->parts[1]),
           lam_fmt_bytes(d, sizeof d, (double)z->parts[2]));
    if (z->sliced)
        printf("run                   %zu layers (%s), about %s of program\n", z->est.layers, z->machine,
               lam_fmt_bytes(a, sizeof a, z->est.bytes));
    else
        printf("run                   cannot slice: %s\n", z->why);
    printf("peak memory           %s (this command)\n", lam_fmt_bytes(a, sizeof a, (double)z->peak));
}

static const char usage_text[] =
    "usage: lamina info MODEL [--json] [-m MACHINE] [slice options]\n"
    "Report triangles, vertices, edges, shells and cavities, bounding box,\n"
    "surface area, volume, and mesh defects of a .ug, .stl or .obj model;\n"
    "the memory its arrays take, the layers and estimated program size of the\n"
    "run that -m and the slice options define (as 'lamina slice' takes them),\n"
    "and the command's peak memory (resident set).\n";

int cmd_info(int argc, char **argv)
{
    args a;
    int rc = cli_parse_args("info", usage_text, OPT_MODEL | OPT_JSON | OPT_SLICE | OPT_SET, argc, argv, &a);
    if (rc) {
        cli_args_free(&a);
        return rc < 0 ? EXIT_OK : rc;
    }
    int json = a.json;
    lam_error err;
    lam_error_clear(&err);
    lam_model *m;
    /* -m's units are what --units converts into, as for slice */
    lam_profile *machine = NULL;
    if (a.machine && (rc = cli_profile("info", &a, &machine, NULL))) {
        cli_args_free(&a);
        return rc;
    }
    rc = cli_load_model(&a, machine, &m, &err);
    lam_profile_free(machine);
    if (rc) {
        cli_args_free(&a);
        return cli_fail(&err);
    }
    sizes z;
    memset(&z, 0, sizeof z);
    if ((rc = measure("info", &a, m, &z))) {
        lam_model_free(m);
        cli_args_free(&a);
        return rc;
    }
    const char *w[4];
    int nw;
    warnings(&m->stats, w, &nw);
    for (int i = 0; i < nw; i++) fprintf(stderr, "lamina: warning: %s: %s\n", m->path, w[i]);
    cli_repair_note(m, 0);
    if (json) print_json(m, w, nw, &z);
    else print_text(m, &z);
    lam_model_free(m);
    cli_args_free(&a);
    return EXIT_OK;
}
