/* SVG contact sheet of a slicing run: one small panel per layer (at most
 * LAM_SVG_MAX_PANELS, evenly chosen above that and said in the title),
 * solids filled, holes cut out (one even-odd path per layer), each panel
 * labelled with its layer index and cut height. Every panel uses the same
 * scale, the model's extent in the layer frame, v pointing up. */
#ifndef LAM_SVG_H
#define LAM_SVG_H

#include "slice.h"
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

/* Write the whole sheet. */
int lam_svg_write(const lam_svg *svg, lam_writer *w);

/* Write the whole sheet to the file `path` (lam_writer_file: whole or not
 * at all). Errors: the writer's, in err. */
int lam_svg_save(const lam_svg *svg, const char *path, lam_error *err);

void lam_svg_free(lam_svg *svg);

#endif
