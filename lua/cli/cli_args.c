/* The option parser shared by the commands: a table of options (below) and
 * the profile keys' own options (core/profile/profile_keys.c). */
#include "cli_args.h"
#include "pool.h"

#include "cli.h"
#include "json_sink.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
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

/* ---- the options that are not profile keys -------------------------------- */

/* An option's action: val is its value (NULL for a flag), opt the option
 * as given (for messages). Returns 0 or EXIT_USAGE after printing. */
struct cli_opt;
typedef int (*opt_fn)(const char *cmd, args *a, const struct cli_opt *o, const char *opt, const char *val);

typedef struct cli_opt {
    const char *name;        /* long name, without "--" */
    char letter;             /* short form, or 0 */
    unsigned group;          /* OPT_* */
    const char *arg;         /* its value in messages, NULL: a flag */
    opt_fn fn;
    size_t field;            /* o_flag, o_text: the member of args it sets */
} cli_opt;

/* A flag: sets its int member of args to 1. */
static int o_flag(const char *cmd, args *a, const cli_opt *o, const char *opt, const char *val)
{
    (void)cmd, (void)opt, (void)val;
    *(int *)(void *)((char *)a + o->field) = 1;
    return 0;
}

/* A value kept as given (a path, a name): its const char * member of args. */
static int o_text(const char *cmd, args *a, const cli_opt *o, const char *opt, const char *val)
{
    (void)cmd, (void)opt;
    *(const char **)(void *)((char *)a + o->field) = val;
    return 0;
}

/* An output file: a path, or "-" for standard output (see cli_args.h). */
static int o_output(const char *cmd, args *a, const cli_opt *o, const char *opt, const char *val)
{
    if (!*val) return cli_usage(cmd, "%s needs a file name (or - for standard output)", opt);
    return o_text(cmd, a, o, opt, val);
}

static int o_axis(const char *cmd, args *a, const cli_opt *o, const char *opt, const char *val)
{
    (void)o, (void)opt;
    lam_error err;
    lam_error_clear(&err);
    if (strlen(val) == 1 && strchr("xyzXYZ", val[0])) return lam_frame_axis(val[0], &a->so.frame, &err), 0;
    double *d = NULL;
    long n = parse_list(val, &d);
    int bad = n != 3 || lam_frame_direction(d, &a->so.frame, &err) != LAM_OK;
    free(d);
    return bad ? cli_usage(cmd, "unknown axis '%s' (x, y, z or a direction DX,DY,DZ)", val) : 0;
}

/* --widths and --planes: o->field says which */
static int o_layers(const char *cmd, args *a, const cli_opt *o, const char *opt, const char *val)
{
    free(a->list);
    a->list = NULL;
    long n = parse_list(val, &a->list);
    if (n < 1) return cli_usage(cmd, "%s takes numbers separated by commas (got '%s')", opt, val);
    int widths = o->field == offsetof(args, so.widths);
    a->so.widths = widths ? a->list : NULL;
    a->so.nwidths = widths ? (size_t)n : 0;
    a->so.planes = widths ? NULL : a->list;
    a->so.nplanes = widths ? 0 : (size_t)n;
    return 0;
}

static int o_fill(const char *cmd, args *a, const cli_opt *o, const char *opt, const char *val)
{
    (void)o, (void)opt;
    if (strcmp(val, "evenodd") && strcmp(val, "nonzero"))
        return cli_usage(cmd, "--fill takes evenodd or nonzero (got '%s')", val);
    a->so.fill_nonzero = !strcmp(val, "nonzero");
    return 0;
}

static int o_show(const char *cmd, args *a, const cli_opt *o, const char *opt, const char *val)
{
    (void)o, (void)opt;
    if (a->show) return cli_usage(cmd, "--show given twice");
    if (!*val) return cli_usage(cmd, "--show needs a profile name or path");
    a->show = val;
    return 0;
}

static int add_set(const char *cmd, args *a, const char *shown, const char *name, const char *value);

static int o_set(const char *cmd, args *a, const cli_opt *o, const char *opt, const char *val)
{
    (void)o;
    char shown[160], name[128];
    snprintf(shown, sizeof shown, "%s %s", opt, val);
    const char *eq = strchr(val, '=');
    if (!eq || eq == val || (size_t)(eq - val) >= sizeof name)
        return cli_usage(cmd, "%s: expected KEY=VALUE ('lamina machines --keys' lists the keys)", shown);
    memcpy(name, val, (size_t)(eq - val));
    name[eq - val] = '\0';
    return add_set(cmd, a, shown, name, eq + 1);
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

static int o_max_layers(const char *cmd, args *a, const cli_opt *o, const char *opt, const char *val)
{
    (void)o;
    char *end;
    errno = 0;
    double x = strtod(val, &end);
    if (end == val || *end || errno == ERANGE || !(x >= 1) || x != floor(x) || x > 1e15)
        return cli_usage(cmd, "%s takes a whole number of layers >= 1 (got '%s')", opt, val);
    a->so.max_layers = (size_t)x;
    return 0;
}

static int o_max_output(const char *cmd, args *a, const cli_opt *o, const char *opt, const char *val)
{
    (void)o;
    if (!(a->max_output = parse_size(val)))
        return cli_usage(cmd, "%s takes a size in bytes, such as 500M or 8G (got '%s')", opt, val);
    return 0;
}

/* -q and -v: the last one given wins */
static int o_talk(const char *cmd, args *a, const cli_opt *o, const char *opt, const char *val)
{
    (void)cmd, (void)opt, (void)val;
    a->talk = o->letter == 'q' ? -1 : 1;
    return 0;
}

int cli_threads_arg(const char *cmd, const char *opt, const char *val, unsigned *out)
{
    char *end;
    errno = 0;
    long n = strtol(val, &end, 10);
    if (end == val || *end || errno || n < 1 || n > LAM_MAX_THREADS)
        return cli_usage(cmd, "%s takes a number of threads from 1 to %d (got '%s')", opt, LAM_MAX_THREADS, val);
    *out = (unsigned)n;
    return 0;
}

int cli_threads_env(const char *cmd, unsigned otherwise, unsigned *out)
{
    const char *env = getenv("LAMINA_THREADS");
    if (!env || !*env) {
        *out = otherwise;
        return 0;
    }
    int bad;
    *out = lam_default_threads(&bad);
    if (bad)
        return cli_usage(cmd, "LAMINA_THREADS must be a number of threads from 1 to %d (got '%s')", LAM_MAX_THREADS,
                         env);
    return 0;
}

/* -j N: worker threads (pool.h); LAMINA_THREADS or the processors when not given */
static int o_jobs(const char *cmd, args *a, const cli_opt *o, const char *opt, const char *val)
{
    (void)o;
    return cli_threads_arg(cmd, opt, val, &a->threads);
}

/* --layers A:B (1-based, inclusive) or K/N (the K-th of N near-equal
 * parts); checked against the run's layer count once the slicer knows it */
static int o_part(const char *cmd, args *a, const cli_opt *o, const char *opt, const char *val)
{
    (void)o;
    unsigned long long x, y;
    char sep, extra;
    if (sscanf(val, "%llu%c%llu%c", &x, &sep, &y, &extra) != 3 || (sep != ':' && sep != '/') || !isdigit((unsigned char)*val) ||
        !isdigit((unsigned char)strchr(val, sep)[1]))
        return cli_usage(cmd, "%s takes A:B (layers A to B, from 1) or K/N (part K of N) (got '%s')", opt, val);
    if (x < 1 || y < x)
        return cli_usage(cmd, sep == ':' ? "%s %s: the first layer is 1 and A:B needs A <= B"
                                         : "%s %s: K/N needs 1 <= K <= N", opt, val);
    a->layers = val;
    a->layers_a = (size_t)x;
    a->layers_b = (size_t)y;
    a->layers_split = sep == '/';
    return 0;
}

/* A layer number of --json-layers: digits, >= 1; "" is 0 (not given). */
static int layer_number(const char *t, size_t n, size_t *out)
{
    unsigned long long x = 0;
    for (size_t i = 0; i < n; i++) {
        if (!isdigit((unsigned char)t[i]) || x > 1000000000000000ULL) return -1;
        x = 10 * x + (unsigned)(t[i] - '0');
    }
    if (n && !x) return -1;
    *out = (size_t)x;
    return 0;
}

/* --json-layers A:B (1-based, inclusive; A: to the last layer, :B from the
 * first); the end is checked against the run's layers by cli_json_opts */
static int o_json_layers(const char *cmd, args *a, const cli_opt *o, const char *opt, const char *val)
{
    (void)o;
    const char *colon = strchr(val, ':');
    size_t x = 0, y = 0;
    if (!colon || layer_number(val, (size_t)(colon - val), &x) || layer_number(colon + 1, strlen(colon + 1), &y))
        return cli_usage(cmd, "%s takes A:B, A: or :B (layers A to B of the run, from 1) (got '%s')", opt, val);
    if (y && x > y) return cli_usage(cmd, "%s %s: A:B needs A <= B", opt, val);
    a->json_layers = val;
    a->json_first = x;
    a->json_last = y;
    return 0;
}

static const char *const json_vector_modes[] = { "all", "summary", "none" }; /* LAM_JSON_VECTORS_* */

/* --json-vectors all|summary|none */
static int o_json_vectors(const char *cmd, args *a, const cli_opt *o, const char *opt, const char *val)
{
    (void)o;
    for (size_t i = 0; i < sizeof json_vector_modes / sizeof *json_vector_modes; i++)
        if (!strcmp(val, json_vector_modes[i])) return a->json_vectors = json_vector_modes[i], 0;
    return cli_usage(cmd, "%s takes all, summary or none (got '%s')", opt, val);
}

/* --json-contours all|none */
static int o_json_contours(const char *cmd, args *a, const cli_opt *o, const char *opt, const char *val)
{
    (void)o;
    if (strcmp(val, "all") && strcmp(val, "none")) return cli_usage(cmd, "%s takes all or none (got '%s')", opt, val);
    a->json_contours = val;
    return 0;
}

int cli_json_opts(const char *cmd, const args *a, size_t layers, lam_json_opts *o)
{
    memset(o, 0, sizeof *o);
    for (size_t i = 0; a->json_vectors && i < sizeof json_vector_modes / sizeof *json_vector_modes; i++)
        if (!strcmp(a->json_vectors, json_vector_modes[i])) o->vectors = (int)i;
    o->no_contours = a->json_contours && !strcmp(a->json_contours, "none");
    o->first = a->json_first;
    o->last = a->json_last;
    size_t end = o->last ? o->last : o->first;
    if (end > layers)
        return cli_usage(cmd, "--json-layers %s: the run has %zu layer%s (A:B needs 1 <= A <= B <= %zu)",
                         a->json_layers, layers, layers == 1 ? "" : "s", layers);
    return EXIT_OK;
}

/* --units: a name of the profile key `units` (the one table, lam_unit_mm) */
static int o_units(const char *cmd, args *a, const cli_opt *o, const char *opt, const char *val)
{
    (void)o;
    if (lam_unit_mm(val) > 0) {
        a->units = val;
        return 0;
    }
    const lam_key *k = lam_key_find("units");
    char list[160] = "";
    size_t n = 0;
    for (size_t i = 0; k && k->choices && k->choices[i] && n < sizeof list; i++)
        n += (size_t)snprintf(list + n, sizeof list - n, "%s%s", i ? ", " : "", k->choices[i]);
    return cli_usage(cmd, "%s %s: the units lamina knows are %s", opt, val, list);
}

/* --scale, --rotate, --translate, --place: into a->xform (xform.h's
 * parsers, which Lua shares); the message names the option and its value */
static int o_xform(const char *cmd, args *a, const cli_opt *o, const char *opt, const char *val)
{
    lam_error err;
    lam_error_clear(&err);
    int (*parse)(lam_xform *, const char *, lam_error *) =
        !strcmp(o->name, "scale")    ? lam_xform_parse_scale
        : !strcmp(o->name, "rotate") ? lam_xform_parse_rotate
        : !strcmp(o->name, "place")  ? lam_xform_parse_place
                                     : lam_xform_parse_translate;
    if (parse(&a->xform, val, &err)) return cli_usage(cmd, "%s %s: %s", opt, val, err.msg);
    return 0;
}

#define F(member) offsetof(args, member)
static const cli_opt options[] = {
    { "units", 0, OPT_MODEL, "UNIT", o_units, 0 },
    { "scale", 0, OPT_MODEL, "F|FX,FY,FZ", o_xform, 0 },
    { "rotate", 0, OPT_MODEL, "AXIS:DEG", o_xform, 0 },
    { "place", 0, OPT_MODEL, "WHERE", o_xform, 0 },
    { "translate", 0, OPT_MODEL, "X,Y,Z", o_xform, 0 },
    { "no-repair", 0, OPT_MODEL, NULL, o_flag, F(no_repair) },
    { "jobs", 'j', OPT_PLAN | OPT_JOBS, "N", o_jobs, 0 },
    { "machine", 'm', OPT_SLICE, "MACHINE", o_text, F(machine) },
    { "axis", 'a', OPT_SLICE, "AXIS", o_axis, 0 },
    { "widths", 0, OPT_SLICE, "W1,W2,...", o_layers, F(so.widths) },
    { "planes", 0, OPT_SLICE, "P1,P2,...", o_layers, F(so.planes) },
    { "fill", 0, OPT_SLICE, "RULE", o_fill, 0 },
    { "allow-open", 0, OPT_SLICE, NULL, o_flag, F(allow_open) },
    { "max-layers", 0, OPT_SLICE, "N", o_max_layers, 0 },
    { "max-output", 0, OPT_PLAN, "SIZE", o_max_output, 0 },
    { "set", 's', OPT_SET, "KEY=VALUE", o_set, 0 },
    { "validate", 0, OPT_PLAN, NULL, o_flag, F(validate) },
    { "output", 'o', OPT_PLAN | OPT_OUTPUT, "FILE", o_output, F(out) },
    { "svg", 0, OPT_SVG, "FILE", o_output, F(svg) },
    { "json", 0, OPT_JSON_FILE, "FILE", o_output, F(json_out) },
    { "json-layers", 0, OPT_JSON_FILE, "A:B", o_json_layers, 0 },
    { "json-vectors", 0, OPT_JSON_FILE, "all|summary|none", o_json_vectors, 0 },
    { "json-contours", 0, OPT_JSON_FILE, "all|none", o_json_contours, 0 },
    { "html", 0, OPT_PLAN, "FILE", o_output, F(html) },
    { "layers", 0, OPT_PART, "A:B|K/N", o_part, 0 },
    { "layout", 0, OPT_BUILD, "FILE", o_output, F(layout) },
    { "program", 0, OPT_PROGRAM, "FILE", o_text, F(program) },
    { "json", 0, OPT_JSON, NULL, o_flag, F(json) },
    { "show", 0, OPT_SHOW, "NAME|PATH", o_show, 0 },
    { "keys", 0, OPT_SHOW, NULL, o_flag, F(keys) },
    { "quiet", 'q', OPT_TALK, NULL, o_talk, 0 },
    { "verbose", 'v', OPT_TALK, NULL, o_talk, 0 },
};
#undef F
#define NOPTIONS (sizeof options / sizeof options[0])

/* ---- profile keys -------------------------------------------------------- */

/* The group of a key's own option: planning values with the planning
 * options, the rest (layer width, cut, gap) with the slicing ones. */
static unsigned key_group(const lam_key *k)
{
    /* the frame also says how a program read back was written */
    if (k->offset == offsetof(lam_profile, frame_machine)) return OPT_PLAN | OPT_PROGRAM;
    /* so does the beam offset (validate.h: where the contour passes lie) */
    if (k->offset == offsetof(lam_profile, beam_offset)) return OPT_PLAN | OPT_PROGRAM;
    return k->flags & LAM_KEY_PLAN ? OPT_PLAN : OPT_SLICE;
}

/* Check name=value on a scratch profile with the loader's rules, and keep it. */
static int add_set(const char *cmd, args *a, const char *shown, const char *name, const char *value)
{
    lam_profile *tmp = calloc(1, sizeof *tmp);
    cli_set *ns = realloc(a->sets, (a->nsets + 1) * sizeof *ns);
    if (!tmp || !ns) {
        free(tmp);
        if (ns) a->sets = ns;
        fprintf(stderr, "lamina %s: out of memory\n", cmd);
        return EXIT_INPUT;
    }
    a->sets = ns;
    lam_error err;
    lam_error_clear(&err);
    int rc = lam_profile_set(tmp, name, value, &err);
    lam_profile_free(tmp);
    if (rc) return cli_usage(cmd, "%s: %s", shown, err.msg);
    cli_set *s = &a->sets[a->nsets++];
    s->key = lam_key_find(name);
    s->value = value;
    snprintf(s->shown, sizeof s->shown, "%s", shown);
    return 0;
}

/* ---- parsing ------------------------------------------------------------- */

/* One option found: a row of options[], or a key's own option. */
typedef struct found {
    const cli_opt *o;
    const lam_key *k;
} found;

static const char *found_arg(const found *f)
{
    if (f->o) return f->o->arg;
    return f->k->type == LAM_KEY_BOOLEAN ? NULL : "VALUE";
}

static unsigned found_group(const found *f)
{
    return f->o ? f->o->group : key_group(f->k);
}

/* By long name (len bytes of name) or by letter (len 0); of two rows of
 * one name (--json, a flag or a file) the one of the command's groups. */
static int find_option(const char *name, size_t len, char letter, unsigned groups, found *f)
{
    f->o = NULL;
    f->k = NULL;
    for (size_t i = 0; i < NOPTIONS; i++)
        if (len ? strlen(options[i].name) == len && !strncmp(options[i].name, name, len) : options[i].letter == letter)
            if (!f->o || (!(f->o->group & groups) && options[i].group & groups)) f->o = &options[i];
    if (f->o) return 1;
    for (size_t i = 0; i < lam_profile_nkeys; i++) {
        const lam_key *k = &lam_profile_keys[i];
        if (k->option && (len ? strlen(k->option) == len && !strncmp(k->option, name, len) : k->letter == letter))
            return f->k = k, 1;
    }
    return 0;
}

static int unknown_option(const char *cmd, unsigned groups, const char *opt)
{
    const char *names[LAM_KEYS_MAX + NOPTIONS];
    char bufs[LAM_KEYS_MAX + NOPTIONS][64];
    size_t n = 0;
    for (size_t i = 0; i < NOPTIONS; i++)
        if (options[i].group & groups) snprintf(bufs[n], sizeof bufs[n], "--%s", options[i].name), names[n] = bufs[n], n++;
    for (size_t i = 0; i < lam_profile_nkeys; i++)
        if (lam_profile_keys[i].option && key_group(&lam_profile_keys[i]) & groups)
            snprintf(bufs[n], sizeof bufs[n], "--%s", lam_profile_keys[i].option), names[n] = bufs[n], n++;
    char word[64];
    snprintf(word, sizeof word, "%.*s", (int)strcspn(opt, "="), opt);
    const char *best = lam_key_nearest(word, names, n);
    if (best) return cli_usage(cmd, "unknown option '%s' (did you mean '%s'?)", opt, best);
    /* --bead-width: a profile key spelt as an option */
    char key[64];
    size_t j = 0;
    for (const char *c = word + strspn(word, "-"); *c && j + 1 < sizeof key; c++) key[j++] = *c == '-' ? '_' : *c;
    key[j] = '\0';
    const lam_key *k = j ? lam_key_find(key) : NULL;
    if (k && !(k->flags & LAM_KEY_LOADER) && groups & OPT_SET)
        return cli_usage(cmd, "unknown option '%s' (did you mean '--set %s=...'?)", opt, k->name);
    return cli_usage(cmd, "unknown option '%s'", opt);
}

/* The model options (OPT_MODEL), as a table of the help: in the order
 * they apply (xform.h), which is not the order given */
static void help_model(void)
{
    fputs("How the model is loaded, in this order (docs/cli.md):\n"
          "      --units UNIT        the model's units: mm, cm, m, um, in or ft (default: the\n"
          "                          machine's), converted to the machine profile's units\n"
          "      --scale F|FX,FY,FZ  then scale by F, or per axis (repeatable: factors multiply)\n"
          "      --rotate AXIS:DEG   then rotate about x, y or z through the origin, right-handed\n"
          "                          (repeatable, applied in the order given; x:90,z:45 is both)\n"
          "      --place WHERE       then plate: lowest point on z = 0 and the footprint centred\n"
          "                          on the origin; none (default): where the file has it\n"
          "      --translate X,Y,Z   then move by X,Y,Z (repeatable: offsets add)\n"
          "      --no-repair         build the model from the file as it is: no repair on load\n",
          stdout);
}

/* The command's help: its usage text, the model options, then its
 * profile-key options. */
static void help(const char *usage, unsigned groups)
{
    fputs(usage, stdout);
    if (groups & OPT_MODEL) help_model();
    int head = 0;
    for (size_t i = 0; i < lam_profile_nkeys; i++) {
        const lam_key *k = &lam_profile_keys[i];
        if (!k->option || !(key_group(k) & groups)) continue;
        if (!head++)
            printf("Profile values (each option is short for --set KEY=VALUE; 'lamina machines --keys'\n"
                   "lists every key):\n");
        char left[64];
        const char *arg = k->type == LAM_KEY_BOOLEAN ? "" : k->type == LAM_KEY_INTEGER ? " N"
                                                         : k->type == LAM_KEY_NUMBER  ? " X"
                                                                                      : " VALUE";
        if (k->letter) snprintf(left, sizeof left, "-%c, --%s%s", k->letter, k->option, arg);
        else snprintf(left, sizeof left, "    --%s%s", k->option, arg);
        /* a key of one planner says so: the other's profiles refuse it */
        const char *only = k->planner == LAM_READ_LADRP ? " (ladrp profiles)"
                           : k->planner == LAM_READ_SLS ? " (sls profiles)"
                                                        : "";
        if (k->type == LAM_KEY_BOOLEAN)
            printf("  %-24s --set %s=%s%s\n", left, k->name, strncmp(k->option, "no-", 3) ? "true" : "false", only);
        else
            printf("  %-24s --set %s=%s%s\n", left, k->name, arg + 1, only);
    }
}

/* Standard output takes one output: a program without -o goes there, and
 * so does every output option given "-". */
static int one_stdout(const char *cmd, unsigned groups, args *a)
{
    int defaulted = groups & OPT_PLAN && !a->out;
    if (defaulted) a->out = "-";
    const cli_opt *first = NULL;
    for (size_t i = 0; i < NOPTIONS; i++) {
        const cli_opt *o = &options[i];
        if (o->fn != o_output || !(o->group & groups)) continue;
        const char *v = *(const char **)(void *)((char *)a + o->field);
        if (!v || strcmp(v, "-")) continue;
        if (!first) {
            first = o;
            continue;
        }
        if (defaulted && first->field == offsetof(args, out))
            return cli_usage(cmd, "the program (without -o) and --%s - both write to standard output: give -o FILE",
                             o->name);
        char a1[40];
        if (first->letter) snprintf(a1, sizeof a1, "-%c", first->letter);
        else snprintf(a1, sizeof a1, "--%s", first->name);
        return cli_usage(cmd, "%s - and --%s - both write to standard output: give one of them a file", a1, o->name);
    }
    return EXIT_OK;
}

int cli_parse_args(const char *cmd, const char *usage_text, unsigned groups, int argc, char **argv, args *a)
{
    memset(a, 0, sizeof *a);
    lam_slice_opts_init(&a->so);
    lam_xform_init(&a->xform);
    int only_args = 0, rc = 0;
    for (int i = 1; i < argc && !rc; i++) {
        const char *o = argv[i];
        if (only_args || o[0] != '-' || !o[1]) {
            if (groups & OPT_BUILD) {
                if (a->path) return cli_usage(cmd, "more than one job given ('%s' and '%s')", a->path, o);
                a->path = o;
                continue;
            }
            if (!(groups & OPT_MODEL))
                return cli_usage(cmd, "unexpected argument '%s'%s%s%s", o, groups & OPT_SHOW ? " (to print a profile: --show " : "",
                                 groups & OPT_SHOW ? o : "", groups & OPT_SHOW ? ")" : "");
            if (a->path) return cli_usage(cmd, "more than one model given ('%s' and '%s')", a->path, o);
            a->path = o;
            continue;
        }
        if (!strcmp(o, "--")) {
            only_args = 1;
            continue;
        }
        if (!strcmp(o, "-h") || !strcmp(o, "--help")) {
            help(usage_text, groups);
            return -1;
        }
        int lng = o[1] == '-';
        const char *name = o + (lng ? 2 : 1), *eq = lng ? strchr(name, '=') : NULL;
        const char *attached = lng ? (eq ? eq + 1 : NULL) : (o[2] ? o + 2 : NULL);
        found f;
        if (!find_option(name, lng ? (eq ? (size_t)(eq - name) : strlen(name)) : 0, lng ? 0 : o[1], groups, &f) || (!lng && !o[1]))
            return unknown_option(cmd, groups, o);
        char opt[80];
        snprintf(opt, sizeof opt, "%.*s", (int)(lng ? (eq ? (size_t)(eq - o) : strlen(o)) : 2), o);
        if (!(found_group(&f) & groups)) return cli_usage(cmd, "option %s does not apply to '%s'", opt, cmd);
        const char *val = NULL;
        if (found_arg(&f)) {
            if (attached) val = attached;
            else if (i + 1 < argc) val = argv[++i];
            else return cli_usage(cmd, "option %s needs a value", opt);
        } else if (attached) {
            return cli_usage(cmd, "option %s takes no value", opt);
        }
        if (f.o) {
            rc = f.o->fn(cmd, a, f.o, opt, val);
        } else {
            char shown[160];
            snprintf(shown, sizeof shown, "%s%s%s", opt, val ? " " : "", val ? val : "");
            if (!val) val = strncmp(f.k->option, "no-", 3) ? "true" : "false";
            rc = add_set(cmd, a, shown, f.k->name, val);
        }
    }
    if (rc) return rc;
    if (groups & OPT_MODEL && !a->path) return cli_usage(cmd, "no model given");
    if (groups & OPT_BUILD && !a->path) return cli_usage(cmd, "no job given (a build job file: docs/builds.md)");
    /* LAMINA_THREADS is checked for every command, also those without -j
     * (info and check read a big binary STL with it) */
    unsigned otherwise = groups & (OPT_PLAN | OPT_JOBS) ? lam_online_cores() : 0;
    if (!a->threads && (rc = cli_threads_env(cmd, otherwise, &a->threads))) return rc;
    if ((rc = one_stdout(cmd, groups, a))) return rc;
    if ((a->json_layers || a->json_vectors || a->json_contours) && !a->json_out)
        return cli_usage(cmd, "%s says what --json FILE holds: give --json FILE too",
                         a->json_layers ? "--json-layers" : a->json_vectors ? "--json-vectors" : "--json-contours");
    int width = 0;
    for (size_t i = 0; i < a->nsets; i++) width |= a->sets[i].key->offset == offsetof(lam_profile, layer_width);
    if ((a->so.widths || a->so.planes) && width) return cli_usage(cmd, "give one of -w, --widths and --planes");
    return EXIT_OK;
}

void cli_args_free(args *a)
{
    free(a->list);
    free(a->sets);
    a->list = NULL;
    a->sets = NULL;
    a->nsets = 0;
}

int cli_apply_sets(const char *cmd, const args *a, lam_profile *p)
{
    lam_error err;
    lam_error_clear(&err);
    for (size_t i = 0; i < a->nsets; i++)
        if (lam_profile_set(p, a->sets[i].key->name, a->sets[i].value, &err))
            return err.code == LAM_ENOMEM ? cli_fail(&err) : cli_usage(cmd, "%s: %s", a->sets[i].shown, err.msg);
    if (a->nsets && lam_profile_check(p, &err)) return cli_usage(cmd, "%s", err.msg);
    /* a value the profile's planner does not read would do nothing: refused
     * against the process the values leave (-s process=... comes first) */
    for (size_t i = 0; i < a->nsets; i++)
        if (!lam_key_read_by(a->sets[i].key, p->process)) {
            lam_key_unread(a->sets[i].key, NULL, p->process, p->name, &err);
            return cli_usage(cmd, "%s: %s", a->sets[i].shown, err.msg);
        }
    return EXIT_OK;
}

int cli_profile(const char *cmd, args *a, lam_profile **out, lam_plan_opts *po)
{
    lam_error err;
    lam_error_clear(&err);
    *out = NULL;
    lam_profile *p = NULL;
    if (a->machine ? lam_profile_find(a->machine, &p, &err) : lam_profile_builtin_sls(&p, &err)) return cli_fail(&err);
    int rc = cli_apply_sets(cmd, a, p);
    if (rc) {
        lam_profile_free(p);
        return rc;
    }
    if (!a->so.widths && !a->so.planes && p->layer_width > 0) a->so.width = p->layer_width;
    a->so.cut = (lam_cut)p->cut;
    a->so.gap = p->gap;
    /* a machine's units say what the automatic gap may be at most; the
     * built-in profile stands for no machine, and model units for nothing */
    if (a->machine) a->so.gap_limit = lam_profile_gap_limit(p);
    if (po) {
        lam_plan_opts_from_profile(po, p);
        po->max_output = a->max_output;
        po->threads = a->threads;
    }
    *out = p;
    return EXIT_OK;
}

int cli_fail_limit(const lam_error *err, int over, const char *option)
{
    int rc = cli_fail(err);
    if (over || err->code == LAM_ELIMIT) fprintf(stderr, "lamina: raise the limit with %s\n", option);
    return rc;
}
