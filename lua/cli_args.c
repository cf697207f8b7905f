/* The option parser shared by slice, validate and check. */
#include "cli_args.h"

#include "cli.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Parse "a,b,c" into a malloc'd array. Returns count, or -1 on a bad number. */
static long parse_list(const char *s, double **out)
{
    size_t cap = 8, n = 0;
    double *v = malloc(cap * sizeof *v);
    if (!v) return -1;
    const char *p = s;
    for (;;) {
        char *end;
        errno = 0;
        double x = strtod(p, &end);
        if (end == p || errno == ERANGE || !isfinite(x)) {
            free(v);
            return -1;
        }
        if (n == cap) {
            double *nv = realloc(v, 2 * cap * sizeof *nv);
            if (!nv) {
                free(v);
                return -1;
            }
            v = nv;
            cap *= 2;
        }
        v[n++] = x;
        if (*end == '\0') break;
        if (*end != ',') {
            free(v);
            return -1;
        }
        p = end + 1;
    }
    *out = v;
    return (long)n;
}

static int parse_number(const char *s, double *x)
{
    char *end;
    errno = 0;
    *x = strtod(s, &end);
    return end != s && *end == '\0' && errno != ERANGE && isfinite(*x);
}

/* A byte count: a whole number, optionally followed by k, M, G or T
 * (powers of 1024; K too). 0 when malformed or out of range. */
static unsigned long long parse_size(const char *s)
{
    char *end;
    errno = 0;
    double x = strtod(s, &end);
    if (end == s || errno == ERANGE || !(x >= 1) || x != floor(x)) return 0;
    static const char units[] = "kMGT";
    const char *u = *end ? strchr(units, *end == 'K' ? 'k' : *end) : NULL;
    if (*end && (!u || end[1])) return 0;
    for (const char *p = units; u && p <= u; p++) x *= 1024;
    return x < 1.8e19 ? (unsigned long long)x : 0;
}

/* Which group an option belongs to (0: not a known option). */
static unsigned group_of(const char *o)
{
    static const char *const slice_opts[] = { "-m", "--machine", "-a", "--axis", "-w", "--width", "--widths",
                                              "--planes", "--cut", "--gap", "--allow-open", "--fill", "--max-layers",
                                              NULL };
    static const char *const plan_opts[] = { "--first-line", "--angle", "--angle-step", "--min-deposit",
                                             "--no-alternate", "--perimeters", "--beam-offset", "--frame", "--islands",
                                             "-o", "--output", "--validate", "--max-output", NULL };
    for (int i = 0; slice_opts[i]; i++)
        if (!strcmp(o, slice_opts[i])) return OPT_SLICE;
    for (int i = 0; plan_opts[i]; i++)
        if (!strcmp(o, plan_opts[i])) return OPT_PLAN;
    if (!strcmp(o, "--json")) return OPT_JSON;
    if (!strcmp(o, "--svg")) return OPT_SVG;
    return 0;
}

int cli_parse_args(const char *cmd, const char *usage_text, unsigned groups, int argc, char **argv, args *a)
{
    memset(a, 0, sizeof *a);
    lam_slice_opts_init(&a->so);
    lam_error err;
    lam_error_clear(&err);
#define NEED() do { if (i + 1 >= argc) return cli_usage(cmd, "option %s needs a value", argv[i]); } while (0)
    for (int i = 1; i < argc; i++) {
        const char *o = argv[i];
        unsigned g = o[0] == '-' && o[1] ? group_of(o) : 0;
        if (!strcmp(o, "-h") || !strcmp(o, "--help")) {
            fputs(usage_text, stdout);
            return -1;
        } else if (g && !(g & groups)) {
            return cli_usage(cmd, "option %s does not apply to '%s'", o, cmd);
        } else if (!strcmp(o, "--json")) {
            a->json = 1;
        } else if (!strcmp(o, "--validate")) {
            a->validate = 1;
        } else if (!strcmp(o, "--fill")) {
            NEED();
            const char *v = argv[++i];
            if (strcmp(v, "evenodd") && strcmp(v, "nonzero"))
                return cli_usage(cmd, "--fill takes evenodd or nonzero (got '%s')", v);
            a->so.fill_nonzero = !strcmp(v, "nonzero");
        } else if (!strcmp(o, "-m") || !strcmp(o, "--machine")) {
            NEED();
            a->machine = argv[++i];
        } else if (!strcmp(o, "-a") || !strcmp(o, "--axis")) {
            NEED();
            const char *v = argv[++i];
            if (strlen(v) == 1 && strchr("xyzXYZ", v[0])) {
                lam_frame_axis(v[0], &a->so.frame, &err);
            } else {
                double *d = NULL;
                long n = parse_list(v, &d);
                int bad = n != 3 || lam_frame_direction(d, &a->so.frame, &err) != LAM_OK;
                free(d);
                if (bad) return cli_usage(cmd, "unknown axis '%s' (x, y, z or a direction DX,DY,DZ)", v);
            }
        } else if (!strcmp(o, "-w") || !strcmp(o, "--width")) {
            NEED();
            if (!parse_number(argv[++i], &a->so.width) || !(a->so.width > 0))
                return cli_usage(cmd, "layer width must be a positive number (got '%s')", argv[i]);
            a->set_width = 1;
        } else if (!strcmp(o, "--widths") || !strcmp(o, "--planes")) {
            NEED();
            free(a->list);
            a->list = NULL;
            long n = parse_list(argv[++i], &a->list);
            if (n < 1) return cli_usage(cmd, "%s takes numbers separated by commas (got '%s')", o, argv[i]);
            a->so.widths = a->so.planes = NULL;
            a->so.nwidths = a->so.nplanes = 0;
            if (!strcmp(o, "--widths")) {
                a->so.widths = a->list;
                a->so.nwidths = (size_t)n;
            } else {
                a->so.planes = a->list;
                a->so.nplanes = (size_t)n;
            }
        } else if (!strcmp(o, "--cut")) {
            NEED();
            const char *v = argv[++i];
            if (!strcmp(v, "floor")) a->so.cut = LAM_CUT_FLOOR;
            else if (!strcmp(v, "middle")) a->so.cut = LAM_CUT_MIDDLE;
            else if (!strcmp(v, "ceiling")) a->so.cut = LAM_CUT_CEILING;
            else return cli_usage(cmd, "--cut takes floor, middle or ceiling (got '%s')", v);
            a->set_cut = 1;
        } else if (!strcmp(o, "--gap")) {
            NEED();
            if (!parse_number(argv[++i], &a->so.gap) || a->so.gap < 0)
                return cli_usage(cmd, "--gap takes a tolerance >= 0 (got '%s')", argv[i]);
            a->set_gap = 1;
        } else if (!strcmp(o, "--max-layers")) {
            NEED();
            double x;
            if (!parse_number(argv[++i], &x) || !(x >= 1) || x != floor(x) || x > 1e15)
                return cli_usage(cmd, "--max-layers takes a whole number of layers >= 1 (got '%s')", argv[i]);
            a->so.max_layers = (size_t)x;
        } else if (!strcmp(o, "--max-output")) {
            NEED();
            if (!(a->max_output = parse_size(argv[++i])))
                return cli_usage(cmd, "--max-output takes a size in bytes, such as 500M or 8G (got '%s')", argv[i]);
        } else if (!strcmp(o, "--allow-open")) {
            a->allow_open = 1;
        } else if (!strcmp(o, "--first-line")) {
            NEED();
            const char *v = argv[++i];
            if (strcmp(v, "edge") && strcmp(v, "center"))
                return cli_usage(cmd, "--first-line takes edge or center (got '%s')", v);
            a->set_first = 1;
            a->first_center = !strcmp(v, "center");
        } else if (!strcmp(o, "--angle") || !strcmp(o, "--angle-step") || !strcmp(o, "--min-deposit")) {
            NEED();
            double x;
            if (!parse_number(argv[++i], &x)) return cli_usage(cmd, "%s takes a number (got '%s')", o, argv[i]);
            if (!strcmp(o, "--angle")) a->angle = x, a->set_angle = 1;
            else if (!strcmp(o, "--angle-step")) a->angle_step = x, a->set_step = 1;
            else if (x < 0) return cli_usage(cmd, "--min-deposit takes a length >= 0 (got '%s')", argv[i]);
            else a->min_deposit = x, a->set_min = 1;
        } else if (!strcmp(o, "--perimeters")) {
            NEED();
            double x;
            if (!parse_number(argv[++i], &x) || x < 0 || x > 1000 || x != floor(x))
                return cli_usage(cmd, "--perimeters takes a whole number from 0 to 1000 (got '%s')", argv[i]);
            a->perimeters = (int)x;
            a->set_perimeters = 1;
        } else if (!strcmp(o, "--islands")) {
            a->islands = 1;
        } else if (!strcmp(o, "--beam-offset")) {
            a->beam_offset = 1;
        } else if (!strcmp(o, "--no-alternate")) {
            a->no_alternate = 1;
        } else if (!strcmp(o, "--frame")) {
            NEED();
            const char *v = argv[++i];
            if (strcmp(v, "model") && strcmp(v, "machine"))
                return cli_usage(cmd, "--frame takes model or machine (got '%s')", v);
            a->set_frame = 1;
            a->frame_machine = !strcmp(v, "machine");
        } else if (!strcmp(o, "--svg")) {
            NEED();
            a->svg = argv[++i];
        } else if (!strcmp(o, "-o") || !strcmp(o, "--output")) {
            NEED();
            a->out = argv[++i];
        } else if (o[0] == '-' && o[1]) {
            return cli_usage(cmd, "unknown option '%s'", o);
        } else if (a->path) {
            return cli_usage(cmd, "more than one model given ('%s' and '%s')", a->path, o);
        } else {
            a->path = o;
        }
    }
#undef NEED
    if (!a->path) return cli_usage(cmd, "no model given");
    if ((a->so.widths || a->so.planes) && a->set_width)
        return cli_usage(cmd, "give one of -w, --widths and --planes");
    return EXIT_OK;
}

static void apply_overrides(const args *a, lam_plan_opts *po);

void cli_apply_profile(args *a, const lam_profile *p, lam_plan_opts *po)
{
    if (!a->set_width && !a->so.widths && !a->so.planes && p->layer_width > 0) a->so.width = p->layer_width;
    if (!a->set_cut) a->so.cut = (lam_cut)p->cut;
    if (!a->set_gap) a->so.gap = p->gap;
    lam_plan_opts_from_profile(po, p);
    apply_overrides(a, po);
}

static void apply_overrides(const args *a, lam_plan_opts *po)
{
    po->max_output = a->max_output;
    if (a->set_frame) po->frame_machine = a->frame_machine;
    if (a->set_first) po->first_center = a->first_center;
    if (a->set_angle) po->angle = a->angle;
    if (a->set_step) po->angle_step = a->angle_step;
    if (a->set_min) po->min_deposit = a->min_deposit;
    if (a->no_alternate) po->alternate = 0;
    if (a->set_perimeters) po->perimeters = a->perimeters;
    if (a->beam_offset) po->beam_offset = 1;
    if (a->islands) po->islands = 1;
}

void cli_args_free(args *a)
{
    free(a->list);
    a->list = NULL;
}

int cli_fail_limit(const lam_error *err, int over, const char *option)
{
    int rc = cli_fail(err);
    if (over || err->code == LAM_ELIMIT) fprintf(stderr, "lamina: raise the limit with %s\n", option);
    return rc;
}

int cli_load_profile(const args *a, lam_profile **out, lam_error *err)
{
    return a->machine ? lam_profile_find(a->machine, out, err) : lam_profile_builtin_sls(out, err);
}
