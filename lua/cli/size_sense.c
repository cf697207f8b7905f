#include "size_sense.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fmt.h"
#include "views.h"

/* the mm one model unit was taken as on load (--units), 0: the machine's */
static double loaded_unit_mm;

void cli_size_sense_loaded(double unit_mm) { loaded_unit_mm = unit_mm; }

/* The option that makes a model e mm across (as loaded, one unit taken as
 * u0 mm) plausible: the unit that brings it nearest CLI_SENSE_AIM_MM
 * within the bounds, else a power of ten for --scale (whose factors
 * multiply, so it adds to any --scale given). */
static void remedy(char *buf, size_t size, double e, double u0)
{
    static const char *const name[] = { "m", "cm", "in", "mm", "um" };
    static const char *const word[] = { "metres", "centimetres", "inches", "millimetres", "micrometres" };
    int best = -1;
    double best_e = 0;
    for (int i = 0; i < 5; i++) {
        double mm = lam_unit_mm(name[i]);
        double f = e * mm / u0;
        if (mm == u0 || f < CLI_SENSE_MIN_MM || f > CLI_SENSE_MAX_MM) continue;
        if (best < 0 || fabs(log(f / CLI_SENSE_AIM_MM)) < fabs(log(best_e / CLI_SENSE_AIM_MM))) best = i, best_e = f;
    }
    if (best >= 0) {
        snprintf(buf, size, "if it was drawn in %s, --units %s makes it %s mm", word[best], name[best], LAM_NUM(best_e));
        return;
    }
    double f = pow(10, round(log10(CLI_SENSE_AIM_MM / e)));
    snprintf(buf, size, "--scale %s makes it %s mm", LAM_NUM(f), LAM_NUM(e * f));
}

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
        char fix[160];
        remedy(fix, sizeof fix, ext * mm, loaded_unit_mm > 0 ? loaded_unit_mm : mm);
        fprintf(stderr,
                "lamina: warning: %s: the model is %s across (x %s, y %s, z %s) and %s's units are %s: %s mm, %s "
                "than %s mm; was it drawn in another unit? %c%s\n",
                path, LAM_NUM(ext), LAM_NUM(b[3] - b[0]), LAM_NUM(b[4] - b[1]), LAM_NUM(b[5] - b[2]),
                machine->name ? machine->name : "the profile", machine->units ? machine->units : "mm",
                LAM_NUM(ext * mm), big ? "larger" : "smaller", LAM_NUM(big ? CLI_SENSE_MAX_MM : CLI_SENSE_MIN_MM),
                fix[0] == 'i' ? 'I' : fix[0], fix + 1);
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
