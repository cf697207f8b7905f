/* lamina build JOB.yaml -o PROGRAM [--json F] [--html F] [--layout F]:
 * a build plate (docs/builds.md): the job's parts placed on the machine's
 * plate, planned into one program, shared between the machine's lasers,
 * with the build time per laser and per part. Every output is written
 * through an atomic writer: a run that fails leaves none. */
#include "cli.h"
#include "cli_args.h"
#include "cli_build.h"
#include "cli_estimate.h"
#include "cli_join.h"
#include "build_job.h"
#include "build_plan.h"
#include "fmt.h"
#include "plugin.h"
#include "profile.h"
#include "progress.h"
#include "tee.h"
#include "json_sink.h"
#include "svg.h"
#include "views.h"
#include "writer.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char usage_text[] =
    "usage: lamina build JOB.yaml [-o FILE] [--json FILE] [--html FILE] [--svg FILE] [--layout FILE]\n"
    "                             [-s KEY=VALUE ...] [-j N] [--max-output SIZE] [-q | -v]\n"
    "                             [--layers A:B|K/N -o PART]\n"
    "                             [--json-layers A:B] [--json-vectors all|summary|none]\n"
    "                             [--json-contours all|none]\n"
    "  JOB.yaml         the build: machine, parts, styles (docs/builds.md)\n"
    "  -o, --output     the plate's program (default: standard output)\n"
    "      --json       the run as JSON: the build, each layer's vectors with their part,\n"
    "                   style and laser, each layer's time per laser and per part\n"
    "      --json-layers  only layers A to B in the JSON (from 1; A: or :B for the rest)\n"
    "      --json-vectors every vector (all, the default), a summary per layer (summary:\n"
    "                   count and length of each kind) or none\n"
    "      --json-contours the layers' contours in the JSON (all, the default) or none\n"
    "      --html       a viewer of the run\n"
    "      --svg        a contact sheet of the plate's layers and their scan paths\n"
    "      --layout     an SVG of the plate: footprints, names, the lasers' fields\n"
    "  -s, --set        KEY=VALUE: a machine profile key on top of the job's\n"
    "      --layers     plan only layers A to B (from 1) or part K of N of the plate into a\n"
    "                   part file for 'lamina join' (which writes the whole plate's program)\n"
    "  -j, --jobs       threads that plan layers (the program is the same for any number)\n"
    "  -q, --quiet      no progress and no summary; -v: each layer's time per laser too\n";

typedef struct totals {
    lam_scan_time all;       /* layers' estimates summed (busiest laser's) */
    lam_scan_time laser[LAM_LASERS_MAX];
    double worst_balance;
    size_t worst_layer;
    cli_progress *progress;
    lam_svg *svg;            /* --svg: each layer's panel */
    const char *path;        /* -v: each layer's lasers on standard error */
    int verbose;
} totals;

typedef struct bjob {
    args a;
    lam_error err;
    lam_build *b;
    lam_build_run *run;
    lam_writer *w, *jw, *hw;
    lam_sink sink;
    totals t;
    cli_progress progress;
    lam_svg *svg;            /* --svg */
    size_t first, count;     /* --layers: the plate layers of the part file */
} bjob;

/* -v: a layer's time, each laser's and the balance. */
static void layer_note(totals *t, size_t k, const lam_scan_time *layer, const lam_scan_time *lasers, size_t n,
                       double bal)
{
    char a[64];
    cli_progress_hide(t->progress);
    fprintf(stderr, "lamina: %s: layer %zu: %s;", t->path, k + 1, lam_fmt_duration(lam_scan_time_total(layer), a, sizeof a));
    for (size_t l = 0; l < n; l++)
        fprintf(stderr, "%s laser %zu %s", l ? "," : "", l + 1,
                lam_fmt_duration(lasers[l].exposure + lasers[l].jump, a, sizeof a));
    fprintf(stderr, "; balance %.3f\n", bal);
}

static void on_planned(void *user, size_t k, const lam_scan_time *layer, const lam_scan_time *lasers, size_t n)
{
    totals *t = user;
    lam_scan_time_add(&t->all, layer);
    for (size_t l = 0; l < n && l < LAM_LASERS_MAX; l++) lam_scan_time_add(&t->laser[l], &lasers[l]);
    double bal = lam_lasers_balance(lasers, n);
    if (bal > t->worst_balance) t->worst_balance = bal, t->worst_layer = k + 1;
    if (t->verbose) layer_note(t, k, layer, lasers, n, bal);
    cli_progress_step(t->progress, k + 1);
}

/* The job and its machine, -s values on top, the parts loaded and placed:
 * every input is read before an output is checked against them. */
static int open_inputs(bjob *j)
{
    if (lam_build_load(j->a.path, &j->b, &j->err)) return cli_fail(&j->err);
    if (j->a.nsets && cli_apply_sets("build", &j->a, j->b->profile)) return EXIT_USAGE;
    lam_load_opts lo = { .threads = j->a.threads, .no_repair = j->a.no_repair };
    if (lam_build_run_new(j->b, &lo, &j->run, &j->err)) return cli_fail(&j->err);
    const char *outs[][2] = { { "-o", j->a.out }, { "--json", j->a.json_out }, { "--html", j->a.html },
                              { "--layout", j->a.layout }, { "--svg", j->a.svg } };
    for (size_t i = 0; i < sizeof outs / sizeof *outs; i++)
        if (cli_output_check(outs[i][0], outs[i][1], &j->err)) return cli_fail_cmd("build", &j->err);
    return EXIT_OK;
}

/* --layers: a part file's sink for the plate's layers asked. */
static int part_sink(bjob *j)
{
    size_t n = lam_build_run_layers(j->run), first, last;
    int rc = cli_part_range("build", &j->a, n, &first, &last);
    if (rc) return rc;
    char *text = NULL;
    size_t len = 0;
    rc = cli_part_profile(j->b->profile, &text, &len, &j->err);
    lam_part_meta meta = { 0, first, last, n, text, len, j->a.path };
    if (!rc) rc = lam_build_run_identity(j->run, text, len, &meta.identity, &j->err);
    if (!rc) rc = lam_part_sink(&meta, NULL, j->w, &j->sink, &j->err);
    free(text);
    j->first = first - 1;
    j->count = last - first + 1;
    return rc ? cli_fail(&j->err) : EXIT_OK;
}

/* --svg: a sheet of the plate's layers, the plate's extent its panels'. */
static int open_svg(bjob *j)
{
    const lam_plate *p = lam_build_run_plate(j->run);
    double h = p->diameter / 2;
    double box[4] = { p->round ? -h : 0, p->round ? -h : 0, p->round ? h : p->width, p->round ? h : p->depth };
    char title[600];
    snprintf(title, sizeof title, "lamina: %s", j->a.path);
    return lam_svg_new(lam_build_run_layers(j->run), box, title, &j->svg, &j->err);
}

static int add_panel(void *user, const lam_layer *sec, lam_error *err)
{
    const totals *t = user;
    return t->svg ? lam_svg_add(t->svg, sec, err) : LAM_OK;
}

/* The program's sink, teed with the views (--json, --html, --svg). */
static int open_outputs(bjob *j)
{
    const args *a = &j->a;
    const lam_profile *p = j->b->profile;
    lam_json_opts jo;
    if (a->json_out && cli_json_opts("build", a, lam_build_run_layers(j->run), &jo)) return EXIT_USAGE;
    if (cli_writer("-o", a->out, &j->w, &j->err) || (a->json_out && cli_writer("--json", a->json_out, &j->jw, &j->err)) ||
        (a->html && cli_writer("--html", a->html, &j->hw, &j->err)))
        return cli_fail_cmd("build", &j->err);
    unsigned long long limit = a->max_output ? a->max_output : LAM_DEFAULT_MAX_OUTPUT;
    lam_writer_set_limit(j->w, limit);
    if (j->jw) lam_writer_set_limit(j->jw, limit);
    if (j->hw) lam_writer_set_limit(j->hw, limit);
    if (a->layers) return part_sink(j);
    if (lam_program_sink(p->writer, &p->dialect, j->w, &j->sink, &j->err)) return cli_fail_cmd("build", &j->err);
    if (a->svg && open_svg(j)) return cli_fail(&j->err);
    if (!j->jw && !j->hw && !j->svg) return EXIT_OK;
    lam_views views = { .json = j->jw, .json_opts = j->jw ? &jo : NULL, .html = j->hw, .svg = j->svg,
                        .frame = lam_build_run_frame(j->run) };
    lam_sink all[2] = { j->sink };
    int rc = lam_views_sink(&views, &all[1], &j->err);
    if (!rc && (rc = lam_tee_sink(all, 2, &j->sink, &j->err))) all[1].destroy(all[1].ctx);
    return rc ? cli_fail_cmd("build", &j->err) : EXIT_OK;
}

static int run_plan(bjob *j)
{
    j->t.progress = &j->progress;
    j->t.svg = j->svg;
    j->t.path = j->a.path;
    j->t.verbose = j->a.talk > 0;
    lam_run_opts o = { .threads = j->a.threads, .planned = on_planned, .section = add_panel, .user = &j->t,
                       .layer_first = j->first, .layer_count = j->count };
    cli_progress_begin(&j->progress, "planning", j->a.path, lam_build_run_layers(j->run));
    int rc = lam_build_run_plan(j->run, &o, &j->sink, &j->err);
    cli_progress_end(&j->progress);
    if (!rc) return EXIT_OK;
    int full = lam_writer_over_limit(j->w) || (j->jw && lam_writer_over_limit(j->jw)) ||
               (j->hw && lam_writer_over_limit(j->hw));
    return cli_fail_limit(&j->err, full, CLI_RAISE_OUTPUT);
}

static int commit(lam_writer **w, lam_error *err)
{
    lam_writer *tmp = *w;
    *w = NULL;
    int over = tmp && lam_writer_over_limit(tmp);
    if (tmp && lam_writer_commit(tmp, err)) return cli_fail_limit(err, over, CLI_RAISE_OUTPUT);
    return EXIT_OK;
}

static int commit_outputs(bjob *j)
{
    /* the sheet first: it is the one written only now, so the one that can
     * still pass --max-output, and then no program is left either */
    int rc = LAM_OK;
    if (j->svg && cli_save_svg(j->svg, j->a.svg, j->a.max_output, &j->err)) rc = cli_fail_cmd("build", &j->err);
    if (!rc) rc = commit(&j->w, &j->err);
    if (!rc) rc = commit(&j->jw, &j->err);
    if (!rc) rc = commit(&j->hw, &j->err);
    if (!rc && j->a.layout) rc = cli_build_layout(j->run, j->b->profile, j->a.layout, &j->err);
    return rc;
}

static void job_free(bjob *j)
{
    if (j->sink.destroy) j->sink.destroy(j->sink.ctx);
    lam_writer_abort(j->w);
    lam_writer_abort(j->jw);
    lam_writer_abort(j->hw);
    lam_svg_free(j->svg);
    lam_build_run_free(j->run);
    lam_build_free(j->b);
    cli_args_free(&j->a);
}

int cmd_build(int argc, char **argv)
{
    bjob j;
    memset(&j, 0, sizeof j);
    int rc = cli_parse_args("build", usage_text, OPT_BUILD | OPT_PLAN | OPT_JSON_FILE | OPT_SVG | OPT_TALK | OPT_SET | OPT_PART,
                            argc, argv, &j.a);
    if (rc) {
        cli_args_free(&j.a);
        return rc < 0 ? EXIT_OK : rc;
    }
    lam_error_clear(&j.err);
    if (j.a.validate) rc = cli_usage("build", "--validate is for one part: 'lamina validate MODEL' checks a model");
    cli_progress_init(&j.progress, j.a.talk, !j.a.out || !strcmp(j.a.out, "-"));
    if (!rc) rc = open_inputs(&j);
    if (!rc) rc = open_outputs(&j);
    if (!rc) rc = run_plan(&j);
    if (!rc) rc = commit_outputs(&j);
    if (!rc && j.a.talk >= 0 && !j.a.layers) cli_build_summary(j.a.path, j.run, j.b->profile, &j.t.all, j.t.laser, j.t.worst_balance,
                                                j.t.worst_layer);
    job_free(&j);
    return rc;
}
