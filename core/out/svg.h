/* SVG contact sheet of a slicing run: one small panel per layer (at most
 * LAM_SVG_MAX_PANELS, evenly chosen above that and said in the title),
 * solids filled, holes cut out (one even-odd path per layer, class
 * "section") and outlined in red (class "hole"), each panel labelled with
 * its layer number (1-based, as the viewer and the JSON count) and cut
 * height; lam_svg_* functions take 0-based layer indices. Every panel uses the same scale, the
 * model's extent in the layer frame, v pointing up; below the panels, the
 * axes (u right, v up, named x/y/z when they are world axes) and a scale
 * bar (class "scalebar": a line 1, 2 or 5 times a power of ten model units
 * long, at most 60 px, and its label "LENGTH UNITS", UNITS the job's
 * lam_job_info.units when a plan feeds the sheet, else "model units").
 *
 * Cells and captions. A cell is a 200 px square panel (its drawing,
 * clipped to the square: class "drawing") over a caption band of
 * LAM_SVG_CAPTION_BAND px, cells LAM_SVG_CELL_GAP px apart, whatever the
 * layer count or the part's aspect ratio (the scale fits the larger
 * extent). The caption (class "caption") is two lines, "layer N  h=CUT"
 * and "(C contours, V vectors[, D drawn])", at x = LAM_SVG_CAPTION_MARGIN.
 * A line of n characters is estimated n * 0.6 * font-size px wide (sans-serif
 * digits; letters are mostly narrower) and font-size tall (from
 * font-size above its baseline to a quarter of it below); the font size is
 * LAM_SVG_CAPTION_FONT, or smaller (to a tenth of a pixel, rounded down)
 * so that the longest line of any caption fits 200 - 2 * margin px (one
 * size for the sheet, so its captions read alike); the first baseline is
 * margin + font-size below the panel, the second 1.3 font-sizes lower.
 * So each caption lies inside its cell's band, and no two captions, nor
 * a caption and a drawing, overlap. The title is sized to the sheet's
 * width by the same estimate (at most 15 px), and the sheet is at least as
 * wide as its footer (axes, scale bar and label, legend).
 *
 * Level of detail. A contact sheet's cell cannot show thousands of 0.1 mm
 * hatch lines, and drawing them all made a 267-layer part's sheet hundreds
 * of megabytes. A layer of at most LAM_SVG_CELL_VECTORS vectors is drawn
 * whole; past it its panel draws no travel or jump, every contour edge (a
 * pass joined into one path) when they are at most half of
 * LAM_SVG_CELL_VECTORS, else none (the section's outline shows where they
 * run), and of the other vectors the first and then one in k, k the least
 * that brings them within what is left: a panel draws at most
 * LAM_SVG_CELL_VECTORS of its layer's vectors. The caption says how many were
 * drawn ("D drawn") and a note under the footer (class "note") says the
 * sheet was thinned. In every path (sections, holes, joined contours) a
 * point within 0.3 px of the last one drawn is left out.
 *
 * Size. The sheet is held in memory and written at the end; its writer's
 * limit (lam_writer_set_limit: the CLI's --max-output) stops it, and a
 * file writer then leaves no file (docs/limits.md).
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
#define LAM_SVG_CELL_VECTORS 1000  /* a panel's vectors drawn before thinning */
#define LAM_SVG_CAPTION_BAND 34    /* px: a cell's caption band, below its panel */
#define LAM_SVG_CAPTION_FONT 12.0  /* px: the captions' largest font size */
#define LAM_SVG_CAPTION_MARGIN 2   /* px: the captions' margin in their band */
#define LAM_SVG_CELL_GAP 10        /* px: between cells, and the sheet's margin */

typedef struct lam_svg lam_svg;

/* Start a sheet for a run of nlayers layers whose sections lie inside
 * uvbox (umin vmin umax vmax). title is copied. */
int lam_svg_new(size_t nlayers, const double uvbox[4], const char *title, lam_svg **out, lam_error *err);

/* Name the units of the scale bar's label (copied; NULL or "" unknown:
 * "model units"), for a sheet no plan feeds (a plan's job names them at
 * its begin, replacing these). Errors: LAM_ENOMEM. */
int lam_svg_set_units(lam_svg *svg, const char *units, lam_error *err);

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
