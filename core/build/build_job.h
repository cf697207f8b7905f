/* Build job files (issue 25, item 1): a YAML mapping that names the
 * machine, may give any profile key, lists build styles and the parts.
 *
 *   machine: lpbf-cli          # a shipped name, or a path (from the job's folder)
 *   layer_width: 0.04          # any profile key: the job's value wins
 *   plate: {width: 200, depth: 200, margin: 5}
 *   styles:
 *     fast: {power: 300, speed: 1400}
 *     core: {hatch_distance: 0.12}    # named after a region: every part's core
 *   parts:
 *     - model: bracket.stl     # from the job's folder
 *       copies: 4
 *       rotate: x:90           # or [x:90, z:45]
 *       style: fast            # every region; or {core: fast, upskin: ...}
 *     - {model: pin.stl, at: [40, 60], units: in, scale: 2, z: 0, name: pin}
 *
 * Every error is file:line:column with what is wrong; an unknown key says
 * the nearest one it may have meant. */
#ifndef LAM_BUILD_JOB_H
#define LAM_BUILD_JOB_H

#include "build.h"
#include "error.h"

/* Read job file `path` into a new build (lam_build_free). Errors:
 * LAM_EIO, LAM_ESYNTAX, LAM_EINVAL with the position, the machine
 * profile's own errors, LAM_ENOMEM. */
int lam_build_load(const char *path, lam_build **out, lam_error *err);

/* The same from text in memory; `path` stands for the file (its folder is
 * where relative paths start; NULL: the current folder, "<job>" in
 * messages). */
int lam_build_load_buf(const char *path, const char *text, size_t len, lam_build **out, lam_error *err);

#endif
