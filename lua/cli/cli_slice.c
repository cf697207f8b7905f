/* lamina slice MODEL [-m MACHINE] [options]: slice, plan and write a machine
 * program, optionally an SVG contact sheet. The machine profile's widths,
 * cut, gap and raster options are defaults the command line overrides.
 * Without -m the program is the thesis's SLS contour dialect (the built-in
 * twin of machines/sls-contours.yaml). Everything is written through atomic
 * writers: a run that fails leaves no output file. */
#include "cli.h"
#include "repair_note.h"
#include "cli_args.h"
#include "cli_check.h"
#include "cli_estimate.h"
#include "cli_join.h"
#include "dialect.h"
#include "fmt.h"
#include "json_sink.h"
#include "views.h"
#include "model.h"
#include "planner.h"
#include "plugin.h"
#include "profile.h"
#include "progress.h"
#include "size_sense.h"
#include "slice.h"
#include "cli_view.h"
#include "tee.h"
#include "writer.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char usage_text[] =
    "usage: lamina slice MODEL [-m MACHINE] [-s KEY=VALUE ...] [-a x|y|z|DX,DY,DZ]\n"
    "                          [-w WIDTH | --widths W1,W2,... | --planes P1,P2,...]\n"
    "                          [--cut floor|middle|ceiling] [--gap TOL] [--allow-open]\n"
    "                          [--first-line edge|center] [--angle DEG] [--angle-step DEG]\n"
    "                          [--min-deposit LEN] [--no-alternate] [--perimeters N] [--islands]\n"
    "                          [--beam-offset] [--frame model|machine] [--fill evenodd|nonzero]\n"
    "                          [--validate] [--max-layers N] [--max-output SIZE] [-j N]\n"
    "                          [--svg FILE] [--html FILE] [--json FILE] [-o FILE] [-q | -v]\n"
    "                          [--json-layers A:B] [--json-vectors all|summary|none]\n"
    "                          [--json-contours all|none]\n"
    "                          [--layers A:B|K/N]\n"
    "  -m, --machine    machine profile: a shipped name (see 'lamina machines') or a path\n"
    "                   (default: the thesis's SLS contours)\n"
    "  -s, --set        KEY=VALUE: any key of the machine profile, checked as in its YAML\n"
    "                   (bead_width=0.1, raster.angle=90 or angle=90); repeatable\n"
    "  -a, --axis       slice axis or direction (default z)\n"
    "      --widths     layer widths from the model's minimum; must cover the model\n"
    "      --planes     explicit layer boundaries, strictly increasing\n"
    "      --allow-open drop outlines that stay open instead of failing\n"
    "      --fill       evenodd (default: nesting parity) or nonzero (overlapping bodies merge)\n"
    "      --validate   check every label with Embree first; write nothing if any disagrees\n"
    "      --max-layers refuse runs of more layers (default 1000000)\n"
    "      --max-output refuse programs larger than SIZE bytes (k, M, G, T: powers of\n"
    "                   1024; default 4G), estimated before planning and as written\n"
    "  -j, --jobs       threads that slice and plan (default: LAMINA_THREADS, else the\n"
    "                   processors); the program is the same for every number\n"
    "      --svg        write a contact sheet of the layers and their scan paths\n"
    "      --html       write a viewer of the run: one HTML file to open in a browser\n"
    "      --json       write the run as JSON (layer interchange, docs/json.md): the job,\n"
    "                   each layer's contours and planned vectors, lengths and build time\n"
    "      --json-layers  only layers A to B in the JSON (from 1; A: or :B for the rest)\n"
    "      --json-vectors every vector (all, the default), a summary per layer (summary:\n"
    "                   count and length of each kind) or none\n"
    "      --json-contours the layers' contours in the JSON (all, the default) or none\n"
    "  -o, --output     program file (default: standard output)\n"
    "  -q, --quiet      no progress line and no notes; warnings and errors only\n"
    "  -v, --verbose    every per-layer note, and the time each stage takes\n"
    "MODEL - reads standard input; an output FILE - writes standard output (one at most).\n"
    "      --layers     plan only layers A to B (from 1, inclusive) or part K of N equal\n"
    "                   parts of the run the other options define, into a part file for\n"
    "                   'lamina join' (which writes the whole run's program)\n"
    "Values: --name=VALUE or --name VALUE; -- ends the options. The profile's values are\n"
    "defaults that -s and the options below override.\n";

/* Per-layer reports and the SVG preview, before each layer is planned. */
typedef struct report {
    const char *path;
    cli_view view;      /* --svg, --html */
    lam_rays *v;        /* --validate */
    const lam_frame *frame;
    int fill_nonzero;
    vreport vr;
    size_t open_total, gaps_total, gap_layers;
    double gap_max;
    size_t degenerate_layers, slivers, twins;
    cli_progress progress;
} report;

static int on_layer(void *ctx, const lam_layer *L, lam_error *err)
{
    report *r = ctx;
    size_t notes = cli_progress_notes(&r->progress);
    cli_progress_step(&r->progress, L->index + 1);
    if (L->nopen || L->gaps_closed || L->slivers || L->twins) cli_progress_hide(&r->progress);
    for (size_t k = 0; k < L->nopen; k++)
        if (r->open_total++ < (notes > 20 ? notes : 20)) /* what fails the run is told also with -q */
            fprintf(stderr, "lamina: %s: layer %zu (h=%s): open outline from (%g, %g) to (%g, %g) could not be closed\n",
                    r->path, L->index + 1, LAM_NUM(L->cut), L->open[k].start[0], L->open[k].start[1], L->open[k].end[0],
                    L->open[k].end[1]);
    if (L->gaps_closed) {
        if (r->gap_layers++ < notes)
            fprintf(stderr, "lamina: %s: layer %zu (h=%s): closed %zu gap%s, largest %g (gap tolerance %g)\n", r->path,
                    L->index + 1, LAM_NUM(L->cut), L->gaps_closed, L->gaps_closed == 1 ? "" : "s", L->max_gap, L->gap);
        r->gaps_total += L->gaps_closed;
        if (L->max_gap > r->gap_max) r->gap_max = L->max_gap;
    }
    /* degenerate loops (contour.h): reported like bridged gaps */
    if (L->slivers || L->twins) {
        if (r->degenerate_layers++ < notes) {
            fprintf(stderr, "lamina: %s: layer %zu (h=%s):", r->path, L->index + 1, LAM_NUM(L->cut));
            if (L->slivers) fprintf(stderr, " dropped %zu loop%s of no area%s", L->slivers, L->slivers == 1 ? "" : "s",
                                    L->twins ? "," : "");
            if (L->twins) fprintf(stderr, " cancelled %zu coincident loops", L->twins);
            fputc('\n', stderr);
        }
        r->slivers += L->slivers;
        r->twins += L->twins;
    }
    if (r->v) {
        lam_validate_opts vo;
        lam_validate_opts_init(&vo);
        vo.fill_nonzero = r->fill_nonzero;
        vo.gap = L->gap; /* a layer with gaps bridged is compared with the loss check's allowance */
        int rc = vreport_layer(&r->vr, r->v, L, r->frame, &vo, NULL, err);
        if (rc) return rc;
    }
    return cli_view_layer(&r->view, L, err);
}

/* The program's sink and the views (--json, --svg, --html: views.h, one
 * vector stream decoded once) fed by one plan: *sink becomes a tee that
 * owns them both. On failure *sink is left as it was. */
static int tee_outputs(lam_sink *sink, lam_writer *jw, const lam_json_opts *jo, report *rep, const args *a,
                       lam_slicer *s, const lam_plan_opts *po, lam_error *err)
{
    lam_views views = { .json = jw, .json_opts = jo };
    int rc = cli_view_open(&rep->view, a, s, po, &views, err);
    if (rc || !(views.json || views.html || views.svg)) return rc;
    lam_sink all[2] = { *sink };
    if ((rc = lam_views_sink(&views, &all[1], err))) return rc;
    if ((rc = lam_tee_sink(all, 2, sink, err))) all[1].destroy(all[1].ctx);
    return rc;
}

/* Everything one `lamina slice` holds, released by job_free. */
typedef struct job {
    args a;
    lam_error err;
    lam_profile *prof;
    lam_model *m;
    lam_slicer *s;
    lam_writer *w, *jw;
    lam_sink sink;
    report rep;
    lam_plan_opts po;
    lam_scan_time est;
    lam_ladrp_stats ladrp;   /* LADRP: the run's moves, for the estimate */
    lam_json_opts jopts;     /* what --json holds */
} job;

/* The profile, the model, the slicer and (--validate) the rays: every input
 * is read now (a plugin only later, checked at commit), so no output may
 * replace one, and --svg, written last, is told now. */
static int open_inputs(job *j)
{
    int rc = cli_profile("slice", &j->a, &j->prof, &j->po);
    if (rc) return rc;
    if (cli_load_model(&j->a, j->prof, &j->m, &j->err)) return cli_fail(&j->err);
    j->a.path = j->rep.path = j->m->path; /* "<stdin>" for "-" */
    cli_repair_note(j->m, j->a.talk < 0);
    const char *outs[][2] = { { "-o", j->a.out }, { "--svg", j->a.svg }, { "--json", j->a.json_out },
                              { "--html", j->a.html } };
    for (size_t i = 0; i < sizeof outs / sizeof *outs; i++)
        if (cli_output_check(outs[i][0], outs[i][1], &j->err)) return cli_fail_cmd("slice", &j->err);
    if (lam_slicer_new(j->m, &j->a.so, &j->s, &j->err))
        return j->err.code == LAM_EUSAGE ? cli_usage("slice", "%s", j->err.msg)
                                         : cli_fail_limit(&j->err, 0, CLI_RAISE_LAYERS);
    if (j->a.validate) {
        if (lam_rays_new(j->m, &j->rep.v, &j->err)) return cli_fail(&j->err);
        j->rep.frame = lam_slicer_frame(j->s);
        j->rep.fill_nonzero = j->a.so.fill_nonzero;
    }
    return EXIT_OK;
}

/* The program's writer and sink (a part file's with --layers), the views,
 * every output held to the limit as it is written. */
static int open_outputs(job *j)
{
    const args *a = &j->a;
    if (a->json_out && cli_json_opts("slice", a, lam_slicer_count(j->s), &j->jopts)) return EXIT_USAGE;
    if (cli_writer("-o", a->out, &j->w, &j->err) || (a->json_out && cli_writer("--json", a->json_out, &j->jw, &j->err)))
        return cli_fail_cmd("slice", &j->err);
    unsigned long long limit = a->max_output ? a->max_output : LAM_DEFAULT_MAX_OUTPUT;
    lam_writer_set_limit(j->w, limit);
    if (j->jw) lam_writer_set_limit(j->jw, limit);
    j->po.time = &j->est;
    j->po.totals = &j->ladrp;
    if (a->layers) return cli_part_setup(&j->a, j->prof, j->s, &j->po, j->w, &j->sink);
    int rc = lam_program_sink(j->prof->writer, &j->prof->dialect, j->w, &j->sink, &j->err);
    if (!rc) rc = tee_outputs(&j->sink, j->jw, &j->jopts, &j->rep, a, j->s, &j->po, &j->err);
    if (rc) return cli_fail_cmd("slice", &j->err);
    /* the estimate in the program's own bytes (the defaults if the
     * writer cannot be sampled: it then fails the run itself) */
    lam_job_info cj;
    char label[128];
    lam_plan_job(j->s, j->m, &j->po, &cj, label);
    lam_program_costs(j->prof, &cj, &j->po.costs, NULL);
    return EXIT_OK;
}

/* The run: sizes sensed and checked first, then every layer planned. */
static int run_plan(job *j)
{
    cli_progress_stage(&j->rep.progress, "reading the model and preparing the layers");
    cli_size_sense(j->a.path, j->a.machine ? j->prof : NULL, j->m, j->s, &j->po);
    if (!j->a.layers && cli_check_outputs(j->a.json_out, j->a.html, j->s, j->m, &j->po, &j->err))
        return cli_fail_limit(&j->err, 0, CLI_RAISE_OUTPUT);
    cli_progress_begin(&j->rep.progress, "slicing", j->a.path, lam_slicer_count(j->s));
    int rc = lam_plan_run(j->s, j->m, &j->po, &j->sink, on_layer, &j->rep, &j->err);
    cli_progress_end(&j->rep.progress);
    if (!rc) return EXIT_OK;
    int full = lam_writer_over_limit(j->w) || (j->jw && lam_writer_over_limit(j->jw)) ||
               (j->rep.view.hw && lam_writer_over_limit(j->rep.view.hw));
    return j->err.code == LAM_EUSAGE ? cli_usage("slice", "%s", j->err.msg) : cli_fail_limit(&j->err, full, CLI_RAISE_OUTPUT);
}

/* What the run found, said once for the run when the notes were cut
 * short; a disagreeing label or an open outline (without --allow-open)
 * fails it. */
static int report_run(job *j)
{
    const report *r = &j->rep;
    const char *path = j->a.path;
    size_t notes = cli_progress_notes(&j->rep.progress);
    if (notes && r->gap_layers > notes)
        fprintf(stderr, "lamina: %s: closed %zu gaps in %zu layers, largest %g (gap tolerance %g)\n", path,
                r->gaps_total, r->gap_layers, r->gap_max, lam_slicer_gap(j->s));
    if (notes && r->degenerate_layers > notes)
        fprintf(stderr, "lamina: %s: dropped %zu loops of no area, cancelled %zu coincident loops, in %zu layers\n",
                path, r->slivers, r->twins, r->degenerate_layers);
    if (r->vr.disagreeing || r->vr.areas_differ) {
        fprintf(stderr, "lamina: %s: %zu contour%s and %zu layer area%s disagree with the model; nothing written\n",
                path, r->vr.disagreeing, r->vr.disagreeing == 1 ? "" : "s", r->vr.areas_differ,
                r->vr.areas_differ == 1 ? "" : "s");
        return EXIT_CHECK;
    }
    if (r->open_total) {
        fprintf(stderr, "lamina: %s: %zu outline%s stayed open (gap tolerance %g)%s\n", path, r->open_total,
                r->open_total == 1 ? "" : "s", lam_slicer_gap(j->s),
                j->a.allow_open ? "; dropped (--allow-open)" : "; use --gap to close larger gaps or --allow-open to drop them");
        if (!j->a.allow_open) return EXIT_INPUT;
    }
    if (j->po.kind == LAM_PLAN_SLS && notes && !j->a.layers && lam_scan_estimates(&j->po.scan))
        cli_print_estimate(path, &j->po, &j->est);
    if (j->po.kind == LAM_PLAN_LADRP && notes && !j->a.layers)
        cli_print_ladrp_estimate(path, &j->po, lam_slicer_count(j->s), &j->ladrp);
    return EXIT_OK;
}

/* The sheet and the viewer, the program, the JSON: each whole or not at all. */
static int commit_outputs(job *j)
{
    if (cli_view_save(&j->rep.view, &j->err))
        return j->err.code == LAM_ELIMIT ? cli_fail_limit(&j->err, 1, CLI_RAISE_OUTPUT) : cli_fail_cmd("slice", &j->err);
    lam_writer *tmp = j->w;
    j->w = NULL;
    int over = lam_writer_over_limit(tmp), rc = EXIT_OK;
    if (lam_writer_commit(tmp, &j->err))
        rc = j->err.code == LAM_EUSAGE ? cli_fail_cmd("slice", &j->err) : cli_fail_limit(&j->err, over, CLI_RAISE_OUTPUT);
    cli_progress_stage(&j->rep.progress, "writing the outputs");
    if (!rc && j->jw) {
        tmp = j->jw;
        j->jw = NULL;
        if (lam_writer_commit(tmp, &j->err))
            rc = j->err.code == LAM_ELIMIT ? cli_fail_limit(&j->err, 1, CLI_RAISE_OUTPUT) : cli_fail_cmd("slice", &j->err);
    }
    return rc;
}

static void job_free(job *j)
{
    if (j->sink.destroy) j->sink.destroy(j->sink.ctx);
    lam_writer_abort(j->w);
    lam_writer_abort(j->jw);
    cli_view_free(&j->rep.view);
    lam_rays_free(j->rep.v);
    lam_slicer_free(j->s);
    lam_model_free(j->m);
    lam_profile_free(j->prof);
    cli_args_free(&j->a);
}

int cmd_slice(int argc, char **argv)
{
    job j;
    memset(&j, 0, sizeof j);
    int rc = cli_parse_args("slice", usage_text,
                            OPT_MODEL | OPT_SLICE | OPT_SET | OPT_PLAN | OPT_SVG | OPT_JSON_FILE | OPT_TALK | OPT_PART,
                            argc, argv, &j.a);
    if (rc) {
        cli_args_free(&j.a);
        return rc < 0 ? EXIT_OK : rc;
    }
    lam_error_clear(&j.err);
    j.rep.path = j.a.path;
    j.rep.vr.out = stderr;
    cli_progress_init(&j.rep.progress, j.a.talk, !j.a.out || !strcmp(j.a.out, "-"));
    j.rep.vr.progress = &j.rep.progress;
    rc = open_inputs(&j);
    if (!rc) rc = open_outputs(&j);
    if (!rc) rc = run_plan(&j);
    if (!rc) rc = report_run(&j);
    if (!rc) rc = commit_outputs(&j);
    job_free(&j);
    return rc;
}
