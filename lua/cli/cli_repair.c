/* lamina repair MODEL -o OUT [--json] [-q | -v] [load options]: the model
 * loaded as every command loads it (cli_load_model: units, placement,
 * then repair.h's pass), what repair did on one line of standard error,
 * what stays open as warnings, and the repaired mesh written to OUT:
 * binary STL, or OBJ for a name ending in .obj (mesh_write.h), whole or
 * not at all (writer.h; never over the input). Exit 3 when the mesh
 * written is still open (docs/repair.md says why). */
#include "cli.h"
#include "cli_args.h"
#include "cli_repair.h"
#include "mesh_write.h"
#include "model.h"
#include "repair.h"
#include "repair_note.h"
#include "writer.h"

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* The model options (--units, --scale, --rotate, --place, --translate,
 * --no-repair) are OPT_MODEL's: the shared parser prints their table after
 * this text. */
static const char usage_text[] =
    "usage: lamina repair MODEL -o FILE [--json] [-q | -v] [model options]\n"
    "Load a .ug, .stl or .obj model as 'lamina slice' loads it and repairs it (welds\n"
    "cracks, drops degenerate and duplicate facets, orients the facets of each shell,\n"
    "fills holes) and write the repaired mesh to FILE: binary STL, or Wavefront OBJ\n"
    "for a name ending in .obj. One line on standard error says what was repaired;\n"
    "a warning says what remains open. Exit 3 when the mesh written is still open.\n"
    "Without a machine profile, --units converts to millimetres.\n"
    "  -o, --output     the repaired mesh (-: standard output, when it is not a terminal)\n"
    "      --json       the repair report as one JSON object on standard output\n"
    "  -q, --quiet      no summary line; warnings and errors only\n"
    "  -v, --verbose    also the mesh's counts before and after repair\n"
    "MODEL - reads standard input. Values: --name=VALUE or --name VALUE; -- ends the options.\n";

/* What the output option allows, before anything is read. */
static int check_output(const char *out, const args *a)
{
    if (!out)
        return cli_usage("repair", "give the output: -o FILE (binary STL, or OBJ for a name ending in .obj; "
                                   "- for standard output)");
    if (strcmp(out, "-")) return EXIT_OK;
    if (a->json) return cli_usage("repair", "-o - and --json both write to standard output: give -o a file");
    /* binary STL is no text: as gzip does, not to a terminal */
    if (isatty(STDOUT_FILENO))
        return cli_usage("repair", "-o -: binary STL is not written to a terminal (give a file, or redirect "
                                   "standard output)");
    return EXIT_OK;
}

static void json_counts(FILE *o, const lam_model_stats *s)
{
    fprintf(o, "{\"triangles\":%zu,\"vertices\":%zu,\"shells\":%zu,\"boundary_edges\":%zu,\"nonmanifold_edges\":%zu,"
               "\"area\":",
            s->triangles, s->vertices, s->shells, s->boundary_edges, s->nonmanifold_edges);
    cli_json_number(o, s->area);
    fputs(",\"volume\":", o);
    cli_json_number(o, s->volume);
    fputc('}', o);
}

/* The report as one JSON object (docs/repair.md lists the fields): the
 * repair report as the run's JSON and `info --json` have it, and the
 * mesh's counts before and after. */
static void print_json(const lam_model *m, const lam_model_stats *before, const char *out, const char *summary)
{
    FILE *o = stdout;
    fputs("{\"model\":", o);
    cli_json_string(o, m->path);
    fputs(",\"format\":", o);
    cli_json_string(o, m->format);
    fputs(",\"output\":", o);
    cli_json_string(o, strcmp(out, "-") ? out : "<stdout>");
    fprintf(o, ",\"output_format\":\"%s\",\"repair\":",
            lam_mesh_format_for(out) == LAM_MESH_OBJ ? "obj" : "stl-binary");
    cli_repair_json(o, &m->repair);
    fprintf(o, ",\"closed\":%s,\"summary\":", m->stats.boundary_edges ? "false" : "true");
    cli_json_string(o, summary);
    fputs(",\"before\":", o);
    json_counts(o, before);
    fputs(",\"after\":", o);
    json_counts(o, &m->stats);
    fputs("}\n", o);
}

/* What was done (a note: not with -q; "nothing to repair" too, which the
 * other commands leave unsaid), the counts (-v), and what remains
 * (warnings, always): the words of every command (repair_note.h). */
static void print_text(const args *a, const lam_model *m, const lam_model_stats *before)
{
    const lam_repair_report *r = &m->repair;
    const lam_model_stats *s = &m->stats;
    int quiet = a->talk < 0;
    if (!r->ran) {
        if (!quiet) fprintf(stderr, "lamina: %s: not repaired (--no-repair)\n", m->path);
        if (s->boundary_edges || s->nonmanifold_edges)
            fprintf(stderr, "lamina: warning: %s: %zu open edge%s and %zu non-manifold edge%s (not repaired: "
                            "--no-repair)\n",
                    m->path, s->boundary_edges, s->boundary_edges == 1 ? "" : "s", s->nonmanifold_edges,
                    s->nonmanifold_edges == 1 ? "" : "s");
    } else {
        if (!quiet && !lam_repair_acted(r)) fprintf(stderr, "lamina: %s: nothing to repair\n", m->path);
        cli_repair_note(m, quiet);
    }
    if (a->talk > 0)
        fprintf(stderr,
                "lamina: %s: before: %zu triangles, %zu vertices, %zu open edges; "
                "after: %zu triangles, %zu vertices, %zu open edges\n",
                m->path, before->triangles, before->vertices, before->boundary_edges, s->triangles, s->vertices,
                s->boundary_edges);
}

/* Load (load options, no repair yet: the counts before), repair unless
 * --no-repair. On failure the exit status, after the message. */
static int load(args *a, lam_model **m, lam_model_stats *before)
{
    lam_error err;
    lam_error_clear(&err);
    int no_repair = a->no_repair;
    a->no_repair = 1;
    int rc = cli_load_model(a, NULL, m, &err);
    a->no_repair = no_repair;
    if (rc) return cli_fail_cmd("repair", &err);
    *before = (*m)->stats;
    /* the same pass loading runs (import.c's finish): built, then repaired */
    if (!no_repair && lam_model_repair(m, NULL, &err)) {
        lam_model_free(*m);
        *m = NULL;
        return cli_fail(&err);
    }
    return EXIT_OK;
}

/* Write m to out, whole or not at all. */
static int write_out(const lam_model *m, const char *out)
{
    lam_error err;
    lam_error_clear(&err);
    lam_writer *w = NULL;
    if (cli_writer("-o", out, &w, &err)) return cli_fail_cmd("repair", &err);
    if (lam_model_write_mesh(m, lam_mesh_format_for(out), w, &err)) {
        lam_writer_abort(w);
        return cli_fail(&err);
    }
    if (lam_writer_commit(w, &err)) return cli_fail_cmd("repair", &err);
    return EXIT_OK;
}

/* The command once its arguments are read. */
static int repair(args *a, const char *out)
{
    lam_model *m = NULL;
    lam_model_stats before = { 0 };
    int rc = load(a, &m, &before);
    if (rc) return rc;
    lam_error err;
    lam_error_clear(&err);
    /* an output that would replace the input is told before any report
     * (the writer asks again when it opens and before it renames);
     * standard output too, when the JSON goes there at the end */
    if (cli_output_check("-o", out, &err) || (a->json && cli_stdout_check(&err))) {
        lam_model_free(m);
        return cli_fail_cmd("repair", &err);
    }
    char summary[512];
    lam_repair_summary(&m->repair, summary, sizeof summary);
    print_text(a, m, &before);
    rc = write_out(m, out);
    if (!rc && a->json) print_json(m, &before, out, summary);
    if (!rc && m->stats.boundary_edges) rc = EXIT_CHECK;
    lam_model_free(m);
    return rc;
}

int cmd_repair(int argc, char **argv)
{
    args a;
    memset(&a, 0, sizeof a);
    int rc = cli_parse_args("repair", usage_text, OPT_MODEL | OPT_JSON | OPT_TALK | OPT_OUTPUT, argc, argv, &a);
    if (!rc) rc = check_output(a.out, &a);
    if (!rc) rc = repair(&a, a.out);
    cli_args_free(&a);
    return rc < 0 ? EXIT_OK : rc; /* -1: --help was printed */
}
