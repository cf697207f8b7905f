/* Reading back the contour programs lamina writes, so that a program can be
 * checked as the machine will get it (`lamina validate --program`).
 *
 * Formats, told apart by content:
 * - CLI (Common Layer Interface) when the file starts with "$$HEADERSTART":
 *   binary when its header holds "$$BINARY" (the cli-binary plugin's
 *   output), else ASCII (the cli-ascii profile's). ASCII: one command per
 *   line, "$$LAYER/z" and "$$POLYLINE/id,dir,n,x1,y1,...,xn,yn"; "//...//"
 *   comments and blank lines are skipped, "$$HATCHES/..." lines are read
 *   over (they are not contours), header lines other than $$UNITS and
 *   $$LAYERS are read over. Binary: after the header, little-endian
 *   commands 127 (layer, float32 z), 128 (layer, uint16 z), 130 (polyline,
 *   int32 id dir n, n float32 pairs), 129 (polyline, uint16 id dir n and
 *   pairs); hatches 132 (int32 id n, n float32 quadruples) and 131 (uint16)
 *   are read over. A polyline must be closed
 *   (its last point repeats its first, which is then dropped) and have dir
 *   0 (clockwise, hole) or 1 (counter-clockwise, solid): dir 2 (an open
 *   line) is not a contour. $$LAYERS, when given, must count the layers.
 *   Coordinates are taken as written; $$UNITS (how many millimetres one
 *   is) is kept in units_mm for the caller to compare with the model's.
 * - A lamina run's JSON (json_sink.h, `lamina slice --json`) when the file
 *   starts with "{": each layer's contours ("solid" their label, "id" their
 *   id, points in the output frame, projected on the job's plane into the
 *   layer frame), and the job's layer_frame: where the layers lie in the
 *   model (has_frame). Read by a strict reader
 *   (program_json.c) that gives every error a line and column.
 * - Otherwise the SLS dialect of the thesis (the sls-contours profile and
 *   `lamina slice` without a profile): blocks "contour Z", then one or more
 *   "loop N", N lines "X Y Z", "endloop", then "endcontour"; blank lines
 *   between; hatch blocks "hatches ..." to "endhatches" are read over. Each loop is a contour of the program; consecutive contours
 *   with the same Z make a layer. The dialect writes no label: a loop's
 *   direction is its label (counter-clockwise solid, clockwise hole).
 *
 * Precision: every number's written form says how far it may be from what
 * was meant (half a unit in its last decimal place; for float32, half an
 * ulp): the largest such distance over the coordinates and over the heights
 * is kept, for the checks' tolerances.
 *
 * Errors: LAM_ESYNTAX / LAM_EINVAL at file:line:column (text) or at a byte
 * offset (binary), LAM_EIO when the file cannot be read, LAM_ENOMEM. A
 * file that is none of these (its first statement not the SLS dialect's,
 * a JSON document whose "format" is not "lamina-run") is refused without
 * quoting any of it: it may be anything. Every reader stays within len:
 * no NUL terminator is needed. */
#ifndef LAM_PROGRAM_READ_H
#define LAM_PROGRAM_READ_H

#include <stddef.h>

#include "error.h"
#include "slice.h"

typedef enum lam_program_format {
    LAM_PROGRAM_SLS,
    LAM_PROGRAM_CLI_ASCII,
    LAM_PROGRAM_CLI_BINARY,
    LAM_PROGRAM_JSON
} lam_program_format;

typedef struct lam_program_contour {
    size_t first, n;         /* points xyz[3 * first ...] (no repeated closing point) */
    int dir;                 /* CLI: 1 counter-clockwise (solid), 0 clockwise (hole); SLS: -1 */
    long id;                 /* CLI: the polyline's id; SLS: its 1-based number in the file */
    long line, column;       /* where it starts (text; 0 for binary) */
    long long offset;        /* binary: byte offset of its command; -1 for text */
} lam_program_contour;

typedef struct lam_program_layer {
    double z;                /* the height as written */
    size_t first, n;         /* its contours */
    long line, column;       /* where it starts (CLI: its $$LAYER; SLS: its first loop's
                                contour; JSON: the layer's object); 0 for binary */
    long long offset;        /* binary: byte offset of its layer command; -1 for text */
    double floor, ceiling;   /* JSON: the layer's slab as the run says; NAN otherwise */
} lam_program_layer;

typedef struct lam_program {
    lam_program_format format;
    double *xyz;             /* 3 per point: SLS as written (x y z); CLI (x, y, the layer's z);
                                JSON (u, v, w) in the layer frame */
    size_t npoints;
    lam_program_contour *contours;
    size_t ncontours;
    lam_program_layer *layers;
    size_t nlayers;
    double quantum_xy;       /* the largest written coordinate's uncertainty */
    double quantum_z;        /* the same for heights */
    int has_frame;           /* JSON: the file says where its layers lie: */
    lam_frame frame;         /* the layer frame in the model (job.layer_frame) */
    int frame_machine;       /* whether it was written in the machine frame */
    double units_mm;         /* CLI's $$UNITS: millimetres per coordinate unit; 0 when
                                the file does not say (SLS, JSON: model units) */
    long units_line, units_column; /* where $$UNITS stands */
} lam_program;

/* Read the program at path. On success *out is a new program the caller
 * frees with lam_program_free. */
int lam_program_read(const char *path, lam_program **out, lam_error *err);

/* The same from a buffer in memory (path for messages). */
int lam_program_read_buf(const char *path, const unsigned char *data, size_t len, lam_program **out,
                         lam_error *err);

/* Layer i of p as a lam_layer in frame f, for the checks of validate.h:
 * points in (u, v) (SLS: the written x y z projected on f's u and v, or
 * taken as u v w when frame_machine; CLI: as written), labels from the
 * written direction field (CLI) or from each loop's direction (SLS), depth
 * and parent -1 (unknown: a program does not say), cut, floor and ceiling
 * the written height (the caller may change them). out is overwritten;
 * release it with lam_layer_clear. Errors: LAM_EINVAL at the contour's
 * position when an SLS point is not in its contour's plane (more than the
 * written precision off: another axis or frame was meant), LAM_ENOMEM. */
int lam_program_layer_make(const lam_program *p, size_t i, const lam_frame *f, int frame_machine, const char *path,
                           lam_layer *out, lam_error *err);

/* Free what lam_program_layer_make put in *L and zero it. */
void lam_layer_clear(lam_layer *L);

/* Read a run's JSON (data[0..len)) into p, which the caller allocated
 * zeroed and frees (lam_program_read_buf calls it). */
int lam_program_read_json(const char *path, const unsigned char *data, size_t len, lam_program *p, lam_error *err);

/* Multiply every coordinate, height and precision of p by k > 0 (a CLI
 * program's $$UNITS against the model's units). */
void lam_program_scale(lam_program *p, double k);

/* "sls-contours", "cli-ascii", "cli-binary" or "lamina-run" (JSON). */
const char *lam_program_format_name(lam_program_format f);

void lam_program_free(lam_program *p);

#endif
