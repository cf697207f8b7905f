/* lamina's public C API: include this one header and link with
 * `pkg-config --cflags --libs lamina`.
 *
 * A library user loads a mesh (import.h; file.h: the input size limits),
 * builds a model (model.h: transformed on load by xform.h, repaired by
 * repair.h, written back out by mesh_write.h), slices it (slice.h; frame.h: the layer frame;
 * layer.h, contour.h: layers of contours), may offset, fill or check the
 * layers (offset.h, winding.h: the fill rule, section.h, validate.h,
 * drc.h, rays.h), plans them for a machine profile (profile.h,
 * profile_keys.h: its keys and fields, planner.h, plan.h, hatch.h: scan
 * strategies, dialect.h) and writes programs or previews through a
 * lam_writer (writer.h, svg.h, html.h: the browser viewer; vstream.h: a
 * plan as a stream of vectors), the run as JSON (json_sink.h; tee.h feeds
 * one plan to several sinks). Plans of layers made already
 * (plan_layers.h), their data kept for a reader (plan_data.h), part files
 * of a run joined into one program (part.h) and validation over many
 * layers (validate_run.h) are the pieces the Lua binding and the
 * executable are built from; so are the number formatting (fmt.h), the
 * thread count and worker pools (pool.h) and where lamina finds its data
 * (paths.h).
 * Every fallible function returns LAM_OK or a LAM_E* code with the message
 * in a lam_error (error.h). Plugins are written against lamina_plugin.h
 * alone, which does not need this library.
 *
 * The library opens Embree and GEOS itself when first needed (validation,
 * hatching, offsets: lazylib.h), so a program does not link them.
 *
 * The headers not included here (nest.h, enclose.h, geos.h, lexnum.h,
 * prefetch.h, grow.h, buf.h, hugemem.h, test_hooks.h, viewer_html.h,
 * lazylib.h, geos_lazy.h, embree_lazy.h, hatch_internal.h) are internal to
 * core/ and not installed; lua/ and lua/cli/ are compiled against the
 * installed headers only (the Makefile's INC_DIR), so they cannot use them. */
#ifndef LAMINA_H
#define LAMINA_H

#include "version.h"
#include "error.h"
#include "mesh.h"
#include "file.h"
#include "import.h"
#include "model.h"
#include "xform.h"
#include "repair.h"
#include "mesh_write.h"
#include "frame.h"
#include "layer.h"
#include "slice.h"
#include "contour.h"
#include "winding.h"
#include "offset.h"
#include "section.h"
#include "rays.h"
#include "validate.h"
#include "drc.h"
#include "writer.h"
#include "vocab.h"
#include "plan.h"
#include "hatch.h"
#include "support.h"
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
#include "fmt.h"
#include "pool.h"
#include "paths.h"
#include "validate_run.h"
#include "plan_layers.h"
#include "plan_data.h"
#include "plan_record.h"
#include "views.h"
#include "part.h"
#include "blayer.h"
#include "lasers.h"
#include "arrange.h"
#include "build.h"
#include "build_job.h"
#include "build_run.h"
#include "build_plan.h"

#endif
