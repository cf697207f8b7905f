/* A build (issue 25): parts placed on a machine's plate, each with copies,
 * an orientation and a build style per region, planned as one program.
 *
 * A build is made from a job file (build_job.c: `lamina build JOB.yaml`) or
 * from Lua (`lamina.build{...}`) through the same calls: lam_build_new with
 * the machine profile (the job's overrides already applied), then
 * lam_build_style_set for each key of each named style, then
 * lam_build_part_add for each part. lam_build_place (build_plan.h) loads
 * the models, arranges them (arrange.h) and lam_build_plan plans the plate.
 *
 * Build styles: a style is a named set of exposure and hatching values
 * (power, speed, point_distance, exposure_time, hatch_distance,
 * hatch_strategy, hatch_angle, ...: the keys a region section of a profile
 * has, profile_keys.h). Every region (contour, core, upskin, downskin) of
 * every part is exposed with one style: by default the style named after
 * the region, which is the profile's own values for that region (the
 * shipped powder-bed profiles' default set); a part may name one style for
 * all its regions (each key applies to the regions that have it) or one per
 * region. A style named after a region and defined by the job changes that
 * region's default. */
#ifndef LAM_BUILD_H
#define LAM_BUILD_H

#include <stddef.h>

#include "error.h"
#include "profile.h"
#include "vocab.h"
#include "xform.h"

#define LAM_BUILD_MAX_STYLES 256
#define LAM_BUILD_MAX_KEYS 64
#define LAM_BUILD_MAX_COPIES 10000
#define LAM_BUILD_MAX_PARTS 10000 /* instances, copies counted */

/* A key of a style: the row of the core region (or of another region's
 * section, for a key only sections have) and the value as text. */
typedef struct lam_style_key {
    char *key;               /* short name: "power", "hatch_distance" */
    char *text;              /* its value as written */
    long line, column;       /* where (0: not from a file) */
} lam_style_key;

typedef struct lam_build_style {
    char *name;
    lam_style_key keys[LAM_BUILD_MAX_KEYS];
    size_t nkeys;
    long line, column;
} lam_build_style;

/* A part as the job lists it (before copies are made). */
typedef struct lam_build_part {
    char *model;             /* the model's path (owned) */
    char *name;              /* its name, the labels' stem (owned; NULL: from the path) */
    lam_xform xform;         /* units, scale and rotations (no placement: the build places) */
    size_t copies;           /* >= 1 */
    int has_at;              /* 1: at[] is the centre of the footprint box on the plate */
    double at[2];
    double z;                /* the part's lowest point above the plate (0: on it) */
    int style[LAM_REGIONS];  /* the style of each region: an index into the build's
                                styles, or -1: the style named after the region */
    int style_whole;         /* 1: one style named for every region (keys a region
                                does not have are skipped for it) */
    long line, column;       /* where the job lists it (0: not from a file) */
} lam_build_part;

typedef struct lam_build {
    char *path;              /* the job file, or NULL (Lua) */
    lam_profile *profile;    /* the machine with the job's values (owned) */
    lam_build_style *styles;
    size_t nstyles;
    lam_build_part *parts;
    size_t nparts;
} lam_build;

/* A new build for machine p (taken over: freed with the build). The
 * machine must be a powder-bed (sls) profile. Errors: LAM_EINVAL (another
 * process), LAM_ENOMEM; p is freed on error too. */
int lam_build_new(lam_profile *p, const char *path, lam_build **out, lam_error *err);

void lam_build_free(lam_build *b);

/* The style named `name` (created if new) gets key = text; the key must be
 * one a region section has (lam_style_key_check). line, column: where, for
 * messages (0: none). Errors: LAM_EINVAL with "did you mean", LAM_ELIMIT
 * past LAM_BUILD_MAX_STYLES or _KEYS, LAM_ENOMEM. */
int lam_build_style_set(lam_build *b, const char *name, const char *key, const char *text, long line, long column,
                        lam_error *err);

/* The index of style `name`, or -1. */
int lam_build_style_find(const lam_build *b, const char *name);

/* Add a part (spec copied; its strings too). Style indices must be valid.
 * Errors: LAM_EINVAL (copies 0 or past LAM_BUILD_MAX_COPIES, `at` with
 * copies > 1, z < 0 or not finite), LAM_ELIMIT (instances past
 * LAM_BUILD_MAX_PARTS), LAM_ENOMEM. */
int lam_build_part_add(lam_build *b, const lam_build_part *spec, lam_error *err);

/* Initialise a part spec: one copy, no styles (-1), identity transform. */
void lam_build_part_init(lam_build_part *spec);

/* The region names a style may name ("contour", "core", "upskin",
 * "downskin"): lam_kind_name of the regions. The region of a name, or -1. */
int lam_region_find(const char *name);

/* Check that short key `key` is a style key: a row of some region
 * (profile_keys.h), a number or choice. LAM_EINVAL ("KEY is not a build
 * style key (did you mean ...?)") otherwise. */
int lam_style_key_check(const char *key, lam_error *err);

/* Machine p's values for one part: a copy of *p (strings borrowed from p)
 * with the styles of the part's regions applied: style_of[r] is the style
 * of region r (NULL: none: region r keeps p's values). A key a region does
 * not have is skipped when the style was named for the whole part
 * (whole = 1), an error otherwise; a value out of range is an error at
 * the key's line and column in `file`. */
int lam_build_styled_profile(const lam_profile *p, const lam_build_style *const style_of[LAM_REGIONS], int whole,
                             const char *file, lam_profile *out, lam_error *err);

#endif
