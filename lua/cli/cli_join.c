/* lamina join PART... [-o PROGRAM]: the program of a run sliced
 * in parts (`lamina slice ... --layers A:B`), byte for byte what the whole
 * run writes; and the part-file side of `lamina slice --layers`.
 *
 * The parts may come in any order; join puts them in layer order and
 * refuses, before writing anything, parts of different runs, overlapping
 * parts and layers no part holds; a corrupt or truncated part stops it
 * with nothing written (every part is read through once, to its end
 * hash, before anything is written). The build-time estimate is
 * printed as the whole run prints it (join adds a powder-bed job's
 * per-layer estimates in layer order, and measures a LADRP job's moves
 * as they are checked). */
#include "cli.h"
#include "cli_estimate.h"
#include "cli_join.h"
#include "dialect.h"
#include "part.h"
#include "plugin.h"
#include "profile.h"

#include <stdlib.h>
#include <string.h>

static const char usage_text[] =
    "usage: lamina join PART... [-o PROGRAM]\n"
    "Assemble the part files of one run (lamina slice ... --layers A:B or K/N)\n"
    "into the program the whole run writes, in the machine's dialect.\n"
    "  -o, --output     program file (default: standard output)\n"
    "Parts may be given in any order; every layer must be in exactly one part.\n";

int cli_part_range(const char *cmd, const args *a, size_t n, size_t *first, size_t *last)
{
    *first = a->layers_a;
    *last = a->layers_b;
    if (a->svg) return cli_usage(cmd, "--svg draws the whole run: it cannot go with --layers");
    if (a->json_out || a->html || a->layout)
        return cli_usage(cmd, "%s describes the whole run: it cannot go with --layers",
                         a->json_out ? "--json" : a->html ? "--html" : "--layout");
    if (!a->out || !strcmp(a->out, "-"))
        return cli_usage(cmd, "--layers writes a binary part file: give it a file (-o FILE)");
    if (a->layers_split) {
        /* part K of N: layers floor((K-1) n / N) + 1 .. floor(K n / N) */
        size_t k = a->layers_a, parts = a->layers_b;
        if (parts > n)
            return cli_usage(cmd, "--layers %s: the run has %zu layer%s, too few for %zu parts", a->layers, n,
                             n == 1 ? "" : "s", parts);
        *first = (size_t)((unsigned long long)(k - 1) * n / parts) + 1;
        *last = (size_t)((unsigned long long)k * n / parts);
    } else if (*last > n) {
        return cli_usage(cmd, "--layers %s: the run has %zu layer%s (A:B needs 1 <= A <= B <= %zu)", a->layers, n,
                         n == 1 ? "" : "s", n);
    }
    return EXIT_OK;
}

int cli_part_profile(const lam_profile *prof, char **text, size_t *len, lam_error *err)
{
    lam_writer *mw = NULL;
    int rc = lam_writer_memory(&mw, err);
    if (!rc) rc = lam_profile_dump(prof, mw);
    if (!rc) rc = lam_writer_take(mw, text, len, err);
    else lam_writer_abort(mw);
    return rc;
}

int cli_part_setup(args *a, const lam_profile *prof, const lam_slicer *s, lam_plan_opts *po, lam_writer *w,
                   lam_sink *sink)
{
    size_t n = lam_slicer_count(s), first, last;
    int rc = cli_part_range("slice", a, n, &first, &last);
    if (rc) return rc;
    lam_error err;
    lam_error_clear(&err);
    char *text = NULL;
    size_t len = 0;
    rc = cli_part_profile(prof, &text, &len, &err);
    lam_part_meta meta = { 0, first, last, n, text, len, a->path };
    if (!rc) rc = lam_part_identity(a->path, text, len, s, &meta.identity, &err);
    if (!rc) rc = lam_part_sink(&meta, po->time, w, sink, &err);
    free(text);
    if (rc) return cli_fail(&err);
    po->layer_first = first - 1;
    po->layer_count = last - first + 1;
    return EXIT_OK;
}

static int join(const char *out, char **paths, size_t n)
{
    lam_error err;
    lam_error_clear(&err);
    lam_part **parts = calloc(n, sizeof *parts);
    lam_profile *prof = NULL;
    lam_writer *w = NULL;
    lam_sink sink = { 0 };
    int rc = EXIT_OK;
    if (!parts) {
        lam_error_nomem(&err, NULL);
        rc = cli_fail(&err);
        goto done;
    }
    for (size_t i = 0; i < n; i++)
        if (lam_part_open(paths[i], &parts[i], &err)) {
            rc = cli_fail(&err);
            goto done;
        }
    if (lam_part_order(parts, n, &err)) {
        rc = cli_fail(&err);
        goto done;
    }
    const lam_part_meta *meta = lam_part_get_meta(parts[0]);
    char name[600];
    snprintf(name, sizeof name, "%s (the machine profile it holds)", paths[0]);
    if (lam_profile_load_buf(name, meta->profile, meta->profile_len, &prof, &err)) {
        rc = cli_fail(&err);
        goto done;
    }
    lam_plan_opts po;
    lam_plan_opts_from_profile(&po, prof);
    int sls = po.kind == LAM_PLAN_SLS;
    if (cli_writer("-o", out ? out : "-", &w, &err)) {
        rc = cli_fail_cmd("join", &err);
        goto done;
    }
    if (lam_program_sink(prof->writer, &prof->dialect, w, &sink, &err)) {
        rc = cli_fail(&err);
        goto done;
    }
    lam_scan_time est;
    memset(&est, 0, sizeof est);
    /* every part is read to its end hash before a byte is written: a
     * corrupt part is reported as such (not as whatever its bad numbers
     * would make the writer say), and standard output, which cannot be
     * taken back, gets nothing */
    lam_sink check;
    cli_ladrp_meter meter; /* LADRP: the run's moves, as the whole run counts them */
    cli_ladrp_meter_sink(&meter, &check);
    if (lam_part_join(parts, n, &check, NULL, NULL, &err)) {
        rc = cli_fail(&err);
        goto done;
    }
    if (lam_part_join(parts, n, &sink, &est, NULL, &err)) {
        rc = cli_fail(&err);
        goto done;
    }
    if (sls && lam_scan_estimates(&po.scan)) cli_print_estimate(meta->model, &po, &est);
    if (po.kind == LAM_PLAN_LADRP) cli_print_ladrp_estimate(meta->model, &po, meta->layers, &meter.st);
    lam_writer *tmp = w;
    w = NULL;
    if (lam_writer_commit(tmp, &err)) rc = cli_fail_cmd("join", &err);
done:
    if (sink.destroy) sink.destroy(sink.ctx);
    lam_writer_abort(w);
    lam_profile_free(prof);
    for (size_t i = 0; parts && i < n; i++) lam_part_close(parts[i]);
    free(parts);
    return rc;
}

int cmd_join(int argc, char **argv)
{
    const char *out = NULL;
    int rc = EXIT_OK;
    char **paths = calloc((size_t)argc + 1, sizeof *paths);
    size_t n = 0;
    if (!paths) {
        fprintf(stderr, "lamina: out of memory\n");
        return EXIT_INPUT;
    }
    int opts = 1;
    for (int i = 1; i < argc && !rc; i++) {
        const char *s = argv[i];
        if (!opts || s[0] != '-' || !strcmp(s, "-")) {
            paths[n++] = argv[i];
        } else if (!strcmp(s, "--")) {
            opts = 0;
        } else if (!strcmp(s, "--help") || !strcmp(s, "-h")) {
            fputs(usage_text, stdout);
            free(paths);
            return EXIT_OK;
        } else if (!strcmp(s, "-o") || !strcmp(s, "--output")) {
            if (i + 1 >= argc) rc = cli_usage("join", "%s needs a file name", s);
            else out = argv[++i];
        } else if (!strncmp(s, "--output=", 9)) {
            out = s + 9;
        } else if (!strncmp(s, "-o", 2)) {
            out = s + 2;
        } else {
            rc = cli_usage("join", "unknown option '%s'", s);
        }
    }
    if (!rc && !n) rc = cli_usage("join", "give the part files to join");
    if (!rc) rc = join(out, paths, n);
    free(paths);
    return rc;
}
