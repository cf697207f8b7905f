/* lamina info MODEL [--json]: the model report of SPEC 2.4. */
#include "cli.h"
#include "cli_args.h"
#include "model.h"

#include <string.h>

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

static void print_json(const lam_model *m, const char *w[4], int nw)
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
    fputs("]}\n", o);
}

static void print_text(const lam_model *m)
{
    const lam_model_stats *s = &m->stats;
    char a[64], b[64], c[64];
    printf("model                 %s\n", m->path);
    printf("format                %s\n", m->format);
    printf("triangles             %zu\n", s->triangles);
    printf("vertices              %zu\n", s->vertices);
    printf("edges                 %zu\n", s->edges);
    printf("shells                %zu (%zu cavit%s)\n", s->shells, s->cavities, s->cavities == 1 ? "y" : "ies");
    const char *axis = "xyz";
    for (int j = 0; j < 3; j++)
        printf("bbox %c                [%s, %s] (size %s)\n", axis[j], cli_num(a, sizeof a, s->bbox[j]),
               cli_num(b, sizeof b, s->bbox[j + 3]), cli_num(c, sizeof c, s->bbox[j + 3] - s->bbox[j]));
    printf("surface area          %s\n", cli_num(a, sizeof a, s->area));
    printf("volume                %s\n", cli_num(a, sizeof a, s->volume));
    printf("boundary edges        %zu\n", s->boundary_edges);
    printf("non-manifold edges    %zu\n", s->nonmanifold_edges);
    printf("degenerate triangles  %zu\n", s->degenerate_tris);
    printf("orientation conflicts %zu\n", s->orientation_conflicts);
    printf("wires                 %zu\n", s->wires);
}

static const char usage_text[] =
    "usage: lamina info MODEL [--json]\n"
    "Report triangles, vertices, edges, shells and cavities, bounding box,\n"
    "surface area, volume, and mesh defects of a .ug, .stl or .obj model.\n";

int cmd_info(int argc, char **argv)
{
    args a;
    int rc = cli_parse_args("info", usage_text, OPT_MODEL | OPT_JSON, argc, argv, &a);
    cli_args_free(&a);
    if (rc) return rc < 0 ? EXIT_OK : rc;
    const char *path = a.path;
    int json = a.json;
    lam_error err;
    lam_error_clear(&err);
    lam_model *m;
    if (cli_load_model(path, &m, &err)) return cli_fail(&err);
    const char *w[4];
    int nw;
    warnings(&m->stats, w, &nw);
    for (int i = 0; i < nw; i++) fprintf(stderr, "lamina: warning: %s: %s\n", m->path, w[i]);
    if (json) print_json(m, w, nw);
    else print_text(m);
    lam_model_free(m);
    return EXIT_OK;
}
