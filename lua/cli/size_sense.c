#include "size_sense.h"

#include <stdio.h>

#include "fmt.h"
#include "views.h"

int cli_size_sense(const char *path, const lam_profile *machine, const lam_model *m, const lam_slicer *s,
                   const lam_plan_opts *po)
{
    int n = 0;
    size_t layers = lam_slicer_count(s);
    if (layers > CLI_SENSE_LAYERS) {
        const double *planes = lam_slicer_planes(s);
        double span = planes[layers] - planes[0];
        fprintf(stderr,
                "lamina: warning: %s: %zu layers (%s along the axis in layers of %s on average), more than %d: "
                "is the layer width in the model's units? (--max-layers N refuses runs of more than N layers)\n",
                path, layers, LAM_NUM(span), lam_fmt_num((char[LAM_FMT_NUM]){ 0 }, span / (double)layers, 6),
                CLI_SENSE_LAYERS);
        n++;
    }
    double mm = machine ? lam_profile_unit_mm(machine) : 0;
    const double *b = m->stats.bbox;
    double ext = 0;
    for (int k = 0; k < 3; k++)
        if (b[k + 3] - b[k] > ext) ext = b[k + 3] - b[k];
    if (mm > 0 && ext > 0 && (ext * mm > CLI_SENSE_MAX_MM || ext * mm < CLI_SENSE_MIN_MM)) {
        int big = ext * mm > CLI_SENSE_MAX_MM;
        fprintf(stderr,
                "lamina: warning: %s: the model is %s across (x %s, y %s, z %s) and %s's units are %s: %s mm, %s "
                "than %s mm; was it drawn in another unit?\n",
                path, LAM_NUM(ext), LAM_NUM(b[3] - b[0]), LAM_NUM(b[4] - b[1]), LAM_NUM(b[5] - b[2]),
                machine->name ? machine->name : "the profile", machine->units ? machine->units : "mm",
                LAM_NUM(ext * mm), big ? "larger" : "smaller", LAM_NUM(big ? CLI_SENSE_MAX_MM : CLI_SENSE_MIN_MM));
        n++;
    }
    if (po) {
        lam_job_estimate e;
        lam_plan_estimate(s, po, &e);
        /* past the limit the run is refused with the same numbers */
        double limit = po->max_output ? (double)po->max_output : (double)LAM_DEFAULT_MAX_OUTPUT;
        if (e.bytes > CLI_SENSE_BYTES && e.bytes <= limit) {
            char a[32], l[32];
            fprintf(stderr, "lamina: warning: %s: the program will be about %s (%zu layers), more than %s "
                            "(--max-output SIZE refuses larger programs)\n",
                    path, lam_fmt_bytes(a, sizeof a, e.bytes), e.layers, lam_fmt_bytes(l, sizeof l, CLI_SENSE_BYTES));
            n++;
        }
    }
    return n;
}

static int open_json(void *arg, lam_writer *w, lam_sink *out, lam_error *err)
{
    (void)arg;
    lam_views v = { .json = w };
    return lam_views_sink(&v, out, err);
}

static int open_html(void *arg, lam_writer *w, lam_sink *out, lam_error *err)
{
    (void)arg;
    lam_views v = { .html = w };
    return lam_views_sink(&v, out, err);
}

int cli_check_outputs(const char *json, const char *html, const lam_slicer *s, const lam_model *m,
                      const lam_plan_opts *po, lam_error *err)
{
    if (!json && !html) return LAM_OK;
    lam_job_estimate e;
    lam_plan_estimate(s, po, &e);
    lam_job_info job;
    char label[128];
    lam_plan_job(s, m, po, &job, label);
    const char *path[2] = { json, html }, *opt[2] = { "--json", "--html" };
    lam_sink_open open[2] = { open_json, open_html };
    for (int k = 0; k < 2; k++) {
        if (!path[k]) continue;
        lam_out_costs c;
        int rc = lam_out_costs_measure(open[k], NULL, &job, &c, err);
        if (rc) return rc;
        lam_job_estimate_bytes(&e, &c);
        char what[1100];
        snprintf(what, sizeof what, "%s %s", opt[k], path[k]);
        if ((rc = lam_check_output_estimate(&e, po, what, po->max_output, err))) return rc;
    }
    return LAM_OK;
}
