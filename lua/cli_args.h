/* Options shared by the commands that slice (slice, validate, check):
 * one parser, so every command spells an option the same way. */
#ifndef LAM_CLI_ARGS_H
#define LAM_CLI_ARGS_H

#include "planner.h"
#include "profile.h"
#include "slice.h"

/* Option groups a command accepts. */
enum {
    OPT_SLICE = 1,     /* -m -a -w --widths --planes --cut --gap --allow-open --fill */
    OPT_PLAN = 2,      /* raster and SLS options, --frame, -o, --validate */
    OPT_JSON = 4,      /* --json */
    OPT_SVG = 8        /* --svg FILE */
};

typedef struct args {
    const char *path, *out, *svg, *machine;
    lam_slice_opts so;
    double *list;
    int allow_open, set_width, set_cut, set_gap, set_frame, json, validate;
    int set_first, first_center, set_angle, set_step, set_min, no_alternate, frame_machine;
    int perimeters, set_perimeters, beam_offset, islands;
    double angle, angle_step, min_deposit;
    unsigned long long max_output;  /* --max-output, 0: the default */
} args;

/* Parse argv[1..] for command cmd, accepting the option groups in
 * `groups`. Returns 0, -1 when --help was printed (usage text), or
 * EXIT_USAGE after printing the problem. Free with cli_args_free. */
int cli_parse_args(const char *cmd, const char *usage, unsigned groups, int argc, char **argv, args *a);
void cli_args_free(args *a);

/* The machine profile for a run: -m's, or the built-in SLS profile. */
int cli_load_profile(const args *a, lam_profile **out, lam_error *err);

/* Report err (cli_fail); when it is a limit (LAM_ELIMIT, or `over`) also
 * say that `option` raises it. */
int cli_fail_limit(const lam_error *err, int over, const char *option);
#define CLI_RAISE_LAYERS "--max-layers N"
#define CLI_RAISE_OUTPUT "--max-output SIZE (bytes, or with k, M, G or T)"

/* Profile defaults under the command line's overrides. */
void cli_apply_profile(args *a, const lam_profile *p, lam_plan_opts *po);

#endif
