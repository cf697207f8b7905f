#include "repair_note.h"

#include "cli.h"
#include "repair.h"

void cli_repair_note(const lam_model *m, int quiet)
{
    const lam_repair_report *r = &m->repair;
    if (!r->ran) return;
    char line[512];
    lam_repair_summary(r, line, sizeof line);
    if (!quiet && line[0]) fprintf(stderr, "lamina: %s: repaired: %s\n", m->path, line);
    if (r->boundary_edges || r->nonmanifold_edges)
        fprintf(stderr, "lamina: warning: %s: after repair %zu open edge%s and %zu non-manifold edge%s remain\n",
                m->path, r->boundary_edges, r->boundary_edges == 1 ? "" : "s", r->nonmanifold_edges,
                r->nonmanifold_edges == 1 ? "" : "s");
    if (r->crossing_edges)
        fprintf(stderr,
                "lamina: warning: %s: after repair the surface crosses itself (%zu edge%s through other facets); "
                "--fill nonzero slices overlapping parts as one\n",
                m->path, r->crossing_edges, r->crossing_edges == 1 ? "" : "s");
}

void cli_repair_json(FILE *o, const lam_repair_report *r)
{
    fprintf(o, "{\"ran\":%s", r->ran ? "true" : "false");
#define COUNT(f) fprintf(o, ",\"" #f "\":%zu", r->f);
    LAM_REPAIR_COUNTS(COUNT)
#undef COUNT
#define MEASURE(f) fputs(",\"" #f "\":", o), cli_json_number(o, r->f);
    LAM_REPAIR_MEASURES(MEASURE)
#undef MEASURE
    fprintf(o, ",\"crossings_unknown\":%s", r->crossings_unknown ? "true" : "false");
    fputc('}', o);
}
