/* Machine profiles: YAML files (libyaml document API) describing a machine's
 * process, widths, feed rates, raster options and command dialect.
 * A profile is data only: nothing in it can run code (YAML tags beyond the
 * core schema are refused). Every error names file:line:column (1-based) of
 * the offending node: the key for an unknown or duplicate key, the value for
 * a wrong type or range, the mapping for a missing key, the exact character
 * inside a template for template errors (single-line plain or quoted
 * scalars and `|` blocks; other scalars: the scalar's start), the problem
 * mark for malformed YAML. Numbers must be plain scalars read whole and
 * finite; booleans true/false/yes/no. A `|`/`>` block template loses its
 * final line break. See machines/README.md for the keys. */
#ifndef LAM_PROFILE_H
#define LAM_PROFILE_H

#include <stddef.h>

#include "error.h"
#include "profile_keys.h"
#include "writer.h"

/* lam_profile itself, field by field, is in profile_keys.h beside the key
 * table that describes its fields. */

/* Load a profile from a file, resolving `inherits:` (a shipped profile name
 * or a path relative to the inheriting file; chains allowed, cycles are an
 * error). On success *out is a new profile (lam_profile_free).
 * Errors: LAM_EIO, LAM_ESYNTAX (malformed YAML), LAM_EINVAL (unknown key,
 * missing key, wrong type, value out of range, bad template), with position. */
int lam_profile_load(const char *path, lam_profile **out, lam_error *err);

/* Find a profile by name or path: a string containing '/' or ending in
 * .yaml/.yml is a path; otherwise NAME.yaml in the machine directories
 * (lam_machine_dirs). */
int lam_profile_find(const char *name_or_path, lam_profile **out, lam_error *err);

/* Load a profile from YAML text in memory; `name` stands for the file in
 * messages. `inherits:` resolves relative to the current directory. */
int lam_profile_load_buf(const char *name, const char *text, size_t len, lam_profile **out, lam_error *err);

/* The thesis's SLS contour dialect, built in: what `lamina slice` writes
 * without -m (the same profile as machines/sls-contours.yaml, which a test
 * keeps identical), so it works without any machine directory. */
int lam_profile_builtin_sls(lam_profile **out, lam_error *err);

/* Its YAML text (static). */
const char *lam_profile_builtin_sls_text(void);

void lam_profile_free(lam_profile *p);

/* The directories searched for shipped profiles, in order: $LAMINA_MACHINES
 * (colon-separated), then from the executable's directory ../machines (the
 * build tree) and ../share/lamina/machines (an installed tree); from the C
 * module lamina.so's directory (a stock lua5.4, paths.h) ../machines,
 * ../../../share/lamina/machines (lib/lua/5.4/lamina.so installed) and
 * ../../../share/lua/5.4/lamina/machines (a LuaRocks tree). Returns the number
 * of directories stored into dirs (each malloc'd; caller frees). */
size_t lam_machine_dirs(char **dirs, size_t max);

/* How many millimetres one unit of the profile's `units` is: mm 1, cm 10,
 * m 1000, um (or µm) 0.001, in (inch) 25.4, ft 304.8; 0 for other units. */
double lam_profile_unit_mm(const lam_profile *p);

/* The centre of the machine's plate in plate coordinates (where
 * `--place plate` puts a part's footprint): (width/2, depth/2) for a
 * rectangular plate (coordinates from its front-left corner), the origin
 * for a round plate (from its centre) or a profile without a plate. */
void lam_profile_plate_centre(const lam_profile *p, double c[2]);

/* The most the automatic gap-closing tolerance may be on this machine:
 * LAM_GAP_MM (0.05 mm) in the profile's units (mm, cm, m, um, in, inch,
 * ft); 0 (no limit) for other units. */
double lam_profile_gap_limit(const lam_profile *p);

/* Write the resolved profile as YAML (what `lamina machines --show` prints):
 * the keys its planner reads (lam_key_read_by), so that the text loads again. */
int lam_profile_dump(const lam_profile *p, lam_writer *w);

/* Set key `name` of p from text, as one more YAML file on top of p would
 * (`--set KEY=VALUE`): every row but the loader's; the value is checked
 * with the loader's rules and messages; strings and templates replace
 * p's (p owns them). Errors: LAM_EINVAL (unknown key, with "did you mean";
 * a bad value), LAM_ENOMEM. p is unchanged on error. */
int lam_profile_set(struct lam_profile *p, const char *name, const char *text, lam_error *err);

#endif
