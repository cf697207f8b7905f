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
 * format fmt. Binary STL: an 80-byte header, the count, per facet its
 * unit normal and three float32 vertices; OBJ: `v` lines with the
 * shortest round-trip numbers, then `f` lines. Errors: the writer's
 * (sticky; the caller commits or aborts w), LAM_EINVAL for an STL of more
 * than 2^32 - 1 facets. */
int lam_model_write_mesh(const lam_model *md, int fmt, lam_writer *w, lam_error *err);

#endif
