/* SVG contact sheet of a slicing run: one small panel per layer (at most
 * LAM_SVG_MAX_PANELS, evenly chosen above that and said in the title),
 * solids filled, holes cut out (one even-odd path per layer, class
 * "section") and outlined in red (class "hole"), each panel labelled with
 * its layer number (1-based, as the viewer and the JSON count) and cut
 * height; lam_svg_* functions take 0-based layer indices. Every panel uses the same scale, the
 * model's extent in the layer frame, v pointing up; below the panels, the
 * axes (u right, v up, named x/y/z when they are world axes) and a scale
 * bar (class "scalebar": a line 1, 2 or 5 times a power of ten model units
 * long, at most 60 px, and its label "LENGTH UNITS").
 *
 * Fed by a planning run (lam_svg_consumer), each panel also draws the layer's
 * planned vectors (vstream.h) over a lighter fill: one <path> per vector
 * whose class is its kind (deposit, contour, core, upskin, downskin;
 * travel and jump dashed grey; a contour pass's edges joined into one
 * path), coloured from dark blue through magenta to orange along the
 * layer's order, with a legend.
 *
 * Every string written (the title, the unit name, a vector's kind) goes
 * through escape.h (LAM_ESC_XML): whatever bytes it holds, the sheet is
 * well-formed XML and the string only ever shows as text. */
#ifndef LAM_SVG_H
#define LAM_SVG_H

#include "plan.h"
#include "slice.h"
#include "vstream.h"
#include "writer.h"

#define LAM_SVG_MAX_PANELS 100

typedef struct lam_svg lam_svg;

/* Start a sheet for a run of nlayers layers whose sections lie inside
 * uvbox (umin vmin umax vmax). title is copied. */
int lam_svg_new(size_t nlayers, const double uvbox[4], const char *title, lam_svg **out, lam_error *err);

/* Is layer `index` one of the panels? */
int lam_svg_wants(const lam_svg *svg, size_t index);

/* Record a layer's panel (only if wanted; otherwise a no-op). */
int lam_svg_add(lam_svg *svg, const lam_layer *layer, lam_error *err);

/* Mark a point (layer-frame u, v) on layer `index`'s panel with a red ring
 * (design-rule violations); a layer without a panel is ignored. */
int lam_svg_mark(lam_svg *svg, size_t index, double u, double v, lam_error *err);

/* Make *out a consumer of the plan's vector stream (vstream.h, views.h)
 * that draws each wanted layer's planned vectors on its panel; f is the
 * run's frame (borrowed; it names the axes), frame_machine as in the plan
 * options. The sheet is borrowed: it must outlive the consumer, which has
 * no destroy. Errors of its calls (out of memory) go to err, which must
 * outlive it. */
int lam_svg_consumer(lam_svg *svg, const lam_frame *f, int frame_machine, lam_vec_consumer *out, lam_error *err);

/* Write the whole sheet. */
int lam_svg_write(const lam_svg *svg, lam_writer *w);

/* Write the whole sheet to the file `path` (lam_writer_file: whole or not
 * at all). Errors: the writer's, in err. */
int lam_svg_save(const lam_svg *svg, const char *path, lam_error *err);

void lam_svg_free(lam_svg *svg);

#endif
