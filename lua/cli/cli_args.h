/* The option parser the commands share (info, slice, validate, check,
 * machines): one table of options, so every command spells an option the
 * same way. GNU conventions: `--name=value` and `--name value`, `-x value`
 * and `-xvalue`, `--` ends the options, an unknown option gets "did you
 * mean". Every machine-profile key can be given as `--set KEY=VALUE` (`-s`);
 * the convenience options (`-w`, `--angle`, `--islands`, ...) are the
 * options of the key table's rows (core/profile/profile_keys.c), short for --set.
 *
 * Standard streams: a MODEL of `-` is standard input (the commands load it
 * with cli_load_model), and every output option (a row of the table whose
 * action is o_output: -o, --svg, --json FILE, ...) takes `-` for standard
 * output. Two outputs to `-` in one run is a usage error; for commands
 * with -o, a program without -o goes to standard output and counts as one
 * (a->out is then "-"). */
#ifndef LAM_CLI_ARGS_H
#define LAM_CLI_ARGS_H

#include <stddef.h>

#include "planner.h"
#include "profile.h"
#include "profile_keys.h"
#include "slice.h"
#include "xform.h"

/* Option groups a command accepts. */
enum {
    OPT_MODEL = 1,     /* one MODEL argument, and how it is loaded: --units --scale
                          --rotate --translate --place --no-repair */
    OPT_SLICE = 2,     /* -m -a --widths --planes --fill --allow-open, and the slicing keys' options */
    OPT_PLAN = 4,      /* --validate -o --html, and the planning keys' options */
    OPT_JSON = 8,      /* --json */
    OPT_SVG = 16,      /* --svg FILE */
    OPT_SET = 32,      /* -s/--set KEY=VALUE */
    OPT_SHOW = 64,     /* machines: --show NAME, --keys */
    OPT_PROGRAM = 128, /* validate: --program FILE, and --frame (how it was written) */
    OPT_TALK = 256,    /* -q/--quiet, -v/--verbose (progress.h) */
    OPT_JSON_FILE = 512, /* slice: --json FILE (the run as JSON), instead of the --json flag */
    OPT_PART = 1024,   /* slice: --layers A:B or K/N (a part file) */
    OPT_JOBS = 2048,   /* -j N without the rest of OPT_PLAN (validate) */
    OPT_OUTPUT = 4096, /* -o FILE without the rest of OPT_PLAN, and no standard-output default (repair) */
    OPT_BUILD = 8192   /* build: one JOB argument (a->path), --layout FILE */
};

/* A profile value from the command line: --set KEY=VALUE or an option short for it. */
typedef struct cli_set {
    const lam_key *key;
    const char *value;
    char shown[160];         /* the option as given, for messages: "--set gap=x", "-w 0" */
} cli_set;

typedef struct args {
    const char *path, *out, *svg, *machine, *show, *program;
    const char *json_out;    /* slice --json FILE */
    const char *layout;      /* build --layout FILE */
    const char *html;        /* slice --html FILE */
    lam_slice_opts so;
    double *list;
    int allow_open, json, validate, keys;
    cli_set *sets;           /* in command-line order; later ones win */
    size_t nsets;
    unsigned long long max_output;  /* --max-output, 0: the default */
    int talk;                /* -q: -1, -v: 1 (the last given wins), else 0 */
    unsigned threads;        /* -j N (OPT_PLAN, OPT_JOBS): LAMINA_THREADS or the online processors */
    const char *layers;      /* --layers as given (NULL: the whole run) */
    size_t layers_a, layers_b; /* A:B (1-based, inclusive), or with layers_split K/N */
    int layers_split;
    int no_repair;           /* --no-repair: the mesh as the file has it (repair.h) */
    /* OPT_MODEL: the transform on load (xform.h) as the options give it:
     * --scale, --rotate, --translate and --place; the units (--units,
     * NULL: the machine's) are turned into a factor by cli_load_model,
     * which knows the machine. */
    lam_xform xform;
    const char *units;
    /* slice, build: what --json FILE holds (cli_json_opts) */
    const char *json_layers;  /* --json-layers as given (NULL: every layer) */
    size_t json_first, json_last; /* its A and B (0: from the first, to the last layer) */
    const char *json_vectors; /* --json-vectors as given (NULL: all) */
    const char *json_contours; /* --json-contours as given (NULL: all) */
} args;

/* Parse argv[1..] for command cmd, accepting the option groups in
 * `groups`. Returns 0, -1 when --help was printed (usage text and the
 * profile options of the command's groups), or EXIT_USAGE after printing
 * the problem. Free with cli_args_free. */
int cli_parse_args(const char *cmd, const char *usage, unsigned groups, int argc, char **argv, args *a);

/* -j N's value: a number of threads from 1 to LAM_MAX_THREADS into *out,
 * else a usage error of cmd naming opt (EXIT_USAGE). */
int cli_threads_arg(const char *cmd, const char *opt, const char *val, unsigned *out);

/* LAMINA_THREADS into *out when it is set (a usage error when it is not a
 * number of threads), else `otherwise`. */
int cli_threads_env(const char *cmd, unsigned otherwise, unsigned *out);
void cli_args_free(args *a);

/* The machine profile of a run: -m's, or the built-in SLS profile, with the
 * command line's profile values applied; the slicing options take the
 * profile's layer width, cut and gap unless the command line gave its own
 * layers, and po (when not NULL) its planning values. Returns EXIT_OK with
 * *out to free, or the exit status after printing the problem. */
int cli_profile(const char *cmd, args *a, lam_profile **out, lam_plan_opts *po);

/* Load the command's MODEL (a->path, "-": standard input) with its load
 * options: -j threads, --no-repair, and --units/--scale/--rotate/
 * --translate/--place converted for `machine` (its units and plate; NULL:
 * millimetres, no plate). (cli_load.c) */
int cli_load_model(const args *a, const lam_profile *machine, struct lam_model **m, lam_error *err);

/* What --json holds (json_sink.h's lam_json_opts) as --json-layers,
 * --json-vectors and --json-contours say, the range checked against the run's `layers` (a
 * usage error of cmd, EXIT_USAGE, for one past its end). */
struct lam_json_opts;
int cli_json_opts(const char *cmd, const args *a, size_t layers, struct lam_json_opts *o);

/* The profile values of the command line applied to p (machines --show). */
int cli_apply_sets(const char *cmd, const args *a, lam_profile *p);

/* Report err (cli_fail); when it is a limit (LAM_ELIMIT, or `over`) also
 * say that `option` raises it. */
int cli_fail_limit(const lam_error *err, int over, const char *option);
#define CLI_RAISE_LAYERS "--max-layers N"
#define CLI_RAISE_OUTPUT "--max-output SIZE (bytes, or with k, M, G or T)"

#endif
