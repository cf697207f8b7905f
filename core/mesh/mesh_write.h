/* Writing a model's mesh back out (`lamina repair MODEL -o OUT`): binary
 * STL or Wavefront OBJ, so that the repaired mesh can be checked in
 * another tool. */
#ifndef LAM_MESH_WRITE_H
#define LAM_MESH_WRITE_H

#include "error.h"
#include "model.h"
#include "writer.h"

enum { LAM_MESH_STL = 0, LAM_MESH_OBJ = 1 };

/* The format for an output path: LAM_MESH_OBJ for a name ending in .obj
 * (any case), LAM_MESH_STL otherwise. */
int lam_mesh_format_for(const char *path);

/* Write md's triangles (as oriented: outward, cavities inward) to w in
 * format fmt, streamed (a buffer of 32 kB, and for OBJ an index per
 * vertex). Binary STL: an 80-byte header "lamina VERSION binary STL of
 * SOURCE" (never "solid" first), the count, per facet its unit normal
 * (from the vertices in double; 0 for a facet of no area) and three
 * float32 corners, attribute 0, little-endian. OBJ: a comment, a `v` line
 * per vertex a triangle uses (in the mesh's order, the shortest numbers
 * that read back as the doubles), then an `f` line per triangle (1-based).
 * Wires are not written. Errors: the writer's (sticky, with its path and
 * reason; the caller commits or aborts w), LAM_EINVAL for an STL of more
 * than 2^32 - 1 facets or a coordinate beyond float32 (told before a byte
 * is written), LAM_ENOMEM. */
int lam_model_write_mesh(const lam_model *md, int fmt, lam_writer *w, lam_error *err);

#endif
