/* lam_xform: units, scale, rotations, placement and translation applied to
 * a mesh's vertices as it is loaded (issue 24), before the model is built,
 * so that every later stage (repair, slicing, validation, programs) sees
 * the part where the machine will build it.
 *
 * The steps, always in this order:
 *   1. scale: units (the model's unit over the machine's) times --scale,
 *      per axis (a negative factor mirrors; the model's orientation is
 *      recomputed from adjacency and volume after, so that is harmless);
 *   2. rotations about the model axes through the origin, in the order
 *      given (--rotate x:90 --rotate z:45: first about x, then about z),
 *      right-handed, degrees;
 *   3. placement: LAM_PLACE_PLATE moves the lowest point to z = 0 and the
 *      centre of the bounding box's footprint to plate_centre;
 *   4. translation.
 * Identity steps are skipped, so a default lam_xform leaves every vertex
 * bit for bit as read (outputs do not change without an option).
 *
 * Parsing: the text forms the command line and Lua share. Errors are
 * LAM_EUSAGE with a message saying what is wrong with the text ("the axis
 * must be x, y or z"), without the text itself: the caller names its
 * option and the value given ("--rotate q:90: the axis must be x, y or
 * z", "rotate 'q:90': ..."). A failed parse leaves x as it was. */
#ifndef LAM_XFORM_H
#define LAM_XFORM_H

#include <stddef.h>

#include "error.h"
#include "mesh.h"

#define LAM_XFORM_MAX_ROT 16

enum { LAM_PLACE_NONE = 0, LAM_PLACE_PLATE = 1 };

typedef struct lam_xform {
    double scale[3];     /* per axis; 0 in all three means 1 (zero-initialised: identity) */
    size_t nrot;
    struct {
        int axis;        /* 0 x, 1 y, 2 z */
        double deg;
    } rot[LAM_XFORM_MAX_ROT];
    int place;           /* LAM_PLACE_NONE or LAM_PLACE_PLATE */
    double plate_centre[2]; /* where LAM_PLACE_PLATE puts the footprint's centre */
    double translate[3];
} lam_xform;

/* An identity transform (scale 1, no rotation, no placement, no offset). */
void lam_xform_init(lam_xform *x);

/* 1 when x changes nothing (NULL is the identity). */
int lam_xform_is_identity(const lam_xform *x);

/* Millimetres in one `unit` ("mm", "cm", "m", "um", "\xc2\xb5m", "in",
 * "inch", "ft"); 0 for an unknown name (NULL too). The table is the
 * profile key `units`' (lam_key_unit_mm, profile_keys.c), so a model's
 * unit and a machine's are the same names with the same factors. */
double lam_unit_mm(const char *unit);

/* Multiply the scale by factor on every axis (the units conversion). */
void lam_xform_scale_by(lam_xform *x, double factor);

/* "F" or "FX,FY,FZ": non-zero finite factors, multiplied into x's scale
 * (so two --scale options multiply). */
int lam_xform_parse_scale(lam_xform *x, const char *text, lam_error *err);

/* "AXIS:DEG" (x, y or z, also upper case; degrees, finite), or several
 * separated by commas ("x:90,z:45", applied in that order): appended to
 * x's rotations (LAM_EUSAGE past LAM_XFORM_MAX_ROT). Multiples of 90
 * degrees turn exactly (integer coordinates stay integers). */
int lam_xform_parse_rotate(lam_xform *x, const char *text, lam_error *err);

/* "X,Y,Z": finite offsets, added to x's translation (two add up). */
int lam_xform_parse_translate(lam_xform *x, const char *text, lam_error *err);

/* "plate" or "none" into x->place (the last one given wins). */
int lam_xform_parse_place(lam_xform *x, const char *text, lam_error *err);

/* Apply x to every vertex of m (x NULL or the identity: nothing). A
 * coordinate that leaves the range lam_coord_problem accepts is LAM_EGEOM
 * naming the step ("after scaling (units and --scale), vertex 3's x
 * coordinate (inf) is not a finite number"); m is then partly transformed
 * and only good to free. Placement looks at every vertex of the mesh,
 * as the model's bounding box does (lam_model_stats.bbox). */
int lam_xform_apply(const lam_xform *x, lam_mesh *m, lam_error *err);

#endif
