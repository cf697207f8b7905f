/* The machine-profile keys: one table row per key (name, type, range or
 * choices, default, where it lives in lam_profile, doc string), as Redis
 * declares its configuration and dialect.c its commands' fields.
 *
 * The table drives everything that knows a key by name: the YAML loader and
 * its messages (profile.c), `lamina machines --show` (lam_profile_dump),
 * `--set KEY=VALUE` (lam_profile_set, profile.h: a list's value is read as
 * YAML) and the convenience options (lua/cli/cli_args.c), the Lua
 * machine fields and machine:override (lua/l_machine.c) and the key
 * reference in machines/README.md (`lamina machines --keys`, checked by a
 * test). Adding a key is one row in profile_keys.c, a field in lam_profile
 * and its use in a planner.
 *
 * A key in a section is written `section.key` ("raster.angle"): in YAML it
 * is `key:` inside the `section:` mapping. Messages name keys the way the
 * YAML loader always has: "bead_width must be greater than 0, got '0'".
 *
 * The profile type is here, not in profile.h, because the table is made of
 * its field offsets: the loader (profile.c) uses the table, the table only
 * the type. */
#ifndef LAM_PROFILE_KEYS_H
#define LAM_PROFILE_KEYS_H

#include <stddef.h>

#include "dialect.h"
#include "error.h"
#include "hatch.h"

/* A machine profile (profile.h loads one): the fields the table's rows
 * live in (lam_key.offset). */
typedef enum lam_process { LAM_PROCESS_LADRP, LAM_PROCESS_SLS } lam_process;
typedef enum lam_first_line { LAM_FIRST_EDGE, LAM_FIRST_CENTER } lam_first_line;

/* Most lasers a profile may give (lam_profile.laser_field). */
#define LAM_PROFILE_LASERS_MAX 16

typedef struct lam_profile {
    char *name;              /* `name:` */
    char *path;              /* the file it was loaded from */
    char *description;       /* optional */
    lam_process process;
    char *units;             /* default "mm" */
    double bead_width;       /* LADRP: required, > 0; SLS: copy of spot_width */
    double spot_width;       /* SLS: required, > 0 */
    double layer_width;      /* > 0; 0 when absent (the slicer's default applies) */
    int cut;                 /* lam_cut (slice.h); default LAM_CUT_MIDDLE */
    double feed_rate;        /* >= 0, deposit feed, default 0 */
    double travel_rate;      /* >= 0, default feed_rate */
    double gap;              /* gap-closing tolerance, >= 0; LAM_GAP_AUTO (`gap: auto`, the
                                default): the slicer's, scaled with the model */
    int frame_machine;       /* `frame: machine` -> 1, `model` (default) -> 0 */
    /* raster (LADRP) */
    lam_first_line first_line;   /* default edge */
    double angle, angle_step;    /* degrees, default 0 */
    int alternate;               /* boustrophedon, default true */
    double min_deposit;          /* >= 0, default 0 */
    int perimeters;              /* passes around each contour offset by d/2, default 0 */
    int islands;                 /* raster island by island, nearest next; default false */
    /* SLS */
    int beam_offset;             /* contours inset by spot/2, default false */
    lam_scan_cfg scan;           /* hatching, skins, exposure, time (hatch.h);
                                    scan.compensation is not a key: the planner's */
    /* the build plate (builds, core/build): 0 when absent */
    double plate_width, plate_depth;   /* plate.width, plate.depth: a rectangular plate */
    double plate_diameter;             /* plate.diameter: a round plate (instead of width/depth) */
    double plate_margin;               /* plate.margin: kept free along the edge, default 0 */
    double spacing;                    /* between parts' footprints, default 0 */
    double gas_flow[2];                /* gas_flow: [dx, dy], the direction the gas flows in
                                          (plate x, y; any length); 0 0: none */
    size_t nlasers;                    /* lasers: [{field: [x0, y0, x1, y1]}, ...]; 0: none given */
    double laser_field[LAM_PROFILE_LASERS_MAX][4]; /* each laser's field on the plate (x0 < x1, y0 < y1) */
    /* design rules (optional) */
    double max_overhang_deg;     /* 0 when absent */
    char *writer;                /* "text" (default: the dialect) or a plugin writer name; never NULL */
    lam_dialect dialect;
} lam_profile;

typedef enum lam_key_type {
    LAM_KEY_NUMBER,   /* double, finite, in [lo, hi] ((lo, hi] with LAM_KEY_ABOVE) */
    LAM_KEY_INTEGER,  /* int, a whole number in [lo, hi] */
    LAM_KEY_BOOLEAN,  /* int 0 or 1: true/false/yes/no */
    LAM_KEY_CHOICE,   /* int: index into choices */
    LAM_KEY_STRING,   /* char *, malloc'd, owned by the profile; with choices, one of them */
    LAM_KEY_TEMPLATE, /* lam_template of a dialect command (dialect.h) */
    LAM_KEY_NUMBERS,  /* double[count]: a YAML list of exactly `count` finite
                         numbers in [lo, hi] (gas_flow: [dx, dy]); with
                         LAM_KEY_OPTIONAL all 0 means "not given" */
    LAM_KEY_LASERS    /* the lasers: nlasers and laser_field of lam_profile
                         (offset: nlasers), a YAML list of 1 to
                         LAM_PROFILE_LASERS_MAX mappings {field: [x0, y0, x1,
                         y1]} with x0 < x1, y0 < y1 */
} lam_key_type;

enum lam_key_flag {
    LAM_KEY_ABOVE = 1 << 0,      /* number: lo itself is excluded */
    LAM_KEY_OPTIONAL = 1 << 1,   /* 0 / NULL means "not given": no default,
                                    left out of dumps, nil in Lua */
    LAM_KEY_FIXED = 1 << 2,      /* what the machine is (identity, dialect):
                                    machine:override cannot change it */
    LAM_KEY_PLAN = 1 << 3,       /* a planning value: machine:plan's options
                                    and the planning command-line options */
    LAM_KEY_NONEMPTY = 1 << 4,   /* string: "" is refused */
    LAM_KEY_FLAT = 1 << 5,       /* in a section, but known in Lua and to
                                    --set by its own name (raster.angle: angle) */
    LAM_KEY_LOADER = 1 << 6,     /* read by the loader only (inherits): no
                                    field, never dumped or set afterwards */
    LAM_KEY_NEED = 1 << 7,       /* every profile must give it */
    LAM_KEY_NEED_LADRP = 1 << 8, /* a ladrp profile must give it */
    LAM_KEY_NEED_SLS = 1 << 9,   /* an sls profile must give it */
    LAM_KEY_AUTO = 1 << 10       /* number: also the word `auto`, stored as
                                    -1 (decided per run: the gap from the
                                    model's size) */
};

/* Which planner reads a key (lam_key.planner). A key read by one planner
 * only is refused where a user gives it to a profile of the other process
 * (lam_key_unread): it would do nothing. */
enum lam_key_planner {
    LAM_READ_BOTH,  /* the same meaning for every profile */
    LAM_READ_LADRP, /* the raster planner only (raster.*) */
    LAM_READ_SLS    /* the powder-bed planner only (hatching, exposure) */
};

typedef struct lam_key {
    const char *name;            /* "bead_width", "raster.angle" */
    const char *alias;           /* another name for the same row, or NULL:
                                    layer_thickness, the powder-bed word for
                                    layer_width (YAML, --set, messages use
                                    the name) */
    lam_key_type type;
    unsigned flags;              /* lam_key_flag */
    double lo, hi;               /* number, integer: the range */
    const char *const *choices;  /* choice, string: the names, NULL-ended */
    const char *def;             /* the default as YAML text; NULL: none */
    const char *follows;         /* no default of its own: when not given,
                                    the value of this key (travel_rate:
                                    feed_rate) */
    const char *option;          /* the command-line option that is short
                                    for --set KEY=VALUE ("angle" for
                                    --angle), or NULL; a boolean's option
                                    is a flag: "no-..." sets false, any
                                    other name true */
    char letter;                 /* its one-letter form ('w' for -w), or 0 */
    int cmd;                     /* template: the lam_cmd */
    size_t count;                /* numbers: how many */
    size_t offset;               /* where it lives in lam_profile */
    int planner;                 /* lam_key_planner: who reads it */
    const char *instead;         /* a one-planner key: what the other planner
                                    reads for the same purpose, as KEY or
                                    KEY=VALUE ("hatch_angle" for
                                    raster.angle), or NULL: nothing */
    const char *doc;             /* one line for the reference */
} lam_key;

/* The row of the field at `offset` in lam_profile, or NULL. */
const lam_key *lam_key_at(size_t offset);

/* The table, in the order `lamina machines --show` writes the keys (the
 * rows of a section are adjacent). */
extern const lam_key lam_profile_keys[];
extern const size_t lam_profile_nkeys;

/* Most rows the table may have (loader and Lua bookkeeping arrays). */
#define LAM_KEYS_MAX 256

/* The row named `name` ("raster.angle"), a row by its alias
 * ("layer_thickness"), or a flat row by its own name ("angle"); NULL when
 * there is none. */
const lam_key *lam_key_find(const char *name);

/* The row's section length: "raster.angle" -> 6, "gap" -> 0. */
size_t lam_key_section_len(const lam_key *k);

/* The key's name without its section ("raster.angle" -> "angle"). */
const char *lam_key_short(const lam_key *k);

/* Its name in Lua and in Lua messages: the short name for flat rows, else
 * the whole name. */
const char *lam_key_lua_name(const lam_key *k);

/* Whether a profile of process `process` (lam_process) reads key k. */
int lam_key_read_by(const lam_key *k, int process);

/* Record why key k does nothing for a profile of `process` (call when
 * !lam_key_read_by): "raster.angle is read by the ladrp planner only, and
 * cli-ascii is an sls profile: set hatch_angle instead". `as` names the key
 * as the user wrote it (NULL: its name), `profile` the profile (NULL:
 * "this"). Returns LAM_EINVAL (no position). */
int lam_key_unread(const lam_key *k, const char *as, int process, const char *profile, lam_error *err);

/* Millimetres per unit of a `units` name (the row's choices: mm 1, cm 10,
 * m 1000, um and µm 0.001, in and inch 25.4, ft 304.8); 0 for any other. */
double lam_key_unit_mm(const char *units);

/* Check a text value of a string row: not empty when LAM_KEY_NONEMPTY, one
 * of the row's choices when it has some (units). Errors: LAM_EINVAL "units
 * must be mm, cm, ..., got '<script>'", "name must not be empty". */
int lam_key_check_text(const lam_key *k, const char *text, lam_error *err);

/* The name among names[0..n) nearest to word by edit distance, if it is at
 * most 2 edits away (for "did you mean"); NULL otherwise. */
const char *lam_key_nearest(const char *word, const char *const *names, size_t n);

/* Record "KEY must be WHAT, got GOT" for a value of the wrong kind: WHAT is
 * what the row's type takes ("a number", "true or false", "floor, middle
 * or ceiling", "text", "a template (text) or null"), `got` what was there
 * ("'abc'", "a list"). Returns LAM_EINVAL. */
int lam_key_expected(const lam_key *k, const char *as, const char *got, lam_error *err);

/* Read a number, integer, boolean or choice key's value from text[0..len)
 * (what a plain YAML scalar holds) into *x (a choice's index, a boolean's
 * 0/1), and check it against the row. `as` names the key in messages
 * (NULL: its name). Errors (LAM_EINVAL, no position): "KEY must be a number,
 * got 'abc'" and the range messages of lam_key_check. */
int lam_key_scan(const lam_key *k, const char *as, const char *text, size_t len, double *x, lam_error *err);

/* Check a number or integer value x against the row's range; `shown` is x
 * as the user wrote it (for "got ..."). Booleans and choices always pass.
 * Errors: LAM_EINVAL "KEY must be greater than 0, got '0'", "... 0 or more",
 * "... from 0 to 90", "... a whole number from 0 to 1000". */
int lam_key_check(const lam_key *k, const char *as, double x, const char *shown, lam_error *err);

/* A number, integer, boolean or choice key's value in p. */
double lam_key_get(const struct lam_profile *p, const lam_key *k);

/* Whether row k has a value in p: an optional row's value not 0 (a number
 * list with a number not 0, at least one laser, a present template, a
 * string not NULL); always 1 for a row that is not optional. */
int lam_key_given(const struct lam_profile *p, const lam_key *k);

/* Check numbers row k's values v[0..n): n is the row's count, each finite
 * and in its range. `as` names the key (NULL: its name). Errors:
 * LAM_EINVAL "gas_flow must be a list of 2 numbers, got 3 numbers",
 * "gas_flow must be finite numbers, got inf". */
int lam_key_check_numbers(const lam_key *k, const char *as, const double *v, size_t n, lam_error *err);

/* Check one laser's field f = {x0, y0, x1, y1}: finite, x0 < x1 and
 * y0 < y1. Errors: LAM_EINVAL "a laser's field must have x0 < x1 and
 * y0 < y1, got [0, 0, 0, 250]". */
int lam_key_check_field(const double f[4], lam_error *err);

/* Store a checked number, integer, boolean or choice value into p, and
 * keep what follows it: a key that `follows` this one and had its value
 * takes the new one (a travel rate that followed the feed rate), and an sls
 * profile's bead width is its spot width; a plate's shape is one: a
 * diameter clears the width and depth, a width or depth the diameter. */
void lam_key_put(struct lam_profile *p, const lam_key *k, double x);

/* The same without the values that follow (the loader settles those once
 * the whole chain is read). */
void lam_key_store(struct lam_profile *p, const lam_key *k, double x);

/* After lam_profile_set: the keys a profile must give for its process are
 * there (a changed process may need another width), and a plate's width
 * and depth go together (lam_profile_check_plate). LAM_EINVAL otherwise. */
int lam_profile_check(const struct lam_profile *p, lam_error *err);

/* The plate's keys of p agree: width and depth both or neither, a
 * diameter without them. Errors: LAM_EINVAL "plate.width and plate.depth
 * go together: give both (a rectangular plate) or plate.diameter (a round
 * one)", "plate.diameter excludes plate.width and plate.depth". */
int lam_profile_check_plate(const struct lam_profile *p, lam_error *err);

#endif
