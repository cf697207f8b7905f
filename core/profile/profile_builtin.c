/* The built-in SLS contour profile (see lam_profile_builtin_sls). This text
 * must stay identical to machines/sls-contours.yaml; test_profile checks it. */
#include "profile.h"

#include <string.h>

static const char sls_contours_yaml[] =
    "# The SLS contour dialect of the thesis (section 2.2): per contour\n"
    "#   contour Z\n"
    "#   loop P\n"
    "#   X Y Z        (P lines, solids counter-clockwise, holes clockwise)\n"
    "#   endloop\n"
    "#   endcontour\n"
    "# with a blank line between contours. Byte for byte what `lamina slice`\n"
    "# writes without a profile. Beyond the thesis, with hatching on\n"
    "# (hatch_strategy, SPEC 4.5) each block of hatch vectors (a region, stripe\n"
    "# or island) is written as\n"
    "#   hatches KIND N Z       (KIND core, upskin or downskin; N vectors)\n"
    "#   X0 Y0 Z0 X1 Y1 Z1      (N lines, each exposed from its first point)\n"
    "#   endhatches\n"
    "name: sls-contours\n"
    "description: SLS contours of the thesis (contour/loop/endloop/endcontour)\n"
    "process: sls\n"
    "units: mm\n"
    "spot_width: 0.1\n"
    "cut: middle\n"
    "dialect:\n"
    "  contour_begin: \"contour {z:%.6f}\"\n"
    "  loop_begin: \"loop {n}\"\n"
    "  vertex: \"{x:%.6f} {y:%.6f} {z:%.6f}\"\n"
    "  loop_end: \"endloop\"\n"
    "  contour_end: \"endcontour\"\n"
    "  hatches_begin: \"hatches {kind} {n} {z:%.6f}\"\n"
    "  hatch: \"{x0:%.6f} {y0:%.6f} {z0:%.6f} {x1:%.6f} {y1:%.6f} {z1:%.6f}\"\n"
    "  hatches_end: \"endhatches\"\n"
    "  separator: \"\"           # an empty line between two blocks\n";

const char *lam_profile_builtin_sls_text(void)
{
    return sls_contours_yaml;
}

int lam_profile_builtin_sls(lam_profile **out, lam_error *err)
{
    return lam_profile_load_buf("sls-contours (built in)", sls_contours_yaml, strlen(sls_contours_yaml), out, err);
}
