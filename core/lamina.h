/* lamina's public C API: include this one header and link with
 * `pkg-config --cflags --libs lamina`.
 *
 * A library user loads a mesh (import.h; file.h: the input size limits),
 * builds a model (model.h), slices it (slice.h: layers of contours,
 * contour.h), may offset, fill or check the layers (offset.h, fill.h,
 * section.h, validate.h, drc.h, rays.h), plans them for a machine profile
 * (profile.h, planner.h, plan.h, hatch.h: scan strategies, dialect.h) and
 * writes programs or previews through a lam_writer (writer.h, svg.h,
 * html.h: the browser viewer; vstream.h: a plan as a stream of vectors),
 * the run as JSON (json_sink.h; tee.h feeds one plan to several sinks).
 * Every fallible function returns LAM_OK or a LAM_E* code with the message
 * in a lam_error (error.h). Plugins are written against lamina_plugin.h
 * alone, which does not need this library.
 *
 * The library opens Embree and GEOS itself when first needed (validation,
 * hatching, offsets: lazylib.h), so a program does not link them.
 *
 * The headers not included here (nest.h, enclose.h, geos.h, lexnum.h,
 * fmt.h, paths.h, prefetch.h, grow.h, test_hooks.h, viewer_html.h,
 * lazylib.h, geos_lazy.h, embree_lazy.h) are internal to core/ and not
 * installed. */
#ifndef LAMINA_H
#define LAMINA_H

#include "version.h"
#include "error.h"
#include "mesh.h"
#include "file.h"
#include "import.h"
#include "model.h"
#include "slice.h"
#include "contour.h"
#include "fill.h"
#include "offset.h"
#include "section.h"
#include "rays.h"
#include "validate.h"
#include "drc.h"
#include "writer.h"
#include "plan.h"
#include "hatch.h"
#include "dialect_template.h"
#include "dialect.h"
#include "profile.h"
#include "profile_keys.h"
#include "planner.h"
#include "tee.h"
#include "json_sink.h"
#include "plugin.h"
#include "program_read.h"
#include "svg.h"
#include "vstream.h"
#include "html.h"

#endif
